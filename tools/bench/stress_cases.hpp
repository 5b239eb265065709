// SPDX-License-Identifier: MIT
// Stiff and extreme inputs: generated meshes for every case of the stress suite, and the
// invariants every method must keep on them (run by the tests, summarized by
// `tangent bench --stress`).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "tangent/tangent.hpp"

namespace tangent::bench {

struct StressCase {
  std::string name;
  std::vector<float> positions, normals, uvs;
  std::vector<std::uint32_t> indices;
  // Vertices whose input is broken (NaN/Inf): corners away from them must equal `clean`.
  std::vector<std::uint32_t> brokenVertices;
  const StressCase* clean = nullptr;
  MeshArrays arrays() const { return {positions, normals, uvs, indices}; }
};

std::vector<StressCase> stressCases();

struct StressOutcome {
  std::size_t corners = 0;
  std::size_t notFinite = 0;
  std::size_t notUnit = 0;          // | |xyz| - 1 | > 1e-6
  std::size_t notOrthogonal = 0;    // |dot(T, N)| > 1e-5 where N is a usable normal
  std::size_t badW = 0;             // w not exactly +-1
  std::size_t changedOnRerun = 0;   // bits differ between two runs
  std::size_t changedAwayFromBrokenInput = 0;
  std::size_t undefinedCorners = 0;  // frames substituted (neighbour or fixed), as the report says
  Report report;
  double milliseconds = 0;
  bool passed() const {
    return notFinite == 0 && notUnit == 0 && notOrthogonal == 0 && badW == 0 && changedOnRerun == 0 && changedAwayFromBrokenInput == 0;
  }
};

StressOutcome runStressCase(const StressCase& stressCase, const Options& options);

}  // namespace tangent::bench
