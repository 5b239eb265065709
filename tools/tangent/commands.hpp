#pragma once

#include <string>
#include <vector>

namespace tangent::cli {

// Exit codes shared by every command.
constexpr int kExitOk = 0;
constexpr int kExitInputFailed = 1;
constexpr int kExitUsage = 2;

int bakeCommand(const std::vector<std::string>& args);
int infoCommand(const std::vector<std::string>& args);
int checkCommand(const std::vector<std::string>& args);
int benchCommand(const std::vector<std::string>& args);

}  // namespace tangent::cli
