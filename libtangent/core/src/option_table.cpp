// SPDX-License-Identifier: MIT
#include "tangent/option_table.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <vector>

namespace tangent::options {
namespace {

constexpr unsigned kCli = kCommandLine;
constexpr unsigned kCliPython = kCommandLine | kPython;
constexpr unsigned kEverywhere = kCommandLine | kPython | kNpm;
constexpr unsigned kBakes = kBake | kBakeTree;

constexpr std::string_view kCheckNames = "present|format|finite|unit|w|w-uniform|orthogonal|handedness|reference";
constexpr std::string_view kAssetRootHelp = "folder buffer and image URIs may not leave (default: the input's folder)";
// check.cpp kGenerators, then "lengyel" (lengyel/angle, as --method lengyel)
constexpr std::string_view kGeneratorNames =
    "mikktspace|lengyel/angle|lengyel/area|lengyel/uniform|flat|meshopt|lengyel";

// clang-format off
constexpr Option kTable[] = {
  // tangent bake (and Python's bake and bake_tree), and the core on arrays.
  {"output", 'o', Kind::path, "", "", 0, 0, false, kBake, kCli, "FILE",
   "output file (.glb, or .gltf + .bin); one input only. \"-\": a .glb on standard output (messages go to stderr)"},
  {"out-dir", 0, Kind::path, "", "", 0, 0, false, kBake, kCli, "DIR", "write each output into DIR under the input's name"},
  {"method", 0, Kind::choice, "mikktspace|lengyel|flat|meshopt", "mikktspace", 0, 0, false, kArrays | kBakes, kEverywhere, "NAME",
   "how tangents are computed (meshopt: meshoptimizer's default weighting)"},
  {"weighting", 0, Kind::choice, "angle|area|uniform", "angle", 0, 0, false, kArrays | kBakes, kEverywhere, "NAME",
   "how lengyel weighs each triangle's share of a vertex"},
  {"threads", 0, Kind::integer, "", "0", 0, 256, false, kArrays | kBakes, kCliPython, "N",
   "worker threads, 0 for all hardware threads; the output never depends on it"},
  {"uv-origin", 0, Kind::choice, "top-left|bottom-left", "top-left", 0, 0, false, kArrays, kPython | kNpm, "ORIGIN",
   "where UV (0, 0) is: top-left as in glTF, or bottom-left (the w of MikkTSpace's own convention)"},
  {"all", 0, Kind::flag, "", "false", 0, 0, false, kBakes, kCliPython, "",
   "bake every triangle primitive, normal texture or not (TEXCOORD_0)"},
  {"overwrite", 0, Kind::flag, "", "false", 0, 0, false, kBakes, kCliPython, "", "recompute valid existing TANGENT too"},
  {"asset-root", 0, Kind::path, "", "", 0, 0, false, kBakes, kCliPython, "DIR", kAssetRootHelp},
  {"keep-external", 0, Kind::flag, "", "false", 0, 0, false, kBakes, kCliPython, "",
   "a .glb output keeps its images as files, copied beside it, instead of embedding them (a .glb is one "
   "self-contained file by default; a .gltf's images are always files)"},
  {"recursive", 0, Kind::flag, "", "false", 0, 0, false, kBake, kCli, "",
   "inputs are folders: bake every .gltf/.glb/.obj/.ply/.off under them into the same relative path under "
   "--out-dir, keeping a manifest (DIR/tangent-manifest.json) so that a re-run skips unchanged files"},
  {"force", 0, Kind::flag, "", "false", 0, 0, false, kBakeTree, kCliPython, "",
   "with --recursive: bake everything, whatever the manifest says"},
  {"verify", 0, Kind::flag, "", "false", 0, 0, false, kBakeTree, kCliPython, "",
   "with --recursive: hash every input, even where its size and modification time say it is unchanged"},
  {"tangent-format", 0, Kind::choice, "float|short|byte", "float", 0, 0, false, kBakes, kCliPython, "F",
   "TANGENT as float or normalized SHORT/BYTE (KHR_mesh_quantization, declared used and required); kept "
   "TANGENTs stay as they are"},
  {"normals", 0, Kind::choice, "flat|smooth|keep", "flat", 0, 0, false, kBakes, kCliPython, "MODE",
   "for a primitive without NORMAL: write flat normals (what the specification requires of clients) or "
   "smooth ones and compute tangents from them, or leave it as it is"},
  {"crease-angle", 0, Kind::number, "", "60", 0, 180, false, kBakes, kCliPython, "DEG",
   "with normals smooth: triangles meeting at more than DEG degrees stay sharp"},
  {"report", 0, Kind::path, "", "", 0, 0, false, kBake, kCli, "FILE.json",
   "write what was done, per file and primitive (\"-\": standard output)"},
  {"quiet", 'q', Kind::flag, "", "false", 0, 0, false, kBake, kCli, "", "print errors only"},

  // tangent check (and Python's check).
  {"format", 0, Kind::choice, "text|json|junit|github|sarif|codeclimate|html", "text", 0, 0, false, kCheck, kCli, "FORMAT",
   "the report's form (codeclimate: GitLab's code quality report; html: one page with thumbnails from "
   "tangent-view's error view, docs/check.md)"},
  {"recursive", 0, Kind::flag, "", "false", 0, 0, false, kCheck, kCli, "",
   "inputs may be folders: check every .gltf/.glb/.obj/.ply/.off under them, the files bake --recursive "
   "would bake; a file given is checked as it is"},
  {"allow-empty", 0, Kind::flag, "", "false", 0, 0, false, kCheck, kCli, "",
   "folders with nothing to check give an empty report and exit 0 (without it: an error, exit 2, so that a "
   "CI pointed at the wrong folder fails)"},
  {"output", 'o', Kind::path, "", "", 0, 0, false, kCheck, kCli, "FILE",
   "write the report to FILE (\"-\": standard output, the default)"},
  {"quiet", 'q', Kind::flag, "", "false", 0, 0, false, kCheck, kCli, "",
   "no progress line on a terminal: the report, and errors on stderr, only"},
  {"only", 0, Kind::list, kCheckNames, "", 0, 0, false, kCheck, kCliPython, "CHECKS",
   "run only these checks (comma-separated on the command line)"},
  {"ignore", 0, Kind::list, kCheckNames, "", 0, 0, false, kCheck, kCliPython, "CHECKS", "leave these checks out"},
  {"tolerance", 0, Kind::number, "", "1", 0, 180, true, kCheck, kCliPython, "DEG",
   "degrees orthogonal and reference allow on top of the rounding limits; on the command line "
   "CHECK=DEG sets one of them (orthogonal=DEG or reference=DEG)", "orthogonal|reference"},
  {"orthogonal-tolerance", 0, Kind::number, "", "", 0, 180, true, kCheck, kPython, "DEG",
   "orthogonal's tolerance alone (the command line's --tolerance orthogonal=DEG)"},
  {"reference-tolerance", 0, Kind::number, "", "", 0, 180, true, kCheck, kPython, "DEG",
   "reference's tolerance alone (the command line's --tolerance reference=DEG)"},
  {"min-coverage", 0, Kind::number, "", "0.5", 0, 1, false, kCheck, kCliPython, "FRACTION",
   "warn where reference compared fewer than FRACTION of a primitive's corners, or handedness of its "
   "triangles (0: never), as rounded UVs/positions leave the rest undecided (a warning: the exit code stays)"},
  {"allow-missing", 0, Kind::flag, "", "false", 0, 0, false, kCheck, kCliPython, "",
   "a primitive without TANGENT is skipped, not a finding (clients compute MikkTSpace)"},
  {"config", 0, Kind::path, "", "", 0, 0, false, kCheck, kCli, "FILE.json",
   "settings from a file (only, ignore, tolerance, method, minCoverage, allowMissing, all); options on the "
   "command line override it"},
  {"method", 0, Kind::choice, "mikktspace|lengyel", "mikktspace", 0, 0, false, kCheck, kCliPython, "NAME",
   "the same as --reference mikktspace or lengyel/angle"},
  {"reference", 0, Kind::choice, kGeneratorNames, "mikktspace", 0, 0, false, kCheck, kCliPython, "NAME",
   "what reference is measured against (the names --identify reports; lengyel is lengyel/angle)"},
  {"all", 0, Kind::flag, "", "false", 0, 0, false, kCheck, kCliPython, "",
   "check every triangle primitive (TEXCOORD_0 without a normal texture)"},
  {"asset-root", 0, Kind::path, "", "", 0, 0, false, kCheck, kCliPython, "DIR", kAssetRootHelp},
  {"identify", 0, Kind::flag, "", "false", 0, 0, false, kCheck, kCliPython, "",
   "name the generator closest to the stored tangents (one of --reference's names) with its median and max "
   "angle, or none of these (with the nearest)"},

  // tangent bench (the command line only).
  {"max-triangles", 0, Kind::integer, "", "1000000", 100, 1e9, false, kBench, kCli, "N",
   "largest resolution of the analytic surfaces"},
  {"repeats", 0, Kind::integer, "", "3", 1, 100, false, kBench, kCli, "N", "timed runs per measurement; the median is reported"},
  {"out-dir", 0, Kind::path, "", "", 0, 0, false, kBench, kCli, "DIR",
   "where bench.csv, bench.json, plot.png and plot.svg (--peers: peers.csv) go (default bench-results)"},
  {"assets", 0, Kind::path, "", "", 0, 0, false, kBench, kCli, "PATH",
   "a glTF file or folder of them; may be given more than once (default ../shared/assets when present)"},
  {"no-plot", 0, Kind::flag, "", "false", 0, 0, false, kBench, kCli, "", "skip gnuplot"},
  {"stress", 0, Kind::flag, "", "false", 0, 0, false, kBench, kCli, "",
   "run the stress suite instead and print its summary (exit 1 on failure)"},
  {"peers", 0, Kind::flag, "", "false", 0, 0, false, kBench, kCli, "",
   "instead: every --assets file and a generated sphere and torus, each method and meshoptimizer's two "
   "modes against the reference MikkTSpace C (max and p99 angle, w mismatches) with each one's time on one "
   "thread; a Markdown table. Needs a build with ../shared/peers"},
  {"triangles", 0, Kind::integer, "", "100000", 8, 1e9, false, kBench, kCli, "N",
   "--peers: triangles of the generated sphere and torus"},
};
// clang-format on

bool isChoice(std::string_view choices, std::string_view value) {
  for (const std::string_view name : choiceNames(choices))
    if (name == value) return true;
  return false;
}

std::string formatNumber(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

// The whole of `text` as a finite real number.
std::optional<double> parseReal(std::string_view text) {
  const std::string copy(text);
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(copy.c_str(), &end);
  if (copy.empty() || end != copy.c_str() + copy.size() || errno == ERANGE || !std::isfinite(value))
    return std::nullopt;
  return value;
}

std::optional<std::string> checkNumber(const Option& option, std::string_view value) {
  if (!option.prefixes.empty()) {
    const std::size_t equals = value.find('=');
    if (equals != std::string_view::npos) {
      if (!isChoice(option.prefixes, value.substr(0, equals)))
        return std::string(value.substr(0, equals)) + "=...: only " + describeChoices(option.prefixes) + " take one";
      value.remove_prefix(equals + 1);
    }
  }
  const std::string range =
      (option.minOpen ? "(" : "[") + formatNumber(option.min) + ", " + formatNumber(option.max) + "]";
  const std::optional<double> number = parseReal(value);
  if (!number || *number < option.min || (option.minOpen && *number == option.min) || *number > option.max)
    return std::string(value) + " is not a number in " + range;
  return std::nullopt;
}

std::optional<std::string> checkInteger(const Option& option, std::string_view value) {
  const std::optional<double> number = parseReal(value);
  if (!number || *number != std::floor(*number) || value.find_first_of(".eE") != std::string_view::npos ||
      *number < option.min || *number > option.max)
    return std::string(value) + " is not a whole number from " + formatNumber(option.min) + " to " +
           formatNumber(option.max);
  return std::nullopt;
}

// A space that help's wrapping never breaks at (between a choice and its "|").
constexpr char kKeptSpace = '\x01';

// Appends `text` to `out` in words, breaking lines before `width`; continuation lines start at
// column `indent`. `column`: where `out`'s current line stands.
void wrap(std::string& out, std::string_view text, std::size_t indent, std::size_t width, std::size_t column) {
  bool firstWord = true;
  while (!text.empty()) {
    const std::size_t space = text.find(' ');
    const std::string_view word = text.substr(0, space);
    if (!firstWord && column + 1 + word.size() > width) {
      out += "\n" + std::string(indent, ' ');
      column = indent;
    } else if (!firstWord) {
      out += ' ';
      ++column;
    }
    for (const char c : word) out += c == kKeptSpace ? ' ' : c;
    column += word.size();
    firstWord = false;
    if (space == std::string_view::npos) break;
    text.remove_prefix(space + 1);
  }
  out += '\n';
}

// What help says of an option: its choices (the default marked) or its default, then its text.
std::string helpLine(const Option& option) {
  const std::string text(option.help);
  std::string names;
  if (option.kind == Kind::choice || option.kind == Kind::list) {
    for (const std::string_view name : choiceNames(option.choices)) {
      if (!names.empty()) names += option.kind == Kind::choice ? std::string{kKeptSpace, '|', ' '} : " ";
      names += std::string(name) + (name == option.defaultValue ? std::string{kKeptSpace} + "(default)" : "");
    }
    return option.kind == Kind::choice ? names + "; " + text : text + ": " + names;
  }
  if ((option.kind == Kind::number || option.kind == Kind::integer) && !option.defaultValue.empty())
    return text + " (default " + std::string(option.defaultValue) + ")";
  return text;
}

}  // namespace

std::span<const Option> table() {
  return kTable;
}

const Option* find(std::span<const Option> table, std::string_view name, unsigned commands, unsigned frontEnds) {
  for (const Option& option : table)
    if (option.name == name && (option.commands & commands) && (option.frontEnds & frontEnds)) return &option;
  return nullptr;
}

const Option* findShort(std::span<const Option> table, char shortName, unsigned commands, unsigned frontEnds) {
  for (const Option& option : table)
    if (shortName != '\0' && option.shortName == shortName && (option.commands & commands) &&
        (option.frontEnds & frontEnds))
      return &option;
  return nullptr;
}

const Option* find(std::string_view name, unsigned commands, unsigned frontEnds) {
  return find(kTable, name, commands, frontEnds);
}

const Option* findShort(char shortName, unsigned commands, unsigned frontEnds) {
  return findShort(kTable, shortName, commands, frontEnds);
}

std::string pythonName(std::string_view name) {
  std::string out(name);
  for (char& c : out) c = c == '-' ? '_' : c;
  return out;
}

std::string npmName(std::string_view name) {
  std::string out;
  for (std::size_t i = 0; i < name.size(); ++i) {
    if (name[i] == '-' && i + 1 < name.size()) {
      out += static_cast<char>(name[++i] - 'a' + 'A');
      continue;
    }
    out += name[i];
  }
  return out;
}

std::vector<std::string_view> choiceNames(std::string_view choices) {
  std::vector<std::string_view> names;
  while (!choices.empty()) {
    const std::size_t bar = choices.find('|');
    names.push_back(choices.substr(0, bar));
    if (bar == std::string_view::npos) break;
    choices.remove_prefix(bar + 1);
  }
  return names;
}

std::string describeChoices(std::string_view choices) {
  const std::vector<std::string_view> names = choiceNames(choices);
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i)
    out += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + std::string(names[i]);
  return out;
}

std::optional<std::string> checkValue(const Option& option, std::string_view value) {
  switch (option.kind) {
    case Kind::flag:
      if (value == "true" || value == "false") return std::nullopt;
      return "'" + std::string(value) + "' is not true or false";
    case Kind::choice:
      if (isChoice(option.choices, value)) return std::nullopt;
      return "'" + std::string(value) + "' is not " + describeChoices(option.choices);
    case Kind::integer:
      return checkInteger(option, value);
    case Kind::number:
      return checkNumber(option, value);
    case Kind::path:
      if (value.empty()) return "needs a " + std::string(option.valueName == "DIR" ? "folder" : "file") + " name";
      return std::nullopt;
    case Kind::text:
      return std::nullopt;
    case Kind::list: {
      if (value.empty()) return std::nullopt;  // no names (Python's [])
      std::optional<std::string> wrong;
      std::string_view rest = value;
      while (!wrong) {
        const std::size_t comma = rest.find(',');
        const std::string_view name = rest.substr(0, comma);
        if (!isChoice(option.choices, name))
          wrong = "'" + std::string(name) + "' is not one of " + describeChoices(option.choices);
        if (comma == std::string_view::npos) break;
        rest.remove_prefix(comma + 1);
      }
      return wrong;
    }
  }
  return std::nullopt;
}

std::string helpText(unsigned commands, std::size_t width) {
  return helpText(kTable, commands, width);
}

std::string helpText(std::span<const Option> table, unsigned commands, std::size_t width) {
  constexpr std::size_t kIndent = 25;  // where the help column starts
  std::string out = "options:\n";
  for (const Option& option : table) {
    if (!(option.commands & commands) || !(option.frontEnds & kCommandLine)) continue;
    std::string spec = "  ";
    if (option.shortName != '\0') spec += std::string("-") + option.shortName + ", ";
    spec += "--" + std::string(option.name);
    if (!option.valueName.empty()) spec += " " + std::string(option.valueName);
    out += spec;
    std::size_t column = spec.size();
    if (column + 2 > kIndent) {
      out += "\n" + std::string(kIndent, ' ');
      column = kIndent;
    } else {
      out += std::string(kIndent - column, ' ');
      column = kIndent;
    }
    wrap(out, helpLine(option), kIndent, width, column);
  }
  out += "  -h, --help" + std::string(kIndent - 12, ' ') + "this text\n";
  return out;
}

bool applyOption(Options& options, const Option& option, std::string_view value) {
  if (!(option.commands & kArrays)) return false;
  if (option.name == "method") {
    if (const auto method = parseMethod(value)) options.method = *method;
  } else if (option.name == "weighting") {
    if (const auto weighting = parseWeighting(value)) options.weighting = *weighting;
  } else if (option.name == "uv-origin") {
    if (const auto origin = parseUvOrigin(value)) options.uvOrigin = *origin;
  } else if (option.name == "threads") {
    options.threads = static_cast<unsigned>(std::strtoul(std::string(value).c_str(), nullptr, 10));
  } else {
    return false;
  }
  return true;
}

}  // namespace tangent::options
