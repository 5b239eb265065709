// SPDX-License-Identifier: MIT
// Per-triangle tangent directions from edge and UV deltas.
// Source: E. Lengyel, "Computing Tangent Space Basis Vectors for an Arbitrary Mesh", 2001.
// Solving [e1 e2] = [dP/du dP/dv] [du1 du2; dv1 dv2] gives
//   dP/du = (e1 dv2 - e2 dv1) / det,  dP/dv = (e2 du1 - e1 du2) / det,  det = du1 dv2 - du2 dv1.
// Only directions are kept: the sign of det carries the UV orientation, the magnitudes are
// dropped so that tiny or huge UV scales cannot overflow or underflow later sums.
#pragma once

#include <array>
#include <cstdint>

#include "vec3.hpp"

namespace tangent::detail {

enum class TriangleKind : std::uint8_t { usable, degenerate, zeroUvArea, nonFinite };

struct TriangleTangent {
  Vec3 tangent{0, 0, 0};     // unit dP/du; zero when the UV area is zero
  Vec3 bitangent{0, 0, 0};   // unit dP/dv; zero when the UV area is zero
  Vec3 faceNormal{0, 0, 0};  // unit geometric normal (zero when degenerate, or not asked for)
  double area = 0;           // 3D area
  int orientation = 0;       // sign of the UV area; 0 when tangent is zero
  bool coincident = false;   // two corners share a position exactly (MikkTSpace's "degenerate")
  // usable: non-zero 3D and UV area. degenerate: zero 3D area (coincident or collinear
  // corners); a collinear triangle with distinct corners may still carry tangent directions.
  TriangleKind kind = TriangleKind::degenerate;
};

// What the phases after the triangle pass read of a triangle (lengyel.hpp's TriangleData): its
// directions, UV orientation and kind, kept apart from what only the pass uses (face normal,
// area, coincident corners) so that the stored array is smaller.
struct TriangleTerms {
  Vec3 tangent{0, 0, 0};
  Vec3 bitangent{0, 0, 0};
  int orientation = 0;
  TriangleKind kind = TriangleKind::degenerate;
};

// Evaluates the triangle starting from a canonical corner (the smallest by bit pattern), so
// that rotating the corner order never changes a bit of the result. The face normal (three
// divisions) only where asked for: only a corner with an invalid normal reads it.
TriangleTangent triangleTangent(const std::array<Vec3, 3>& positions, const std::array<Vec2, 3>& uvs,
                                bool wantFaceNormal = true);

// Below this fraction of the operands' magnitude a result is rounding noise (~64 ulps).
constexpr double kTriangleRelativeZero = 1e-14;

// triangleTangent of `count` (up to 4) triangles, the same bits: the arithmetic `lanes`
// triangles at a time in vector registers (4: AVX2, where TANGENT_DOUBLE_LANES4 is defined;
// 2: SSE2 or SIMD128; 1: one triangleTangent each), the corner order and the finite test per
// triangle. wantFaceNormal as triangleTangent's, per triangle.
void triangleTangents(const std::array<Vec3, 3>* positions, const std::array<Vec2, 3>* uvs, const bool* wantFaceNormal,
                      int count, int lanes, TriangleTangent* out);

// Up to four triangles as the lanes read them: each turned to start at its canonical corner,
// values by corner, axis and lane (triangle_tangent_lanes.cpp).
struct TriangleLanes {
  double p[3][3][4];
  double t[3][2][4];
  bool active[4];          // finite: the lanes write its result (the others are written before)
  bool wantFaceNormal[4];
};
// Lanes first and first + 1 into out[first], out[first + 1].
void evaluateTriangleLanes2(const TriangleLanes& lanes, int first, TriangleTangent* out);
#if defined(__SSE2__) && defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define TANGENT_DOUBLE_LANES4 1
// The four lanes in AVX2 registers, where the processor has it.
void evaluateTriangleLanes4(const TriangleLanes& lanes, TriangleTangent* out);
#endif

// Interior angle at corner `corner` (0..2), in radians; 0 for a zero-length edge.
double cornerAngle(const std::array<Vec3, 3>& positions, int corner);

// A unit vector perpendicular to the unit vector n, fixed for a given n.
Vec3 fixedPerpendicular(const Vec3& n);

}  // namespace tangent::detail
