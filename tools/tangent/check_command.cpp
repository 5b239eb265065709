// SPDX-License-Identifier: MIT
// `tangent check`: its options, the files it checks (given, or found under --recursive
// folders), one report over them all in the format asked for (check_formats.hpp: text, JSON,
// JUnit, GitHub, SARIF, code quality; check_html.hpp: HTML), and the exit code.
#include <unistd.h>

#include <chrono>
#include <ctime>
#include <filesystem>
#include <iostream>
#include <set>
#include <sstream>
#include <utility>

#include "check_formats.hpp"
#include "check_html.hpp"
#include "commands.hpp"
#include "tangent/arguments.hpp"
#include "tangent/batch.hpp"
#include "tangent/check.hpp"
#include "tangent/gltf.hpp"
#include "tangent/text.hpp"

namespace tangent::cli {

using options::Arguments;
using options::parseArguments;
namespace {

const char* kCheckUsageHead =
    "usage: tangent check IN... [options]\n"
    "       tangent check DIR... --recursive [options]\n"
    "\n"
    "Checks the TANGENT of every primitive whose material has a normal texture: present, float\n"
    "or normalized BYTE/SHORT VEC4 (format), finite, unit, w exactly +-1 and the same on a\n"
    "triangle's corners (w, w-uniform), orthogonal to NORMAL, handedness matching the normal\n"
    "texture's UV orientation, and close to freshly computed tangents (reference). Limits for\n"
    "quantized data follow from the rounding step (docs/check.md, \"Limits per component type\").\n"
    "One report covers every file (one that cannot be read is named, the rest are still checked);\n"
    "while several are checked, a progress line shows on stderr when it is a terminal.\n"
    "\n";
const char* kCheckUsageTail = "exit codes: 0 clean, 1 findings, 2 unreadable input or usage error\n";

std::string isoTimestampUtc(std::chrono::system_clock::time_point when) {
  const std::time_t seconds = std::chrono::system_clock::to_time_t(when);
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%S", &utc);
  return text;
}


int usageError(const std::string& message) {
  std::cerr << "tangent check: " << message << " (see tangent check --help)\n";
  return kExitUsage;
}

// A file to check, and how the progress line names it: by its path in its tree (led by the
// folder's name when there are several), as bake --recursive names it.
struct CheckInput {
  std::filesystem::path path, shownAs;
};

// The inputs as given; with `recursive`, each folder replaced by the files bake --recursive would
// bake under it (gltf::findInputs, sorted), named lexically normal ("./a/x.glb" is "a/x.glb", as
// code-review tools want paths from the repository root). A file reached twice is checked once.
std::vector<CheckInput> filesToCheck(const std::vector<std::string>& inputs, bool recursive) {
  namespace fs = std::filesystem;
  std::vector<CheckInput> files;
  std::set<fs::path> seen;
  auto add = [&](const fs::path& path, const fs::path& shownAs) {
    std::error_code ec;
    const fs::path absolute = fs::absolute(path, ec).lexically_normal();
    if (seen.insert(ec ? path : absolute).second) files.push_back({path, shownAs.empty() ? path : shownAs});
  };
  std::size_t folders = 0;
  for (const auto& input : inputs) {
    std::error_code ec;
    folders += recursive && fs::is_directory(input, ec);
  }
  for (const auto& input : inputs) {
    std::error_code ec;
    if (!recursive || !fs::is_directory(input, ec)) {
      add(input, {});
      continue;
    }
    std::vector<gltf::LeftOutEntry> leftOut;
    for (const fs::path& found : gltf::findInputs(input, {}, &leftOut)) {
      const fs::path path = found.lexically_normal();
      add(path, pathInTree(path, input, folders > 1));
    }
    for (gltf::LeftOutEntry& entry : leftOut) entry.path = entry.path.lexically_normal();
    warnLeftOut(leftOut);
  }
  return files;
}

// Each file checked in turn (an unreadable one an entry with its error), with the start time
// and duration of each for JUnit.
std::vector<gltf::FileCheck> checkFiles(const std::vector<CheckInput>& files, const gltf::CheckOptions& options, bool quiet,
                                        RunTimes& times) {
  std::vector<gltf::FileCheck> checks;
  ProgressLine progress(!quiet && files.size() > 1 && ::isatty(STDERR_FILENO));
  for (std::size_t n = 0; n < files.size(); ++n) {
    const std::string input = files[n].path.string();
    progress.show(n, files.size(), files[n].shownAs);
    times.startedUtc.push_back(isoTimestampUtc(std::chrono::system_clock::now()));
    const auto started = std::chrono::steady_clock::now();
    try {
      checks.push_back(gltf::checkFile(input, options));
    } catch (const gltf::InputError& e) {
      // Unreadable: reported in every format as a file with an error (exit code 2).
      gltf::FileCheck unreadableFile;
      unreadableFile.file = input;
      unreadableFile.error = e.what();
      unreadableFile.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
      checks.push_back(std::move(unreadableFile));
    }
  }
  progress.clear();
  return checks;
}

// The report in the format --format names.
std::string formatReport(const std::string& formatName, const std::vector<gltf::FileCheck>& checks, const gltf::CheckOptions& options,
                         const RunTimes& times, const std::string& output) {
  std::ostringstream report;
  if (formatName == "json") writeJson(report, checks, options);
  else if (formatName == "junit") writeJunit(report, checks, times);
  else if (formatName == "github") writeGithub(report, checks);
  else if (formatName == "sarif") writeSarif(report, checks, options);
  else if (formatName == "codeclimate") writeCodeClimate(report, checks);
  else if (formatName == "html") report << htmlReport(checks, options, output);
  else writeText(report, checks);
  return report.str();
}

}  // namespace

int checkCommand(const std::vector<std::string>& args) {
  const Arguments parsed = parseArguments(args, options::kCheck);
  if (parsed.help) {
    std::cout << kCheckUsageHead << options::helpText(options::kCheck) << kCheckUsageTail;
    return kExitOk;
  }
  if (!parsed.error.empty()) return usageError(parsed.error);
  const std::vector<std::string>& inputs = parsed.operands;
  const std::string formatName = parsed.last("format") ? *parsed.last("format") : "text";
  const std::string output = parsed.last("output") ? *parsed.last("output") : "-";
  const bool recursive = parsed.flag("recursive");
  gltf::CheckOptions options;
  // The config file first, whatever its place: the command line overrides it.
  if (const std::string* config = parsed.last("config")) {
    try {
      gltf::applyCheckConfig(*config, options);
    } catch (const std::exception& e) {
      return usageError(shown(e.what()));
    }
  }
  for (const auto& [option, value] : parsed.values) gltf::applyCheckOption(options, *option, value);
  if (!options.assetRoot.empty() && !std::filesystem::is_directory(options.assetRoot))
    return usageError("--asset-root " + shown(options.assetRoot.string()) + " is not a directory");
  if (inputs.empty()) return usageError("no input files");
  if (options.enabled.none()) return usageError("--only/--ignore leave no check to run");
  if (!recursive) {
    for (const auto& input : inputs) {
      std::error_code ec;
      if (std::filesystem::is_directory(input, ec))
        return usageError(shown(input) + ": is a directory; add --recursive to check every .gltf, .glb, .obj, .ply and .off under it");
    }
  }
  std::vector<CheckInput> files;
  try {
    files = filesToCheck(inputs, recursive);
  } catch (const std::exception& e) {  // a folder that cannot be listed
    std::cerr << "tangent check: " << shown(e.what()) << "\n";
    return kExitUsage;
  }
  if (files.empty()) {
    // As ESLint and pytest do: nothing found is an error unless asked for (a wrong path in CI).
    const bool allowed = parsed.flag("allow-empty");
    std::cerr << "tangent check: " << (allowed ? "" : "error: ") << "no .gltf, .glb, .obj, .ply or .off file under "
              << shown(inputs.front()) << (inputs.size() > 1 ? " or the other folders" : "")
              << (allowed ? "" : " (--allow-empty: an empty report, exit 0)") << "\n";
    if (!allowed) return kExitUsage;
  }
  // The report never goes over an input or a file one uses (refused before anything is read).
  if (output != "-") {
    gltf::ProtectedFiles inputFiles;
    for (const auto& file : files) inputFiles.addInput(file.path);
    if (inputFiles.contains(output))
      return usageError("-o " + shown(output) + " is an input or a file an input uses; the report is never written over one");
  }

  RunTimes times;
  const std::vector<gltf::FileCheck> checks = checkFiles(files, options, parsed.flag("quiet"), times);
  bool unreadable = false, findings = false;
  for (const auto& check : checks) {
    unreadable = unreadable || !check.error.empty();
    findings = findings || !check.clean();
  }
  if (!writeTextOutput(output, formatReport(formatName, checks, options, times, output), "check")) return kExitUsage;
  for (const auto& check : checks) {
    if (!check.error.empty()) std::cerr << "error: " << shown(check.error) << "\n";
  }
  return unreadable ? kExitUsage : findings ? kExitInputFailed : kExitOk;
}

}  // namespace tangent::cli
