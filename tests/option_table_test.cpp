// SPDX-License-Identifier: MIT
// The option table (tangent/option_table.hpp) against the library: its defaults are the
// defaults of the structs the options set, every option a front end passes on changes what it
// names, every choice is one the library parses, and bake's and check's help list it all.
#include "tangent/option_table.hpp"

#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "tangent/batch.hpp"
#include "tangent/check.hpp"

namespace {

namespace options = tangent::options;
using tangent::gltf::BatchOptions;
using tangent::gltf::CheckOptions;

// Every option's state, in one text, whatever struct the command fills.
std::string stateOf(const BatchOptions& batch) {
  const tangent::Options& core = batch.bake.tangents;
  return tangent::gltf::manifestOptions(batch.bake).dump() +
         " crease=" + std::to_string(batch.bake.creaseAngleDegrees) + " threads=" + std::to_string(core.threads) +
         " origin=" + std::string(tangent::toString(core.uvOrigin)) + " force=" + std::to_string(batch.force) +
         " verify=" + std::to_string(batch.verify);
}
std::string stateOf(const CheckOptions& check) {
  return tangent::gltf::toJson(check).dump() + " identify=" + std::to_string(check.identify) +
         " root=" + check.assetRoot.string();
}

// Applies `value` of `option` to default options of the command `command`; returns the state
// and whether the option was one the command's apply function knows.
std::pair<std::string, bool> applied(unsigned command, const options::Option& option, const std::string& value) {
  if (command == options::kCheck) {
    CheckOptions check;
    const bool known = tangent::gltf::applyCheckOption(check, option, value);
    return {stateOf(check), known};
  }
  BatchOptions batch;
  bool known = false;
  if (command == options::kArrays)
    known = options::applyOption(batch.bake.tangents, option, value);
  else if (command == options::kBake)
    known = tangent::gltf::applyBakeOption(batch.bake, option, value);
  else
    known = tangent::gltf::applyBatchOption(batch, option, value);
  return {stateOf(batch), known};
}

std::string defaultState(unsigned command) {
  return command == options::kCheck ? stateOf(CheckOptions()) : stateOf(BatchOptions());
}

// What a library-side option (not a command line's own: output places, formats) may be set to
// other than its default.
std::vector<std::string> otherValues(const options::Option& option) {
  std::vector<std::string> values;
  switch (option.kind) {
    case options::Kind::flag:
      return {"true"};
    case options::Kind::choice:
    case options::Kind::list: {
      for (const std::string_view name : options::choiceNames(option.choices))
        if (name != option.defaultValue) values.emplace_back(name);
      return values;
    }
    case options::Kind::integer:
      return {std::to_string(static_cast<int>(option.max))};
    case options::Kind::number:
      return {std::to_string(option.max / 4)};  // 45 degrees, 0.25: never a default
    case options::Kind::path:
    case options::Kind::text:
      return {"somewhere"};
  }
  return values;
}

constexpr unsigned kCommands[] = {options::kArrays, options::kBake, options::kBakeTree, options::kCheck};

TEST(OptionTable, DefaultsAreTheLibrarysDefaults) {
  for (const unsigned command : kCommands) {
    for (const options::Option& option : options::table()) {
      if (!(option.commands & command) || option.defaultValue.empty()) continue;
      const auto [state, known] = applied(command, option, std::string(option.defaultValue));
      if (!known) continue;  // a command line's own option (format, quiet)
      EXPECT_EQ(state, defaultState(command))
          << "--" << option.name << " " << option.defaultValue << " (command bit " << command << ")";
    }
  }
}

// Every option Python or npm passes on reaches the library, and every one of its values does
// something: an option or a choice the apply functions missed would leave the state unchanged.
TEST(OptionTable, EveryValueOfEveryOptionTakesEffect) {
  for (const unsigned command : kCommands) {
    for (const options::Option& option : options::table()) {
      if (!(option.commands & command)) continue;
      const bool passedOn = option.frontEnds & (options::kPython | options::kNpm);
      for (const std::string& value : otherValues(option)) {
        ASSERT_FALSE(options::checkValue(option, value).has_value()) << option.name << " " << value;
        const auto [state, known] = applied(command, option, value);
        EXPECT_EQ(known, passedOn) << "--" << option.name << " (command bit " << command << ")";
        if (passedOn) {
          EXPECT_NE(state, defaultState(command)) << "--" << option.name << " " << value << " changed nothing";
        }
      }
    }
  }
}

TEST(OptionTable, ValuesAreCheckedByKind) {
  const options::Option* threads = options::find("threads", options::kBake, options::kCommandLine);
  const options::Option* crease = options::find("crease-angle", options::kBake, options::kCommandLine);
  const options::Option* tolerance = options::find("tolerance", options::kCheck, options::kCommandLine);
  const options::Option* only = options::find("only", options::kCheck, options::kCommandLine);
  ASSERT_TRUE(threads && crease && tolerance && only);
  auto accepted = [](const options::Option& option, const char* value) {
    return !options::checkValue(option, value).has_value();
  };
  EXPECT_TRUE(accepted(*threads, "256"));
  for (const char* bad : {"257", "-1", "1.5", "1e2", "", "x", "4 "}) EXPECT_FALSE(accepted(*threads, bad)) << bad;
  EXPECT_TRUE(accepted(*crease, "0"));
  EXPECT_TRUE(accepted(*crease, "180"));
  for (const char* bad : {"180.5", "nan", "inf", "-0.1", "60deg"}) EXPECT_FALSE(accepted(*crease, bad)) << bad;
  EXPECT_TRUE(accepted(*tolerance, "orthogonal=2"));
  EXPECT_FALSE(accepted(*tolerance, "0"));  // (0, 180]
  EXPECT_EQ(options::checkValue(*tolerance, "unit=2").value_or(""), "unit=...: only orthogonal or reference take one");
  EXPECT_TRUE(accepted(*only, "unit,w"));
  EXPECT_EQ(options::checkValue(*only, "unit,units").value_or("").substr(0, 26), "'units' is not one of pres");
  EXPECT_EQ(options::pythonName("crease-angle"), "crease_angle");
  EXPECT_EQ(options::npmName("uv-origin"), "uvOrigin");
}

// The names the glTF layer knows are the table's choices: every check and every generator.
TEST(OptionTable, ChoicesAreTheGltfLayersNames) {
  const options::Option* only = options::find("only", options::kCheck, options::kPython);
  const options::Option* reference = options::find("reference", options::kCheck, options::kPython);
  ASSERT_TRUE(only && reference);
  std::string checks;
  for (const char* name : tangent::gltf::kCheckNames) checks += (checks.empty() ? "" : "|") + std::string(name);
  EXPECT_EQ(only->choices, checks);
  EXPECT_EQ(
      options::describeChoices(reference->choices),
      tangent::gltf::generatorNames().replace(tangent::gltf::generatorNames().rfind(" or "), 4, ", ") + " or lengyel");
}

// The help of bake, check and bench names every command-line option of theirs, and only those; no
// line is wider than the terminal it was wrapped for.
TEST(OptionTable, HelpListsEveryCommandLineOption) {
  for (const unsigned command : {options::kBake | options::kBakeTree, unsigned(options::kCheck), unsigned(options::kBench)}) {
    const std::string help = options::helpText(command);
    for (const options::Option& option : options::table()) {
      const bool listed = help.find("--" + std::string(option.name) + " ") != std::string::npos ||
                          help.find("--" + std::string(option.name) + "\n") != std::string::npos;
      const bool expected = (option.commands & command) && (option.frontEnds & options::kCommandLine);
      if (expected) {
        EXPECT_TRUE(listed) << option.name;
      }
      if (!(option.frontEnds & options::kCommandLine)) {
        EXPECT_FALSE(listed) << option.name << " is not a command-line option";
      }
    }
    std::istringstream lines(help);
    for (std::string line; std::getline(lines, line);) EXPECT_LE(line.size(), 100u) << line;
  }
}

}  // namespace
