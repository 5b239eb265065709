// SPDX-License-Identifier: MIT
#include "arguments.hpp"

namespace tangent::cli {
namespace {

// What a missing value's message asks for: "NAME (mikktspace, lengyel, flat or meshopt)".
std::string wanted(const options::Option& option) {
  std::string text(option.valueName);
  if (option.kind == options::Kind::choice || option.kind == options::Kind::list)
    text += " (" + options::describeChoices(option.choices) + ")";
  return text;
}

}  // namespace

Arguments parseArguments(const std::vector<std::string>& args, unsigned commands) {
  using options::Kind;
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
    const options::Option* option = isLong ? options::find(spelled.substr(2), commands, options::kCommandLine)
                                    : arg.size() == 2 ? options::findShort(arg[1], commands, options::kCommandLine)
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
      if (const auto why = options::checkValue(*option, value)) out.error = spelled + ": " + *why;
    out.values.emplace_back(option, std::move(value));
  }
  return out;
}

}  // namespace tangent::cli
