// SPDX-License-Identifier: MIT
// The one way every writer of this project puts a file on disk (glb, gltf + bin, copied
// images, reports, manifests): the bytes go to a temporary beside the destination, named
// ".NAME.tmp-PID-N", are written, synced and closed with every step checked, and only then
// renamed over the destination. A failure at any step removes the temporary and names the
// file and the reason ("No space left on device"); the previous file stays as it was.
//
// Only regular files are replaced (writeTargetOf is the rule): a name not yet there or a
// regular file is written as above; a symbolic link is followed and its target written so
// (beside the target; the link stays) where that target's name ends in the extension of the
// name given (a link out.glb -> /etc/passwd is refused, not followed); a character device, a
// FIFO with a reader, or a name for a descriptor (/dev/stdout, /proc/self/fd/N) is opened and
// written in place, never renamed over; a block device, a socket, a FIFO without a reader or a
// folder is refused.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace tangent::output {

// Writes the pieces, one after another, to `path` atomically (see above). Throws
// std::runtime_error naming `path` and the reason.
void writeFileAtomic(const std::filesystem::path& path, const std::vector<std::span<const std::uint8_t>>& pieces);
void writeFileAtomic(const std::filesystem::path& path, std::string_view text);

// Where the bytes for `path` go.
struct WriteTarget {
  enum class Kind {
    replace,     // `file` (a regular file, or a name not yet there) is replaced atomically
    inPlace,     // `file` (a device, FIFO, or a descriptor of another process) is opened and written
    descriptor,  // `path` names this process's open descriptor `descriptor`: written to it
  };
  Kind kind = Kind::replace;
  std::filesystem::path file;
  int descriptor = -1;
};
// The rule above, for `path`: links followed (at most 40), every name under /proc written in
// place. Throws std::runtime_error naming `path` for what is refused (block device, socket,
// folder, a loop of links, a link to a file, or to a name not there yet, whose extension is not
// the non-empty one of `path`).
WriteTarget writeTargetOf(const std::filesystem::path& path);

// Temporaries of processes that no longer run (killed, or the machine went down) in
// `folder`: removed, once per folder and process. Called for every folder a writer writes to.
void removeStaleTemporaries(const std::filesystem::path& folder);

// A path (file or empty folder) removed when the process dies of SIGINT, SIGTERM or SIGHUP
// while the guard lives. writeFileAtomic guards its temporaries this way.
class TemporaryGuard {
 public:
  explicit TemporaryGuard(const std::filesystem::path& path);
  ~TemporaryGuard();
  TemporaryGuard(const TemporaryGuard&) = delete;
  TemporaryGuard& operator=(const TemporaryGuard&) = delete;

 private:
  int slot_ = -1;
};

// A file written as writeFileAtomic writes it (temporary beside `path`, written, synced,
// closed), but left as that temporary until commit() renames it over `path`: for files that
// may replace what is there only once another file is written (the image copies of a bake,
// after its output). Destroyed before commit() (the other write failed), the temporary is
// removed and `path` was never touched. The constructor throws as writeFileAtomic does.
// Where `path` is not replaced but written in place (writeTargetOf), the constructor writes
// it and commit() has nothing left to do: bytes sent to a device cannot be taken back.
class StagedFile {
 public:
  StagedFile(const std::filesystem::path& path, const std::vector<std::span<const std::uint8_t>>& pieces);
  ~StagedFile();
  StagedFile(const StagedFile&) = delete;
  StagedFile& operator=(const StagedFile&) = delete;
  const std::filesystem::path& path() const { return path_; }
  // Renames the temporary over `path`; throws std::runtime_error naming it (the temporary is
  // then removed).
  void commit();

 private:
  friend void commitAll(std::span<StagedFile* const> files);
  // commit(), keeping what `path` held (a hard link beside it, named as a temporary) for undo().
  void commitKeepingPrevious();
  // Puts back what `path` held before commitKeepingPrevious() (removes `path` where nothing
  // was there); "" when done, else what could not be put back and where its bytes are.
  std::string undo();
  void dropPrevious();

  // path_: as the caller named it (messages); target_: the regular file renamed over.
  std::filesystem::path path_, target_, temporary_, previous_;
  std::unique_ptr<TemporaryGuard> guard_;
  bool committed_ = false;
};

// Staged files renamed into place as one, in order: each keeps what its path held until all
// are in place. Where a rename fails (a folder appeared where a file goes), those renamed
// before it are put back as they were, the rest are removed, and std::runtime_error names the
// file that failed and the reason (and any file that could not be put back).
void commitAll(std::span<StagedFile* const> files);
// For tests only: called by commitAll after each file is in place, with how many are (null:
// not called), so that a test can send a signal between two renames.
extern void (*commitAllAfterRename)(std::size_t renamed);

// For programs (the CLI, the viewer), not libraries: installs handlers for SIGINT, SIGTERM and
// SIGHUP that remove the guarded temporaries, print `message` (when not empty) on stderr, and
// then let the signal end the process as it would have (exit status 128 + signal).
void removeTemporariesOnSignal(const char* message = "");

// For programs that installed removeTemporariesOnSignal(): while one of these lives (in any
// thread), SIGINT, SIGTERM and SIGHUP do not end the process at once; the last one to go
// raises the first signal that came meanwhile, and the handler then runs as ever. Once a
// handler has set out to end the process, a new one never finishes constructing. For short steps
// that must not stop half-way: commitAll, whose renames keep each replaced file's earlier bytes
// under a temporary name until every file is in place (stopped between two renames, some files
// would be new, some old, and the old bytes of the new ones only in temporaries that the next
// run deletes).
class SignalDeferral {
 public:
  SignalDeferral();
  ~SignalDeferral();
  SignalDeferral(const SignalDeferral&) = delete;
  SignalDeferral& operator=(const SignalDeferral&) = delete;
};

// For a batch (several files, each written whole): while on, the first SIGINT or SIGTERM only
// asks to stop (stopRequested() turns true; `notice` is printed), so that the current file is
// finished and recorded; a second one ends the process as the handler above does. Needs
// removeTemporariesOnSignal() first.
void stopGracefullyOnSignal(const char* notice);
bool stopRequested();

// Largest .glb the format can describe (its length fields are 32-bit).
inline constexpr std::uint64_t kMaxGlbBytes = 0xFFFFFFFFull;

// Throws std::runtime_error naming `path`, the size and the way out (.gltf output) when a .glb of
// these chunk sizes (unpadded) would not fit the format's 32-bit lengths.
void checkGlbFits(const std::filesystem::path& path, std::uint64_t jsonBytes, std::uint64_t binBytes);

}  // namespace tangent::output
