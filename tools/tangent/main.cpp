// SPDX-License-Identifier: MIT
// `tangent`: bake tangents into glTF, describe assets.
#include <cerrno>
#include <cstring>
#include <iostream>

#include "commands.hpp"

namespace {

const char* kUsage =
    "usage: tangent <command> [options]\n"
    "\n"
    "commands:\n"
    "  bake IN OUT | IN... (-o OUT | --out-dir DIR) | DIR... --recursive --out-dir DIR\n"
    "                                        compute TANGENT for primitives with a normal texture\n"
    "  check IN... | DIR... --recursive [--format text|json|junit|github|sarif|codeclimate|html]\n"
    "                                        validate stored tangents (for CI)\n"
    "  info IN... [--json]                   meshes, primitives, attributes, which need tangents\n"
    "  bench [--stress | --peers]            error against run time; the stress suite; against the reference C\n"
    "\n"
    "  -V, --version                         the version\n"
    "  -h, --help                            this text\n"
    "\n"
    "'tangent <command> --help' describes a command's options.\n"
    "exit codes: 0 done (check: clean), 1 an input failed (check: findings), 2 usage error\n";

int run(std::vector<std::string> args);

}  // namespace

int main(int argc, char** argv) {
  // Ctrl-C and kill: the files being written are removed (a batch's journal keeps what is done).
  tangent::output::removeTemporariesOnSignal("tangent: interrupted; files being written were removed\n");
  int status = tangent::cli::kExitInputFailed;
  try {
    status = run(std::vector<std::string>(argv + 1, argv + argc));
  } catch (const std::exception& e) {
    // Every command answers bad input itself; this is what none foresaw (memory, the system).
    std::cerr << "tangent: " << tangent::cli::shown(e.what()) << "\n";
    status = tangent::cli::kExitInputFailed;
  }
  // Output that did not reach its destination (a full disk, a closed pipe) is a failure.
  errno = 0;
  std::cout.flush();
  if (!std::cout) {
    std::cerr << "tangent: cannot write to standard output" << (errno ? std::string(": ") + std::strerror(errno) : "") << "\n";
    if (status == tangent::cli::kExitOk) status = tangent::cli::kExitInputFailed;
  }
  return status;
}

namespace {

int run(std::vector<std::string> args) {
  if (args.empty()) {
    std::cerr << kUsage;
    return tangent::cli::kExitUsage;
  }
  const std::string command = args.front();
  args.erase(args.begin());
  if (command == "--help" || command == "-h" || command == "help") {
    std::cout << kUsage;
    return tangent::cli::kExitOk;
  }
  if (command == "--version" || command == "-V") {
    std::cout << "tangent 0.1.0\n";
    return tangent::cli::kExitOk;
  }
  if (command == "bake") return tangent::cli::bakeCommand(args);
  if (command == "info") return tangent::cli::infoCommand(args);
  if (command == "check") return tangent::cli::checkCommand(args);
  if (command == "bench") return tangent::cli::benchCommand(args);
  std::cerr << "tangent: unknown command '" << tangent::text::shown(command) << "' (see tangent --help)\n";
  return tangent::cli::kExitUsage;
}

}  // namespace
