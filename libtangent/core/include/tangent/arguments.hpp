// SPDX-License-Identifier: MIT
// A command line read through an option table (tangent/option_table.hpp): `tangent bake`, `check`
// and `bench` parse with the library's table, `tangent-view` with its own, so every program's
// options, value checks, messages and help come from one parser.
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "tangent/option_table.hpp"

namespace tangent::options {

struct Arguments {
  std::vector<std::string> operands;
  // Each option given, in command-line order, with its checked value ("true" for a flag).
  std::vector<std::pair<const Option*, std::string>> values;
  bool help = false;         // -h or --help
  bool afterDashes = false;  // "--" was given: every argument after it is an operand
  std::string error;         // a usage error in one line ("" when the line was read)

  // The last value given for `name`, or null.
  const std::string* last(std::string_view name) const {
    const std::string* found = nullptr;
    for (const auto& [option, value] : values)
      if (option->name == name) found = &value;
    return found;
  }
  bool flag(std::string_view name) const {
    const std::string* value = last(name);
    return value && isTrue(*value);
  }
};

// Reads `args` with the command-line options of `commands` (options::Command bits). Accepts
// `--name VALUE`, `--name=VALUE`, the one-letter forms (-o FILE) and "--" before operands.
Arguments parseArguments(const std::vector<std::string>& args, unsigned commands);
// The same with another program's table (its own Command bits).
Arguments parseArguments(const std::vector<std::string>& args, std::span<const Option> table, unsigned commands);

}  // namespace tangent::options
