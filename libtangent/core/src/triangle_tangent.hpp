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

// Up to four triangles as the lanes read them: each turned to start at its canonical corner,
// values by corner, axis and lane (triangle_tangent_lanes.cpp).
struct TriangleLanes {
  double p[3][3][4];
  double t[3][2][4];
  bool active[4];          // finite: the lanes write its result (the others are written before)
  bool wantFaceNormal[4];
  int start[4];            // the canonical corner: lane corner c is the triangle's corner (start + c) % 3
  // The triangle's corner k's position (for its weight) where it is finite.
  Vec3 position(int lane, int k) const {
    const int c = (k - start[lane] + 3) % 3;
    return {p[c][0][lane], p[c][1][lane], p[c][2][lane]};
  }
};

// Where triangles are read from: their corners' vertices (indices), each position at its
// vertex's weld representative (weldOf), UVs at the vertex itself.
struct TriangleSource {
  const float* positions;
  const float* uvs;
  const std::uint32_t* indices;
  const std::uint32_t* weldOf;
};

// triangleTangent of triangles first .. first + count - 1 (count up to 4) of `source`, the
// same bits, into out[0 .. count): the arithmetic `lanes` triangles at a time in vector
// registers (4: AVX2, where TANGENT_DOUBLE_LANES4 is defined; 2: SSE2 or SIMD128; 1: one
// triangleTangent each), the finite test and the corner order per triangle on the stored
// floats (their order is their doubles' order). `values` keeps the corners' positions.
void triangleTangentsAt(const TriangleSource& source, std::size_t first, int count, const bool* wantFaceNormal, int lanes,
                        TriangleLanes& values, TriangleTangent* out);

// Lanes first and first + 1 into out[first], out[first + 1].
void evaluateTriangleLanes2(const TriangleLanes& lanes, int first, TriangleTangent* out);
#if defined(__SSE2__) && defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define TANGENT_DOUBLE_LANES4 1
// The four lanes in AVX2 registers, where the processor has it.
void evaluateTriangleLanes4(const TriangleLanes& lanes, TriangleTangent* out);
#endif

// Method `flat`'s frames of up to four triangles' corners, flatTriangleFrames' arithmetic
// (lengyel.hpp) in lanes: in, per lane its triangle's dP/du and dP/dv, whether it is usable,
// its UV side (-1 or 1), and per corner its unit normal; out, per corner its unit tangent, w,
// and whether it got a frame (the same bits as flatTriangleFrames).
struct FlatLanes {
  double tangent[3][4], bitangent[3][4];
  double normal[3][3][4];  // corner, axis, lane
  double uvSide[4];
  bool usable[4];
  double frame[3][3][4];   // corner, axis, lane
  double w[3][4];
  bool framed[3][4];
};
// `width` as triangleTangentsAt's lanes (2 or 4): all four lanes evaluated (a lane past the
// block's triangles is not usable: never framed).
void flatFrameLanes(FlatLanes& lanes, int width);
void flatFrameLanes2(FlatLanes& lanes, int first);
#if defined(TANGENT_DOUBLE_LANES4)
void flatFrameLanes4(FlatLanes& lanes);
#endif

// Interior angle at corner `corner` (0..2), in radians; 0 for a zero-length edge.
double cornerAngle(const std::array<Vec3, 3>& positions, int corner);

// A unit vector perpendicular to the unit vector n, fixed for a given n.
Vec3 fixedPerpendicular(const Vec3& n);

}  // namespace tangent::detail
