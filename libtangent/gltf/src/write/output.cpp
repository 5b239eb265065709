// SPDX-License-Identifier: MIT
#include "tangent/output.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <mutex>
#include <set>
#include <stdexcept>
#include <string>

namespace tangent::output {
namespace fs = std::filesystem;

namespace {

// Guarded paths, readable from a signal handler: fixed slots, each claimed with an atomic flag.
constexpr int kSlots = 256;
constexpr std::size_t kSlotBytes = 4096;
struct Slot {
  std::atomic<int> state{0};  // 0 free, 1 being filled, 2 guarded
  char path[kSlotBytes] = {};
};
// Zeros in .bss, touched only when used: initialized at start, the 1 MiB took 256 page faults
// in every run.
constinit Slot slots[kSlots];

const char* signalMessage = "";
const char* gracefulNotice = "";
std::atomic<bool> graceful{false}, stopAsked{false};
static_assert(std::atomic<bool>::is_always_lock_free, "read from a signal handler");
// Live SignalDeferrals (kDying once a signal handler has set out to end the process), and the
// first signal that came while there were some (0: none).
constexpr int kDying = -(1 << 30);
std::atomic<int> deferrals{0}, deferredSignal{0};
static_assert(std::atomic<int>::is_always_lock_free, "read from a signal handler");

void onSignal(int signal) {
  if (graceful.load() && (signal == SIGINT || signal == SIGTERM) && !stopAsked.exchange(true)) {
    const ssize_t ignored = ::write(STDERR_FILENO, gracefulNotice, std::strlen(gracefulNotice));
    (void)ignored;
    return;
  }
  // No SignalDeferral may begin once the process is set to end here (their constructors wait),
  // and while any lives the signal waits for the last.
  for (int live = deferrals.load();;) {
    if (live < 0) break;  // another signal's handler is ending the process already
    if (live == 0) {
      if (deferrals.compare_exchange_weak(live, kDying)) break;
      continue;
    }
    int none = 0;
    deferredSignal.compare_exchange_strong(none, signal);  // the first one is kept
    if (deferrals.load() > 0) return;  // the last SignalDeferral to end raises it
    // The last one ended meanwhile, maybe before it could see the signal: whoever takes it
    // back from deferredSignal handles it.
    if (deferredSignal.exchange(0) == 0) return;
    live = deferrals.load();
  }
  // Newest first: a folder guarded before the files inside it goes after them.
  for (int i = kSlots - 1; i >= 0; --i) {
    if (slots[i].state.load() != 2) continue;
    if (::unlink(slots[i].path) != 0) ::rmdir(slots[i].path);
  }
  if (signalMessage[0] != '\0') {
    const ssize_t ignored = ::write(STDERR_FILENO, signalMessage, std::strlen(signalMessage));
    (void)ignored;
  }
  ::signal(signal, SIG_DFL);
  ::raise(signal);
}

std::string reason(int error) { return std::strerror(error); }

// ".NAME.tmp-PID-N" -> PID, or -1 when `name` is not one of ours.
long temporaryOwner(const std::string& name) {
  if (name.size() < 2 || name[0] != '.') return -1;
  const std::size_t tag = name.rfind(".tmp-");
  if (tag == std::string::npos || tag == 0) return -1;
  const std::size_t dash = name.find('-', tag + 5);
  if (dash == std::string::npos || dash == tag + 5 || dash + 1 == name.size()) return -1;
  long pid = 0;
  for (std::size_t i = tag + 5; i < dash; ++i) {
    if (name[i] < '0' || name[i] > '9' || pid > 100000000) return -1;
    pid = pid * 10 + (name[i] - '0');
  }
  for (std::size_t i = dash + 1; i < name.size(); ++i) {
    if (name[i] < '0' || name[i] > '9') return -1;
  }
  return pid;
}

}  // namespace

TemporaryGuard::TemporaryGuard(const fs::path& path) {
  const std::string text = path.string();
  if (text.size() >= kSlotBytes) return;  // not guarded: the path cannot be opened either
  for (int i = 0; i < kSlots; ++i) {
    int expected = 0;
    if (slots[i].state.compare_exchange_strong(expected, 1)) {
      std::memcpy(slots[i].path, text.c_str(), text.size() + 1);
      slots[i].state.store(2);
      slot_ = i;
      return;
    }
  }
}

TemporaryGuard::~TemporaryGuard() {
  if (slot_ >= 0) slots[slot_].state.store(0);
}

void removeTemporariesOnSignal(const char* message) {
  signalMessage = message ? message : "";
  struct sigaction action {};
  action.sa_handler = onSignal;
  sigemptyset(&action.sa_mask);
  for (int signal : {SIGINT, SIGTERM, SIGHUP}) sigaction(signal, &action, nullptr);
}

void stopGracefullyOnSignal(const char* notice) {
  gracefulNotice = notice ? notice : "";
  graceful.store(true);
}

bool stopRequested() { return stopAsked.load(); }

SignalDeferral::SignalDeferral() {
  for (int live = deferrals.load();;) {
    // A signal handler is ending the process: nothing more may begin.
    if (live < 0) {
      for (;;) ::pause();
    }
    if (deferrals.compare_exchange_weak(live, live + 1)) return;
  }
}

SignalDeferral::~SignalDeferral() {
  if (deferrals.fetch_sub(1) != 1) return;
  if (const int signal = deferredSignal.exchange(0); signal != 0) ::raise(signal);
}

void removeStaleTemporaries(const fs::path& folder) {
  static std::mutex mutex;
  static std::set<fs::path> cleaned;
  std::error_code ec;
  const fs::path key = fs::absolute(folder, ec).lexically_normal();
  {
    std::lock_guard lock(mutex);
    if (!cleaned.insert(key).second) return;
  }
  for (fs::directory_iterator it(key, ec), end; !ec && it != end; it.increment(ec)) {
    const long pid = temporaryOwner(it->path().filename().string());
    if (pid <= 0 || pid == ::getpid()) continue;
    if (::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) continue;  // still running (or not ours to ask)
    std::error_code ignored;
    if (it->is_regular_file(ignored)) fs::remove(it->path(), ignored);
  }
}

void writeFileAtomic(const fs::path& path, std::string_view text) {
  writeFileAtomic(path, {std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size())});
}

void writeFileAtomic(const fs::path& path, const std::vector<std::span<const std::uint8_t>>& pieces) {
  StagedFile(path, pieces).commit();
}

namespace {

// ".NAME.tmp-PID-N" beside `path`, N new on every call.
fs::path temporaryBeside(const fs::path& path) {
  static std::atomic<unsigned> counter{0};
  const fs::path folder = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  return folder / ("." + path.filename().string() + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
}

// "/proc/PID/fd/N" (PID this process, as /proc/self and /dev/fd resolve) -> N, else -1.
int ownDescriptorNamed(const fs::path& path) {
  const std::string prefix = "/proc/" + std::to_string(::getpid()) + "/fd/";
  const std::string text = path.string();
  if (text.rfind(prefix, 0) != 0 || text.size() == prefix.size() || text.size() > prefix.size() + 9) return -1;
  int descriptor = 0;
  for (std::size_t i = prefix.size(); i < text.size(); ++i) {
    if (text[i] < '0' || text[i] > '9') return -1;
    descriptor = descriptor * 10 + (text[i] - '0');
  }
  return descriptor;
}

// `path` with its folder's links resolved (the name itself as it is), where that folder exists.
fs::path withRealFolder(const fs::path& path) {
  std::error_code ec;
  const fs::path absolute = fs::absolute(path, ec);
  if (ec) return path;
  const fs::path folder = fs::canonical(absolute.parent_path(), ec);
  return ec ? absolute.lexically_normal() : folder / absolute.filename();
}

// Writes every piece to `fd`, which stays open; throws "PATH: write failed: REASON". With
// `startWriteback` (a file to be synced), each 8 MiB written is handed to the disk at once
// (sync_file_range starts the writeback and does not wait), so that the fsync after waits for
// the last part only instead of the whole file: the disk writes while the rest is copied.
void writeAll(int fd, const fs::path& path, const std::vector<std::span<const std::uint8_t>>& pieces, bool startWriteback) {
  constexpr std::size_t kWritebackBytes = std::size_t(8) << 20;
  std::size_t total = 0, handedOver = 0;
  for (const auto& piece : pieces) {
    const std::uint8_t* at = piece.data();
    std::size_t left = piece.size();
    while (left > 0) {
      const ssize_t written = ::write(fd, at, std::min<std::size_t>(left, kWritebackBytes));
      if (written < 0 && errno == EINTR) continue;
      if (written <= 0) throw std::runtime_error(path.string() + ": write failed: " + reason(written < 0 ? errno : ENOSPC));
      at += written;
      left -= static_cast<std::size_t>(written);
      total += static_cast<std::size_t>(written);
#if defined(__linux__) && defined(SYNC_FILE_RANGE_WRITE)
      if (startWriteback && total - handedOver >= kWritebackBytes) {
        ::sync_file_range(fd, static_cast<off_t>(handedOver), static_cast<off_t>(total - handedOver), SYNC_FILE_RANGE_WRITE);
        handedOver = total;  // advice only: where it fails, fsync does it all
      }
#endif
    }
  }
  (void)startWriteback;
  (void)handedOver;
}

void writeInPlace(const WriteTarget& target, const fs::path& path, const std::vector<std::span<const std::uint8_t>>& pieces) {
  if (target.kind == WriteTarget::Kind::descriptor) {
    // What this process printed through its streams goes first, in order.
    std::cout.flush();
    std::cerr.flush();
    std::fflush(nullptr);
    if (::fcntl(target.descriptor, F_GETFD) < 0)
      throw std::runtime_error(path.string() + ": descriptor " + std::to_string(target.descriptor) + " is not open");
    writeAll(target.descriptor, path, pieces, false);
    return;
  }
  // Non-blocking for the open only: a FIFO nobody reads refuses at once instead of waiting.
  struct stat status {};
  const bool regular = ::stat(target.file.c_str(), &status) == 0 && S_ISREG(status.st_mode);
  const int fd = ::open(target.file.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC | O_NONBLOCK | (regular ? O_TRUNC : 0));
  if (fd < 0) {
    const int error = errno;
    if (error == ENXIO && S_ISFIFO(status.st_mode))
      throw std::runtime_error(path.string() + ": a FIFO that nobody reads; not written (start its reader first)");
    throw std::runtime_error(path.string() + ": cannot be opened for writing: " + reason(error));
  }
  const int flags = ::fcntl(fd, F_GETFL);
  if (flags >= 0) ::fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
  try {
    writeAll(fd, path, pieces, false);
  } catch (...) {
    ::close(fd);
    throw;
  }
  if (::close(fd) != 0 && errno != EINTR) throw std::runtime_error(path.string() + ": write failed: " + reason(errno));
}

}  // namespace

WriteTarget writeTargetOf(const fs::path& path) {
  fs::path at = path;
  // A file replaced or created through links must be of the kind named: `out.glb` -> /etc/passwd
  // (run as root) would otherwise replace the system's file with a glTF.
  auto replaced = [&path](const fs::path& file, int links) -> WriteTarget {
    if (links > 0 && (path.extension().empty() || file.extension() != path.extension()))
      throw std::runtime_error(path.string() + ": is a symbolic link to " + file.string() + ", which does not end in " +
                               (path.extension().empty() ? std::string("an extension") : path.extension().string()) +
                               " as the name given does; not written (a link is followed only to a file of the same kind: "
                               "remove the link or choose another name)");
    return {WriteTarget::Kind::replace, file, -1};
  };
  for (int links = 0;; ++links) {
    if (links > 40) throw std::runtime_error(path.string() + ": more than 40 symbolic links to follow (a loop?); not written");
    const fs::path real = withRealFolder(at);
    if (const int descriptor = ownDescriptorNamed(real); descriptor >= 0)
      return {WriteTarget::Kind::descriptor, real, descriptor};
    // Names under /proc are the kernel's: written in place, whatever they lead to.
    if (real.string().rfind("/proc/", 0) == 0) return {WriteTarget::Kind::inPlace, real, -1};
    struct stat status {};
    if (::lstat(at.c_str(), &status) != 0) {
      if (errno == ENOENT) return replaced(at, links);  // not there yet: created
      throw std::runtime_error(path.string() + ": cannot be examined: " + reason(errno));
    }
    if (S_ISLNK(status.st_mode)) {
      std::error_code ec;
      const fs::path next = fs::read_symlink(at, ec);
      if (ec) throw std::runtime_error(path.string() + ": cannot read the link: " + ec.message());
      at = next.is_absolute() ? next : at.parent_path() / next;
      continue;
    }
    if (S_ISREG(status.st_mode)) return replaced(at, links);
    if (S_ISDIR(status.st_mode)) throw std::runtime_error(path.string() + ": is a folder; not written");
    if (S_ISBLK(status.st_mode)) throw std::runtime_error(path.string() + ": is a block device; not written (give a file name)");
    if (S_ISSOCK(status.st_mode)) throw std::runtime_error(path.string() + ": is a socket; a socket cannot be written as a file");
    return {WriteTarget::Kind::inPlace, at, -1};  // character device, FIFO
  }
}

StagedFile::StagedFile(const fs::path& path, const std::vector<std::span<const std::uint8_t>>& pieces) : path_(path) {
  const WriteTarget target = writeTargetOf(path);
  if (target.kind != WriteTarget::Kind::replace) {
    writeInPlace(target, path, pieces);
    committed_ = true;
    return;
  }
  target_ = target.file;
  removeStaleTemporaries(target_.parent_path().empty() ? fs::path(".") : target_.parent_path());
  const fs::path temp = temporaryBeside(target_);
  auto guard = std::make_unique<TemporaryGuard>(temp);
  const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd < 0) throw std::runtime_error(path.string() + ": cannot create a temporary file beside it: " + reason(errno));
  auto fail = [&](const char* step, int error) {
    ::close(fd);
    ::unlink(temp.c_str());
    throw std::runtime_error(path.string() + ": " + step + ": " + reason(error));
  };
  try {
    writeAll(fd, path, pieces, true);
  } catch (...) {
    ::close(fd);
    ::unlink(temp.c_str());
    throw;
  }
  // Delayed allocation can report a full disk only here.
  if (::fsync(fd) != 0 && errno != EINVAL && errno != EROFS) fail("write failed", errno);
  if (::close(fd) != 0) {
    const int error = errno;
    ::unlink(temp.c_str());
    throw std::runtime_error(path.string() + ": write failed: " + reason(error));
  }
  temporary_ = temp;
  guard_ = std::move(guard);
}

StagedFile::~StagedFile() {
  if (!committed_ && !temporary_.empty()) ::unlink(temporary_.c_str());
  if (!previous_.empty()) ::unlink(previous_.c_str());
}

void StagedFile::commit() {
  if (committed_) return;
  committed_ = true;
  if (::rename(temporary_.c_str(), target_.c_str()) != 0) {
    const int error = errno;
    ::unlink(temporary_.c_str());
    throw std::runtime_error(path_.string() + ": cannot rename the temporary file into place: " + reason(error));
  }
  guard_.reset();
}

void StagedFile::commitKeepingPrevious() {
  if (committed_) return;
  // What `path` holds stays reachable under a second name; a folder is kept out of this (the
  // rename below fails on it), and where the file system has no hard links it is moved aside.
  struct stat status {};
  fs::path previous;
  bool movedAside = false;
  if (::lstat(target_.c_str(), &status) == 0 && !S_ISDIR(status.st_mode)) {
    previous = temporaryBeside(target_);
    if (::link(target_.c_str(), previous.c_str()) != 0) {
      if (::rename(target_.c_str(), previous.c_str()) != 0) {
        const int error = errno;
        committed_ = true;
        ::unlink(temporary_.c_str());
        throw std::runtime_error(path_.string() + ": cannot keep the file there aside while replacing it: " + reason(error));
      }
      movedAside = true;
    }
  }
  committed_ = true;
  if (::rename(temporary_.c_str(), target_.c_str()) != 0) {
    const int error = errno;
    ::unlink(temporary_.c_str());
    if (movedAside) ::rename(previous.c_str(), target_.c_str());
    else if (!previous.empty()) ::unlink(previous.c_str());
    throw std::runtime_error(path_.string() + ": cannot rename the temporary file into place: " + reason(error));
  }
  guard_.reset();
  previous_ = previous;
}

std::string StagedFile::undo() {
  if (!committed_ || target_.empty()) return "";  // nothing renamed (or written in place: not undone)
  if (previous_.empty()) {
    if (::unlink(target_.c_str()) != 0 && errno != ENOENT)
      return path_.string() + " could not be removed again: " + reason(errno);
    return "";
  }
  if (::rename(previous_.c_str(), target_.c_str()) != 0) {
    const std::string problem =
        path_.string() + " could not be put back (" + reason(errno) + "); its earlier bytes are in " + previous_.string();
    previous_.clear();  // left for the user
    return problem;
  }
  previous_.clear();
  return "";
}

void StagedFile::dropPrevious() {
  if (!previous_.empty()) ::unlink(previous_.c_str());
  previous_.clear();
}

void (*commitAllAfterRename)(std::size_t renamed) = nullptr;

void commitAll(std::span<StagedFile* const> files) {
  // A signal meanwhile ends the process only once every file is in place and the earlier
  // bytes dropped, or every file is put back.
  const SignalDeferral deferral;
  std::size_t done = 0;
  try {
    for (; done < files.size(); ++done) {
      files[done]->commitKeepingPrevious();
      if (commitAllAfterRename) commitAllAfterRename(done + 1);
    }
  } catch (const std::exception& e) {
    std::string message = e.what();
    for (std::size_t i = done; i-- > 0;) {
      if (const std::string problem = files[i]->undo(); !problem.empty()) message += "; " + problem;
    }
    throw std::runtime_error(message);
  }
  for (StagedFile* file : files) file->dropPrevious();
}

void checkGlbFits(const fs::path& path, std::uint64_t jsonBytes, std::uint64_t binBytes) {
  const std::uint64_t total = 12 + 8 + (jsonBytes + 3) / 4 * 4 + (binBytes == 0 ? 0 : 8 + (binBytes + 3) / 4 * 4);
  if (total <= kMaxGlbBytes) return;
  throw std::runtime_error(path.string() + ": a .glb would be " + std::to_string(total) +
                           " bytes, but the format's 32-bit lengths allow at most " + std::to_string(kMaxGlbBytes) +
                           " (4 GiB); write .gltf output instead (its .bin has no such limit)");
}

}  // namespace tangent::output
