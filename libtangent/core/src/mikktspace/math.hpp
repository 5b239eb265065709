// SPDX-License-Identifier: MIT
// The kernel's arithmetic: a double vector (V3) for the full path's sums, and the reference's
// own float operations (F3; mikktspace.c's vsub, vscale, vdot, Length, Normalize, NotZero) for
// its zero tests, projections and opposite-tangent test, so that they see its roundings.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "../gram_schmidt.hpp"
#include "../workspace.hpp"

namespace tangent::detail::mikk {

struct V3 {
  double x = 0, y = 0, z = 0;
};
inline V3 operator+(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline V3 operator-(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline V3 operator*(V3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
inline double dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline V3 cross(V3 a, V3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline double length(V3 a) { return std::sqrt(dot(a, a)); }
// Whether every component is +0 or -0 (NaN is not zero), without branches.
inline bool isZero(V3 v) {
  return ((bitCast<std::uint64_t>(v.x) | bitCast<std::uint64_t>(v.y) | bitCast<std::uint64_t>(v.z)) << 1) == 0;
}

inline std::size_t nextCorner(std::size_t c) { return c % 3 == 2 ? c - 2 : c + 1; }
inline std::size_t previousCorner(std::size_t c) { return c % 3 == 0 ? c + 2 : c - 1; }

// The reference's float arithmetic, operation for operation (mikktspace.c: vsub, vscale,
// vdot, Length, Normalize, NotZero), so that its zero tests and its opposite-tangent test
// see the same roundings.
struct F3 {
  float x = 0, y = 0, z = 0;
};
inline F3 fsub(F3 a, F3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline F3 fadd(F3 a, F3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline F3 fscale(float s, F3 a) { return {s * a.x, s * a.y, s * a.z}; }
inline float fdot(F3 a, F3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline float flength(F3 a) { return std::sqrt(a.x * a.x + a.y * a.y + a.z * a.z); }
inline bool notZero(float x) { return std::abs(x) > std::numeric_limits<float>::min(); }
inline bool notZero(F3 a) { return notZero(a.x) || notZero(a.y) || notZero(a.z); }
// The reference's projection onto the plane of a (raw) normal, normalized where not zero.
inline F3 referenceProjected(F3 v, F3 n) {
  F3 p = fsub(v, fscale(fdot(n, v), n));
  if (notZero(p)) p = fscale(1 / flength(p), p);
  return p;
}

// Gram-Schmidt of `sum` against the unit normal n; false where nothing of it lies in the
// tangent plane.
inline bool orthonormalize(V3 sum, V3 n, V3& out) {
  const double s[3] = {sum.x, sum.y, sum.z}, unit[3] = {n.x, n.y, n.z};
  double t[3];
  if (!detail::orthonormalize(s, unit, t)) return false;
  out = {t[0], t[1], t[2]};
  return true;
}

inline V3 projected(V3 v, V3 n) { return v - n * dot(n, v); }

}  // namespace tangent::detail::mikk
