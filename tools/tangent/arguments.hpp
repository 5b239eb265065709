// SPDX-License-Identifier: MIT
// A command line read through the option table (tangent/option_table.hpp): bake and check parse
// with it, so their options, value checks and messages are the table's.
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "tangent/option_table.hpp"

namespace tangent::cli {

struct Arguments {
  std::vector<std::string> operands;
  // Each option given, in command-line order, with its checked value ("true" for a flag).
  std::vector<std::pair<const options::Option*, std::string>> values;
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
    return value && options::isTrue(*value);
  }
};

// Reads `args` with the command-line options of `commands` (options::Command bits). Accepts
// `--name VALUE`, `--name=VALUE`, the one-letter forms (-o FILE) and "--" before operands.
Arguments parseArguments(const std::vector<std::string>& args, unsigned commands);

}  // namespace tangent::cli
