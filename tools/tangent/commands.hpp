// SPDX-License-Identifier: MIT
#pragma once

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "tangent/batch.hpp"
#include "tangent/gltf.hpp"
#include "tangent/output.hpp"
#include "tangent/text.hpp"

namespace tangent::cli {

// File-derived text (paths, names, messages that quote them) on its way to a terminal or a
// log: control characters and bytes that are not UTF-8 escaped, cut past a few kilobytes.
using text::shown;

// Exit codes shared by every command.
constexpr int kExitOk = 0;
constexpr int kExitInputFailed = 1;
constexpr int kExitUsage = 2;
constexpr int kExitInterrupted = 130;  // 128 + SIGINT, as shells report a process Ctrl-C ended

// Writes `text` to `path`, or to standard output when `path` is "-" (every report and output
// file a command writes takes "-"). Returns false, after a message on stderr, when it cannot.
// Files are written atomically (tangent/output.hpp): a failure leaves the previous file.
// `keep` (may be null): files never written over (a command's inputs and the files they use,
// what it wrote): refused with a message naming the file.
inline bool writeTextOutput(const std::string& path, const std::string& text, const char* command,
                            const gltf::ProtectedFiles* keep = nullptr) {
  if (path != "-" && keep && keep->contains(path)) {
    std::cerr << "tangent " << command << ": " << shown(path)
              << ": is an input, a file an input uses or an output of this run; a report is never written over one\n";
    return false;
  }
  if (path == "-") {
    std::cout << text << std::flush;
    if (!std::cout) std::cerr << "tangent " << command << ": cannot write to standard output\n";
    return static_cast<bool>(std::cout);
  }
  try {
    output::writeFileAtomic(path, text);
    return true;
  } catch (const std::exception& e) {
    std::cerr << "tangent " << command << ": " << shown(e.what()) << "\n";
    return false;
  }
}

// How the progress line names `file`, found under `folder` (a folder of the command line): its
// path in the tree, led by the folder's name when the command was given several folders.
inline std::filesystem::path pathInTree(const std::filesystem::path& file, const std::filesystem::path& folder,
                                        bool severalFolders) {
  std::filesystem::path root = folder.lexically_normal();
  if (!root.has_filename()) root = root.parent_path();  // "dir/" names dir
  return file.lexically_relative(severalFolders ? root.parent_path() : root);
}

// Each entry of a walked tree named like an input but not a file (gltf::findInputs' leftOut),
// on stderr: a FIFO, a device or a dangling link named like an asset is read by no command,
// and should not drop out of a run without a word.
inline void warnLeftOut(const std::vector<gltf::LeftOutEntry>& leftOut) {
  for (const auto& entry : leftOut)
    std::cerr << "warning: " << shown(entry.path.string()) << ": left out (" << entry.why << "); only files are read\n";
}

// One line on a terminal (stderr) while a batch runs (bake's inputs, check's files): files done
// of all, the current file, time so far and the time left at the pace so far. Nothing when off
// (not a terminal, --quiet).
class ProgressLine {
 public:
  explicit ProgressLine(bool on) : on_(on), started_(std::chrono::steady_clock::now()) {}
  void show(std::size_t done, std::size_t total, const std::filesystem::path& current) {
    if (!on_) return;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
    std::cerr << "\r[" << done << "/" << total << "] " << tail(shown(current.string())) << "  " << clock(elapsed);
    if (done > 0) std::cerr << ", about " << clock(elapsed / static_cast<double>(done) * static_cast<double>(total - done)) << " left";
    std::cerr << "\033[K" << std::flush;
    visible_ = true;
  }
  bool onTerminal() const { return on_; }
  void clear() {
    if (!visible_) return;
    std::cerr << "\r\033[K" << std::flush;
    visible_ = false;
  }

 private:
  // The end of a long path, where names differ, cut at a character boundary.
  static std::string tail(const std::string& text, std::size_t width = 48) {
    if (text.size() <= width) return text;
    std::size_t start = text.size() - (width - 3);
    while (start < text.size() && (static_cast<unsigned char>(text[start]) & 0xC0) == 0x80) ++start;
    return "..." + text.substr(start);
  }
  static std::string clock(double seconds) {
    const auto whole = static_cast<long long>(seconds + 0.5);
    char text[32];
    std::snprintf(text, sizeof text, "%lld:%02lld", whole / 60, whole % 60);
    return text;
  }
  bool on_;
  bool visible_ = false;
  std::chrono::steady_clock::time_point started_;
};

int bakeCommand(const std::vector<std::string>& args);
int infoCommand(const std::vector<std::string>& args);
int checkCommand(const std::vector<std::string>& args);
int benchCommand(const std::vector<std::string>& args);

}  // namespace tangent::cli
