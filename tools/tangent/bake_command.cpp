// SPDX-License-Identifier: MIT
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "tangent/arguments.hpp"
#include "commands.hpp"
#include "tangent/batch.hpp"
#include "tangent/gltf.hpp"
#include "tangent/text.hpp"

namespace tangent::cli {

using options::Arguments;
using options::parseArguments;
namespace {

const char* kBakeUsageHead =
    "usage: tangent bake IN OUT [options]\n"
    "       tangent bake IN... (-o OUT | --out-dir DIR) [options]\n"
    "       tangent bake FOLDER... --recursive --out-dir DIR [options]\n"
    "\n"
    "Computes TANGENT for every triangle primitive whose material reads the tangent frame (a\n"
    "normalTexture, a clearcoat normal texture, anisotropy), from the UV set that texture uses,\n"
    "and writes a new file. Inputs: .gltf, .glb, .obj, .ply, .off\n"
    "(OBJ/PLY/OFF become .glb; they carry no materials, so all their meshes are baked).\n"
    "The input is never written to; outputs are written atomically.\n"
    "\n";

// -o -: the bake goes to a private temporary folder, then its bytes to standard output.
class StdoutTarget {
 public:
  StdoutTarget() {
    namespace fs = std::filesystem;
    for (int attempt = 0;; ++attempt) {
      dir_ = fs::temp_directory_path() / ("tangent-bake-" + std::to_string(::getpid()) + "-" + std::to_string(attempt));
      if (fs::create_directory(dir_)) break;  // throws where the folder cannot be made at all
    }
    dirGuard_ = std::make_unique<output::TemporaryGuard>(dir_);
    fileGuard_ = std::make_unique<output::TemporaryGuard>(file());
  }
  ~StdoutTarget() {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
    fileGuard_.reset();
    dirGuard_.reset();
  }
  StdoutTarget(const StdoutTarget&) = delete;
  StdoutTarget& operator=(const StdoutTarget&) = delete;
  std::filesystem::path file() const { return dir_ / "stdout.glb"; }
  // Streams the baked file; refuses when the bake placed files beside it (external images
  // kept by --keep-external, whose relative URIs a stream cannot carry).
  void send(const std::filesystem::path& input) const {
    namespace fs = std::filesystem;
    for (const auto& entry : fs::directory_iterator(dir_)) {
      if (entry.path() != file())
        throw std::runtime_error(input.string() + ": -o - writes one .glb, but the asset refers to external files (" +
                                 entry.path().filename().string() + "); write it with -o FILE, or leave out --keep-external");
    }
    std::ifstream in(file(), std::ios::binary);
    std::cout << in.rdbuf();
    std::cout.flush();
    if (!in || !std::cout) throw std::runtime_error("-o -: could not write the baked file to standard output");
  }

 private:
  std::filesystem::path dir_;
  std::unique_ptr<output::TemporaryGuard> dirGuard_, fileGuard_;  // removed on SIGINT/SIGTERM
};

// A batch's failure message, led by the input file where it does not start with it (a write
// that failed names the output file, a full disk for one): each failed line says which file.
std::string namingInput(const std::filesystem::path& input, const std::string& message) {
  const std::string name = input.string();
  return message.compare(0, name.size(), name) == 0 ? message : name + ": " + message;
}

int usageError(const std::string& message) {
  std::cerr << "tangent bake: " << message << " (see tangent bake --help)\n";
  return kExitUsage;
}

// --report FILE ("-": standard output, the human-readable lines then go to stderr).
// `keep`: the run's inputs, the files they use and its outputs, never written over.
int writeReport(const std::filesystem::path& reportPath, const nlohmann::ordered_json& report, const gltf::ProtectedFiles* keep) {
  if (reportPath.empty()) return kExitOk;
  return writeTextOutput(reportPath.string(), text::dumpJson(report, 2) + "\n", "bake", keep) ? kExitOk : kExitInputFailed;
}

// Whether --report names an input, a file one uses or one of `outputs` (a .gltf's .bin too):
// checked before anything is baked.
bool reportWouldReplace(const std::filesystem::path& reportPath, const gltf::ProtectedFiles& inputs,
                        const std::vector<std::filesystem::path>& outputs) {
  namespace fs = std::filesystem;
  if (reportPath.empty() || reportPath == "-") return false;
  if (inputs.contains(reportPath)) return true;
  std::error_code ec;
  const fs::path report = fs::absolute(reportPath, ec).lexically_normal();
  for (fs::path output : outputs) {
    if (output.empty()) continue;  // standard output
    for (int twice = 0; twice < 2; ++twice, output.replace_extension(".bin"))
      if (fs::absolute(output, ec).lexically_normal() == report) return true;
  }
  return false;
}

// Ctrl-C's notice, on a line of its own: over a progress line it replaces that line first.
constexpr const char* kStopNotice = "tangent: stopping after the current file (press Ctrl-C again to stop at once)\n";
constexpr const char* kStopNoticeOverProgress =
    "\r\033[Ktangent: stopping after the current file (press Ctrl-C again to stop at once)\n";

// --recursive: where a folder's tree is written: --out-dir itself for one folder, --out-dir/NAME
// for each of several.
std::filesystem::path treeTarget(const std::vector<std::filesystem::path>& folders, const std::filesystem::path& folder,
                                 const std::filesystem::path& outDir) {
  return folders.size() == 1 ? outDir : outDir / folder.filename();
}

// Two folders of one name would share OUT/NAME and its manifest (each run replacing the
// other's records): refused whatever files they hold, with a message.
bool foldersShareAName(const std::vector<std::filesystem::path>& folders, const std::filesystem::path& outDir) {
  std::map<std::string, std::filesystem::path> byName;
  for (const auto& folder : folders) {
    if (folders.size() < 2) break;
    const auto [at, inserted] = byName.emplace(folder.filename().string(), folder);
    if (!inserted) {
      std::cerr << "error: " << shown(at->second.string()) << " and " << shown(folder.string()) << " would both be written to "
                << shown((outDir / folder.filename()).string()) << ", with one manifest (nothing was written; rename one)\n";
      return true;
    }
  }
  return false;
}

// Every input of the run and its output, known before anything is written.
struct TreePlan {
  std::vector<std::filesystem::path> inputs, outputs;
};

// The run's inputs and outputs; false, with a message, where a folder cannot be listed or two
// files of one folder would become the same .glb (the run is then refused as a whole).
bool planTrees(const std::vector<std::filesystem::path>& folders, const std::filesystem::path& outDir, TreePlan& plan) {
  for (const auto& folder : folders) {
    const std::filesystem::path target = treeTarget(folders, folder, outDir);
    try {
      std::vector<gltf::LeftOutEntry> leftOut;
      for (const auto& input : gltf::findInputs(folder, target, &leftOut)) {
        plan.inputs.push_back(input);
        plan.outputs.push_back(gltf::outputPathInTree(input, folder, target));
      }
      warnLeftOut(leftOut);
    } catch (const std::exception& e) {
      std::cerr << "error: " << shown(e.what()) << "\n";
      return false;
    }
  }
  if (const auto collisions = gltf::outputCollisions(plan.inputs, plan.outputs); !collisions.empty()) {
    std::cerr << "error: " << shown(gltf::describeCollisions(collisions)) << "\n";
    return false;
  }
  return true;
}

// What the bake of the trees gave: the report's entries, the count of each outcome and how many
// files were done (fewer than planned where Ctrl-C stopped the run).
struct TreeRun {
  nlohmann::ordered_json report = nlohmann::ordered_json::array();
  std::map<gltf::FileOutcome, std::size_t> counts;
  std::size_t done = 0;
};

// Bakes each folder's tree in turn, a line per file on `log` (failures on stderr), under a
// progress line; stops after the current file on Ctrl-C.
TreeRun runTrees(const std::vector<std::filesystem::path>& folders, const std::filesystem::path& outDir, gltf::BatchOptions& batch,
                 std::size_t total, bool quiet, std::ostream& log) {
  TreeRun run;
  ProgressLine progress(!quiet && ::isatty(STDERR_FILENO));
  batch.stopRequested = output::stopRequested;
  // The progress names each file by its path in its tree (led by the folder's name when there
  // are several), as the output tree has it.
  const std::filesystem::path* currentFolder = nullptr;
  batch.onStart = [&](std::size_t, std::size_t, const std::filesystem::path& input) {
    progress.show(run.done, total, pathInTree(input, *currentFolder, folders.size() > 1));
  };
  output::stopGracefullyOnSignal(progress.onTerminal() ? kStopNoticeOverProgress : kStopNotice);
  for (const auto& folder : folders) {
    const std::filesystem::path target = treeTarget(folders, folder, outDir);
    currentFolder = &folder;
    if (output::stopRequested()) break;
    try {
      gltf::bakeTree(folder, target, batch, [&](const gltf::BatchEntry& entry) {
        ++run.done;
        ++run.counts[entry.outcome];
        progress.clear();
        // A file that failed last time and has not changed still fails.
        // Named by its input where the message names only an output (a write that failed).
        if (entry.outcome == gltf::FileOutcome::failed)
          std::cerr << "error: " << shown(namingInput(entry.input, entry.error)) << (entry.skipped ? " (unchanged since the last run)" : "")
                    << "\n";
        else if (!quiet)
          log << shown(entry.input.string()) << " -> " << shown(entry.output.string()) << ": " << gltf::toString(entry.outcome)
              << "\n" << std::flush;
        run.report.push_back(gltf::toJson(entry));
      });
    } catch (const std::exception& e) {
      ++run.counts[gltf::FileOutcome::failed];
      progress.clear();
      std::cerr << "error: " << shown(e.what()) << "\n";
    }
  }
  progress.clear();
  return run;
}

// --recursive: each folder into --out-dir (into --out-dir/NAME when there are several). Every
// output of the run is known before anything is written: two folders of one name, or two files
// of one folder that become the same .glb, are refused as a whole.
int bakeTrees(const std::vector<std::filesystem::path>& folders, const std::filesystem::path& outDir,
              const gltf::BakeOptions& options, bool force, bool verify, bool quiet, const std::filesystem::path& reportPath) {
  gltf::BatchOptions batch;
  batch.bake = options;
  batch.force = force;
  batch.verify = verify;
  if (foldersShareAName(folders, outDir)) return kExitInputFailed;
  TreePlan plan;
  if (!planTrees(folders, outDir, plan)) return kExitInputFailed;
  gltf::ProtectedFiles reportKeeps;
  if (!reportPath.empty() && reportPath != "-") {
    for (const auto& input : plan.inputs) reportKeeps.addInput(input);
    if (reportWouldReplace(reportPath, reportKeeps, plan.outputs)) {
      std::cerr << "tangent bake: --report " << shown(reportPath.string())
                << " is an input, a file an input uses or an output of this run; the report is never written over one\n";
      return kExitUsage;
    }
  }
  std::ostream& log = reportPath == "-" ? std::cerr : std::cout;
  TreeRun run = runTrees(folders, outDir, batch, plan.inputs.size(), quiet, log);
  const std::size_t failed = run.counts[gltf::FileOutcome::failed];
  if (!quiet)
    log << run.counts[gltf::FileOutcome::baked] << " baked, " << run.counts[gltf::FileOutcome::kept] << " kept, "
        << run.counts[gltf::FileOutcome::unchanged] << " unchanged, " << failed << " failed\n";
  const int written = writeReport(reportPath, run.report, &reportKeeps);
  if (output::stopRequested()) {
    std::cerr << "tangent bake: stopped after " << run.done << " of " << plan.inputs.size()
              << " files; the manifest records them, so the same command continues where this one stopped\n";
    return kExitInterrupted;
  }
  return failed ? kExitInputFailed : written;
}

// One bake's lines: the file's counts, then each primitive with what was done and why.
void printBakeResult(std::ostream& log, const std::filesystem::path& input, const std::string& targetName,
                     const gltf::BakeResult& result) {
  int baked = 0, kept = 0, skipped = 0;
  std::uint64_t split = 0;
  for (const auto& p : result.primitives) {
    baked += p.action == gltf::PrimitiveAction::baked;
    kept += p.action == gltf::PrimitiveAction::kept;
    skipped += p.action == gltf::PrimitiveAction::skipped;
    // Generated normals may leave out vertices no triangle uses: only growth counts.
    split += p.action == gltf::PrimitiveAction::baked && p.verticesOut > p.verticesIn ? p.verticesOut - p.verticesIn : 0;
  }
  log << shown(input.string()) << " -> " << shown(targetName) << ": " << baked << " baked, " << kept << " kept, " << skipped
      << " skipped; " << split << " vertices added by splits\n";
  for (const auto& p : result.primitives) {
    log << "  mesh " << p.mesh << (p.meshName.empty() ? "" : " '" + text::quoted(p.meshName) + "'") << " primitive " << p.primitive
        << ": " << gltf::toString(p.action) << " - " << shown(p.reason);
    if (p.action == gltf::PrimitiveAction::baked) {
      const Report& r = p.tangents;
      log << " [" << toString(r.method) << (r.weighting ? "/" + std::string(toString(*r.weighting)) : "") << ", " << p.verticesIn
          << " -> " << p.verticesOut << " vertices, " << r.mirroredCorners << " mirrored corners";
      if (p.normalsGenerated) log << ", NORMAL generated (" << gltf::toString(*p.normalsGenerated) << ")";
      if (r.degenerateTriangles) log << ", " << r.degenerateTriangles << " degenerate triangles";
      if (r.zeroUvAreaTriangles) log << ", " << r.zeroUvAreaTriangles << " zero-UV-area triangles";
      if (r.nonFiniteTriangles) log << ", " << r.nonFiniteTriangles << " non-finite triangles";
      if (r.nonManifoldFaces) log << ", " << r.nonManifoldFaces << " non-manifold faces";
      if (r.invalidNormals) log << ", " << r.invalidNormals << " invalid normals";
      if (r.inheritedCorners) log << ", " << r.inheritedCorners << " corners inherited a frame";
      if (r.fallbackFromNeighbours + r.fallbackFixed)
        log << ", " << r.fallbackFromNeighbours + r.fallbackFixed << " corners with fallback frames";
      log << "]";
    }
    log << "\n";
  }
  for (const auto& name : result.extensionsRemoved)
    log << "  " << name << " removed from extensionsUsed/extensionsRequired: nothing in the output uses it\n";
  for (const auto& w : result.warnings) std::cerr << "warning: " << shown(w) << "\n";
}

// A bake of files (not --recursive) as the command line asked for it, after its checks.
struct FileBake {
  std::vector<std::filesystem::path> inputs;
  std::filesystem::path output, outDir;  // one of the two
  std::filesystem::path reportPath;
  bool quiet = false;
  bool toStdout = false;  // -o -
  // Where input n goes.
  std::filesystem::path targetOf(const std::filesystem::path& input) const {
    return output.empty() ? gltf::outputPathFor(input, outDir) : output;
  }
};

// Reads the outputs the command line names (-o FILE, --out-dir DIR, or glTF-Transform's
// `IN OUT`) into `run`; kExitOk, or the exit code of the usage error it printed.
int planFileBake(const Arguments& parsed, FileBake& run) {
  namespace fs = std::filesystem;
  std::vector<fs::path>& inputs = run.inputs;
  fs::path& output = run.output;
  const fs::path& outDir = run.outDir;
  // A folder without -o (with --out-dir, or as `bake IN OUT`): the folder form was meant. (With
  // -o, loading refuses the folder as an input, exit 1, as any unreadable input.)
  for (const fs::path& input : inputs) {
    if (output.empty() && fs::is_directory(input))
      return usageError(shown(input.string()) + " is a folder: bake a folder with --recursive --out-dir DIR");
  }
  // glTF-Transform's form: `tangent bake in.glb out.glb`, the same as -o.
  if (inputs.size() == 2 && output.empty() && outDir.empty()) {
    const std::string ext = inputs[1].extension().string();
    if (ext != ".glb" && ext != ".gltf")
      return usageError("two files and no -o or --out-dir: the second (" + shown(inputs[1].string()) +
                        ") is taken as the output, and must end in .glb or .gltf");
    output = inputs[1];
    inputs.pop_back();
  }
  if (!output.empty() && !outDir.empty()) return usageError("give -o FILE or --out-dir DIR, not both");
  if (output.empty() && outDir.empty()) {
    // After "--" every argument is an input, "-o" too: say so where one looks like an option.
    for (const fs::path& input : inputs) {
      const std::string name = input.string();
      if (parsed.afterDashes && (name == "-o" || name == "--output" || name == "--out-dir"))
        return usageError("no output: '" + name + "' comes after '--', where every argument is an input; put -o FILE or --out-dir DIR before '--'");
    }
    return usageError("no output: give -o FILE or --out-dir DIR (or two files: IN OUT)");
  }
  if (!output.empty() && inputs.size() > 1) return usageError("-o takes one input; use --out-dir for several");
  run.toStdout = output == "-";
  if (run.toStdout && ::isatty(STDOUT_FILENO))
    return usageError("-o - writes a binary .glb, and standard output is a terminal; redirect it (> out.glb) or pipe it");
  if (run.toStdout && run.reportPath == "-") return usageError("-o - and --report - cannot both write to standard output");
  if (!outDir.empty()) {
    std::error_code ec;
    fs::create_directories(outDir, ec);
    if (!fs::is_directory(outDir)) return usageError("--out-dir " + outDir.string() + " is not a directory");
  }
  return kExitOk;
}

// What no bake of the run may write over: with several inputs, a file another input uses or an
// earlier bake's output; --report, an input, a file one uses or an output. kExitOk, or the exit
// code of the refusal it printed (before anything was baked).
int protectRunFiles(const FileBake& run, gltf::ProtectedFiles& runFiles, gltf::BakeOptions& options) {
  namespace fs = std::filesystem;
  if (!run.outDir.empty()) {
    std::vector<fs::path> targets;
    for (const fs::path& input : run.inputs) targets.push_back(gltf::outputPathFor(input, run.outDir));
    if (const auto collisions = gltf::outputCollisions(run.inputs, targets); !collisions.empty()) {
      std::cerr << "error: " << shown(gltf::describeCollisions(collisions)) << "\n";
      return kExitInputFailed;
    }
  }
  if (run.inputs.size() > 1 || (!run.reportPath.empty() && run.reportPath != "-")) {
    for (const fs::path& input : run.inputs) runFiles.addInput(input);
    if (run.inputs.size() > 1) options.protectedFiles = &runFiles;
    std::vector<fs::path> outputs;
    for (const fs::path& input : run.inputs) outputs.push_back(run.toStdout ? fs::path() : run.targetOf(input));
    if (reportWouldReplace(run.reportPath, runFiles, outputs))
      return usageError("--report " + shown(run.reportPath.string()) +
                        " is an input, a file an input uses or an output of this run; the report is never written over one");
  }
  return kExitOk;
}

// Each input baked in turn (until Ctrl-C asks to stop), its lines printed and its report entry
// kept; then the report written and the exit code.
int runFileBake(const FileBake& run, const gltf::BakeOptions& options, gltf::ProtectedFiles& runFiles) {
  namespace fs = std::filesystem;
  const std::vector<fs::path>& inputs = run.inputs;
  ProgressLine progress(!run.quiet && inputs.size() > 1 && ::isatty(STDERR_FILENO));
  std::ostream& log = run.reportPath == "-" || run.toStdout ? std::cerr : std::cout;
  int failed = 0;
  nlohmann::ordered_json report = nlohmann::ordered_json::array();
  if (inputs.size() > 1) output::stopGracefullyOnSignal(progress.onTerminal() ? kStopNoticeOverProgress : kStopNotice);
  std::size_t done = 0;
  for (std::size_t n = 0; n < inputs.size() && !output::stopRequested(); ++n, ++done) {
    const fs::path& input = inputs[n];
    std::optional<StdoutTarget> stream;
    if (run.toStdout) {
      try {
        stream.emplace();
      } catch (const std::exception& e) {
        std::cerr << "error: " << shown(input.string()) << ": -o - bakes into a temporary folder first, and none can be made ("
                  << shown(e.what()) << "); set TMPDIR to a writable folder\n";
        return kExitInputFailed;
      }
    }
    const fs::path target = stream ? stream->file() : run.targetOf(input);
    const std::string targetName = stream ? "-" : target.string();
    progress.show(n, inputs.size(), input);
    nlohmann::ordered_json entry = {{"input", input.string()}, {"output", targetName}};
    try {
      const gltf::BakeResult result = gltf::bakeFile(input, target, options);
      for (const fs::path& file : result.filesWritten) runFiles.add(file);
      if (stream) stream->send(input);
      entry["status"] = "ok";
      if (!run.reportPath.empty()) entry.update(gltf::toJson(result));  // the per-primitive report: only when asked for
      if (!run.quiet) {
        progress.clear();
        printBakeResult(log, input, targetName, result);
      }
    } catch (const std::exception& e) {
      ++failed;
      progress.clear();
      std::cerr << "error: " << shown(e.what()) << "\n";
      entry["status"] = "failed";
      entry["error"] = e.what();
    }
    if (!run.reportPath.empty()) report.push_back(std::move(entry));
  }
  progress.clear();
  if (const int written = writeReport(run.reportPath, report, &runFiles); written != kExitOk) return written;
  if (output::stopRequested()) {
    std::cerr << "tangent bake: stopped after " << done << " of " << inputs.size() << " inputs\n";
    return kExitInterrupted;
  }
  if (failed && !run.quiet && inputs.size() > 1) std::cerr << failed << " of " << inputs.size() << " inputs failed\n";
  return failed ? kExitInputFailed : kExitOk;
}

}  // namespace

// The command line read, its options applied, then a folder bake (--recursive) or a file bake:
// its outputs planned, the run's files protected, each input baked.
int bakeCommand(const std::vector<std::string>& args) {
  namespace fs = std::filesystem;
  const Arguments parsed = parseArguments(args, options::kBake | options::kBakeTree);
  if (parsed.help) {
    std::cout << kBakeUsageHead << options::helpText(options::kBake | options::kBakeTree);
    return kExitOk;
  }
  if (!parsed.error.empty()) return usageError(parsed.error);
  gltf::BatchOptions batch;
  for (const auto& [option, value] : parsed.values) gltf::applyBatchOption(batch, *option, value);
  gltf::BakeOptions& options = batch.bake;
  FileBake run;
  run.inputs.assign(parsed.operands.begin(), parsed.operands.end());
  run.output = parsed.last("output") ? *parsed.last("output") : "";
  run.outDir = parsed.last("out-dir") ? *parsed.last("out-dir") : "";
  run.reportPath = parsed.last("report") ? *parsed.last("report") : "";
  run.quiet = parsed.flag("quiet");
  if (!options.assetRoot.empty() && !fs::is_directory(options.assetRoot))
    return usageError("--asset-root " + shown(options.assetRoot.string()) + " is not a directory");
  if (run.inputs.empty()) return usageError("no input files");
  if (parsed.flag("recursive")) {
    if (run.outDir.empty() || !run.output.empty()) return usageError("--recursive needs --out-dir DIR (and no -o)");
    for (const fs::path& input : run.inputs) {
      if (!fs::is_directory(input)) return usageError("--recursive: " + input.string() + " is not a folder");
    }
    return bakeTrees(run.inputs, run.outDir, options, batch.force, batch.verify, run.quiet, run.reportPath);
  }
  if (batch.force || batch.verify) return usageError(std::string(batch.force ? "--force" : "--verify") + " goes with --recursive");
  if (const int planned = planFileBake(parsed, run); planned != kExitOk) return planned;
  gltf::ProtectedFiles runFiles;
  if (const int protectedRun = protectRunFiles(run, runFiles, options); protectedRun != kExitOk) return protectedRun;
  return runFileBake(run, options, runFiles);
}

}  // namespace tangent::cli
