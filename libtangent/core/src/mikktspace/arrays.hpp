// SPDX-License-Identifier: MIT
// The input arrays as the kernel reads them, and the value orders that replace the
// reference's face order (so that no shuffle or corner rotation moves a bit).
#pragma once

#include <array>
#include <cstdint>

#include "../workspace.hpp"
#include "math.hpp"

namespace tangent::detail::mikk {

// Relative size below which a UV determinant or a dP/du is taken as zero: a few float
// roundings, where the reference (float arithmetic) finds exactly zero.
constexpr double kUvZero = 0x1p-22;
// Below this fraction of |e1||e2| a 3D area is rounding noise (report: degenerate).
constexpr double kAreaZero = 1e-14;

struct Arrays {
  const float* positions;
  const float* normals;
  const float* uvs;
  const std::uint32_t* indices;
  std::size_t vertexCount = 0;  // of positions, normals and UVs (0: not known, the lanes take the scalar way)
  V3 position(std::uint32_t v) const { return {positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]}; }
  V3 normal(std::uint32_t v) const { return {normals[3 * v], normals[3 * v + 1], normals[3 * v + 2]}; }
  std::array<std::uint32_t, 8> identityKey(std::uint32_t v) const {
    return {canonicalBits(positions[3 * v]), canonicalBits(positions[3 * v + 1]), canonicalBits(positions[3 * v + 2]),
            canonicalBits(normals[3 * v]),   canonicalBits(normals[3 * v + 1]),   canonicalBits(normals[3 * v + 2]),
            canonicalBits(uvs[2 * v]),       canonicalBits(uvs[2 * v + 1])};
  }
};

// The order in which a triangle picks its first corner: position, then UV bits (+0 and -0
// alike), compared lexicographically and left at the first value that differs (nearly always
// the first).
inline bool shapeBefore(const Arrays& a, std::uint32_t u, std::uint32_t v) {
  for (int i = 0; i < 3; ++i) {
    const std::uint32_t x = canonicalBits(a.positions[3 * u + i]), y = canonicalBits(a.positions[3 * v + i]);
    if (x != y) return x < y;
  }
  for (int i = 0; i < 2; ++i) {
    const std::uint32_t x = canonicalBits(a.uvs[2 * u + i]), y = canonicalBits(a.uvs[2 * v + i]);
    if (x != y) return x < y;
  }
  return false;
}

// First corner (0..2) of triangle t in value order, so that rotations give the same bits.
inline int firstCorner(const Arrays& a, std::size_t t) {
  const std::uint32_t* v = a.indices + 3 * t;
  // Nearly always the first values (x) differ and decide.
  const std::uint32_t x0 = canonicalBits(a.positions[3 * v[0]]), x1 = canonicalBits(a.positions[3 * v[1]]),
                      x2 = canonicalBits(a.positions[3 * v[2]]);
  if (x0 != x1 && x1 != x2 && x0 != x2) {
    const int lower = x1 < x0 ? 1 : 0;
    return x2 < (lower ? x1 : x0) ? 2 : lower;
  }
  int first = shapeBefore(a, v[1], v[0]) ? 1 : 0;
  if (shapeBefore(a, v[2], v[first])) first = 2;
  return first;
}

// Strict order of triangles by value (rotation-free): the order non-manifold edges pair in.
inline bool triangleBefore(const Arrays& a, std::size_t s, std::size_t t) {
  auto sequence = [&](std::size_t tri) {
    std::array<std::array<std::uint32_t, 8>, 3> keys;
    for (int k = 0; k < 3; ++k) keys[k] = a.identityKey(a.indices[3 * tri + k]);
    int first = 0;
    for (int k = 1; k < 3; ++k) {
      if (keys[k] < keys[first]) first = k;
    }
    return std::array<std::array<std::uint32_t, 8>, 3>{keys[first], keys[(first + 1) % 3], keys[(first + 2) % 3]};
  };
  const auto ks = sequence(s), kt = sequence(t);
  if (ks != kt) return ks < kt;
  return s < t;  // exact duplicates: never both paired (see pairBucket)
}

}  // namespace tangent::detail::mikk
