// SPDX-License-Identifier: MIT
// The one table of options every front end takes: `tangent bake`, `tangent check` and `tangent
// bench` parse their command lines with it and print their help from it; Python's keyword arguments (bake, bake_tree,
// check, compute_tangents) are checked against it and get their signatures from it; the npm
// package's option objects are compared with it by tests/python/test_option_table.py. An option is
// spelled `--crease-angle` on the command line, `crease_angle` in Python and `creaseAngle` in npm.
//
// Values travel as text ("true"/"false" for a flag, "60" for a number, "a,b" for a list), checked
// here by kind; each consumer applies a checked value to its own options struct
// (tangent::applyOption below; gltf::applyBakeOption, gltf::applyBatchOption,
// gltf::applyCheckOption), and a test applies every default to a default struct to prove the
// table's defaults are the library's.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "tangent/tangent.hpp"

namespace tangent::options {

enum class Kind {
  flag,     // present or not (Python: bool)
  choice,   // one of `choices`
  integer,  // whole number in [min, max]
  number,   // real number in [min, max] ((min, max] with minOpen)
  path,     // a file or folder (Python: os.PathLike or str; default none)
  text,     // free text
  list,     // comma-separated names from `choices` (Python: a list of str)
};

// The command an option belongs to (a bit each; an option may belong to several).
enum Command : unsigned {
  kArrays = 1u << 0,    // the core on arrays: Python compute_tangents, npm generateTangentsIndexed
  kBake = 1u << 1,      // tangent bake IN OUT, Python bake()
  kBakeTree = 1u << 2,  // tangent bake --recursive, Python bake_tree()
  kCheck = 1u << 3,     // tangent check, Python check()
  kBench = 1u << 4,     // tangent bench
};

// Where an option is taken (a bit each).
enum FrontEnd : unsigned {
  kCommandLine = 1u << 0,
  kPython = 1u << 1,
  kNpm = 1u << 2,
};

struct Option {
  std::string_view name;  // command-line spelling without "--"
  char shortName;         // '\0' or the one-letter form ("-o")
  Kind kind;
  std::string_view choices;       // choice and list: names separated by '|'
  std::string_view defaultValue;  // as text; "" where there is none (path, list, text)
  double min, max;                // integer and number
  bool minOpen;                   // number: min itself is refused
  unsigned commands;              // Command bits
  unsigned frontEnds;             // FrontEnd bits
  std::string_view valueName;     // in help: "NAME", "DEG", "DIR"; "" for a flag
  std::string_view help;          // one sentence or two; the choices and default are added to it
  // The command line's form of a number may be led by one of these names and '=' (check's
  // --tolerance orthogonal=2); '|'-separated, "" for none.
  std::string_view prefixes = {};
};

// Every option, in the order help lists them.
std::span<const Option> table();

// The option `name` (command-line spelling) of `command` taken by `frontEnd`; null when none.
const Option* find(std::string_view name, unsigned commands, unsigned frontEnds);
// By the one-letter form (-o, -q).
const Option* findShort(char shortName, unsigned commands, unsigned frontEnds);
// The same in another program's table (tangent-view's, whose Command bits are its own).
const Option* find(std::span<const Option> table, std::string_view name, unsigned commands, unsigned frontEnds);
const Option* findShort(std::span<const Option> table, char shortName, unsigned commands, unsigned frontEnds);

std::string pythonName(std::string_view name);  // crease-angle -> crease_angle
std::string npmName(std::string_view name);     // crease-angle -> creaseAngle

// Why `value` is not a value of `option` ("'soft' is not flat, smooth or keep"); nullopt when it
// is one. The caller leads it with the option's name as its front end spells it.
std::optional<std::string> checkValue(const Option& option, std::string_view value);

// The names of `choices` ("a|b|c": a choice's or a list's, an option's prefixes), in order.
std::vector<std::string_view> choiceNames(std::string_view choices);

// The names of `choices` for messages: "a, b or c".
std::string describeChoices(std::string_view choices);

// The "options:" block of `tangent COMMAND --help`: every command-line option of `command`,
// with its value name, help, choices and default, wrapped at `width` columns.
std::string helpText(unsigned commands, std::size_t width = 100);
// The same for another program's table.
std::string helpText(std::span<const Option> table, unsigned commands, std::size_t width = 100);

// A checked value of an option of the core on arrays (method, weighting, uv-origin, threads)
// into `options`; false when `option` is not one of them.
bool applyOption(Options& options, const Option& option, std::string_view value);

// "true" for a flag's value of true (the command line's presence, Python's True).
inline bool isTrue(std::string_view value) {
  return value == "true";
}

}  // namespace tangent::options
