// SPDX-License-Identifier: MIT
// `tangent bench`: error against run time. Analytic surfaces with exact tangents at several
// resolutions, every method and setting, 1 and 2 threads, and the peers (reference MikkTSpace
// in C, meshoptimizer in both modes) when built with them; real assets against mikktspace;
// the stress suite with --stress; with --peers, every method and peer against the reference C.
// Table on the terminal, CSV and JSON files, and a log-log plot of error against run time drawn
// by gnuplot (PNG and SVG). The library is timed through its plain-array entry point, the call
// users make.
#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <numeric>
#include <optional>
#include <sstream>
#include <tuple>
#include <thread>

#include "analytic_surfaces.hpp"
#include "tangent/arguments.hpp"
#include "commands.hpp"
#include "peers.hpp"
#include "stress_cases.hpp"
#include "tangent/gltf.hpp"
#include "tangent/scene.hpp"

namespace tangent::cli {

using options::Arguments;
using options::parseArguments;
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using Json = nlohmann::ordered_json;

// A file's scene, or a warning naming it and nothing (the bench goes on with the others). Its
// geometry only: the bench runs no check.
std::optional<gltf::Scene> loadSceneOrWarn(const fs::path& file) {
  try {
    gltf::SceneOptions options;
    options.judge = false;
    return gltf::loadScene(file, options);
  } catch (const std::exception& e) {
    std::cerr << "warning: " << e.what() << "\n";
    return std::nullopt;
  }
}

const char* kBenchUsageHead =
    "usage: tangent bench [options]\n"
    "\n"
    "Error against run time of every method on analytic surfaces (exact tangents known) from\n"
    "about 1e2 to --max-triangles triangles, and agreement with mikktspace on real assets. When\n"
    "built with ../shared/peers, the reference MikkTSpace in C and meshoptimizer (compatible and\n"
    "default modes) are measured on the same arrays and drawn on the same axes. The library is\n"
    "timed through computeCornerTangents on plain arrays, each call with its own workspace (as the\n"
    "peers allocate theirs): the median of --repeats calls.\n"
    "\n";

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
    add("meshopt", Method::meshopt, Weighting::angle);
  }
  return out;
}

double angleDegrees(const float* a, const float* b) {
  const double cross[3] = {double(a[1]) * b[2] - double(a[2]) * b[1], double(a[2]) * b[0] - double(a[0]) * b[2],
                           double(a[0]) * b[1] - double(a[1]) * b[0]};
  const double sine = std::sqrt(cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]);
  return std::atan2(sine, double(a[0]) * b[0] + double(a[1]) * b[1] + double(a[2]) * b[2]) * 180.0 / M_PI;
}

struct Errors {
  double mean = 0, p99 = 0, max = 0;
  std::size_t wErrors = 0;
};

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

double millisecondsSince(Clock::time_point start) { return std::chrono::duration<double, std::milli>(Clock::now() - start).count(); }

// Runs the library the way a caller does: computeCornerTangents on the plain arrays, a
// workspace of its own per call. Milliseconds, the median of `repeats` calls; `sources` (when
// given) receives where each corner's frame came from.
double timedRun(const MeshArrays& mesh, const Options& options, int repeats, std::vector<float>& cornerTangents,
                std::vector<FrameSource>* sources = nullptr) {
  std::vector<double> times;
  cornerTangents.resize(mesh.indices.size() * 4);
  if (sources) sources->resize(mesh.indices.size());
  for (int r = 0; r < repeats; ++r) {
    const auto start = Clock::now();
    computeCornerTangents(mesh, cornerTangents, options, sources ? std::span<FrameSource>(*sources) : std::span<FrameSource>());
    times.push_back(millisecondsSince(start));
  }
  return median(times);
}

// A peer (reference MikkTSpace in C, meshoptimizer) on the same arrays: milliseconds, the
// median of `repeats` calls. Its w is in the bottom-left convention; tangent::handedness turns
// it into uvOrigin's.
double timedPeerRun(bench::Peer peer, const MeshArrays& mesh, UvOrigin uvOrigin, int repeats, std::vector<float>& cornerTangents) {
  std::vector<double> times;
  cornerTangents.resize(mesh.indices.size() * 4);
  for (int r = 0; r < repeats; ++r) {
    const auto start = Clock::now();
    bench::runPeer(peer, mesh, cornerTangents);
    times.push_back(millisecondsSince(start));
  }
  for (std::size_t c = 0; c < mesh.indices.size(); ++c) cornerTangents[4 * c + 3] = handedness(cornerTangents[4 * c + 3], uvOrigin);
  return median(times);
}

// Mean, p99 and max angle and w mismatches of `corners` against `reference` (per vertex through
// `indices`, or per corner), over every corner or only those `compared` marks.
Errors compare(const std::vector<float>& corners, const std::vector<std::uint32_t>& indices, const std::vector<float>& reference,
               bool referencePerVertex, const std::vector<std::uint8_t>* compared = nullptr) {
  Errors e;
  std::vector<double> angles;
  angles.reserve(indices.size());
  for (std::size_t c = 0; c < indices.size(); ++c) {
    if (compared && !(*compared)[c]) continue;
    const float* expected = &reference[4 * (referencePerVertex ? indices[c] : c)];
    angles.push_back(angleDegrees(&corners[4 * c], expected));
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

// The files of --assets: each file given, and the .glb/.gltf files of each folder given, sorted.
std::vector<fs::path> assetFiles(const std::vector<fs::path>& assets) {
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
  return files;
}

// ---- --peers: every method and peer against the reference C ----

// One input of the table, indexed as a vertex buffer is: corners with the same position,
// normal and UV bits share a vertex.
struct PeerInput {
  std::string name;
  std::vector<float> positions, normals, uvs;
  std::vector<std::uint32_t> indices;
  MeshArrays arrays() const { return {positions, normals, uvs, indices}; }
};

PeerInput indexByValue(std::string name, const std::vector<float>& positions, const std::vector<float>& normals,
                       const std::vector<float>& uvs) {
  PeerInput input{std::move(name), {}, {}, {}, {}};
  using Key = std::array<std::uint32_t, 8>;
  std::map<Key, std::uint32_t> vertexOf;
  const std::size_t corners = positions.size() / 3;
  input.indices.reserve(corners);
  for (std::size_t c = 0; c < corners; ++c) {
    Key key;
    for (int i = 0; i < 3; ++i) key[i] = std::bit_cast<std::uint32_t>(positions[3 * c + i]);
    for (int i = 0; i < 3; ++i) key[3 + i] = std::bit_cast<std::uint32_t>(normals[3 * c + i]);
    for (int i = 0; i < 2; ++i) key[6 + i] = std::bit_cast<std::uint32_t>(uvs[2 * c + i]);
    const auto [at, added] = vertexOf.try_emplace(key, static_cast<std::uint32_t>(input.positions.size() / 3));
    if (added) {
      input.positions.insert(input.positions.end(), &positions[3 * c], &positions[3 * c] + 3);
      input.normals.insert(input.normals.end(), &normals[3 * c], &normals[3 * c] + 3);
      input.uvs.insert(input.uvs.end(), &uvs[2 * c], &uvs[2 * c] + 2);
    }
    input.indices.push_back(at->second);
  }
  return input;
}

// The generated sphere and torus, then every normal-mapped primitive with UVs of the files.
std::vector<PeerInput> peerInputs(const std::vector<fs::path>& files, std::size_t triangles) {
  std::vector<PeerInput> inputs;
  for (const std::string surface : {"sphere", "torus"}) {
    bench::AnalyticMesh mesh = bench::makeSurface(surface, triangles);
    inputs.push_back({surface + " (generated)", std::move(mesh.positions), std::move(mesh.normals), std::move(mesh.uvs), std::move(mesh.indices)});
  }
  for (const auto& file : files) {
    const std::optional<gltf::Scene> loaded = loadSceneOrWarn(file);
    if (!loaded) continue;
    const gltf::Scene& scene = *loaded;
    for (const auto& item : scene.items) {
      if (!item.hasUvs || item.positions.empty()) continue;
      std::string name = file.filename().string();
      if (scene.items.size() > 1) name += " " + item.label;
      inputs.push_back(indexByValue(std::move(name), item.positions, item.normals, item.uvNormal));
    }
  }
  return inputs;
}

// tangent bench --peers: the error-against-run-time table with the peers as rows. Every run is
// on one thread (the peers have no other), w in MikkTSpace's convention (as the reference C
// writes it); the library's mikktspace at all threads is one more row, for its time.
int peersTable(const std::vector<fs::path>& assets, std::size_t triangles, int repeats, const fs::path& outDir) {
  if (bench::peers().empty()) {
    std::cerr << "tangent bench --peers: the peers are absent, so there is no reference C to compare with: " << bench::peersNote()
              << "\n";
    return kExitInputFailed;
  }
  const std::vector<PeerInput> inputs = peerInputs(assetFiles(assets), triangles);
  std::ostringstream csv;
  csv << "input,triangles,generator,threads,compared_corners,corners,max_deg,p99_deg,w_mismatches,ms\n";
  std::printf("Against the reference MikkTSpace C (mikktspace.c, genTangSpaceDefault), on the corners whose reference frame comes from\n"
              "their own triangles; times are medians of %d calls, one thread unless said.\n\n",
              repeats);
  std::printf("| input | triangles | generator | max deg | p99 deg | w mismatches | ms |\n|---|---:|---|---:|---:|---:|---:|\n");
  for (const PeerInput& input : inputs) {
    const MeshArrays arrays = input.arrays();
    const std::size_t corners = input.indices.size();
    std::vector<float> reference;
    const double referenceMs = timedPeerRun(bench::Peer::referenceMikktspace, arrays, UvOrigin::bottomLeft, repeats, reference);
    // The corners MikkTSpace gives a frame of their own triangles (a fallback frame is arbitrary).
    std::vector<float> scratch;
    std::vector<FrameSource> sources;
    Options probe;
    probe.uvOrigin = UvOrigin::bottomLeft;
    timedRun(arrays, probe, 1, scratch, &sources);
    std::vector<std::uint8_t> compared(corners);
    for (std::size_t c = 0; c < corners; ++c)
      compared[c] = sources[c] == FrameSource::computed || sources[c] == FrameSource::inherited;
    const std::size_t comparedCount = static_cast<std::size_t>(std::count(compared.begin(), compared.end(), 1));
    auto row = [&](const std::string& generator, unsigned threads, const std::optional<Errors>& e, double ms) {
      const std::string label = generator + (threads == 1 ? "" : " (" + std::to_string(threads) + " threads)");
      if (e) {
        std::printf("| %s | %zu | %s | %.3g | %.3g | %zu | %.2f |\n", input.name.c_str(), corners / 3, label.c_str(), e->max, e->p99,
                    e->wErrors, ms);
      } else {
        std::printf("| %s | %zu | %s | - | - | - | %.2f |\n", input.name.c_str(), corners / 3, label.c_str(), ms);
      }
      csv << '"' << input.name << "\"," << corners / 3 << "," << generator << "," << threads << "," << comparedCount << "," << corners << ","
          << (e ? e->max : 0.0) << "," << (e ? e->p99 : 0.0) << "," << (e ? e->wErrors : 0) << "," << ms << "\n";
    };
    row("mikktspace.c (the reference)", 1, std::nullopt, referenceMs);
    for (const Setting& setting : settings()) {
      if (setting.options.threads != 1) continue;
      Options options = setting.options;  // bottom-left: the reference's w
      std::vector<float> ours;
      const double ms = timedRun(arrays, options, repeats, ours);
      row(setting.label, 1, compare(ours, input.indices, reference, false, &compared), ms);
    }
    for (bench::Peer peer : bench::peers()) {
      if (peer == bench::Peer::referenceMikktspace) continue;
      std::vector<float> theirs;
      const double ms = timedPeerRun(peer, arrays, UvOrigin::bottomLeft, repeats, theirs);
      row(std::string(toString(peer)) + " (peer)", 1, compare(theirs, input.indices, reference, false, &compared), ms);
    }
    Options allThreads;
    allThreads.uvOrigin = UvOrigin::bottomLeft;
    std::vector<float> ours;
    const double ms = timedRun(arrays, allThreads, repeats, ours);
    row("mikktspace", threadCount(allThreads), compare(ours, input.indices, reference, false, &compared), ms);
    std::fflush(stdout);
  }
  std::error_code ec;
  fs::create_directories(outDir, ec);
  if (!writeTextOutput((outDir / "peers.csv").string(), csv.str(), "bench")) return kExitInputFailed;
  std::printf("\nwrote %s/peers.csv\n", outDir.string().c_str());
  return kExitOk;
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
  csv << "surface,triangles,method,threads,mean_deg,p99_deg,max_deg,w_errors,corners,ms\n";
  std::printf("%-12s %9s %-18s %3s %10s %10s %10s %8s %10s\n", "surface", "triangles", "method", "thr", "mean deg", "p99 deg",
              "max deg", "w errors", "ms");
  std::vector<std::size_t> resolutions;
  for (std::size_t r = 100; r <= maxTriangles; r *= 10) resolutions.push_back(r);
  for (const auto& surface : bench::surfaceNames()) {
    for (std::size_t target : resolutions) {
      const bench::AnalyticMesh mesh = bench::makeSurface(surface, target);
      // One row per method: terminal, CSV, JSON, and the plot's rows (kept for sorting).
      auto record = [&](const std::string& label, unsigned threads, double ms, const Errors& e) {
        std::printf("%-12s %9zu %-18s %3u %10.5f %10.5f %10.5f %8zu %10.2f\n", surface.c_str(), mesh.triangles(), label.c_str(), threads,
                    e.mean, e.p99, e.max, e.wErrors, ms);
        std::ostringstream row;
        row << surface << "," << mesh.triangles() << "," << label << "," << threads << "," << e.mean << "," << e.p99 << "," << e.max << ","
            << e.wErrors << "," << mesh.indices.size() << "," << ms << "\n";
        csv << row.str();
        out.plotRows.push_back({{surface, label, threads, mesh.triangles()}, row.str()});
        out.rows.push_back({{"surface", surface}, {"triangles", mesh.triangles()}, {"method", label}, {"threads", threads},
                            {"meanDegrees", e.mean}, {"p99Degrees", e.p99}, {"maxDegrees", e.max}, {"wErrors", e.wErrors},
                            {"ms", ms}});
      };
      const int runs = target >= 1000000 ? std::min(repeats, 3) : repeats;
      for (const Setting& setting : settings()) {
        std::vector<float> corners;
        const double ms = timedRun(mesh.arrays(), setting.options, runs, corners);
        record(setting.label, setting.options.threads, ms, compare(corners, mesh.indices, mesh.exactTangents, true));
      }
      // The peers: one call, its time counted as compute.
      for (bench::Peer peer : bench::peers()) {
        std::vector<float> corners;
        const double ms = timedPeerRun(peer, mesh.arrays(), UvOrigin::bottomLeft, runs, corners);
        record(std::string(toString(peer)), 1, ms, compare(corners, mesh.indices, mesh.exactTangents, true));
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
