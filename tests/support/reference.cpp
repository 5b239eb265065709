// SPDX-License-Identifier: MIT
#include "reference.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <random>

namespace tangent::testing {

CornerArrays deindex(const std::string& name, const MeshArrays& mesh) {
  CornerArrays out;
  out.name = name;
  for (std::uint32_t v : mesh.indices) {
    out.positions.insert(out.positions.end(), &mesh.positions[3 * v], &mesh.positions[3 * v + 3]);
    out.normals.insert(out.normals.end(), &mesh.normals[3 * v], &mesh.normals[3 * v + 3]);
    out.uvs.insert(out.uvs.end(), &mesh.uvs[2 * v], &mesh.uvs[2 * v + 2]);
  }
  return out;
}

std::vector<std::vector<float>> referenceTangents(const std::vector<CornerArrays>& meshes) {
  namespace fs = std::filesystem;
  const fs::path script = fs::path(TANGENT_SOURCE_DIR) / "tests" / "node" / "mikktspace_reference.mjs";
  const fs::path package = fs::path(TANGENT_SOURCE_DIR) / "tests" / "node" / "node_modules" / "mikktspace";
  std::vector<std::vector<float>> results(meshes.size());
  if (!fs::is_directory(package)) {
    ADD_FAILURE() << "npm package mikktspace missing: run scripts/test.sh (npm ci in tests/node)";
    return {};
  }
  std::random_device random;
  const fs::path dir = fs::temp_directory_path() / ("libtangent-reference-" + std::to_string(random()));
  fs::create_directories(dir);
  std::string command = "node '" + script.string() + "'";
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    const CornerArrays& mesh = meshes[m];
    const std::uint32_t n = static_cast<std::uint32_t>(mesh.positions.size() / 3);
    std::ofstream in(dir / ("in" + std::to_string(m)), std::ios::binary);
    in.write(reinterpret_cast<const char*>(&n), 4);
    in.write(reinterpret_cast<const char*>(mesh.positions.data()), static_cast<std::streamsize>(mesh.positions.size() * 4));
    in.write(reinterpret_cast<const char*>(mesh.normals.data()), static_cast<std::streamsize>(mesh.normals.size() * 4));
    in.write(reinterpret_cast<const char*>(mesh.uvs.data()), static_cast<std::streamsize>(mesh.uvs.size() * 4));
    command += " '" + (dir / ("in" + std::to_string(m))).string() + "' '" + (dir / ("out" + std::to_string(m))).string() + "'";
  }
  const int status = std::system(command.c_str());
  if (status != 0) {
    ADD_FAILURE() << "reference MikkTSpace failed: " << command;
    results.clear();
  } else {
    for (std::size_t m = 0; m < meshes.size(); ++m) {
      std::ifstream out(dir / ("out" + std::to_string(m)), std::ios::binary);
      std::vector<char> bytes(std::istreambuf_iterator<char>(out), {});
      results[m].resize(bytes.size() / 4);
      std::memcpy(results[m].data(), bytes.data(), results[m].size() * 4);
      EXPECT_EQ(results[m].size(), meshes[m].positions.size() / 3 * 4) << meshes[m].name;
    }
    // A short answer fails the test above; callers then see no results rather than index past one.
    for (std::size_t m = 0; m < meshes.size(); ++m) {
      if (results[m].size() != meshes[m].positions.size() / 3 * 4) results.clear();
      if (results.empty()) break;
    }
  }
  std::error_code ec;
  fs::remove_all(dir, ec);
  return results;
}

std::string Agreement::describe() const {
  char text[400];
  std::snprintf(text, sizeof text,
                "%zu corners, %zu compared: median %.5f deg, p99 %.5f deg, max %.5f deg, w mismatches %zu; "
                "reference zero/non-finite %zu; reference arbitrary (ours substituted) %zu (%zu differ)",
                corners, compared, medianDegrees, p99Degrees, maxDegrees, wMismatches, referenceZero, ourFallback,
                fallbackDisagreeing);
  return text;
}

Agreement compareWithReference(std::span<const float> ours, std::span<const float> reference,
                               std::span<const FrameSource> sources, bool negateW) {
  Agreement a;
  a.corners = ours.size() / 4;
  std::vector<double> angles;
  for (std::size_t c = 0; c < a.corners && 4 * c + 3 < reference.size(); ++c) {
    const float* t = &ours[4 * c];
    const float* r = &reference[4 * c];
    const double referenceLength = std::sqrt(double(r[0]) * r[0] + double(r[1]) * r[1] + double(r[2]) * r[2]);  // zero test
    if (!(referenceLength > 0) || !std::isfinite(referenceLength) || !std::isfinite(r[3])) {
      ++a.referenceZero;
      continue;
    }
    // atan2 of |a x b| and a.b: acos of a dot product near 1 turns float rounding into 0.01 degrees.
    const double u[3] = {t[0], t[1], t[2]}, v[3] = {r[0], r[1], r[2]};
    const double cross[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    const double sine = std::sqrt(cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]);
    const double angle = std::atan2(sine, u[0] * v[0] + u[1] * v[1] + u[2] * v[2]) * 180.0 / M_PI;
    const float referenceW = negateW ? -r[3] : r[3];
    if (!sources.empty() && (sources[c] == FrameSource::neighbour || sources[c] == FrameSource::fixed)) {
      ++a.ourFallback;
      if (angle > 0.01 || referenceW != t[3]) ++a.fallbackDisagreeing;
      continue;
    }
    ++a.compared;
    angles.push_back(angle);
    if (referenceW != t[3]) ++a.wMismatches;
  }
  if (!angles.empty()) {
    std::sort(angles.begin(), angles.end());
    a.medianDegrees = angles[angles.size() / 2];
    a.p99Degrees = angles[std::min(angles.size() - 1, angles.size() * 99 / 100)];
    a.maxDegrees = angles.back();
  }
  return a;
}

}  // namespace tangent::testing
