// SPDX-License-Identifier: MIT
// Shared by the fuzz targets: a folder holding the base buffer and image (so that relative
// URIs can resolve), and the core's output contract checked on every corner.
#pragma once

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <span>
#include <string>
#include <vector>

#include "tangent/tangent.hpp"

namespace tangent::fuzz {

inline std::filesystem::path assetFolder() {
  const std::filesystem::path folder =
      std::filesystem::temp_directory_path() / ("libtangent-fuzz-" + std::to_string(::getpid()));
  std::filesystem::create_directories(folder);
  std::ofstream(folder / "base.bin", std::ios::binary) << std::string(140, '\0');
  std::ofstream(folder / "tex.png", std::ios::binary) << "not decoded";
  return folder;
}

[[noreturn]] inline void contractBroken(const char* what, std::size_t corner, const float* t) {
  std::fprintf(stderr, "core contract broken at corner %zu: %s (%g %g %g %g)\n", corner, what, t[0], t[1], t[2], t[3]);
  std::abort();
}

// Every corner gets a finite unit tangent, w = +-1, and a vertex of the split.
inline void computeAndCheck(std::span<const float> positions, std::span<const float> normals, std::span<const float> uvs,
                            std::span<const std::uint32_t> corners, Method method, unsigned threads = 1) {
  std::vector<float> tangents(corners.size() * 4, -7.0f);  // garbage: an untouched corner shows
  std::vector<std::uint32_t> cornerVertex(corners.size(), 0xFFFFFFFFu);
  Options options;
  options.method = method;
  options.threads = threads;
  TangentWorkspace workspace;
  const Report report =
      computeCornerTangents(MeshArrays{positions, normals, uvs, corners}, CornerOutputs{tangents, {}, cornerVertex}, options, workspace);
  for (std::size_t c = 0; c < corners.size(); ++c) {
    const float* t = &tangents[4 * c];
    if (!std::isfinite(t[0]) || !std::isfinite(t[1]) || !std::isfinite(t[2])) contractBroken("not finite", c, t);
    const double length = std::sqrt(double(t[0]) * t[0] + double(t[1]) * t[1] + double(t[2]) * t[2]);
    if (std::abs(length - 1.0) > 1e-3) contractBroken("not unit", c, t);
    if (t[3] != 1.0f && t[3] != -1.0f) contractBroken("w not +-1", c, t);
    if (method == Method::mikktspace && cornerVertex[c] >= report.outputVertices) contractBroken("vertex split out of range", c, t);
  }
}

}  // namespace tangent::fuzz
