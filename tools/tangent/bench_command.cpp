// SPDX-License-Identifier: MIT
// `tangent bench`: error against run time. Analytic surfaces with exact tangents at several
// resolutions, every method and setting, 1 and 2 threads, and the peers (reference MikkTSpace
// in C, meshoptimizer in both modes) when built with them; real assets against mikktspace;
// the stress suite with --stress; with --peers, every method and peer against the reference C.
// Table on the terminal, CSV and JSON files, and a log-log plot of error against run time drawn
// by gnuplot (PNG and SVG). The library is timed through its plain-array entry point, the call
// users make.
// The parts: bench_parts.hpp.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <numeric>
#include <optional>
#include <sstream>
#include <tuple>
#include <thread>

#include "analytic_surfaces.hpp"
#include "bench_parts.hpp"
#include "commands.hpp"
#include "stress_cases.hpp"
#include "tangent/arguments.hpp"
#include "tangent/gltf.hpp"
#include "tangent/scene.hpp"

namespace tangent::cli {

using options::Arguments;
using options::parseArguments;
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;
using namespace measure;

const char* kBenchUsageHead =
    "usage: tangent bench [options]\n"
    "\n"
    "Error against run time of every method on analytic surfaces (exact tangents known) from\n"
    "about 1e2 to --max-triangles triangles, and agreement with mikktspace on real assets. When\n"
    "built with ../shared/peers, the reference MikkTSpace in C and meshoptimizer (compatible and\n"
    "default modes) are measured on the same arrays and drawn on the same axes. The library is\n"
    "timed through computeCornerTangents on plain arrays, each call with its own workspace (as the\n"
    "peers allocate theirs): the median of --repeats calls. Each row also gives the resident\n"
    "memory one more call adds at its peak, per triangle, beyond its input and output arrays\n"
    "(peak B/tri; Linux, one-thread rows; '-' elsewhere).\n"
    "\n";

int stressSummary() {
  int failures = 0;
  std::printf("%-40s %-11s %8s %9s %8s %8s %6s %8s %7s %9s %9s\n", "case", "method", "corners", "undefined", "nonfinite", "nonunit",
              "nonorth", "bad w", "reruns", "contained", "ms");
  for (const auto& stressCase : bench::stressCases()) {
    for (Method method : {Method::mikktspace, Method::lengyel, Method::flat, Method::meshopt}) {
      Options options;
      options.method = method;
      const auto o = bench::runStressCase(stressCase, options);
      failures += !o.passed();
      std::printf("%-40s %-11s %8zu %9zu %8zu %8zu %6zu %8zu %7s %9s %9.3f%s\n", stressCase.name.c_str(), std::string(toString(method)).c_str(),
                  o.corners, o.undefinedCorners, o.notFinite, o.notUnit, o.notOrthogonal, o.badW, o.changedOnRerun ? "DIFFER" : "same",
                  stressCase.clean ? (o.changedAwayFromBrokenInput ? "NO" : "yes") : "-", o.milliseconds, o.passed() ? "" : "  FAIL");
    }
  }
  std::printf("%s\n", failures ? "stress suite: FAILURES" : "stress suite: every case keeps the invariants for every method");
  return failures ? kExitInputFailed : kExitOk;
}

void writePlot(const fs::path& dir, const std::vector<std::string>& surfaces) {
  // One panel per surface: mean error against total time, a series per method (1 thread).
  std::ostringstream script;
  std::vector<std::string> methods;
  for (const Setting& setting : settings())
    if (std::find(methods.begin(), methods.end(), setting.label) == methods.end()) methods.push_back(setting.label);
  const std::size_t libraryMethods = methods.size();
  for (bench::Peer peer : bench::peers()) methods.emplace_back(toString(peer));  // same axes, when built with the peers
  for (const char* terminal : {"pngcairo size 1500,900 font ',10'", "svg size 1500,900 font 'sans,10'"}) {
    const bool png = std::string(terminal).rfind("png", 0) == 0;
    script << "set terminal " << terminal << "\nset output '" << (dir / (png ? "plot.png" : "plot.svg")).string() << "'\n"
           << "set datafile separator ','\nset logscale xy\nset grid\nset key right top\n"
           << "set multiplot layout 2,3 title 'Mean angular error against run time (1 thread; one point per resolution)'\n";
    for (const auto& surface : surfaces) {
      script << "set title '" << surface << "'\nset xlabel 'time per call, ms'\nset ylabel 'mean error, degrees'\nplot ";
      for (std::size_t m = 0; m < methods.size(); ++m) {
        script << (m ? ", " : "") << "'" << (dir / "plot.csv").string() << "' using (strcol(1) eq '" << surface << "' && strcol(3) eq '"
               << methods[m] << "' && $4 == 1 ? $10 : 1/0):5 with linespoints title '" << methods[m]
               << (m >= libraryMethods ? " (peer)" : "") << "'";
      }
      script << "\n";
    }
    script << "unset multiplot\n";
  }
  try {
    output::writeFileAtomic(dir / "plot.gp", script.str());
  } catch (const std::exception& e) {
    std::cerr << "warning: " << shown(e.what()) << "; no plot\n";
    return;
  }
  const std::string command = "gnuplot '" + (dir / "plot.gp").string() + "' 2>&1";
  if (std::system(command.c_str()) != 0) std::cerr << "warning: gnuplot failed; plot.gp is in " << dir << "\n";
}

// The analytic surfaces' rows: the terminal table as it goes, and the CSV, JSON and plot rows.
struct AnalyticResults {
  std::ostringstream csv;
  Json rows = Json::array();
  // The plot reads a copy sorted by series, so that each series' points are consecutive rows
  // and gnuplot joins them (a filtered-out row in between breaks the line).
  using SeriesKey = std::tuple<std::string, std::string, unsigned, std::size_t>;
  std::vector<std::pair<SeriesKey, std::string>> plotRows;
};

// Every method and peer on every analytic surface from 1e2 to `maxTriangles` triangles, against
// the exact tangents.
void benchAnalytic(std::size_t maxTriangles, int repeats, AnalyticResults& out) {
  std::ostringstream& csv = out.csv;
  csv << "surface,triangles,method,threads,mean_deg,p99_deg,max_deg,w_errors,corners,ms,peak_bytes_per_triangle\n";
  std::printf("%-12s %9s %-18s %3s %10s %10s %10s %8s %10s %10s\n", "surface", "triangles", "method", "thr", "mean deg", "p99 deg",
              "max deg", "w errors", "ms", "peak B/tri");
  std::vector<std::size_t> resolutions;
  for (std::size_t r = 100; r <= maxTriangles; r *= 10) resolutions.push_back(r);
  for (const auto& surface : bench::surfaceNames()) {
    for (std::size_t target : resolutions) {
      const bench::AnalyticMesh mesh = bench::makeSurface(surface, target);
      // One row per method: terminal, CSV, JSON, and the plot's rows (kept for sorting).
      auto record = [&](const std::string& label, unsigned threads, double ms, const Errors& e, std::optional<double> bytes) {
        std::printf("%-12s %9zu %-18s %3u %10.5f %10.5f %10.5f %8zu %10.2f %10s\n", surface.c_str(), mesh.triangles(), label.c_str(),
                    threads, e.mean, e.p99, e.max, e.wErrors, ms, bytes ? std::to_string(std::lround(*bytes)).c_str() : "-");
        std::ostringstream row;
        row << surface << "," << mesh.triangles() << "," << label << "," << threads << "," << e.mean << "," << e.p99 << "," << e.max << ","
            << e.wErrors << "," << mesh.indices.size() << "," << ms << "," << (bytes ? std::to_string(*bytes) : "") << "\n";
        csv << row.str();
        out.plotRows.push_back({{surface, label, threads, mesh.triangles()}, row.str()});
        out.rows.push_back({{"surface", surface}, {"triangles", mesh.triangles()}, {"method", label}, {"threads", threads},
                            {"meanDegrees", e.mean}, {"p99Degrees", e.p99}, {"maxDegrees", e.max}, {"wErrors", e.wErrors},
                            {"ms", ms}, {"peakBytesPerTriangle", bytes ? Json(*bytes) : Json(nullptr)}});
      };
      const int runs = target >= 1000000 ? std::min(repeats, 3) : repeats;
      std::vector<float> scratch;  // the memory runs' output
      for (const Setting& setting : settings()) {
        std::vector<float> corners;
        const double ms = timedRun(mesh.arrays(), setting.options, runs, corners);
        record(setting.label, setting.options.threads, ms, compare(corners, mesh.indices, mesh.exactTangents, true),
               peakBytesPerTriangle(mesh.arrays(), setting.options, scratch));
      }
      // The peers: one call, its time counted as compute.
      for (bench::Peer peer : bench::peers()) {
        std::vector<float> corners;
        const double ms = timedPeerRun(peer, mesh.arrays(), UvOrigin::bottomLeft, runs, corners);
        record(std::string(toString(peer)), 1, ms, compare(corners, mesh.indices, mesh.exactTangents, true),
               peerPeakBytesPerTriangle(peer, mesh.arrays(), scratch));
      }
      std::fflush(stdout);
    }
  }
}

// Real assets: every primitive with UVs, each method and peer against mikktspace; the JSON rows.
Json benchAssets(const std::vector<fs::path>& assets, int repeats) {
  Json assetResults = Json::array();
  const std::vector<fs::path> files = assetFiles(assets);
  if (!files.empty())
    std::printf("\n%-28s %-10s %9s %-18s %3s %10s %10s %10s %8s %10s\n", "asset", "primitive", "triangles", "method", "thr", "median deg",
                "p99 deg", "max deg", "w diff", "ms");
  for (const auto& file : files) {
    const std::optional<gltf::Scene> loaded = loadSceneOrWarn(file);
    if (!loaded) continue;
    const gltf::Scene& scene = *loaded;
    for (const auto& item : scene.items) {
      if (!item.hasUvs) continue;
      std::vector<std::uint32_t> identity(item.positions.size() / 3);
      std::iota(identity.begin(), identity.end(), 0u);
      const MeshArrays arrays{item.positions, item.normals, item.uvNormal, identity};
      std::vector<float> reference;
      Options mikk;
      timedRun(arrays, mikk, 1, reference);
      struct Run {
        std::string label;
        unsigned threads;
        std::vector<float> corners;
        double ms = 0;
      };
      std::vector<Run> runs;
      for (const Setting& setting : settings()) {
        Options options = setting.options;
        options.uvOrigin = UvOrigin::topLeft;
        Run run{setting.label, options.threads, {}, {}};
        run.ms = timedRun(arrays, options, repeats, run.corners);
        runs.push_back(std::move(run));
      }
      for (bench::Peer peer : bench::peers()) {
        Run run{std::string(toString(peer)), 1, {}, {}};
        run.ms = timedPeerRun(peer, arrays, UvOrigin::topLeft, repeats, run.corners);
        runs.push_back(std::move(run));
      }
      for (const Run& run : runs) {
        const std::vector<float>& corners = run.corners;
        const Errors e = compare(corners, identity, reference, false);
        std::vector<double> angles(identity.size());
        for (std::size_t c = 0; c < identity.size(); ++c) angles[c] = angleDegrees(&corners[4 * c], &reference[4 * c]);
        std::sort(angles.begin(), angles.end());
        const double med = angles.empty() ? 0 : angles[angles.size() / 2];
        std::printf("%-28s %-10s %9zu %-18s %3u %10.5f %10.5f %10.5f %8zu %10.2f\n", file.filename().string().c_str(),
                    item.label.substr(item.label.rfind(' ') + 1).c_str(), identity.size() / 3, run.label.c_str(), run.threads, med,
                    e.p99, e.max, e.wErrors, run.ms);
        assetResults.push_back({{"asset", file.filename().string()}, {"primitive", item.label}, {"method", run.label},
                                {"threads", run.threads}, {"medianDegrees", med}, {"p99Degrees", e.p99}, {"maxDegrees", e.max},
                                {"wDifferences", e.wErrors}, {"ms", run.ms}});
      }
    }
  }
  return assetResults;
}

}  // namespace

int benchCommand(const std::vector<std::string>& args) {
  const Arguments parsed = parseArguments(args, options::kBench);
  if (parsed.help) {
    std::cout << kBenchUsageHead << options::helpText(options::kBench);
    return kExitOk;
  }
  if (parsed.error.empty() && !parsed.operands.empty()) {
    std::cerr << "tangent bench: takes no input files ('" << shown(parsed.operands.front()) << "'; see --assets)\n";
    return kExitUsage;
  }
  if (!parsed.error.empty()) {
    std::cerr << "tangent bench: " << shown(parsed.error) << " (see tangent bench --help)\n";
    return kExitUsage;
  }
  auto count = [&](std::string_view name, std::size_t fallback) {
    const std::string* value = parsed.last(name);
    return value ? static_cast<std::size_t>(std::stoull(*value)) : fallback;
  };
  const std::size_t maxTriangles = count("max-triangles", 1000000);
  const int repeats = static_cast<int>(count("repeats", 3));
  const std::size_t peerTriangles = count("triangles", 100000);
  const fs::path outDir = parsed.last("out-dir") ? fs::path(*parsed.last("out-dir")) : fs::path("bench-results");
  std::vector<fs::path> assets;
  for (const auto& [option, value] : parsed.values)
    if (option->name == "assets") assets.emplace_back(value);
  const bool plot = !parsed.flag("no-plot"), stress = parsed.flag("stress"), peersOnly = parsed.flag("peers");
  if (stress) return stressSummary();
  if (assets.empty() && fs::is_directory("../shared/assets")) assets.emplace_back("../shared/assets");
  if (peersOnly) return peersTable(assets, peerTriangles, repeats, outDir);
  if (bench::peers().empty()) std::cerr << "tangent bench: " << bench::peersNote() << "\n";
  std::error_code ec;
  fs::create_directories(outDir, ec);

  AnalyticResults analytic;
  benchAnalytic(maxTriangles, repeats, analytic);
  const Json assetResults = benchAssets(assets, repeats);
  std::sort(analytic.plotRows.begin(), analytic.plotRows.end());
  std::ostringstream plotCsv;
  for (const auto& [key, row] : analytic.plotRows) plotCsv << row;
  Json report = {{"machine", {{"hardwareThreads", std::thread::hardware_concurrency()}}},
                 {"repeats", repeats},
                 {"analytic", analytic.rows},
                 {"assetsAgainstMikktspace", assetResults}};
  if (!writeTextOutput((outDir / "bench.csv").string(), analytic.csv.str(), "bench") ||
      !writeTextOutput((outDir / "plot.csv").string(), plotCsv.str(), "bench") ||
      !writeTextOutput((outDir / "bench.json").string(), text::dumpJson(report, 2) + "\n", "bench"))
    return kExitInputFailed;
  if (plot) writePlot(outDir, bench::surfaceNames());
  std::printf("\nwrote %s/bench.csv, bench.json%s\n", outDir.string().c_str(), plot ? ", plot.png, plot.svg" : "");
  return kExitOk;
}

}  // namespace tangent::cli
