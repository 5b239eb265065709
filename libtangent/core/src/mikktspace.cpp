// SPDX-License-Identifier: MIT
// Method `mikktspace` over packed arrays.
// Source: M. S. Mikkelsen, "Simulation of Wrinkled Surfaces Revisited", MSc thesis, 2008, and
// the rules of the reference implementation (mikktspace.h/.c, 2011):
//  * A corner's identity is its (position, normal, UV) value. Triangles with two corners at
//    one position ("coincident") take part in nothing; their corners copy the frame of a
//    corner with the same identity.
//  * Two triangles are neighbours across an edge when its two ends have the same identities
//    on both sides and the edge runs the opposite way. Where more than two triangles share an
//    edge, half-edges are paired greedily in a fixed order (the reference: face order).
//  * A triangle with zero UV area or zero dP/du or dP/dv "groups with any": it adds nothing
//    and takes the UV orientation of the groups that reach it.
//  * A group is the set of corners around one identity connected through neighbour edges
//    between triangles of the same UV orientation. A corner's tangent is the sum, over the
//    triangles of its group whose dP/du and dP/dv are not exactly opposite to its own (the
//    reference's subgroups at its default 180 degree threshold), of dP/du projected onto the
//    normal, normalized and weighted by the corner angle in the tangent plane.
// Where the reference depends on face order or a triangle's first corner we use rules that
// depend on values only, so that no shuffle changes a bit: each triangle is evaluated from its
// smallest corner; non-manifold edges pair in the order of the triangles' values; a zero-UV
// triangle takes the orientation most of its neighbours have (layer by layer outwards from
// oriented triangles, ties +1); a coincident corner copies the heaviest group of its identity;
// exact duplicate triangles share one frame. One triangle never gets mixed w, and no corner is
// left without a frame: FrameSource says where a frame was borrowed or made up.
//
// Layout: a few passes over packed arrays. Weld by hashing and bucket corners by welded
// vertex (counting sort) beside the triangle pass, which needs no weld; then every phase runs
// per triangle or per bucket in parallel (oneTBB); each item's result depends only on the
// input, so any thread count gives the same bits.
// Two paths per bucket. The triangle pass parks each corner's angle-weighted term in its
// output slot (float, eight or four triangles at a time: triangle_lanes.inc); a bucket that
// is one fan (closed or open) of one UV orientation, with every corner in the common case and
// no pair the subgroup rule could split, sums its parked terms rounded to multiples of 2^-40 (exact double sums, so no
// order moves a bit) and writes one frame (fastBucket). Every other bucket takes the full path
// (groupBucket): double-precision angles, sums in value order, the subgroup test, the
// reference's own float sums where terms cancel.
#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string_view>
#include <type_traits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
// GCC on x86-64 also builds the triangle pass for AVX2, chosen at run time (vectorIsa).
#if defined(__SSE2__) && defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define TANGENT_LANES8 1
#include <immintrin.h>
#endif

#include "workspace.hpp"

namespace tangent::detail {
namespace {

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
bool shapeBefore(const Arrays& a, std::uint32_t u, std::uint32_t v) {
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
int firstCorner(const Arrays& a, std::size_t t) {
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

// The group pass's common case, prepared in corner order by the triangle pass: each corner's
// angle-weighted term, parked in its own output slot until the group pass replaces it with
// the frame. Float arithmetic, eight triangles at a time where AVX2 is there, four where SSE2
// is (triangle_lanes.inc); the scalar function does the same operations in the same order, so
// every width gives the same bits.
//
// Slot of corner c: {S.x * angle, S.y * angle, S.z * angle, angle}, S the reference's
// projection of the triangle's dP/du on the corner's raw normal N, angle the corner's angle
// between its edges e1, e2 projected on the plane of N: atan2(|N.A| |N|, |N|^2 (e1.e2) -
// (N.e1)(N.e2)), A = e1 x e2 (from the corner's own edges, so that a rotation of the
// triangle's corners moves no bit). The low kConeBits of the angle's bits say on which side
// of +-kConeMargin each component of S and of the projected dP/dv (as a direction) lies; 0
// where the corner is not the common case (then its bucket takes the full path).
constexpr std::uint32_t kConeBits = 0xFFF;
constexpr float kConeMargin = 1.0f / 64, kConeMargin2 = kConeMargin * kConeMargin;
constexpr float kQuarterPiF = 0.785398163f, kHalfPiF = 1.57079633f, kPiF = 3.14159265f;
constexpr float kSmallestAngle = 0.1f;      // below (or within this of pi) the full path's rules apply
constexpr float kSmallestProduct = 1e-30f;  // below, float products lose digits
constexpr float kSmallestNormal2 = 1e-20f;  // |N|^2 below: the full path

// atan2(y, x) for y >= 0 in float: the double angleBetween's reduction and series.
inline float angleBetweenFloat(float y, float x) {
  const float ax = std::abs(x);
  const bool steep = y > ax;
  const float num = steep ? ax : y, den = steep ? y : ax;
  const bool shift = num > 0.414213562f * den;
  const float t = (shift ? num - den : num) / (shift ? num + den : den);
  const float t2 = t * t, t4 = t2 * t2, t8 = t4 * t4;
  const float p01 = 1.0f - t2 * (1.0f / 3), p23 = 1.0f / 5 - t2 * (1.0f / 7), p45 = 1.0f / 9 - t2 * (1.0f / 11),
              p67 = 1.0f / 13 - t2 * (1.0f / 15);
  float r = t * ((p01 + t4 * p23) + t8 * (p45 + t4 * p67));
  r = r + (shift ? kQuarterPiF : 0.0f);
  if (steep) r = kHalfPiF - r;
  return x < 0 ? kPiF - r : r;
}

// Which side of +-kConeMargin each component of v / |v| lies on (two bits per component),
// without the division: v.i^2 against kConeMargin^2 |v|^2.
inline std::uint32_t coneBits(F3 v) {
  const float bound = kConeMargin2 * fdot(v, v);
  auto side = [&](float x) { return x * x > bound ? (x > 0 ? 1u : 2u) : 0u; };
  return side(v.x) | side(v.y) << 2 | side(v.z) << 4;
}

// Three floats of p at vertex v (a position or a normal), as the reference reads them.
inline F3 floatsAt(const float* p, std::uint32_t v) {
  return F3{p[3 * std::size_t(v)], p[3 * std::size_t(v) + 1], p[3 * std::size_t(v) + 2]};
}

// The reference's corner angle (EvalTspace; Kernel::referenceAngle for a corner): float
// projections of the edges on the raw normal, float cosine clamped to [-1, 1], acos. The
// weight of a corner outside [kSmallestAngle, pi - kSmallestAngle], as in the full path, where
// the reference's rounding moves small angles by a visible fraction.
inline float referenceAngleOf(F3 here, F3 previous, F3 next, F3 raw) {
  const F3 toPrevious = referenceProjected(fsub(previous, here), raw);
  const F3 toNext = referenceProjected(fsub(next, here), raw);
  const float cosine = std::clamp(fdot(toPrevious, toNext), -1.0f, 1.0f);
  return static_cast<float>(std::acos(static_cast<double>(cosine)));
}

// The parked terms of triangle t's three corners (frame: its dP/du, dP/dv; flags: its bits).
void cornerTermsOne(const Arrays& a, std::size_t t, const float* frame, std::uint8_t flags, float* tangents) {
  const std::uint32_t* triangle = a.indices + 3 * t;
  const F3 p[3] = {floatsAt(a.positions, triangle[0]), floatsAt(a.positions, triangle[1]),
                   floatsAt(a.positions, triangle[2])};
  const F3 e01 = fsub(p[1], p[0]), e02 = fsub(p[2], p[0]), e12 = fsub(p[2], p[1]);
  // Corner k's edges to its previous and next corners, and their dot product.
  const F3 toPrevious[3] = {e02, fscale(-1.0f, e01), fscale(-1.0f, e12)};
  const F3 toNext[3] = {e01, e12, fscale(-1.0f, e02)};
  const float edgeDot[3] = {fdot(e02, e01), -fdot(e01, e12), fdot(e12, e02)};
  for (int k = 0; k < 3; ++k) {
    const F3 raw = floatsAt(a.normals, triangle[k]);
    const float normal2 = fdot(raw, raw);
    const F3 e1 = toPrevious[k], e2 = toNext[k];
    const F3 area{e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z, e1.x * e2.y - e1.y * e2.x};
    const float y = std::abs(fdot(raw, area)) * std::sqrt(normal2);
    const float x = normal2 * edgeDot[k] - fdot(raw, toPrevious[k]) * fdot(raw, toNext[k]);
    float angle = angleBetweenFloat(y, x);
    const F3 s = referenceProjected({frame[0], frame[1], frame[2]}, raw);
    const F3 tv{frame[3], frame[4], frame[5]};
    const F3 projectedT = fsub(tv, fscale(fdot(raw, tv), raw));
    const bool common = flags == 0 && normal2 >= kSmallestNormal2 && y - y == 0 && x - x == 0 &&
                        std::max(y, std::abs(x)) >= kSmallestProduct && notZero(s);
    if (common && !(angle >= kSmallestAngle && angle <= kPiF - kSmallestAngle))
      angle = referenceAngleOf(p[k], p[(k + 2) % 3], p[(k + 1) % 3], raw);
    const bool usable = common && angle > 0;
    const std::uint32_t cone = usable ? coneBits(s) | coneBits(projectedT) << 6 : 0;
    float* slot = tangents + 4 * (3 * t + k);
    slot[0] = s.x * angle, slot[1] = s.y * angle, slot[2] = s.z * angle;
    slot[3] = bitCast<float>((bitCast<std::uint32_t>(angle) & ~kConeBits) | cone);
  }
}

// Unit dP/du and dP/dv of triangle t (signed by the UV orientation), its orientation and
// flags. The reference's float formulas (eq. 18, 19 of its source) from the triangle's first
// corner in value order; where float under- or overflows on a triangle that double
// arithmetic resolves (denormal or huge coordinates), the double result.
void evaluateTriangle(const Arrays& a, std::size_t t, float* frame, std::int8_t& orientation, std::uint8_t& flags) {
  const int first = firstCorner(a, t);
  const std::uint32_t* triangle = a.indices + 3 * t;
  const std::uint32_t rotated[5] = {triangle[0], triangle[1], triangle[2], triangle[0], triangle[1]};
  F3 pf[3];
  float uf[3], vf[3];
  for (int k = 0; k < 3; ++k) {
    const std::uint32_t vertex = rotated[first + k];
    pf[k] = {a.positions[3 * vertex], a.positions[3 * vertex + 1], a.positions[3 * vertex + 2]};
    uf[k] = a.uvs[2 * vertex];
    vf[k] = a.uvs[2 * vertex + 1];
  }
  std::fill(frame, frame + 6, 0.0f);
  orientation = 0;
#if defined(__SSE2__)
  // Four lanes at a time: x - x is 0 where x is finite (NaN where not); equal positions
  // compare equal in all lanes (the fourth holds 0 in both).
  const __m128 p0 = _mm_setr_ps(pf[0].x, pf[0].y, pf[0].z, 0), p1 = _mm_setr_ps(pf[1].x, pf[1].y, pf[1].z, 0),
               p2 = _mm_setr_ps(pf[2].x, pf[2].y, pf[2].z, 0);
  const __m128 uv01 = _mm_setr_ps(uf[0], vf[0], uf[1], vf[1]), uv2 = _mm_setr_ps(uf[2], vf[2], 0, 0);
  auto zeroIfFinite = [](__m128 x) { return _mm_sub_ps(x, x); };
  const __m128 finite = _mm_add_ps(_mm_add_ps(zeroIfFinite(p0), zeroIfFinite(p1)),
                                   _mm_add_ps(zeroIfFinite(p2), _mm_add_ps(zeroIfFinite(uv01), zeroIfFinite(uv2))));
  const bool allFinite = _mm_movemask_ps(_mm_cmpeq_ps(finite, _mm_setzero_ps())) == 0xF;
  auto same = [](__m128 x, __m128 y) { return _mm_movemask_ps(_mm_cmpeq_ps(x, y)) == 0xF; };
#else
  bool allFinite = true;
  for (int k = 0; k < 3; ++k) {
    allFinite = allFinite && std::isfinite(pf[k].x) && std::isfinite(pf[k].y) && std::isfinite(pf[k].z) &&
                std::isfinite(uf[k]) && std::isfinite(vf[k]);
  }
  auto same = [](F3 x, F3 y) { return (x.x == y.x) & (x.y == y.y) & (x.z == y.z); };
  const F3 &p0 = pf[0], &p1 = pf[1], &p2 = pf[2];
#endif
  if (!allFinite) {
    flags = kNonFinite | kGroupWithAny;
    return;
  }
  flags = 0;
  const bool coincident = same(p0, p1) | same(p1, p2) | same(p0, p2);
  const V3 p[3] = {{pf[0].x, pf[0].y, pf[0].z}, {pf[1].x, pf[1].y, pf[1].z}, {pf[2].x, pf[2].y, pf[2].z}};
  const V3 e1 = p[1] - p[0], e2 = p[2] - p[0];
  if (!(dot(cross(e1, e2), cross(e1, e2)) > kAreaZero * kAreaZero * dot(e1, e1) * dot(e2, e2))) flags |= kFlat;
  if (coincident) {
    flags |= kCoincident;
    return;
  }

  // The reference, in float.
  const float t21x = uf[1] - uf[0], t21y = vf[1] - vf[0], t31x = uf[2] - uf[0], t31y = vf[2] - vf[0];
  const F3 d1 = fsub(pf[1], pf[0]), d2 = fsub(pf[2], pf[0]);
  const float signedArea = t21x * t31y - t21y * t31x;
  F3 vOs = fsub(fscale(t31y, d1), fscale(t21y, d2));
  F3 vOt = fadd(fscale(-t31x, d1), fscale(t21x, d2));
  bool usable = false;
  if (notZero(signedArea)) {
    const float absArea = std::abs(signedArea);
    const float lengthS = flength(vOs), lengthT = flength(vOt);
    const float sign = signedArea > 0 ? 1.0f : -1.0f;
    if (notZero(lengthS)) vOs = fscale(sign / lengthS, vOs);
    if (notZero(lengthT)) vOt = fscale(sign / lengthT, vOt);
    usable = notZero(lengthS / absArea) && notZero(lengthT / absArea) && std::isfinite(lengthS) && std::isfinite(lengthT);
  }
  if (usable) {
    orientation = signedArea > 0 ? 1 : -1;
    const float values[6] = {vOs.x, vOs.y, vOs.z, vOt.x, vOt.y, vOt.z};
    std::copy(values, values + 6, frame);
    return;
  }

  // Float found nothing: trust it unless its terms under- or overflowed.
  const double du1 = double(uf[1]) - uf[0], dv1 = double(vf[1]) - vf[0], du2 = double(uf[2]) - uf[0], dv2 = double(vf[2]) - vf[0];
  const double det = du1 * dv2 - du2 * dv1;
  const double terms = std::abs(du1 * dv2) + std::abs(du2 * dv1);
  const V3 uDirection = e1 * dv2 - e2 * dv1;  // det * dP/du
  const V3 vDirection = e2 * du1 - e1 * du2;  // det * dP/dv
  const double uLength = length(uDirection), vLength = length(vDirection);
  // Float squares lengths: beyond about 1e+-19 they under- or overflow.
  constexpr double kTiny = 1e-18, kHuge = 1e18;
  const bool floatRange = terms > kTiny * kTiny && terms < kHuge * kHuge && uLength > kTiny && uLength < kHuge &&
                          vLength > kTiny && vLength < kHuge && length(e1) < kHuge && length(e2) < kHuge;
  const bool doubleUsable = std::abs(det) > kUvZero * terms &&
                            uLength > kAreaZero * (length(e1) * std::abs(dv2) + length(e2) * std::abs(dv1)) &&
                            vLength > kAreaZero * (length(e2) * std::abs(du1) + length(e1) * std::abs(du2));
  if (!floatRange && doubleUsable) {
    const double sign = det > 0 ? 1.0 : -1.0;
    orientation = det > 0 ? 1 : -1;
    for (int i = 0; i < 3; ++i) {
      frame[i] = static_cast<float>((&uDirection.x)[i] * (sign / uLength));
      frame[3 + i] = static_cast<float>((&vDirection.x)[i] * (sign / vLength));
    }
    return;
  }
  flags |= kGroupWithAny;
  if (!(flags & kFlat)) flags |= kZeroUv;
}

// One triangle the scalar way, for the lanes' leftovers and tails: its orientation and flags,
// and its corners' parked terms (cornerTermsOne), from a frame that is not kept.
void evaluateAndParkOne(const Arrays& a, std::size_t t, std::int8_t& orientation, std::uint8_t& flags, float* tangents) {
  float frame[6];
  evaluateTriangle(a, t, frame, orientation, flags);
  cornerTermsOne(a, t, frame, flags, tangents);
}

#if defined(__SSE2__)
// Four lanes in SSE2 registers.
namespace lanes4 {
using F = __m128;
using I = __m128i;
using D = __m128d;
constexpr int kWidth = 4;
inline F set1(float x) { return _mm_set1_ps(x); }
inline F zeros() { return _mm_setzero_ps(); }
inline F add(F x, F y) { return _mm_add_ps(x, y); }
inline F sub(F x, F y) { return _mm_sub_ps(x, y); }
inline F mul(F x, F y) { return _mm_mul_ps(x, y); }
inline F div(F x, F y) { return _mm_div_ps(x, y); }
inline F root(F x) { return _mm_sqrt_ps(x); }
inline F maxF(F x, F y) { return _mm_max_ps(x, y); }
inline F andF(F x, F y) { return _mm_and_ps(x, y); }
inline F orF(F x, F y) { return _mm_or_ps(x, y); }
inline F xorF(F x, F y) { return _mm_xor_ps(x, y); }
inline F andnot(F x, F y) { return _mm_andnot_ps(x, y); }  // ~x & y
inline F select(F mask, F x, F y) { return _mm_or_ps(_mm_and_ps(mask, x), _mm_andnot_ps(mask, y)); }
inline F cmpgt(F x, F y) { return _mm_cmpgt_ps(x, y); }
inline F cmpge(F x, F y) { return _mm_cmpge_ps(x, y); }
inline F cmplt(F x, F y) { return _mm_cmplt_ps(x, y); }
inline F cmple(F x, F y) { return _mm_cmple_ps(x, y); }
inline F cmpeq(F x, F y) { return _mm_cmpeq_ps(x, y); }
inline int movemask(F x) { return _mm_movemask_ps(x); }
inline void store(float* p, F x) { _mm_store_ps(p, x); }
inline F load(const float* p) { return _mm_load_ps(p); }
// Lane j: base[stride * index[j]].
inline F gather(const float* base, std::size_t stride, const std::uint32_t (&index)[kWidth]) {
  return _mm_setr_ps(base[stride * index[0]], base[stride * index[1]], base[stride * index[2]],
                     base[stride * index[3]]);
}
inline I asI(F x) { return _mm_castps_si128(x); }
inline F asF(I x) { return _mm_castsi128_ps(x); }
inline I set1I(std::int32_t x) { return _mm_set1_epi32(x); }
inline I andI(I x, I y) { return _mm_and_si128(x, y); }
inline I orI(I x, I y) { return _mm_or_si128(x, y); }
inline I xorI(I x, I y) { return _mm_xor_si128(x, y); }
inline I andnotI(I x, I y) { return _mm_andnot_si128(x, y); }
inline I cmpeqI(I x, I y) { return _mm_cmpeq_epi32(x, y); }
inline I cmpgtI(I x, I y) { return _mm_cmpgt_epi32(x, y); }
inline I shiftLeft6(I x) { return _mm_slli_epi32(x, 6); }
inline void storeI(std::int32_t* p, I x) { _mm_store_si128(reinterpret_cast<I*>(p), x); }
// All ones in lane j where bit j of bits is set.
inline F laneMask(int bits) {
  return asF(_mm_cmpgt_epi32(_mm_and_si128(_mm_set1_epi32(bits), _mm_setr_epi32(1, 2, 4, 8)), _mm_setzero_si128()));
}
inline D lowHalf(F x) { return _mm_cvtps_pd(x); }
inline D highHalf(F x) { return _mm_cvtps_pd(_mm_movehl_ps(x, x)); }
inline D set1D(double x) { return _mm_set1_pd(x); }
inline D addD(D x, D y) { return _mm_add_pd(x, y); }
inline D subD(D x, D y) { return _mm_sub_pd(x, y); }
inline D mulD(D x, D y) { return _mm_mul_pd(x, y); }
inline D cmpgtD(D x, D y) { return _mm_cmpgt_pd(x, y); }
inline int movemaskD(D x) { return _mm_movemask_pd(x); }
// Corner k's slot of each lane's triangle from its four components in four vectors.
inline void storeSlots(float* tangents, std::size_t t, const int (&first)[kWidth], int k, F c0, F c1, F c2, F c3) {
  _MM_TRANSPOSE4_PS(c0, c1, c2, c3);
  const F slot[4] = {c0, c1, c2, c3};
#pragma GCC unroll 4
  for (int j = 0; j < 4; ++j) _mm_storeu_ps(tangents + 4 * (3 * (t + j) + (first[j] + k) % 3), slot[j]);
}
#include "triangle_lanes.inc"
}  // namespace lanes4
#endif

#if defined(TANGENT_LANES8)
// Eight lanes in AVX2 registers: this code only, compiled for AVX2 (no FMA, so no operation
// is fused) and run where the processor has it (vectorIsa).
#pragma GCC push_options
#pragma GCC target("avx2")
// The lambdas here take and return AVX vectors; they are all inlined in this file, so the
// note that such calls pass them differently without AVX does not apply.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"
namespace lanes8 {
using F = __m256;
using I = __m256i;
using D = __m256d;
constexpr int kWidth = 8;
inline F set1(float x) { return _mm256_set1_ps(x); }
inline F zeros() { return _mm256_setzero_ps(); }
inline F add(F x, F y) { return _mm256_add_ps(x, y); }
inline F sub(F x, F y) { return _mm256_sub_ps(x, y); }
inline F mul(F x, F y) { return _mm256_mul_ps(x, y); }
inline F div(F x, F y) { return _mm256_div_ps(x, y); }
inline F root(F x) { return _mm256_sqrt_ps(x); }
inline F maxF(F x, F y) { return _mm256_max_ps(x, y); }
inline F andF(F x, F y) { return _mm256_and_ps(x, y); }
inline F orF(F x, F y) { return _mm256_or_ps(x, y); }
inline F xorF(F x, F y) { return _mm256_xor_ps(x, y); }
inline F andnot(F x, F y) { return _mm256_andnot_ps(x, y); }  // ~x & y
inline F select(F mask, F x, F y) { return _mm256_or_ps(_mm256_and_ps(mask, x), _mm256_andnot_ps(mask, y)); }
// Ordered, non-signalling: the predicates SSE's cmpgt/cmpge/cmplt/cmple/cmpeq have (false
// where either is NaN).
inline F cmpgt(F x, F y) { return _mm256_cmp_ps(x, y, _CMP_GT_OQ); }
inline F cmpge(F x, F y) { return _mm256_cmp_ps(x, y, _CMP_GE_OQ); }
inline F cmplt(F x, F y) { return _mm256_cmp_ps(x, y, _CMP_LT_OQ); }
inline F cmple(F x, F y) { return _mm256_cmp_ps(x, y, _CMP_LE_OQ); }
inline F cmpeq(F x, F y) { return _mm256_cmp_ps(x, y, _CMP_EQ_OQ); }
inline int movemask(F x) { return _mm256_movemask_ps(x); }
inline void store(float* p, F x) { _mm256_store_ps(p, x); }
inline F load(const float* p) { return _mm256_load_ps(p); }
inline F gather(const float* base, std::size_t stride, const std::uint32_t (&index)[kWidth]) {
  return _mm256_setr_ps(base[stride * index[0]], base[stride * index[1]], base[stride * index[2]],
                        base[stride * index[3]], base[stride * index[4]], base[stride * index[5]],
                        base[stride * index[6]], base[stride * index[7]]);
}
inline I asI(F x) { return _mm256_castps_si256(x); }
inline F asF(I x) { return _mm256_castsi256_ps(x); }
inline I set1I(std::int32_t x) { return _mm256_set1_epi32(x); }
inline I andI(I x, I y) { return _mm256_and_si256(x, y); }
inline I orI(I x, I y) { return _mm256_or_si256(x, y); }
inline I xorI(I x, I y) { return _mm256_xor_si256(x, y); }
inline I andnotI(I x, I y) { return _mm256_andnot_si256(x, y); }
inline I cmpeqI(I x, I y) { return _mm256_cmpeq_epi32(x, y); }
inline I cmpgtI(I x, I y) { return _mm256_cmpgt_epi32(x, y); }
inline I shiftLeft6(I x) { return _mm256_slli_epi32(x, 6); }
inline void storeI(std::int32_t* p, I x) { _mm256_store_si256(reinterpret_cast<I*>(p), x); }
inline F laneMask(int bits) {
  const I bit = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
  return asF(_mm256_cmpgt_epi32(_mm256_and_si256(_mm256_set1_epi32(bits), bit), _mm256_setzero_si256()));
}
inline D lowHalf(F x) { return _mm256_cvtps_pd(_mm256_castps256_ps128(x)); }
inline D highHalf(F x) { return _mm256_cvtps_pd(_mm256_extractf128_ps(x, 1)); }
inline D set1D(double x) { return _mm256_set1_pd(x); }
inline D addD(D x, D y) { return _mm256_add_pd(x, y); }
inline D subD(D x, D y) { return _mm256_sub_pd(x, y); }
inline D mulD(D x, D y) { return _mm256_mul_pd(x, y); }
inline D cmpgtD(D x, D y) { return _mm256_cmp_pd(x, y, _CMP_GT_OQ); }
inline int movemaskD(D x) { return _mm256_movemask_pd(x); }
// A 4x4 transpose in each 128-bit half: lane j's slot in the low half of row j, lane j + 4's
// in its high half.
inline void storeSlots(float* tangents, std::size_t t, const int (&first)[kWidth], int k, F c0, F c1, F c2, F c3) {
  const F l01 = _mm256_unpacklo_ps(c0, c1), h01 = _mm256_unpackhi_ps(c0, c1);
  const F l23 = _mm256_unpacklo_ps(c2, c3), h23 = _mm256_unpackhi_ps(c2, c3);
  const F rows[4] = {
      _mm256_shuffle_ps(l01, l23, _MM_SHUFFLE(1, 0, 1, 0)), _mm256_shuffle_ps(l01, l23, _MM_SHUFFLE(3, 2, 3, 2)),
      _mm256_shuffle_ps(h01, h23, _MM_SHUFFLE(1, 0, 1, 0)), _mm256_shuffle_ps(h01, h23, _MM_SHUFFLE(3, 2, 3, 2))};
#pragma GCC unroll 4
  for (int j = 0; j < 4; ++j) {
    _mm_storeu_ps(tangents + 4 * (3 * (t + j) + (first[j] + k) % 3), _mm256_castps256_ps128(rows[j]));
    _mm_storeu_ps(tangents + 4 * (3 * (t + j + 4) + (first[j + 4] + k) % 3), _mm256_extractf128_ps(rows[j], 1));
  }
}
#include "triangle_lanes.inc"
}  // namespace lanes8
#pragma GCC diagnostic pop
#pragma GCC pop_options
#endif

// Strict order of triangles by value (rotation-free): the order non-manifold edges pair in.
bool triangleBefore(const Arrays& a, std::size_t s, std::size_t t) {
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

// Union-find over the corners of one bucket (local indices), the smaller root winning.
class BucketUnionFind {
 public:
  explicit BucketUnionFind(ScratchVector<std::uint32_t>& parent, std::uint32_t count) : parent_(parent) {
    parent_.resize(count);
    for (std::uint32_t i = 0; i < count; ++i) parent_[i] = i;
  }
  std::uint32_t find(std::uint32_t x) {
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
    return x;
  }
  void unite(std::uint32_t a, std::uint32_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }

 private:
  ScratchVector<std::uint32_t>& parent_;
};

// What pairBucket leaves in a bucket's bucketUniform slot for groupBucket (which then writes
// the slot's own value): whether its links form one chain through all its corners, all
// taking part and none a copy, where the pairing could tell; kOneFan: such a chain whose
// triangles have one UV orientation, where orientations are final at pairing.
constexpr std::uint8_t kNotOneChain = 0, kOneChain = 1, kChainUnknown = 2, kOneFan = 3;
// What groupBucket leaves there: bit 0 (kUniformVertex, see WorkspaceData::bucketUniform), and
// kBucketWeight where the fast path kept the group weight of all the bucket's corners once, in
// the bucket's bucketExtra slot (free between the weld and the output pass), not per corner.
constexpr std::uint8_t kUniformVertex = 1, kBucketWeight = 2;

class Kernel {
 public:
  Kernel(WorkspaceData& ws, const MeshArrays& mesh, const CornerOutputs& outputs, UvOrigin origin)
      : wSign_(handedness(1.0f, origin)),
        ws_(ws),
        mesh_(mesh),
        a_{mesh.positions.data(), mesh.normals.data(), mesh.uvs.data(), mesh.indices.data()},
        tangents_(outputs.tangents.data()) {}

  // Welds and buckets (weldAndBucket), then writes the tangents (w in the convention of the
  // call's UV origin, so that the output pass need not rewrite every tangent) and
  // ws.cornerState, and fills the triangle counts of the report.
  void run(Report& report);

 private:
  std::uint32_t id(std::size_t corner) const { return identity_ ? a_.indices[corner] : vertexId_[a_.indices[corner]]; }
  bool participates(std::size_t corner) const { return !(ws_.triangleFlags[corner / 3] & kCoincident); }
  std::uint32_t localIndex(std::uint32_t bucket, std::uint32_t corner) const {
    const std::uint32_t* begin = corners_ + start_[bucket];
    return static_cast<std::uint32_t>(std::lower_bound(begin, corners_ + start_[bucket + 1], corner) - begin);
  }

  void evaluateTriangles(Report& report);
  void pairBucket(std::uint32_t bucket, BucketScratch& scratch);
  void pairNonManifold(const std::uint32_t* outs, std::size_t outCount, const std::uint32_t* ins, std::size_t inCount);
  void resolveGroupWithAny();
  V3 bucketNormal(std::uint32_t bucket, bool& invalid) const;
  // Adds the bucket's corners with a negative w (as stored) to `mirrored`, copies aside.
  void groupBucket(std::uint32_t bucket, BucketScratch& scratch, std::uint64_t& mirrored);
  bool fastBucket(std::uint32_t bucket, const std::uint32_t* list, std::uint32_t count, std::uint64_t& mirrored);
  // Whether the triangles of a bucket's corners share one UV orientation (with a chain of
  // links through all of them from pairBucket: one group of every corner).
  bool oneOrientation(const std::uint32_t* list, std::uint32_t count) const {
    const std::int8_t orientation = ws_.orientation[list[0] / 3];
    bool same = true;
    for (std::uint32_t i = 1; i < count; ++i) same &= ws_.orientation[list[i] / 3] == orientation;
    return same;
  }
  // Whether the links of a bucket's corners form one cycle through all of them with one UV
  // orientation: the common closed fan around a vertex, one group without a union-find.
  // Links pair distinct half-edges, so a walk of `count` steps back to its start has seen
  // every corner once.
  bool closedFan(const std::uint32_t* list, std::uint32_t count) const {
    const std::uint32_t start = list[0];
    const std::int8_t orientation = ws_.orientation[start / 3];
    std::uint32_t c = start;
    for (std::uint32_t step = 0; step < count; ++step) {
      if (!participates(c) || (ws_.cornerState[c] & kCopy)) return false;
      const std::uint32_t d = ws_.cornerLink[c];
      if (d == kNone || ws_.orientation[d / 3] != orientation) return false;
      c = d;
      if (c == start) return step + 1 == count;
    }
    return false;
  }
  void inheritInBucket(std::uint32_t bucket, std::uint32_t corner, float w, bool anyW);
  void fallbacks();
  // The reference's corner angle (EvalTspace): float projections on the raw normal, float
  // cosine clamped to [-1, 1], acos.
  double referenceAngle(std::size_t corner, F3 rawNormal) const {
    auto at = [&](std::size_t c) { return floatsAt(a_.positions, a_.indices[c]); };
    return referenceAngleOf(at(corner), at(previousCorner(corner)), at(nextCorner(corner)), rawNormal);
  }
  // Once a bucket's groups are built its corners' neighbour links are spent: the same slot
  // then holds the corner's group weight (the sum of its angles), which ranks candidate
  // frames; corners of duplicate triangles keep their link to the original. A fast bucket
  // keeps its one weight per bucket instead (kBucketWeight).
  void setWeight(std::size_t corner, float weight) { ws_.cornerLink[corner] = bitCast<std::uint32_t>(weight); }
  float weight(std::size_t corner) const {
    const std::uint32_t bucket = id(corner);
    return bitCast<float>((ws_.bucketUniform[bucket] & kBucketWeight) ? ws_.bucketExtra[bucket] : ws_.cornerLink[corner]);
  }
  // A frame as stored (xyz, w in the output convention) into the corner's slot, with its source
  // and weight.
  void storeFrame(std::size_t corner, const float (&frame)[4], FrameSource source, float weight) {
    std::memcpy(&tangents_[4 * corner], frame, sizeof frame);
    ws_.cornerState[corner] = static_cast<std::uint8_t>((ws_.cornerState[corner] & ~(kSourceMask | kUndefined)) |
                                                        static_cast<std::uint8_t>(source));
    setWeight(corner, weight);
  }
  void writeCorner(std::size_t corner, V3 tangent, float w, FrameSource source, float weight) {
    const float frame[4] = {static_cast<float>(tangent.x), static_cast<float>(tangent.y), static_cast<float>(tangent.z),
                            w * wSign_};
    storeFrame(corner, frame, source, weight);
  }
  // A bucket whose corners all got one frame: whether they are one input vertex (bucketUniform,
  // so that the vertex split need not compare them), and its mirrored corners counted.
  void finishOneFrame(std::uint32_t bucket, const std::uint32_t* list, std::uint32_t count, std::uint64_t& mirrored) {
    const std::uint32_t vertex = a_.indices[list[0]];
    bool oneVertex = true;
    for (std::uint32_t i = 1; i < count; ++i) oneVertex = oneVertex && a_.indices[list[i]] == vertex;
    ws_.bucketUniform[bucket] = oneVertex ? kUniformVertex : 0;
    if (tangents_[4 * list[0] + 3] < 0) mirrored += count;
  }
  void markUndefined(std::size_t corner, float w) {
    if (!anyUndefined_.load(std::memory_order_relaxed)) anyUndefined_.store(true, std::memory_order_relaxed);
    tangents_[4 * corner + 3] = w * wSign_;
    ws_.cornerState[corner] |= kUndefined;
    setWeight(corner, 0);
  }
  bool defined(std::size_t corner) const {
    const std::uint8_t s = ws_.cornerState[corner];
    if (s & kUndefined) return false;
    const auto source = static_cast<FrameSource>(s & kSourceMask);
    return source == FrameSource::computed || source == FrameSource::inherited;
  }
  // Ranking of a candidate frame: heavier group first, then by value.
  bool betterCandidate(std::size_t a, std::size_t b) const {
    if (weight(a) != weight(b)) return weight(a) > weight(b);
    std::uint32_t bitsA[4], bitsB[4];
    std::memcpy(bitsA, &tangents_[4 * a], 3 * sizeof(float));
    std::memcpy(bitsB, &tangents_[4 * b], 3 * sizeof(float));
    bitsA[3] = bitCast<std::uint32_t>(w(a));
    bitsB[3] = bitCast<std::uint32_t>(w(b));
    return std::lexicographical_compare(bitsB, bitsB + 4, bitsA, bitsA + 4);
  }

  // Every w is stored in the output convention (times wSign_); the rules here compare the
  // reference's own w (bottom-left), read back through w().
  float w(std::size_t corner) const { return tangents_[4 * corner + 3] * wSign_; }

  const float wSign_;
  WorkspaceData& ws_;
  const MeshArrays& mesh_;
  Arrays a_;
  float* tangents_;
  // The weld's and the buckets' arrays, taken once they are filled.
  const std::uint32_t* vertexId_ = nullptr;
  bool identity_ = false;  // the weld merged nothing: id(corner) is the corner's index
  const std::uint32_t* start_ = nullptr;
  const std::uint32_t* corners_ = nullptr;
  std::uint64_t groupWithAny_ = 0;  // triangles that group with any (not coincident)
  std::uint64_t coincident_ = 0;    // coincident triangles
  // Whether any corner was marked undefined, any edge is non-manifold: where not, the passes
  // that look for them are skipped.
  std::atomic<bool> anyUndefined_{false}, anyNonManifold_{false};
  const VectorIsa isa_ = activeVectorIsa();
  // Whether the UV orientations are final when the buckets are paired (no zero-UV triangle
  // waits for its neighbours'), so that pairing may vouch for one orientation.
  bool orientationsFinal_ = false;
};

void Kernel::evaluateTriangles(Report& report) {
  const std::size_t triangleCount = ws_.cornerCount / 3;
  struct Counts {
    std::uint64_t flat = 0, zeroUv = 0, nonFinite = 0, groupWithAny = 0, coincident = 0;
  };
  Combinable<Counts> counts;
  forRange(ws_, triangleCount, 4096, [&](std::size_t begin, std::size_t end) {
    Counts local;
    std::size_t t = begin;
#if defined(TANGENT_LANES8)
    if (isa_ == VectorIsa::avx2) {
      for (; t + 8 <= end; t += 8) {
        lanes8::evaluateLanes(a_, t, &ws_.orientation[t], &ws_.triangleFlags[t], tangents_);
      }
    }
#endif
#if defined(__SSE2__)
    if (isa_ != VectorIsa::scalar) {
      for (; t + 4 <= end; t += 4) {
        lanes4::evaluateLanes(a_, t, &ws_.orientation[t], &ws_.triangleFlags[t], tangents_);
      }
    }
#endif
    for (; t < end; ++t) evaluateAndParkOne(a_, t, ws_.orientation[t], ws_.triangleFlags[t], tangents_);
    for (t = begin; t < end; ++t) {
      if (t + 8 <= end) {  // most triangles have no flags: eight at a time where all are 0
        std::uint64_t eight;
        std::memcpy(&eight, &ws_.triangleFlags[t], sizeof eight);
        if (eight == 0) {
          t += 7;
          continue;
        }
      }
      const std::uint8_t flags = ws_.triangleFlags[t];
      local.flat += (flags & (kFlat | kNonFinite)) == kFlat;
      local.zeroUv += (flags & kZeroUv) != 0;
      local.nonFinite += (flags & kNonFinite) != 0;
      local.groupWithAny += (flags & (kGroupWithAny | kCoincident)) == kGroupWithAny;
      local.coincident += (flags & kCoincident) != 0;
    }
    Counts& total = counts.local();
    total.flat += local.flat;
    total.zeroUv += local.zeroUv;
    total.nonFinite += local.nonFinite;
    total.groupWithAny += local.groupWithAny;
    total.coincident += local.coincident;
  });
  counts.combine_each([&](const Counts& c) {
    report.degenerateTriangles += c.flat;
    report.zeroUvAreaTriangles += c.zeroUv;
    report.nonFiniteTriangles += c.nonFinite;
    groupWithAny_ += c.groupWithAny;
    coincident_ += c.coincident;
  });
}

// Pairs the half-edges at one welded vertex: a corner's outgoing edge (to its next corner)
// with the incoming edge of a corner whose previous corner has the same identity. Marks exact
// duplicate triangles (same identities, same winding) as copies of the first of them.
void Kernel::pairBucket(std::uint32_t bucket, BucketScratch& scratch) {
  const std::uint32_t first = start_[bucket], count = start_[bucket + 1] - first;
  const std::uint32_t* list = corners_ + first;
  auto reset = [&] {
    for (std::uint32_t i = 0; i < count; ++i) {
      ws_.cornerState[list[i]] = 0;
      ws_.cornerLink[list[i]] = kNone;
    }
  };
  if (count < 2) {  // one corner: a chain of one where it takes part
    reset();
    ws_.bucketUniform[bucket] = count == 1 && participates(list[0]) ? kOneChain : kNotOneChain;
    return;
  }
  const std::int8_t firstOrientation = ws_.orientation[list[0] / 3];
  bool oneOrientation = true;
  ws_.bucketUniform[bucket] = kChainUnknown;
  // Most buckets: a few corners whose next identities are all different, each of which is
  // the previous identity of at most one corner. Then no triangle duplicates another here
  // (a duplicate has the same next identity) and no edge has more than one half-edge each
  // way: each outgoing edge pairs with the one incoming edge of its identity, if any (what
  // the sorted merge below finds), with no sort. (Previous identities that no next one
  // matches may repeat: the merge links nothing there either.)
  constexpr std::uint32_t kSmall = 16;
  if (count <= kSmall) {
    alignas(16) std::uint32_t outId[kSmall], inId[kSmall];
    std::uint32_t corner[kSmall];
    std::uint32_t n = 0;
    for (std::uint32_t i = 0; i < count; ++i) {
      const std::uint32_t c = list[i];
      ws_.cornerState[c] = 0;
      if (!participates(c)) {
        ws_.cornerLink[c] = kNone;
        continue;
      }
      oneOrientation &= ws_.orientation[c / 3] == firstOrientation;
      corner[n] = c;
      outId[n] = id(nextCorner(c));
      inId[n] = id(previousCorner(c));
      ++n;
    }
    std::uint32_t match[kSmall];
    std::uint8_t successor[kSmall];  // local index of match[i], kSmall where none
    std::uint32_t targets = 0;       // local indices some link reaches
    bool simple = true;
#if defined(__SSE2__)
    // Lane masks of equal identities, four lanes a compare (8 or 16 lanes, those past n
    // zeroed and masked off).
    const std::uint32_t width = n <= 8 ? 8 : 16;
    for (std::uint32_t j = n; j < width; ++j) outId[j] = inId[j] = 0;
    const std::uint32_t lanes = (std::uint32_t(1) << n) - 1;
    auto masks = [&](auto vectorCount) {
      constexpr int kVectors = decltype(vectorCount)::value;
      __m128i outs[kVectors], ins[kVectors];
      for (int v = 0; v < kVectors; ++v) {
        outs[v] = _mm_load_si128(reinterpret_cast<const __m128i*>(outId + 4 * v));
        ins[v] = _mm_load_si128(reinterpret_cast<const __m128i*>(inId + 4 * v));
      }
      std::uint32_t bad = 0;
      for (std::uint32_t i = 0; i < n; ++i) {
        const __m128i key = _mm_set1_epi32(static_cast<int>(outId[i]));
        std::uint32_t sameOut = 0, sameIn = 0;
        auto laneMask = [&](__m128i lanesOf) {
          return static_cast<std::uint32_t>(_mm_movemask_ps(_mm_castsi128_ps(_mm_cmpeq_epi32(key, lanesOf))));
        };
        for (int v = 0; v < kVectors; ++v) {
          sameOut |= laneMask(outs[v]) << (4 * v);
          sameIn |= laneMask(ins[v]) << (4 * v);
        }
        sameOut &= lanes, sameIn &= lanes;
        bad |= (sameOut ^ (std::uint32_t(1) << i)) | (sameIn & (sameIn - 1));
        match[i] = sameIn ? corner[std::countr_zero(sameIn)] : kNone;
        successor[i] = static_cast<std::uint8_t>(sameIn ? std::countr_zero(sameIn) : kSmall);
        targets |= sameIn;
      }
      return bad == 0;
    };
    simple = width == 8 ? masks(std::integral_constant<int, 2>{}) : masks(std::integral_constant<int, 4>{});
#else
    for (std::uint32_t i = 0; i < n; ++i) {
      std::uint32_t sameOut = 0, sameIn = 0;
      match[i] = kNone;
      successor[i] = kSmall;
      for (std::uint32_t j = 0; j < n; ++j) {
        sameOut += outId[i] == outId[j];
        sameIn += outId[i] == inId[j];
        match[i] = outId[i] == inId[j] ? corner[j] : match[i];
        successor[i] = outId[i] == inId[j] ? static_cast<std::uint8_t>(j) : successor[i];
        targets |= outId[i] == inId[j] ? std::uint32_t(1) << j : 0;
      }
      simple &= (sameOut == 1) & (sameIn <= 1);
    }
#endif
    if (simple) {
      // Each corner has at most one successor and one predecessor here, so the links form
      // paths and cycles. One chain through every corner: a cycle from corner 0, or the
      // path from the one corner that no link reaches (one head: one path; a walk from it
      // that sees every corner: no cycle beside it).
      bool oneChain = false;
      if (n == count) {
        const std::uint32_t heads = ((std::uint32_t(1) << n) - 1) & ~targets;
        if (heads == 0 || (heads & (heads - 1)) == 0) {
          const std::uint32_t start = heads == 0 ? 0 : static_cast<std::uint32_t>(std::countr_zero(heads));
          std::uint32_t k = start, seen = 0;
          do {
            k = successor[k];
            ++seen;
          } while (k != kSmall && k != start && seen < n);
          oneChain = seen == n && (heads == 0 ? k == start : k == kSmall);
        }
      }
      const std::uint8_t chain = !oneChain ? kNotOneChain : (oneOrientation && orientationsFinal_ ? kOneFan : kOneChain);
      ws_.bucketUniform[bucket] = chain;
      // One fan of one orientation is one group whatever its links (groupBucket), and where
      // orientations are final nothing after grouping reads the links of corners that are not
      // copies: those links are not written.
      if (chain != kOneFan) {
        for (std::uint32_t i = 0; i < n; ++i) ws_.cornerLink[corner[i]] = match[i];
      }
      return;
    }
  }
  reset();
  // keys: [0, n) outgoing (next id, corner), [n, 2n) incoming (previous id, corner).
  scratch.keys.resize(2 * count);
  std::uint64_t* outs = scratch.keys.data();
  std::size_t n = 0;
  for (std::uint32_t i = 0; i < count; ++i) {
    const std::uint32_t c = list[i];
    if (!participates(c)) continue;
    outs[n++] = (std::uint64_t(id(nextCorner(c))) << 32) | c;
  }
  std::uint64_t* ins = outs + n;
  for (std::size_t i = 0; i < n; ++i) {
    const auto c = static_cast<std::uint32_t>(outs[i]);
    ins[i] = (std::uint64_t(id(previousCorner(c))) << 32) | c;
  }
  sortSmall(outs, outs + n);
  sortSmall(ins, ins + n);
  // Duplicates: same next and same previous identity.
  for (std::size_t i = 0; i < n;) {
    std::size_t j = i + 1;
    while (j < n && (outs[j] >> 32) == (outs[i] >> 32)) ++j;
    for (std::size_t y = i + 1; y < j; ++y) {
      const auto cy = static_cast<std::uint32_t>(outs[y]);
      for (std::size_t x = i; x < y; ++x) {
        const auto cx = static_cast<std::uint32_t>(outs[x]);
        if (!(ws_.cornerState[cx] & kCopy) && id(previousCorner(cx)) == id(previousCorner(cy))) {
          ws_.cornerState[cy] |= kCopy;
          ws_.anyCopy.store(true, std::memory_order_relaxed);
          ws_.cornerLink[cy] = cx;
          break;
        }
      }
    }
    i = j;
  }
  auto isCopy = [&](std::uint64_t key) { return (ws_.cornerState[static_cast<std::uint32_t>(key)] & kCopy) != 0; };
  std::size_t o = 0, k = 0;
  while (o < n && k < n) {
    const std::uint64_t q = std::min(outs[o] >> 32, ins[k] >> 32);
    std::size_t oEnd = o, kEnd = k;
    while (oEnd < n && (outs[oEnd] >> 32) == q) ++oEnd;
    while (kEnd < n && (ins[kEnd] >> 32) == q) ++kEnd;
    std::size_t outCount = 0, inCount = 0;
    std::uint32_t lastOut = kNone, lastIn = kNone;
    for (std::size_t i = o; i < oEnd; ++i) {
      if (!isCopy(outs[i])) ++outCount, lastOut = static_cast<std::uint32_t>(outs[i]);
    }
    for (std::size_t i = k; i < kEnd; ++i) {
      if (!isCopy(ins[i])) ++inCount, lastIn = static_cast<std::uint32_t>(ins[i]);
    }
    if (outCount == 1 && inCount == 1) {
      ws_.cornerLink[lastOut] = lastIn;
    } else if (outCount > 0 && inCount > 0) {
      scratch.items.clear();
      for (std::size_t i = o; i < oEnd; ++i) {
        if (!isCopy(outs[i])) scratch.items.push_back(static_cast<std::uint32_t>(outs[i]));
      }
      const std::size_t split = scratch.items.size();
      for (std::size_t i = k; i < kEnd; ++i) {
        if (!isCopy(ins[i])) scratch.items.push_back(static_cast<std::uint32_t>(ins[i]));
      }
      const std::uint32_t* items = scratch.items.data();
      pairNonManifold(items, split, items + split, scratch.items.size() - split);
    }
    o = oEnd;
    k = kEnd;
  }
}

// The reference's greedy pairing of the half-edges of one edge, in value order of their
// triangles: each unpaired one takes the first later unpaired one running the other way.
void Kernel::pairNonManifold(const std::uint32_t* outs, std::size_t outCount, const std::uint32_t* ins, std::size_t inCount) {
  struct HalfEdge {
    std::uint32_t corner;
    bool outgoing;
    bool paired;
  };
  std::vector<HalfEdge> halfEdges;
  halfEdges.reserve(outCount + inCount);
  for (std::size_t i = 0; i < outCount; ++i) halfEdges.push_back({outs[i], true, false});
  for (std::size_t i = 0; i < inCount; ++i) halfEdges.push_back({ins[i], false, false});
  std::sort(halfEdges.begin(), halfEdges.end(),
            [&](const HalfEdge& x, const HalfEdge& y) { return triangleBefore(a_, x.corner / 3, y.corner / 3); });
  anyNonManifold_.store(true, std::memory_order_relaxed);
  for (std::size_t i = 0; i < halfEdges.size(); ++i) {
    if (halfEdges[i].outgoing) ws_.cornerState[halfEdges[i].corner] |= 32;  // on a non-manifold edge
    if (halfEdges[i].paired) continue;
    for (std::size_t j = i + 1; j < halfEdges.size(); ++j) {
      if (halfEdges[j].paired || halfEdges[j].outgoing == halfEdges[i].outgoing) continue;
      halfEdges[i].paired = halfEdges[j].paired = true;
      const HalfEdge& out = halfEdges[i].outgoing ? halfEdges[i] : halfEdges[j];
      const HalfEdge& in = halfEdges[i].outgoing ? halfEdges[j] : halfEdges[i];
      ws_.cornerLink[out.corner] = in.corner;
      break;
    }
  }
}

// Orientation of the triangles that group with any (zero UV area): see below.
void Kernel::resolveGroupWithAny() {
  const std::size_t triangleCount = ws_.cornerCount / 3;
  auto open = [&](std::size_t t) {
    return ws_.orientation[t] == 0 && (ws_.triangleFlags[t] & (kGroupWithAny | kCoincident)) == kGroupWithAny &&
           !(ws_.cornerState[3 * t] & kCopy);
  };
  auto neighbour = [&](std::size_t t, int k) -> std::size_t {
    const std::uint32_t link = ws_.cornerLink[3 * t + k];
    return link == kNone ? kNone : link / 3;
  };
  std::vector<std::uint32_t> pending = collectIf(ws_, triangleCount, open);
  if (pending.empty()) return;

  // The reference: a group starts at an oriented triangle's corner and spreads around that
  // one vertex, and the first group to reach a zero-UV triangle gives it its orientation. So
  // the groups that can reach one are those of oriented triangles joined to it around one of
  // its vertices through zero-UV triangles. Where all of them agree, the reference's answer
  // does not depend on face order and we give the same; where they disagree, the majority of
  // the triangle's corners (ties +1).
  {
    constexpr std::uint8_t kReachedMinus = 64, kReachedPlus = 128;
    std::vector<std::uint32_t> buckets;
    for (std::uint32_t t : pending) {
      for (int k = 0; k < 3; ++k) buckets.push_back(id(3 * t + k));
    }
    std::sort(buckets.begin(), buckets.end());
    buckets.erase(std::unique(buckets.begin(), buckets.end()), buckets.end());
    ScratchVector<std::uint32_t> parent;
    std::vector<std::uint8_t> reached;
    for (std::uint32_t bucket : buckets) {
      const std::uint32_t first = start_[bucket], count = start_[bucket + 1] - first;
      const std::uint32_t* list = corners_ + first;
      reached.assign(count, 0);
      BucketUnionFind components(parent, count);
      auto find = [&](std::uint32_t x) { return components.find(x); };
      for (std::uint32_t i = 0; i < count; ++i) {
        const std::uint32_t c = list[i];
        const std::uint32_t d = ws_.cornerLink[c];
        if (!participates(c) || (ws_.cornerState[c] & kCopy) || d == kNone) continue;
        if (open(c / 3) && open(d / 3)) components.unite(i, localIndex(bucket, d));
      }
      for (std::uint32_t i = 0; i < count; ++i) {
        const std::uint32_t c = list[i];
        const std::uint32_t d = ws_.cornerLink[c];
        if (!participates(c) || (ws_.cornerState[c] & kCopy) || d == kNone) continue;
        const bool openC = open(c / 3), openD = open(d / 3);
        if (openC == openD) continue;
        const std::uint32_t gwa = openC ? i : localIndex(bucket, d);
        const std::int8_t o = ws_.orientation[openC ? d / 3 : c / 3];
        if (o != 0) reached[find(gwa)] |= o > 0 ? kReachedPlus : kReachedMinus;
      }
      for (std::uint32_t i = 0; i < count; ++i) {
        if (open(list[i] / 3)) ws_.cornerState[list[i]] |= reached[find(i)];
      }
    }
    std::vector<std::int8_t> orientations(pending.size(), 0);
    for (std::size_t i = 0; i < pending.size(); ++i) {
      int plus = 0, minus = 0;
      for (int k = 0; k < 3; ++k) {
        std::uint8_t& state = ws_.cornerState[3 * pending[i] + k];
        plus += (state & kReachedPlus) != 0;
        minus += (state & kReachedMinus) != 0;
        state &= static_cast<std::uint8_t>(~(kReachedPlus | kReachedMinus));
      }
      if (plus + minus > 0) orientations[i] = minus > plus ? -1 : 1;
    }
    for (std::size_t i = 0; i < pending.size(); ++i) {
      if (orientations[i] != 0) ws_.orientation[pending[i]] = orientations[i];
    }
    std::erase_if(pending, [&](std::uint32_t t) { return !open(t); });
    if (pending.empty()) return;
  }

  // Those no group of the reference reaches: outwards from decided triangles, first across
  // edges, then by the triangles that share a corner's identity.
  // Decides every triangle of `candidates` that has a voter, all from one snapshot.
  std::vector<std::int8_t> decided;
  auto decide = [&](std::vector<std::uint32_t>& candidates, bool byVertex) {
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    decided.assign(candidates.size(), 0);
    for (std::size_t i = 0; i < candidates.size(); ++i) {
      const std::uint32_t t = candidates[i];
      if (!open(t)) continue;
      int votes = 0, voters = 0;
      for (int k = 0; k < 3; ++k) {
        if (!byVertex) {
          const std::size_t other = neighbour(t, k);
          if (other != kNone && ws_.orientation[other] != 0) votes += ws_.orientation[other], ++voters;
          continue;
        }
        const std::uint32_t bucket = id(3 * t + k);
        for (std::uint32_t j = start_[bucket]; j < start_[bucket + 1]; ++j) {
          const std::int8_t o = ws_.orientation[corners_[j] / 3];
          if (o != 0) votes += o, ++voters;
        }
      }
      if (voters > 0) decided[i] = votes < 0 ? -1 : 1;
    }
    std::vector<std::uint32_t> done;
    for (std::size_t i = 0; i < candidates.size(); ++i) {
      if (decided[i] != 0) {
        ws_.orientation[candidates[i]] = decided[i];
        done.push_back(candidates[i]);
      }
    }
    return done;
  };
  auto edgeLayers = [&](std::vector<std::uint32_t> layer) {
    while (!layer.empty()) {
      const std::vector<std::uint32_t> done = decide(layer, false);
      layer.clear();
      for (std::uint32_t t : done) {
        for (int k = 0; k < 3; ++k) {
          const std::size_t other = neighbour(t, k);
          if (other != kNone && open(other)) layer.push_back(static_cast<std::uint32_t>(other));
        }
      }
    }
  };
  edgeLayers(pending);
  for (int round = 0; round < 64; ++round) {
    std::erase_if(pending, [&](std::uint32_t t) { return !open(t); });
    if (pending.empty()) break;
    std::vector<std::uint32_t> candidates = pending;
    const std::vector<std::uint32_t> done = decide(candidates, true);
    if (done.empty()) break;
    std::vector<std::uint32_t> layer;
    for (std::uint32_t t : done) {
      for (int k = 0; k < 3; ++k) {
        const std::size_t other = neighbour(t, k);
        if (other != kNone && open(other)) layer.push_back(static_cast<std::uint32_t>(other));
      }
    }
    edgeLayers(std::move(layer));
  }
}

// The unit normal of a welded vertex; a zero or non-finite one is replaced by the sum of its
// triangles' unit normals (summed in value order), else +z.
V3 Kernel::bucketNormal(std::uint32_t bucket, bool& invalid) const {
  const std::uint32_t first = start_[bucket], last = start_[bucket + 1];
  // The bucket's id is its smallest input vertex, one of its identity: read in bucket order.
  V3 n = a_.normal(bucket);
  n = {n.x == 0 ? 0.0 : n.x, n.y == 0 ? 0.0 : n.y, n.z == 0 ? 0.0 : n.z};
  const double len = length(n);
  invalid = !(len > 0 && std::isfinite(len));
  if (!invalid) return n * (1.0 / len);
  std::vector<std::array<double, 3>> faceNormals;
  for (std::uint32_t i = first; i < last; ++i) {
    const std::size_t t = corners_[i] / 3;
    if (ws_.triangleFlags[t] & (kCoincident | kNonFinite | kFlat)) continue;
    const int f = firstCorner(a_, t);
    const V3 p0 = a_.position(a_.indices[3 * t + f]), p1 = a_.position(a_.indices[3 * t + (f + 1) % 3]),
             p2 = a_.position(a_.indices[3 * t + (f + 2) % 3]);
    const V3 c = cross(p1 - p0, p2 - p0);
    const double l = length(c);
    if (l > 0 && std::isfinite(l)) faceNormals.push_back({c.x / l, c.y / l, c.z / l});
  }
  std::sort(faceNormals.begin(), faceNormals.end());
  V3 sum;
  for (const auto& f : faceNormals) sum = sum + V3{f[0], f[1], f[2]};
  const double sumLength = length(sum);
  if (sumLength > 1e-12 && std::isfinite(sumLength)) return sum * (1.0 / sumLength);
  return {0, 0, 1};
}

inline bool orthonormalize(V3 sum, V3 n, V3& out) {
  const double sumLength = length(sum);
  if (!(sumLength > 0) || !std::isfinite(sumLength)) return false;
  const V3 t = sum - n * dot(n, sum);
  const double l = length(t);
  if (!(l > 1e-12 * sumLength)) return false;
  out = t * (1.0 / l);
  return true;
}

inline V3 projected(V3 v, V3 n) { return v - n * dot(n, v); }

constexpr double kHalfPi = 1.5707963267948966;

// atan2(y, x) for y >= 0 (not both zero), within 2e-8 rad: octant reduction, a shift by
// pi/4 to |t| <= tan(pi/8) (one division either way), then the odd series of atan to t^15,
// evaluated in Estrin's form for a short dependency chain. A fraction of libm's cost.
inline double angleBetween(double y, double x) {
  const double ax = std::abs(x);
  const bool steep = y > ax;
  const double num = steep ? ax : y, den = steep ? y : ax;
  const bool shift = num > 0.41421356237309503 * den;
  const double t = shift ? (num - den) / (num + den) : num / den;
  const double t2 = t * t, t4 = t2 * t2, t8 = t4 * t4;
  constexpr double c3 = 1.0 / 3, c5 = 1.0 / 5, c7 = 1.0 / 7, c9 = 1.0 / 9, c11 = 1.0 / 11, c13 = 1.0 / 13, c15 = 1.0 / 15;
  const double p01 = 1.0 - t2 * c3, p23 = c5 - t2 * c7, p45 = c9 - t2 * c11, p67 = c13 - t2 * c15;
  double r = t * ((p01 + t4 * p23) + t8 * (p45 + t4 * p67));
  if (shift) r += 0.78539816339744831;
  if (steep) r = kHalfPi - r;
  return x < 0 ? 2 * kHalfPi - r : r;
}

// angleBetween of two (y, x) pairs at once, operation for operation the same (IEEE double
// arithmetic in SSE2 lanes rounds as the scalar code does), so the same bits; the selects are
// masks, not branches, which mispredict on the mix of acute and obtuse corners of a fan.
inline void angleBetweenPair(const double y[2], const double x[2], double angle[2]) {
#if defined(__SSE2__)
  const __m128d vy = _mm_loadu_pd(y), vx = _mm_loadu_pd(x);
  auto select = [](__m128d mask, __m128d a, __m128d b) { return _mm_or_pd(_mm_and_pd(mask, a), _mm_andnot_pd(mask, b)); };
  auto constant = [](double c) { return _mm_set1_pd(c); };
  const __m128d ax = _mm_andnot_pd(_mm_set1_pd(-0.0), vx);
  const __m128d steep = _mm_cmpgt_pd(vy, ax);
  const __m128d num = select(steep, ax, vy), den = select(steep, vy, ax);
  const __m128d shift = _mm_cmpgt_pd(num, _mm_mul_pd(constant(0.41421356237309503), den));
  const __m128d t = _mm_div_pd(select(shift, _mm_sub_pd(num, den), num), select(shift, _mm_add_pd(num, den), den));
  const __m128d t2 = _mm_mul_pd(t, t), t4 = _mm_mul_pd(t2, t2), t8 = _mm_mul_pd(t4, t4);
  constexpr double c3 = 1.0 / 3, c5 = 1.0 / 5, c7 = 1.0 / 7, c9 = 1.0 / 9, c11 = 1.0 / 11, c13 = 1.0 / 13, c15 = 1.0 / 15;
  const __m128d p01 = _mm_sub_pd(constant(1.0), _mm_mul_pd(t2, constant(c3)));
  const __m128d p23 = _mm_sub_pd(constant(c5), _mm_mul_pd(t2, constant(c7)));
  const __m128d p45 = _mm_sub_pd(constant(c9), _mm_mul_pd(t2, constant(c11)));
  const __m128d p67 = _mm_sub_pd(constant(c13), _mm_mul_pd(t2, constant(c15)));
  __m128d r = _mm_mul_pd(t, _mm_add_pd(_mm_add_pd(p01, _mm_mul_pd(t4, p23)), _mm_mul_pd(t8, _mm_add_pd(p45, _mm_mul_pd(t4, p67)))));
  // r >= +0 (or NaN) here, and r + 0 is r: adding pi/4 in the lanes that shift only.
  r = _mm_add_pd(r, _mm_and_pd(shift, constant(0.78539816339744831)));
  r = select(steep, _mm_sub_pd(constant(kHalfPi), r), r);
  r = select(_mm_cmplt_pd(vx, _mm_setzero_pd()), _mm_sub_pd(constant(2 * kHalfPi), r), r);
  _mm_storeu_pd(angle, r);
#else
  angle[0] = angleBetween(y[0], x[0]);
  angle[1] = angleBetween(y[1], x[1]);
#endif
}

// Rounds x to a multiple of 2^-40 (|x| < 2^11): sums of up to 2^13 / pi such values are exact
// in double, so they come out the same in any order, with no sort.
constexpr double kQuantizer = 0x1.8p12;
inline double quantized(float x) {
  return (static_cast<double>(x) + kQuantizer) - kQuantizer;
}
constexpr std::uint32_t kMostQuantizedTerms = 2048;

// The common bucket from the terms the triangle pass parked in its corners' slots: one fan
// (closed or open) of one orientation, every corner usable (cornerTermsOne), its dP/du and
// its dP/dv each inside one half-space (no pair the reference could find opposite, so no
// subgroups), a sum that does not nearly cancel, a normal that is neither zero nor infinite.
// Then every corner gets the one shared frame, as the full path would give it. False
// (nothing written) where the bucket is not that case.
bool Kernel::fastBucket(std::uint32_t bucket, const std::uint32_t* list, std::uint32_t count, std::uint64_t& mirrored) {
  std::uint32_t cone = kConeBits;
  double x, y, z, angleSum;
#if defined(__SSE2__)
  // The same exact sums two components at a time.
  const __m128d quantizer = _mm_set1_pd(kQuantizer);
  __m128d xy = _mm_setzero_pd(), za = _mm_setzero_pd();
  const __m128i keep = _mm_setr_epi32(-1, -1, -1, static_cast<int>(~kConeBits));
  __m128i bits = _mm_set1_epi32(-1);
  for (std::uint32_t i = 0; i < count; ++i) {
    const __m128i slot = _mm_loadu_si128(reinterpret_cast<const __m128i*>(&tangents_[4 * std::size_t(list[i])]));
    bits = _mm_and_si128(bits, slot);
    const __m128 terms = _mm_castsi128_ps(_mm_and_si128(slot, keep));
    xy = _mm_add_pd(xy, _mm_sub_pd(_mm_add_pd(_mm_cvtps_pd(terms), quantizer), quantizer));
    za = _mm_add_pd(za, _mm_sub_pd(_mm_add_pd(_mm_cvtps_pd(_mm_movehl_ps(terms, terms)), quantizer), quantizer));
  }
  cone &= static_cast<std::uint32_t>(_mm_cvtsi128_si32(_mm_shuffle_epi32(bits, 3)));
  double lanes[4];
  _mm_storeu_pd(lanes, xy);
  _mm_storeu_pd(lanes + 2, za);
  x = lanes[0], y = lanes[1], z = lanes[2], angleSum = lanes[3];
#else
  x = y = z = angleSum = 0;
  for (std::uint32_t i = 0; i < count; ++i) {
    const float* slot = &tangents_[4 * std::size_t(list[i])];
    const std::uint32_t bits = bitCast<std::uint32_t>(slot[3]);
    cone &= bits;
    x += quantized(slot[0]), y += quantized(slot[1]), z += quantized(slot[2]);
    angleSum += quantized(bitCast<float>(bits & ~kConeBits));
  }
#endif
  if (!(cone & 0x3F) || !(cone & (0x3F << 6))) return false;
  // The sum made orthogonal to the raw normal N (as to the unit normal) and normalized: one
  // square root and one division for the bucket.
  const V3 sum{x, y, z}, normal = a_.normal(bucket);
  const double sum2 = dot(sum, sum), normal2 = dot(normal, normal);
  if (!(sum2 >= 0.0025 * angleSum * angleSum) || !(normal2 > 0) || !std::isfinite(normal2)) return false;
  const V3 t = sum - normal * (dot(normal, sum) / normal2);
  const double t2 = dot(t, t);
  if (!(t2 > 1e-24 * sum2)) return false;
  const V3 unit = t * (1.0 / std::sqrt(t2));
  const float w = ws_.orientation[list[0] / 3] > 0 ? 1.0f : -1.0f;
  const float frame[4] = {static_cast<float>(unit.x), static_cast<float>(unit.y), static_cast<float>(unit.z),
                          w * wSign_};
  // storeFrame without its state write: a corner's source and undefined bits are still clear
  // here (pairing cleared them; only its bucket's group pass sets them), and computed is 0.
  static_assert(static_cast<int>(FrameSource::computed) == 0);
  for (std::uint32_t i = 0; i < count; ++i) std::memcpy(&tangents_[4 * std::size_t(list[i])], frame, sizeof frame);
  finishOneFrame(bucket, list, count, mirrored);
  ws_.bucketExtra[bucket] = bitCast<std::uint32_t>(static_cast<float>(angleSum));
  ws_.bucketUniform[bucket] |= kBucketWeight;
  return true;
}

// Groups of one welded vertex, their sums, and the frames of its corners.
void Kernel::groupBucket(std::uint32_t bucket, BucketScratch& scratch, std::uint64_t& mirrored) {
  const std::uint32_t first = start_[bucket], count = start_[bucket + 1] - first;
  const std::uint8_t chain = ws_.bucketUniform[bucket];
  ws_.bucketUniform[bucket] = 0;
  if (count == 0) return;
  const std::uint32_t* list = corners_ + first;
  // Members of each group, group by group: keys = (root, local index); one chain of links
  // between triangles of one orientation (a fan around the vertex, closed or open) is one
  // group of every corner (what the union-find below finds for it), without keys.
  const bool fan = chain == kOneFan ||
                   (chain == kOneChain ? oneOrientation(list, count) : chain == kChainUnknown && closedFan(list, count));
  if (fan && count <= kMostQuantizedTerms && ws_.fastBuckets && fastBucket(bucket, list, count, mirrored)) return;
  bool invalidNormal = false;
  const V3 n = bucketNormal(bucket, invalidNormal);
  if (invalidNormal) {
    for (std::uint32_t i = 0; i < count; ++i) ws_.cornerState[list[i]] |= kInvalidNormal;
  }

  if (!fan) {
    scratch.keys.clear();
    // Union-find over the bucket's corners through pairs of equal orientation.
    BucketUnionFind components(scratch.parent, count);
    auto find = [&](std::uint32_t x) { return components.find(x); };
    for (std::uint32_t i = 0; i < count; ++i) {
      const std::uint32_t c = list[i];
      if (!participates(c) || (ws_.cornerState[c] & kCopy)) continue;
      const std::uint32_t d = ws_.cornerLink[c];
      if (d == kNone || ws_.orientation[c / 3] != ws_.orientation[d / 3]) continue;
      components.unite(i, localIndex(bucket, d));
    }
    for (std::uint32_t i = 0; i < count; ++i) {
      const std::uint32_t c = list[i];
      if (participates(c) && !(ws_.cornerState[c] & kCopy)) scratch.keys.push_back((std::uint64_t(find(i)) << 32) | i);
    }
    sortSmall(scratch.keys.data(), scratch.keys.data() + scratch.keys.size());
  }
  const std::size_t memberCount = fan ? count : scratch.keys.size();
  auto member = [&](std::size_t m) {
    return fan ? static_cast<std::uint32_t>(m) : static_cast<std::uint32_t>(scratch.keys[m]);
  };
  auto rootOf = [&](std::size_t m) { return static_cast<std::uint32_t>(scratch.keys[m] >> 32); };

  // Per contributing member: weighted tangent (3), dP/du projected as the reference projects
  // it (float arithmetic on the raw normal), the triangle's unit dP/dv (3), angle.
  const F3 rawNormal{a_.normals[3 * bucket], a_.normals[3 * bucket + 1], a_.normals[3 * bucket + 2]};
  constexpr int kStride = 10;
  // The corners' common position (equal values; where a component is zero its sign may
  // differ between corners, which moves no angle: only signs of zero terms follow it).
  const V3 here = a_.position(bucket);
  // Every corner of the bucket given the one shared frame of one group (see bucketUniform).
  bool oneFrame = memberCount == count;
  for (std::size_t g = 0; g < memberCount;) {
    std::size_t gEnd = fan ? memberCount : g + 1;
    while (gEnd < memberCount && rootOf(gEnd) == rootOf(g)) ++gEnd;
    const std::int8_t orientation = ws_.orientation[list[member(g)] / 3];
    const float w = orientation > 0 ? 1.0f : -1.0f;  // reference: fSign = +1 where the UV area is positive
    scratch.values.resize(kStride * (gEnd - g));
    scratch.items.clear();  // contributing members, local indices
    double* values = scratch.values.data();
    // Three passes over the group's contributing corners: their projected edges (y, x of the
    // angle parked in the row's first two slots, whether both edges are non-zero in its
    // third) and directions; the angles two at a time; then the weighted terms.
    for (std::size_t m = g; m < gEnd; ++m) {
      const std::uint32_t c = list[member(m)];
      const std::size_t t = c / 3;
      if (ws_.triangleFlags[t] & kGroupWithAny) continue;
      // The triangle's frame again (the triangle pass keeps none: most buckets take the fan
      // shortcut, which needs only the parked terms); the same function, the same bits.
      float frame[6];
      std::int8_t orientationAgain;
      std::uint8_t flagsAgain;
      evaluateTriangle(a_, t, frame, orientationAgain, flagsAgain);
      const V3 toPrevious = projected(a_.position(a_.indices[previousCorner(c)]) - here, n);
      const V3 toNext = projected(a_.position(a_.indices[nextCorner(c)]) - here, n);
      const F3 referenceS = referenceProjected({frame[0], frame[1], frame[2]}, rawNormal);
      double* row = values + kStride * scratch.items.size();
      const bool edges = !isZero(toPrevious) & !isZero(toNext);
      row[0] = edges ? length(cross(toPrevious, toNext)) : 1.0;
      row[1] = edges ? dot(toPrevious, toNext) : 0.0;
      row[2] = edges ? 1.0 : 0.0;
      // The reference's projected direction, so that sums which (nearly) cancel keep its sign.
      row[3] = referenceS.x, row[4] = referenceS.y, row[5] = referenceS.z;
      row[6] = frame[3], row[7] = frame[4], row[8] = frame[5];  // projected only where needed
      scratch.items.push_back(static_cast<std::uint32_t>(m));
    }
    const std::size_t contributingCorners = scratch.items.size();
    for (std::size_t i = 0; i < contributingCorners; i += 2) {
      double* row = values + kStride * i;
      if (i + 1 < contributingCorners) {
        const double y[2] = {row[0], row[kStride]}, x[2] = {row[1], row[kStride + 1]};
        double angle[2];
        angleBetweenPair(y, x, angle);
        row[9] = angle[0], row[kStride + 9] = angle[1];
      } else {
        row[9] = angleBetween(row[0], row[1]);
      }
    }
    for (std::size_t i = 0; i < contributingCorners; ++i) {
      double* row = values + kStride * i;
      double angle = row[2] != 0 ? row[9] : kHalfPi;  // a zero edge counts as perpendicular, as in the reference
      if (angle < 0.1 || angle > 2 * kHalfPi - 0.1) {
        // Near 0 or pi the reference's float cosine decides (acos(0.99999994) is 3.5e-4, not 0),
        // and its rounding moves small angles by a visible fraction.
        angle = referenceAngle(list[member(scratch.items[i])], rawNormal);
      }
      // A corner whose edges project onto one line has no angle; its direction still counts
      // where nothing else does.
      angle = std::max(angle, 1e-12);
      row[0] = row[3] * angle, row[1] = row[4] * angle, row[2] = row[5] * angle;
      row[9] = angle;
    }
    const std::size_t contributing = scratch.items.size();
    // Sum in value order so that face order cannot change a bit.
    std::vector<std::uint32_t> byValue;
    std::uint32_t byValueSmall[32];
    std::uint32_t* sorted = byValueSmall;
    if (contributing > 32) {
      byValue.resize(contributing);
      sorted = byValue.data();
    }
    for (std::uint32_t i = 0; i < contributing; ++i) sorted[i] = i;
    auto lessByValue = [&](std::uint32_t x, std::uint32_t y) {
      const double* p = values + kStride * x;
      const double* q = values + kStride * y;
      if (p[0] != q[0]) return p[0] < q[0];
      if (p[1] != q[1]) return p[1] < q[1];
      return p[2] < q[2];
    };
    if (contributing <= 32) {
      for (std::uint32_t i = 1; i < contributing; ++i) {
        const std::uint32_t value = sorted[i];
        std::uint32_t j = i;
        for (; j > 0 && lessByValue(value, sorted[j - 1]); --j) sorted[j] = sorted[j - 1];
        sorted[j] = value;
      }
    } else {
      std::sort(sorted, sorted + contributing, lessByValue);
    }
    // Subgroups: the reference keeps apart two triangles whose projected dP/du or dP/dv have
    // a float dot product of -1 or less. All vectors well inside one half-space (1e-3 from its
    // boundary) proves there is no such pair; otherwise compare pairs as the reference does.
    auto opposite = [&](std::size_t i, std::size_t j) {
      const double* x = values + kStride * i;
      const double* y = values + kStride * j;
      const F3 si{float(x[3]), float(x[4]), float(x[5])}, sj{float(y[3]), float(y[4]), float(y[5])};
      if (!(fdot(si, sj) > -1.0f)) return true;
      const F3 ti = referenceProjected({float(x[6]), float(x[7]), float(x[8])}, rawNormal);
      const F3 tj = referenceProjected({float(y[6]), float(y[7]), float(y[8])}, rawNormal);
      return !(fdot(ti, tj) > -1.0f);
    };
    bool anyOpposite = false;
    if (contributing > 1) {
      V3 sumS, sumT;
      for (std::size_t i = 0; i < contributing; ++i) {
        sumS = sumS + V3{values[kStride * i + 3], values[kStride * i + 4], values[kStride * i + 5]};
        sumT = sumT + V3{values[kStride * i + 6], values[kStride * i + 7], values[kStride * i + 8]};
      }
      // dP/dv unprojected: its dot with a vector in the plane is that of its projection, whose
      // length is at most 1, so the bound holds for the projections too.
      sumT = projected(sumT, n);
      const double lengthS = length(sumS), lengthT = length(sumT);
      bool halfSpace = true;
      for (std::size_t i = 0; i < contributing && halfSpace; ++i) {
        const double* x = values + kStride * i;
        const V3 si{x[3], x[4], x[5]}, ti{x[6], x[7], x[8]};
        halfSpace = (isZero(si) || dot(si, sumS) > 1e-3 * lengthS) && dot(ti, sumT) > 1e-3 * lengthT;
      }
      if (!halfSpace && contributing <= 4096) {
        for (std::size_t i = 0; i < contributing && !anyOpposite; ++i) {
          for (std::size_t j = i + 1; j < contributing && !anyOpposite; ++j) anyOpposite = opposite(i, j);
        }
      }
    }
    // The sum over a corner's subgroup (self: a contributing index, or kNone for all). Where
    // two terms cancel to a twentieth of their weight, rounding moves the direction: then the
    // reference's own float sum (its float angles), which for two terms does not depend on
    // their order. With more terms the reference's float sum does depend on its face order
    // (measured: 0.03 degrees over the orders of a 7-triangle fan) and the double sum is the
    // better estimate of all of them.
    auto sumOver = [&](std::size_t self, double& weights) {
      V3 sum;
      weights = 0;
      std::size_t terms = 0;
      for (std::size_t i = 0; i < contributing; ++i) {
        if (self != kNone && sorted[i] != self && opposite(sorted[i], self)) continue;
        const double* x = values + kStride * sorted[i];
        sum = sum + V3{x[0], x[1], x[2]};
        weights += x[9];
        ++terms;
      }
      if (length(sum) >= 0.05 * weights) return sum;
      // Cancelling terms magnify every difference in their weights: the reference's float angles.
      F3 floatSum;
      V3 doubleSum;
      for (std::size_t i = 0; i < contributing; ++i) {
        if (self != kNone && sorted[i] != self && opposite(sorted[i], self)) continue;
        const double* x = values + kStride * sorted[i];
        const auto angle = static_cast<float>(referenceAngle(list[member(scratch.items[sorted[i]])], rawNormal));
        const F3 term = fscale(angle, F3{float(x[3]), float(x[4]), float(x[5])});
        floatSum = fadd(floatSum, term);
        doubleSum = doubleSum + V3{term.x, term.y, term.z};
      }
      return terms > 2 ? doubleSum : V3{floatSum.x, floatSum.y, floatSum.z};
    };
    // The group's weight (its angles' sum) in value order too, so that no face order moves it.
    // sumOver(kNone), written out for the common case: no subgroup test per term.
    double angleSum = 0;
    V3 all;
    for (std::size_t i = 0; i < contributing; ++i) {
      const double* x = values + kStride * sorted[i];
      all = all + V3{x[0], x[1], x[2]};
      angleSum += x[9];
    }
    if (!(length(all) >= 0.05 * angleSum)) all = sumOver(kNone, angleSum);
    V3 shared;
    const bool sharedDefined = contributing > 0 && orthonormalize(all, n, shared);
    const auto groupWeight = static_cast<float>(angleSum);
    oneFrame = oneFrame && g == 0 && gEnd == memberCount && sharedDefined && !anyOpposite;
    if (contributing > 0 && !anyOpposite && sharedDefined) {
      // The common case: every member gets the shared frame.
      for (std::size_t m = g; m < gEnd; ++m) {
        writeCorner(list[member(m)], shared, w, FrameSource::computed, groupWeight);
      }
      g = gEnd;
      continue;
    }
    std::size_t nextContributing = 0;
    for (std::size_t m = g; m < gEnd; ++m) {
      const std::uint32_t c = list[member(m)];
      std::size_t self = kNone;
      if (nextContributing < contributing && scratch.items[nextContributing] == m) self = nextContributing++;
      if (contributing == 0) {
        markUndefined(c, orientation != 0 ? w : -1.0f);
      } else if (!anyOpposite || self == kNone) {
        if (sharedDefined) writeCorner(c, shared, w, FrameSource::computed, groupWeight);
        else markUndefined(c, w);
      } else {
        V3 own;
        double weights;
        if (orthonormalize(sumOver(self, weights), n, own)) writeCorner(c, own, w, FrameSource::computed, groupWeight);
        else markUndefined(c, w);
      }
    }
    g = gEnd;
  }
  if (oneFrame) {
    finishOneFrame(bucket, list, count, mirrored);
    return;  // no coincident corners here
  }

  // Coincident corners copy the best frame of their identity (the reference: the first).
  for (std::uint32_t i = 0; i < count; ++i) {
    const std::uint32_t c = list[i];
    if (!participates(c)) inheritInBucket(bucket, c, 0, true);
  }
  for (std::uint32_t i = 0; i < count; ++i) {
    const std::uint32_t c = list[i];
    mirrored += !(ws_.cornerState[c] & kCopy) && tangents_[4 * c + 3] < 0;
  }
}

// Gives `corner` the best computed frame of its bucket (with w, unless anyW); else undefined.
void Kernel::inheritInBucket(std::uint32_t bucket, std::uint32_t corner, float w, bool anyW) {
  std::uint32_t best = kNone;
  for (std::uint32_t i = start_[bucket]; i < start_[bucket + 1]; ++i) {
    const std::uint32_t c = corners_[i];
    if (!participates(c) || (ws_.cornerState[c] & kCopy) || (ws_.cornerState[c] & kUndefined)) continue;
    if (static_cast<FrameSource>(ws_.cornerState[c] & kSourceMask) != FrameSource::computed) continue;
    if (!anyW && this->w(c) != w) continue;
    if (best == kNone || betterCandidate(c, best)) best = c;
  }
  if (best == kNone) {
    markUndefined(corner, anyW ? -1.0f : w);
    return;
  }
  const float* from = &tangents_[4 * best];
  writeCorner(corner, {from[0], from[1], from[2]}, this->w(best), FrameSource::inherited, weight(best));
}

// The rare corners without a frame of their own, after every group is done: one w per
// coincident triangle, then frames borrowed from the vertex, the triangle or its 1-ring.
void Kernel::fallbacks() {
  const std::size_t triangleCount = ws_.cornerCount / 3;
  const std::vector<std::uint32_t> coincident =
      coincident_ == 0 ? std::vector<std::uint32_t>{}
                       : collectFlagged(ws_, ws_.triangleFlags.data(), kCoincident, triangleCount,
                                        [&](std::size_t t) { return (ws_.triangleFlags[t] & kCoincident) != 0; });
  for (std::uint32_t t : coincident) {
    int plus = 0, minus = 0;
    for (int k = 0; k < 3; ++k) {
      const std::size_t c = 3 * t + k;
      if (ws_.cornerState[c] & kUndefined) continue;
      (this->w(c) > 0 ? plus : minus) += 1;
    }
    const float w = plus + minus == 0 ? -1.0f : (minus > plus ? -1.0f : 1.0f);
    for (int k = 0; k < 3; ++k) {
      const std::size_t c = 3 * t + k;  // never a copy: coincident triangles pair with nothing
      const bool wasMirrored = tangents_[4 * c + 3] < 0;
      if (ws_.cornerState[c] & kUndefined) tangents_[4 * c + 3] = w * wSign_;
      else if (this->w(c) != w) inheritInBucket(id(c), static_cast<std::uint32_t>(c), w, false);
      ws_.mirroredCorners += (tangents_[4 * c + 3] < 0) - static_cast<int>(wasMirrored);
    }
  }
  if (!anyUndefined_.load(std::memory_order_relaxed)) return;
  const std::vector<std::uint32_t> undefined =
      collectFlagged(ws_, ws_.cornerState.data(), kUndefined, ws_.cornerCount, [&](std::size_t c) {
        return (ws_.cornerState[c] & kUndefined) && !(ws_.cornerState[c] & kCopy);
      });
  // Each borrows only from frames that were there before this loop: decide all, then write.
  struct Decision {
    std::uint32_t corner;
    V3 tangent;
    FrameSource source;
  };
  std::vector<Decision> decisions;
  decisions.reserve(undefined.size());
  for (std::uint32_t c : undefined) {
    const float w = this->w(c);
    const std::uint32_t bucket = id(c);
    bool invalid;
    const V3 n = bucketNormal(bucket, invalid);
    const bool isCoincident = (ws_.triangleFlags[c / 3] & kCoincident) != 0;
    // 1. Same identity, same w.
    std::uint32_t best = kNone;
    for (std::uint32_t i = start_[bucket]; i < start_[bucket + 1]; ++i) {
      const std::uint32_t d = corners_[i];
      if (d != c && defined(d) && !(ws_.cornerState[d] & kCopy) && this->w(d) == w && (best == kNone || betterCandidate(d, best))) best = d;
    }
    if (best != kNone) {
      const float* from = &tangents_[4 * best];
      decisions.push_back({c, {from[0], from[1], from[2]}, isCoincident ? FrameSource::inherited : FrameSource::neighbour});
      continue;
    }
    // 2. The triangle's other corners, then 3. the corners at its other two vertices.
    for (int pass = 0; pass < 2 && best == kNone; ++pass) {
      for (int k = 1; k < 3; ++k) {
        const std::size_t other = 3 * (c / 3) + (c % 3 + k) % 3;
        if (pass == 0) {
          if (defined(other) && !(ws_.cornerState[other] & kCopy) && this->w(other) == w && (best == kNone || betterCandidate(other, best)))
            best = static_cast<std::uint32_t>(other);
          continue;
        }
        const std::uint32_t otherBucket = id(other);
        for (std::uint32_t i = start_[otherBucket]; i < start_[otherBucket + 1]; ++i) {
          const std::uint32_t d = corners_[i];
          if (defined(d) && !(ws_.cornerState[d] & kCopy) && this->w(d) == w && (best == kNone || betterCandidate(d, best))) best = d;
        }
      }
    }
    V3 tangent;
    if (best != kNone && orthonormalize({tangents_[4 * best], tangents_[4 * best + 1], tangents_[4 * best + 2]}, n, tangent)) {
      decisions.push_back({c, tangent, FrameSource::neighbour});
      continue;
    }
    // 4. A fixed unit vector perpendicular to the normal.
    axisPerpendicular(&n.x, &tangent.x);
    decisions.push_back({c, tangent, FrameSource::fixed});
  }
  for (const Decision& d : decisions) writeCorner(d.corner, d.tangent, w(d.corner), d.source, 0);
}

void Kernel::run(Report& report) {
  const std::size_t cornerCount = ws_.cornerCount, triangleCount = cornerCount / 3;
  ensureSize(ws_.orientation, triangleCount);
  ensureSize(ws_.triangleFlags, triangleCount);
  ensureSize(ws_.cornerLink, cornerCount);
  ensureSize(ws_.cornerState, cornerCount);
  ensureSize(ws_.bucketUniform, ws_.vertexCount);
  // The triangle pass needs no weld: on two threads and more it runs beside the weld and the
  // bucketing. Below four threads, those take the one-thread way, the least work: while one
  // thread welds and buckets, the others evaluate triangles, then all finish them. From four,
  // the weld alone would take longer than the triangle pass on the other threads.
  const unsigned weldThreads = ws_.threads < 4 ? 1 : ws_.threads;
  invokeBoth(ws_, [&] { weldAndBucket(ws_, mesh_, weldThreads); }, [&] { evaluateTriangles(report); });
  vertexId_ = ws_.vertexId.data();
  identity_ = ws_.weldMergedNone;
  start_ = ws_.bucketStart.data();
  corners_ = ws_.bucketCorners.data();

  const std::size_t bucketCount = ws_.vertexCount;
  // Pairing and grouping touch only the bucket's own corners, except where a zero-UV
  // triangle takes its orientation from its neighbours between them (resolveGroupWithAny):
  // without one, each bucket is paired and grouped at once, while its data is in cache.
  const bool fused = groupWithAny_ == 0;
  orientationsFinal_ = fused;
  Combinable<std::uint64_t> mirrored;
  forRange(ws_, bucketCount, 1024, [&](std::size_t begin, std::size_t end) {
    BucketScratch& scratch = ws_.scratch.local();
    std::uint64_t local = 0;
    for (std::size_t b = begin; b < end; ++b) {
      pairBucket(static_cast<std::uint32_t>(b), scratch);
      if (fused) groupBucket(static_cast<std::uint32_t>(b), scratch, local);
    }
    mirrored.local() += local;
  });
  if (anyNonManifold_.load(std::memory_order_relaxed)) {
    Combinable<std::uint64_t> nonManifold;
    forRange(ws_, triangleCount, 1 << 14, [&](std::size_t begin, std::size_t end) {
      std::uint64_t local = 0;
      for (std::size_t t = begin; t < end; ++t)
        local += ((ws_.cornerState[3 * t] | ws_.cornerState[3 * t + 1] | ws_.cornerState[3 * t + 2]) & 32) != 0;
      nonManifold.local() += local;
    });
    report.nonManifoldFaces = nonManifold.combine(std::plus<>());
  }
  if (!fused) {
    resolveGroupWithAny();
    forRange(ws_, bucketCount, 1024, [&](std::size_t begin, std::size_t end) {
      BucketScratch& scratch = ws_.scratch.local();
      std::uint64_t local = 0;
      for (std::size_t b = begin; b < end; ++b) groupBucket(static_cast<std::uint32_t>(b), scratch, local);
      mirrored.local() += local;
    });
  }
  ws_.mirroredCorners = mirrored.combine(std::plus<>());
  fallbacks();
  ws_.bucketUniformKnown = true;
  ws_.wInOutputConvention = true;
}

}  // namespace

VectorIsa activeVectorIsa() {
#if defined(TANGENT_LANES8)
  static const VectorIsa widest = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") ? VectorIsa::avx2 : VectorIsa::sse2;
  }();
#elif defined(__SSE2__)
  constexpr VectorIsa widest = VectorIsa::sse2;
#else
  constexpr VectorIsa widest = VectorIsa::scalar;
#endif
  VectorIsa cap = VectorIsa::avx2;
  if (const char* name = std::getenv("TANGENT_MAX_CPU_ISA")) {
    const std::string_view value(name);
    if (value == "scalar") cap = VectorIsa::scalar;
    if (value == "sse2") cap = VectorIsa::sse2;
  }
  return std::min(widest, cap);
}

Report mikktspaceOnArrays(WorkspaceData& ws, const MeshArrays& mesh, const CornerOutputs& outputs, const Options& options) {
  Report report;
  beginCall(ws, mesh);
  report.method = Method::mikktspace;
  report.weighting = Weighting::angle;
  report.triangles = ws.cornerCount / 3;
  report.corners = ws.cornerCount;
  Kernel(ws, mesh, outputs, options.uvOrigin).run(report);
  finishOutputs(ws, mesh, outputs, options, report);
  return report;
}

}  // namespace tangent::detail
