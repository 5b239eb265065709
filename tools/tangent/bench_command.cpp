// SPDX-License-Identifier: MIT
// `tangent bench`: error against run time. Analytic surfaces with exact tangents at several
// resolutions, every method and setting, 1 and 2 threads, and the peers (reference MikkTSpace
// in C, meshoptimizer in both modes) when built with them; real assets against mikktspace;
// the stress suite with --stress. Table on the terminal, CSV and JSON files, and a log-log
// plot of error against run time drawn by gnuplot (PNG and SVG).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <numeric>
#include <sstream>
#include <tuple>
#include <thread>

#include "analytic_surfaces.hpp"
#include "commands.hpp"
#include "peers.hpp"
#include "stress_cases.hpp"
#include "tangent/gltf.hpp"
#include "tangent/openmesh.hpp"
#include "tangent/scene.hpp"

namespace tangent::cli {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using Json = nlohmann::ordered_json;

const char* kBenchUsage =
    "usage: tangent bench [options]\n"
    "\n"
    "Error against run time of every method on analytic surfaces (exact tangents known) from\n"
    "about 1e2 to --max-triangles triangles, and agreement with mikktspace on real assets. When\n"
    "built with ../shared/peers, the reference MikkTSpace in C and meshoptimizer (compatible and\n"
    "default modes) are measured on the same arrays and drawn on the same axes.\n"
    "\n"
    "options:\n"
    "  --max-triangles N   largest resolution (default 1000000)\n"
    "  --repeats N         timed runs per measurement; the median is reported (default 3)\n"
    "  --out-dir DIR       where bench.csv, bench.json, plot.png and plot.svg go (default bench-results)\n"
    "  --assets PATH       a glTF file or folder of them (default ../shared/assets when present)\n"
    "  --no-plot           skip gnuplot\n"
    "  --stress            run the stress suite instead and print its summary (exit 1 on failure)\n";

struct Setting {
  std::string label;
  Options options;
};

std::vector<Setting> settings() {
  std::vector<Setting> out;
  for (unsigned threads : {1u, 2u}) {
    auto add = [&](const std::string& label, Method method, Weighting weighting) {
      Setting s;
      s.label = label;
      s.options.method = method;
      s.options.weighting = weighting;
      s.options.threads = threads;
      s.options.uvOrigin = UvOrigin::bottomLeft;
      out.push_back(s);
    };
    add("mikktspace", Method::mikktspace, Weighting::angle);
    add("lengyel/angle", Method::lengyel, Weighting::angle);
    add("lengyel/area", Method::lengyel, Weighting::area);
    add("lengyel/uniform", Method::lengyel, Weighting::uniform);
    add("flat", Method::flat, Weighting::angle);
  }
  return out;
}

double angleDegrees(const float* a, const float* b) {
  const double cross[3] = {double(a[1]) * b[2] - double(a[2]) * b[1], double(a[2]) * b[0] - double(a[0]) * b[2],
                           double(a[0]) * b[1] - double(a[1]) * b[0]};
  const double sine = std::sqrt(cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]);
  return std::atan2(sine, double(a[0]) * b[0] + double(a[1]) * b[1] + double(a[2]) * b[2]) * 180.0 / M_PI;
}

struct Timing {
  double build = 0, compute = 0, output = 0;
  double total() const { return build + compute + output; }
};

struct Errors {
  double mean = 0, p99 = 0, max = 0;
  std::size_t wErrors = 0;
};

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

// Runs the library the way a caller does: build the half-edge mesh, compute, copy per corner.
Timing timedRun(const MeshArrays& mesh, const Options& options, int repeats, std::vector<float>& cornerTangents) {
  std::vector<double> build, compute, output;
  cornerTangents.resize(mesh.indices.size() * 4);
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = Clock::now();
    CornerMesh cornerMesh = buildCornerMesh(mesh);
    const auto t1 = Clock::now();
    computeTangents(cornerMesh, options);
    const auto t2 = Clock::now();
    for (std::size_t c = 0; c < mesh.indices.size(); ++c) {
      const TangentVec& t = cornerMesh.mesh.property(cornerMesh.tangent, cornerMesh.cornerHalfedge[c]);
      for (int i = 0; i < 4; ++i) cornerTangents[4 * c + i] = static_cast<float>(t[i]);
    }
    const auto t3 = Clock::now();
    build.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
    compute.push_back(std::chrono::duration<double, std::milli>(t2 - t1).count());
    output.push_back(std::chrono::duration<double, std::milli>(t3 - t2).count());
  }
  return {median(build), median(compute), median(output)};
}

// A peer (reference MikkTSpace in C, meshoptimizer) on the same arrays: one call, no phases.
// Its w is in the bottom-left convention; tangent::handedness turns it into uvOrigin's.
Timing timedPeerRun(bench::Peer peer, const MeshArrays& mesh, UvOrigin uvOrigin, int repeats, std::vector<float>& cornerTangents) {
  std::vector<double> total;
  cornerTangents.resize(mesh.indices.size() * 4);
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = Clock::now();
    bench::runPeer(peer, mesh, cornerTangents);
    total.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
  }
  for (std::size_t c = 0; c < mesh.indices.size(); ++c) cornerTangents[4 * c + 3] = handedness(cornerTangents[4 * c + 3], uvOrigin);
  Timing timing;
  timing.compute = median(total);
  return timing;
}

Errors compare(const std::vector<float>& corners, const std::vector<std::uint32_t>& indices, const std::vector<float>& reference,
               bool referencePerVertex) {
  Errors e;
  std::vector<double> angles(indices.size());
  for (std::size_t c = 0; c < indices.size(); ++c) {
    const float* expected = &reference[4 * (referencePerVertex ? indices[c] : c)];
    angles[c] = angleDegrees(&corners[4 * c], expected);
    if (corners[4 * c + 3] != expected[3]) ++e.wErrors;
  }
  if (angles.empty()) return e;
  e.mean = std::accumulate(angles.begin(), angles.end(), 0.0) / static_cast<double>(angles.size());
  std::sort(angles.begin(), angles.end());
  e.p99 = angles[std::min(angles.size() - 1, angles.size() * 99 / 100)];
  e.max = angles.back();
  return e;
}

int stressSummary() {
  int failures = 0;
  std::printf("%-40s %-11s %8s %9s %8s %8s %6s %8s %7s %9s %9s\n", "case", "method", "corners", "undefined", "nonfinite", "nonunit",
              "nonorth", "bad w", "reruns", "contained", "ms");
  for (const auto& stressCase : bench::stressCases()) {
    for (Method method : {Method::mikktspace, Method::lengyel, Method::flat}) {
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
  std::ofstream script(dir / "plot.gp");
  std::vector<std::string> methods = {"mikktspace", "lengyel/angle", "lengyel/area", "lengyel/uniform", "flat"};
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
               << methods[m] << "' && $4 == 1 ? $13 : 1/0):5 with linespoints title '" << methods[m]
               << (m >= 5 ? " (peer)" : "") << "'";
      }
      script << "\n";
    }
    script << "unset multiplot\n";
  }
  script.close();
  const std::string command = "gnuplot '" + (dir / "plot.gp").string() + "' 2>&1";
  if (std::system(command.c_str()) != 0) std::cerr << "warning: gnuplot failed; plot.gp is in " << dir << "\n";
}

}  // namespace

int benchCommand(const std::vector<std::string>& args) {
  std::size_t maxTriangles = 1000000;
  int repeats = 3;
  fs::path outDir = "bench-results";
  std::vector<fs::path> assets;
  bool plot = true, stress = false;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    try {
      if (arg == "-h" || arg == "--help") {
        std::cout << kBenchUsage;
        return kExitOk;
      } else if (arg == "--max-triangles" && i + 1 < args.size()) maxTriangles = std::stoul(args[++i]);
      else if (arg == "--repeats" && i + 1 < args.size()) repeats = std::clamp(std::stoi(args[++i]), 1, 100);
      else if (arg == "--out-dir" && i + 1 < args.size()) outDir = args[++i];
      else if (arg == "--assets" && i + 1 < args.size()) assets.emplace_back(args[++i]);
      else if (arg == "--no-plot") plot = false;
      else if (arg == "--stress") stress = true;
      else throw std::invalid_argument(arg);
    } catch (const std::exception&) {
      std::cerr << "tangent bench: bad option '" << arg << "'\n\n" << kBenchUsage;
      return kExitUsage;
    }
  }
  if (stress) return stressSummary();
  if (bench::peers().empty()) std::cerr << "tangent bench: " << bench::peersNote() << "\n";
  if (assets.empty() && fs::is_directory("../shared/assets")) assets.emplace_back("../shared/assets");
  std::error_code ec;
  fs::create_directories(outDir, ec);

  std::ostringstream csv;  // written with the others at the end, each file atomically
  csv << "surface,triangles,method,threads,mean_deg,p99_deg,max_deg,w_errors,corners,build_ms,compute_ms,output_ms,total_ms\n";
  Json results = Json::array();
  // The plot reads a copy sorted by series, so that each series' points are consecutive rows
  // and gnuplot joins them (a filtered-out row in between breaks the line).
  using SeriesKey = std::tuple<std::string, std::string, unsigned, std::size_t>;
  std::vector<std::pair<SeriesKey, std::string>> plotRows;
  std::printf("%-12s %9s %-18s %3s %10s %10s %10s %8s %10s %10s %10s %10s\n", "surface", "triangles", "method", "thr", "mean deg",
              "p99 deg", "max deg", "w errors", "build ms", "compute ms", "output ms", "total ms");
  std::vector<std::size_t> resolutions;
  for (std::size_t r = 100; r <= maxTriangles; r *= 10) resolutions.push_back(r);
  for (const auto& surface : bench::surfaceNames()) {
    for (std::size_t target : resolutions) {
      const bench::AnalyticMesh mesh = bench::makeSurface(surface, target);
      // One row per method: terminal, CSV, JSON, and the plot's rows (kept for sorting).
      auto record = [&](const std::string& label, unsigned threads, const Timing& timing, const Errors& e) {
        std::printf("%-12s %9zu %-18s %3u %10.5f %10.5f %10.5f %8zu %10.2f %10.2f %10.2f %10.2f\n", surface.c_str(), mesh.triangles(),
                    label.c_str(), threads, e.mean, e.p99, e.max, e.wErrors, timing.build, timing.compute, timing.output, timing.total());
        std::ostringstream row;
        row << surface << "," << mesh.triangles() << "," << label << "," << threads << "," << e.mean << "," << e.p99 << "," << e.max << ","
            << e.wErrors << "," << mesh.indices.size() << "," << timing.build << "," << timing.compute << "," << timing.output << ","
            << timing.total() << "\n";
        csv << row.str();
        plotRows.push_back({{surface, label, threads, mesh.triangles()}, row.str()});
        results.push_back({{"surface", surface}, {"triangles", mesh.triangles()}, {"method", label}, {"threads", threads},
                           {"meanDegrees", e.mean}, {"p99Degrees", e.p99}, {"maxDegrees", e.max}, {"wErrors", e.wErrors},
                           {"buildMs", timing.build}, {"computeMs", timing.compute}, {"outputMs", timing.output}});
      };
      const int runs = target >= 1000000 ? std::min(repeats, 3) : repeats;
      for (const Setting& setting : settings()) {
        std::vector<float> corners;
        const Timing timing = timedRun(mesh.arrays(), setting.options, runs, corners);
        record(setting.label, setting.options.threads, timing, compare(corners, mesh.indices, mesh.exactTangents, true));
      }
      // The peers: one call, its time counted as compute.
      for (bench::Peer peer : bench::peers()) {
        std::vector<float> corners;
        const Timing timing = timedPeerRun(peer, mesh.arrays(), UvOrigin::bottomLeft, runs, corners);
        record(std::string(toString(peer)), 1, timing, compare(corners, mesh.indices, mesh.exactTangents, true));
      }
      std::fflush(stdout);
    }
  }

  // Real assets: every normal-mapped primitive, each method against mikktspace.
  Json assetResults = Json::array();
  std::vector<fs::path> files;
  for (const auto& path : assets) {
    if (fs::is_directory(path)) {
      for (const auto& entry : fs::directory_iterator(path))
        if (entry.path().extension() == ".glb" || entry.path().extension() == ".gltf") files.push_back(entry.path());
    } else {
      files.push_back(path);
    }
  }
  std::sort(files.begin(), files.end());
  if (!files.empty())
    std::printf("\n%-28s %-10s %9s %-18s %3s %10s %10s %10s %8s %10s\n", "asset", "primitive", "triangles", "method", "thr", "median deg",
                "p99 deg", "max deg", "w diff", "total ms");
  for (const auto& file : files) {
    gltf::Scene scene;
    try {
      scene = gltf::loadScene(file);
    } catch (const std::exception& e) {
      std::cerr << "warning: " << e.what() << "\n";
      continue;
    }
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
        Timing timing;
      };
      std::vector<Run> runs;
      for (const Setting& setting : settings()) {
        Options options = setting.options;
        options.uvOrigin = UvOrigin::topLeft;
        Run run{setting.label, options.threads, {}, {}};
        run.timing = timedRun(arrays, options, repeats, run.corners);
        runs.push_back(std::move(run));
      }
      for (bench::Peer peer : bench::peers()) {
        Run run{std::string(toString(peer)), 1, {}, {}};
        run.timing = timedPeerRun(peer, arrays, UvOrigin::topLeft, repeats, run.corners);
        runs.push_back(std::move(run));
      }
      for (const Run& run : runs) {
        const std::vector<float>& corners = run.corners;
        const Timing& timing = run.timing;
        const Errors e = compare(corners, identity, reference, false);
        std::vector<double> angles(identity.size());
        for (std::size_t c = 0; c < identity.size(); ++c) angles[c] = angleDegrees(&corners[4 * c], &reference[4 * c]);
        std::sort(angles.begin(), angles.end());
        const double med = angles.empty() ? 0 : angles[angles.size() / 2];
        std::printf("%-28s %-10s %9zu %-18s %3u %10.5f %10.5f %10.5f %8zu %10.2f\n", file.filename().string().c_str(),
                    item.label.substr(item.label.rfind(' ') + 1).c_str(), identity.size() / 3, run.label.c_str(), run.threads, med,
                    e.p99, e.max, e.wErrors, timing.total());
        assetResults.push_back({{"asset", file.filename().string()}, {"primitive", item.label}, {"method", run.label},
                                {"threads", run.threads}, {"medianDegrees", med}, {"p99Degrees", e.p99}, {"maxDegrees", e.max},
                                {"wDifferences", e.wErrors}, {"totalMs", timing.total()}});
      }
    }
  }
  std::sort(plotRows.begin(), plotRows.end());
  std::ostringstream plotCsv;
  for (const auto& [key, row] : plotRows) plotCsv << row;
  Json report = {{"machine", {{"hardwareThreads", std::thread::hardware_concurrency()}}},
                 {"repeats", repeats},
                 {"analytic", results},
                 {"assetsAgainstMikktspace", assetResults}};
  if (!writeTextOutput((outDir / "bench.csv").string(), csv.str(), "bench") ||
      !writeTextOutput((outDir / "plot.csv").string(), plotCsv.str(), "bench") ||
      !writeTextOutput((outDir / "bench.json").string(), text::dumpJson(report, 2) + "\n", "bench"))
    return kExitInputFailed;
  if (plot) writePlot(outDir, bench::surfaceNames());
  std::printf("\nwrote %s/bench.csv, bench.json%s\n", outDir.string().c_str(), plot ? ", plot.png, plot.svg" : "");
  return kExitOk;
}

}  // namespace tangent::cli
