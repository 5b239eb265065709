// SPDX-License-Identifier: MIT
// Per-triangle tangent directions from edge and UV deltas.
// Source: E. Lengyel, "Computing Tangent Space Basis Vectors for an Arbitrary Mesh", 2001.
// Solving [e1 e2] = [dP/du dP/dv] [du1 du2; dv1 dv2] gives
//   dP/du = (e1 dv2 - e2 dv1) / det,  dP/dv = (e2 du1 - e1 du2) / det,  det = du1 dv2 - du2 dv1.
// Only directions are kept: the sign of det carries the UV orientation, the magnitudes are
// dropped so that tiny or huge UV scales cannot overflow or underflow later sums.
#pragma once

#include <array>
#include <cmath>
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
  bool wantAngles = false; // in: whether the lanes write `angle` (lengyel's angle weighting)
  double angle[3][4];      // out: cornerAngle of lane corner c (the same bits)
  // The lane corner of the triangle's corner k.
  int laneCorner(int lane, int k) const { return (k - start[lane] + 3) % 3; }
  double cornerAngle(int lane, int k) const { return angle[laneCorner(lane, k)][lane]; }
  // The triangle's corner k's position (for its weight), where the triangle is finite.
  Vec3 position(int lane, int k) const {
    const int c = laneCorner(lane, k);
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
void evaluateTriangleLanes2(TriangleLanes& lanes, int first, TriangleTangent* out);
#if defined(__SSE2__) && defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define TANGENT_DOUBLE_LANES4 1
// The four lanes in AVX2 registers, where the processor has it.
void evaluateTriangleLanes4(TriangleLanes& lanes, TriangleTangent* out);
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
// Method `meshopt`'s corner weights (projectedEdgeWeight, below) of up to four
// triangles in lanes, by lane corner (TriangleLanes' order: lane corner c is the triangle's
// corner (start + c) % 3): in, each corner's unit normal and the triangle's dP/du; out, the
// weight (the same bits as projectedEdgeWeight; 0 where it gives 0).
struct MeshoptLanes {
  double normal[3][3][4];  // lane corner, axis, lane
  double tangent[3][4];
  double weight[3][4];     // lane corner, lane
};
void meshoptWeightLanes(const TriangleLanes& values, MeshoptLanes& lanes, int width);
void meshoptWeightLanes2(const TriangleLanes& values, MeshoptLanes& lanes, int first);
#if defined(TANGENT_DOUBLE_LANES4)
void meshoptWeightLanes4(const TriangleLanes& values, MeshoptLanes& lanes);
#endif

// `width` as triangleTangentsAt's lanes (2 or 4): all four lanes evaluated (a lane past the
// block's triangles is not usable: never framed).
void flatFrameLanes(FlatLanes& lanes, int width);
void flatFrameLanes2(FlatLanes& lanes, int first);
#if defined(TANGENT_DOUBLE_LANES4)
void flatFrameLanes4(FlatLanes& lanes);
#endif

// The angle atan2(y, x) for y >= 0 (a sine's length and a cosine), within 2 ulps of libm's
// (300,000 random pairs: 73% the same bits, the rest 1 ulp off, 0.02% 2), the same bits on
// every platform and vector width: the octant reduction (|x| and y swapped where y > |x|), a
// shift by pi/4 to |t| <= tan(pi/8) (one division either way), and atan's odd series to t^39
// (the next term below 1.2e-17 t) in Estrin's form. Not-a-number where y and x are both 0
// (callers test that case first). triangle_lanes.inc's `angles` is the same in lanes.
inline constexpr double kAtanTanEighthPi = 0.41421356237309503, kAtanQuarterPi = 0.78539816339744831,
                        kAtanHalfPi = 1.5707963267948966, kAtanPi = 3.141592653589793;
// The series' coefficients: (-1)^k / (2k + 1).
constexpr double atanCoefficient(int k) { return (k % 2 ? -1.0 : 1.0) / (2 * k + 1); }
// t + t z P(z), z = t^2, P = sum of atanCoefficient(k) z^(k-1) for k = 1..19, in Estrin's form:
// one statement for the scalar and the lane code (T: double or a vector of them). Always
// inlined and with no call inside: the lanes' copy is then compiled for their instruction set
// (AVX2 inside triangle_tangent_lanes.cpp's target region) even at -O0, never called across it.
template <class T>
[[gnu::always_inline]] inline T atanSeries(T t) {
  constexpr double c1 = atanCoefficient(1), c2 = atanCoefficient(2), c3 = atanCoefficient(3), c4 = atanCoefficient(4),
                   c5 = atanCoefficient(5), c6 = atanCoefficient(6), c7 = atanCoefficient(7), c8 = atanCoefficient(8),
                   c9 = atanCoefficient(9), c10 = atanCoefficient(10), c11 = atanCoefficient(11), c12 = atanCoefficient(12),
                   c13 = atanCoefficient(13), c14 = atanCoefficient(14), c15 = atanCoefficient(15), c16 = atanCoefficient(16),
                   c17 = atanCoefficient(17), c18 = atanCoefficient(18), c19 = atanCoefficient(19);
  const T z = t * t;
  const T a0 = c1 + c2 * z, a1 = c3 + c4 * z, a2 = c5 + c6 * z, a3 = c7 + c8 * z, a4 = c9 + c10 * z, a5 = c11 + c12 * z,
          a6 = c13 + c14 * z, a7 = c15 + c16 * z, a8 = c17 + c18 * z;
  const T z2 = z * z;
  const T b0 = a0 + a1 * z2, b1 = a2 + a3 * z2, b2 = a4 + a5 * z2, b3 = a6 + a7 * z2, b4 = a8 + c19 * z2;
  const T z4 = z2 * z2;
  const T d0 = b0 + b1 * z4, d1 = b2 + b3 * z4;
  const T z8 = z4 * z4;
  const T p = (d0 + d1 * z8) + b4 * (z8 * z8);
  return t + t * (z * p);
}
inline double angleOf(double y, double x) {
  const double ax = std::abs(x);
  const bool steep = y > ax;
  const double num = steep ? ax : y, den = steep ? y : ax;
  const bool shift = num > kAtanTanEighthPi * den;
  const double t = (shift ? num - den : num) / (shift ? num + den : den);
  double r = atanSeries(t) + (shift ? kAtanQuarterPi : 0.0);  // + 0.0 as the lanes add it
  if (steep) r = kAtanHalfPi - r;
  return x < 0 ? kAtanPi - r : r;
}

// Interior angle at corner `corner` (0..2), in radians; 0 for a zero-length edge.
double cornerAngle(const std::array<Vec3, 3>& positions, int corner);

// Method `meshopt`'s corner weight (triangle_tangent.cpp): the angle between corner k's edges
// projected onto the plane of its unit normal, times their projected lengths, over the length
// of the triangle's unit dP/du projected there; 0 where either length is 0 or it is not finite.
double projectedEdgeWeight(const std::array<Vec3, 3>& positions, int k, const Vec3& normal, const Vec3& tangent);

// A unit vector perpendicular to the unit vector n, fixed for a given n.
Vec3 fixedPerpendicular(const Vec3& n);

}  // namespace tangent::detail
