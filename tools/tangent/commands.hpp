// SPDX-License-Identifier: MIT
#pragma once

#include <fstream>
#include <iostream>
#include <string>
#include <vector>

namespace tangent::cli {

// Exit codes shared by every command.
constexpr int kExitOk = 0;
constexpr int kExitInputFailed = 1;
constexpr int kExitUsage = 2;

// Writes `text` to `path`, or to standard output when `path` is "-" (every report and output
// file a command writes takes "-"). Returns false, after a message on stderr, when it cannot.
inline bool writeTextOutput(const std::string& path, const std::string& text, const char* command) {
  if (path == "-") {
    std::cout << text << std::flush;
    return static_cast<bool>(std::cout);
  }
  std::ofstream file(path, std::ios::binary);
  file << text;
  file.close();
  if (!file) std::cerr << "tangent " << command << ": cannot write " << path << "\n";
  return static_cast<bool>(file);
}

int bakeCommand(const std::vector<std::string>& args);
int infoCommand(const std::vector<std::string>& args);
int checkCommand(const std::vector<std::string>& args);
int benchCommand(const std::vector<std::string>& args);

}  // namespace tangent::cli
