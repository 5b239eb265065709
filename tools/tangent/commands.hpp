// SPDX-License-Identifier: MIT
#pragma once

#include <fstream>
#include <iostream>
#include <string>
#include <vector>

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

int bakeCommand(const std::vector<std::string>& args);
int infoCommand(const std::vector<std::string>& args);
int checkCommand(const std::vector<std::string>& args);
int benchCommand(const std::vector<std::string>& args);

}  // namespace tangent::cli
