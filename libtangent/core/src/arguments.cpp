// SPDX-License-Identifier: MIT
#include "tangent/arguments.hpp"

namespace tangent::options {
namespace {

// What a missing value's message asks for: "NAME (mikktspace, lengyel, flat or meshopt)".
std::string wanted(const Option& option) {
  std::string text(option.valueName);
  if (option.kind == Kind::choice || option.kind == Kind::list)
    text += " (" + describeChoices(option.choices) + ")";
  return text;
}

}  // namespace

Arguments parseArguments(const std::vector<std::string>& args, unsigned commands) {
  return parseArguments(args, table(), commands);
}

Arguments parseArguments(const std::vector<std::string>& args, std::span<const Option> options, unsigned commands) {

  Arguments out;
  for (std::size_t i = 0; i < args.size() && out.error.empty(); ++i) {
    const std::string& arg = args[i];
    if (out.afterDashes || arg == "--") {
      if (std::exchange(out.afterDashes, true)) out.operands.push_back(arg);
      continue;
    }
    if (arg == "-h" || arg == "--help") {
      out.help = true;
      continue;
    }
    if (arg.size() < 2 || arg[0] != '-') {  // "-" alone is an operand (standard input or output)
      out.operands.push_back(arg);
      continue;
    }
    const bool isLong = arg[1] == '-';
    const std::size_t equals = isLong ? arg.find('=') : std::string::npos;
    const std::string spelled = arg.substr(0, equals);
    const Option* option = isLong ? find(options, spelled.substr(2), commands, kCommandLine)
                                    : arg.size() == 2 ? findShort(options, arg[1], commands, kCommandLine)
                                                      : nullptr;
    if (!option) {
      out.error = "unknown option '" + spelled + "'";
      break;
    }
    std::string value;
    if (option->kind == Kind::flag) {
      if (equals != std::string::npos) out.error = spelled + " takes no value";
      value = "true";
    } else if (equals != std::string::npos) {
      value = arg.substr(equals + 1);
    } else if (i + 1 < args.size()) {
      value = args[++i];
    } else {
      out.error = spelled + " needs " + wanted(*option);
    }
    if (out.error.empty())
      if (const auto why = checkValue(*option, value)) out.error = spelled + ": " + *why;
    out.values.emplace_back(option, std::move(value));
  }
  return out;
}

}  // namespace tangent::options
