// SPDX-License-Identifier: MIT
// Camera framing on the triangles `tangent check` flags (tangent/framing.hpp).
#include "tangent/framing.hpp"

#include <algorithm>
#include <cmath>

namespace tangent::gltf {
namespace {

using Vec3 = std::array<float, 3>;

Vec3 transformPoint(const std::array<float, 16>& m, const float* p) {
  return {m[0] * p[0] + m[4] * p[1] + m[8] * p[2] + m[12], m[1] * p[0] + m[5] * p[1] + m[9] * p[2] + m[13],
          m[2] * p[0] + m[6] * p[1] + m[10] * p[2] + m[14]};
}

Vec3 transformDirection(const std::array<float, 16>& m, const float* d) {
  return {m[0] * d[0] + m[4] * d[1] + m[8] * d[2], m[1] * d[0] + m[5] * d[1] + m[9] * d[2],
          m[2] * d[0] + m[6] * d[1] + m[10] * d[2]};
}

// The CornerProblem bits a check sets (check's verdict per corner, tangent/verdict.hpp).
std::uint8_t problemBits(std::optional<CheckId> check) {
  if (!check) return 0xff;
  switch (*check) {
    case CheckId::finite: return kProblemNotFinite;
    case CheckId::unit: return kProblemNotUnit;
    case CheckId::w: return kProblemBadW;
    case CheckId::orthogonal: return kProblemNotOrthogonal;
    case CheckId::handedness: return kProblemHandedness;
    case CheckId::reference: return kProblemFarFromReference;
    default: return 0;
  }
}

}  // namespace

std::vector<std::uint8_t> flaggedTriangles(const DrawItem& item, std::optional<CheckId> check) {
  const std::size_t triangles = item.positions.size() / 9;
  std::vector<std::uint8_t> flagged(triangles, 0);
  if (check == CheckId::wUniform) {
    for (std::size_t t = 0; t < triangles && 12 * t + 11 < item.tangents.size(); ++t) {
      const float* w = &item.tangents[12 * t + 3];
      flagged[t] = w[0] != w[4] || w[0] != w[8];
    }
    return flagged;
  }
  const std::uint8_t bits = problemBits(check);
  for (std::size_t t = 0; t < triangles; ++t)
    for (std::size_t c = 3 * t; c < 3 * t + 3 && c < item.cornerProblems.size(); ++c)
      flagged[t] = flagged[t] || (item.cornerProblems[c] & bits) != 0;
  return flagged;
}

std::optional<Framing> frameTriangles(const DrawItem& item, const std::array<float, 16>& world,
                                      std::span<const std::uint8_t> flagged) {
  const std::size_t triangles = item.positions.size() / 9;
  Framing framing;
  Vec3 lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY}, allLo = lo, allHi = hi, normalSum{0, 0, 0};
  for (std::size_t t = 0; t < triangles; ++t) {
    const bool isFlagged = t < flagged.size() && flagged[t] != 0;
    framing.flaggedTriangles += isFlagged;
    for (std::size_t c = 3 * t; c < 3 * t + 3; ++c) {
      const Vec3 p = transformPoint(world, &item.positions[3 * c]);
      if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) continue;
      for (int a = 0; a < 3; ++a) {
        allLo[a] = std::min(allLo[a], p[a]), allHi[a] = std::max(allHi[a], p[a]);
        if (isFlagged) lo[a] = std::min(lo[a], p[a]), hi[a] = std::max(hi[a], p[a]);
      }
      if (isFlagged && 3 * c + 2 < item.normals.size()) {
        const Vec3 n = transformDirection(world, &item.normals[3 * c]);
        if (std::isfinite(n[0] + n[1] + n[2])) normalSum = {normalSum[0] + n[0], normalSum[1] + n[1], normalSum[2] + n[2]};
      }
    }
  }
  if (!(allLo[0] <= allHi[0])) return std::nullopt;  // no finite position
  if (!(lo[0] <= hi[0])) lo = allLo, hi = allHi, framing.flaggedTriangles = 0;
  const float allRadius = std::hypot(allHi[0] - allLo[0], allHi[1] - allLo[1], allHi[2] - allLo[2]) / 2;
  const float minHalf = kMinFrameShare * allRadius / std::sqrt(3.0f);
  for (int a = 0; a < 3; ++a) {
    const float centre = (lo[a] + hi[a]) / 2, half = std::max((hi[a] - lo[a]) / 2, minHalf);
    framing.lo[a] = centre - half, framing.hi[a] = centre + half;
  }
  // The side to look from (viewer/camera.hpp): front sees +z, back -z, right +x, left -x, top +y, bottom -y.
  const float length = std::hypot(normalSum[0], normalSum[1], normalSum[2]);
  if (length > 0.1f * static_cast<float>(std::max<std::size_t>(framing.flaggedTriangles, 1))) {
    const int axis = static_cast<int>(
        std::max_element(normalSum.begin(), normalSum.end(), [](float a, float b) { return std::abs(a) < std::abs(b); }) -
        normalSum.begin());
    static const char* const sides[3][2] = {{"left", "right"}, {"bottom", "top"}, {"back", "front"}};
    framing.camera = sides[axis][normalSum[axis] > 0];
  }
  return framing;
}

}  // namespace tangent::gltf
