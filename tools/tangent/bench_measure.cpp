// SPDX-License-Identifier: MIT
// Timing and error measurement for `tangent bench` (bench_parts.hpp).
#include <algorithm>
#include <cmath>
#include <iostream>
#include <numeric>

#include "bench_parts.hpp"
#include "peak_memory.hpp"

namespace tangent::cli::measure {

namespace fs = std::filesystem;

namespace {

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

double millisecondsSince(Clock::time_point start) { return std::chrono::duration<double, std::milli>(Clock::now() - start).count(); }

std::optional<double> perTriangle(std::optional<std::size_t> bytes, const MeshArrays& mesh) {
  const std::size_t triangles = mesh.indices.size() / 3;
  if (!bytes || triangles == 0) return std::nullopt;
  return static_cast<double>(*bytes) / static_cast<double>(triangles);
}

}  // namespace

std::optional<double> peakBytesPerTriangle(const MeshArrays& mesh, const Options& options, std::vector<float>& cornerTangents) {
  if (threadCount(options) != 1) return std::nullopt;
  cornerTangents.resize(mesh.indices.size() * 4);
  return perTriangle(bench::peakResidentGrowth([&] {
                       TangentWorkspace workspace;  // the call's own, as a first call in a process has
                       computeCornerTangents(mesh, CornerOutputs{cornerTangents}, options, workspace);
                     }),
                     mesh);
}

std::optional<double> peerPeakBytesPerTriangle(bench::Peer peer, const MeshArrays& mesh, std::vector<float>& cornerTangents) {
  cornerTangents.resize(mesh.indices.size() * 4);
  return perTriangle(bench::peakResidentGrowth([&] { bench::runPeer(peer, mesh, cornerTangents); }), mesh);
}

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

double timedRun(const MeshArrays& mesh, const Options& options, int repeats, std::vector<float>& cornerTangents,
                std::vector<FrameSource>* sources) {
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

Errors compare(const std::vector<float>& corners, const std::vector<std::uint32_t>& indices, const std::vector<float>& reference,
               bool referencePerVertex, const std::vector<std::uint8_t>* compared) {
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

}  // namespace tangent::cli::measure
