// SPDX-License-Identifier: MIT
// The triangle pass, one triangle at a time (the lanes' leftovers, and the full path, which
// evaluates a triangle again rather than keep its frame).
// Source: M. S. Mikkelsen, mikktspace.c (2011), EvalTspace and the per-triangle setup of
// GenerateTSpaces; see mikktspace/kernel.cpp for the rules.
#include "triangle.hpp"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <algorithm>

namespace tangent::detail::mikk {

// The parked terms of triangle t's three corners (frame: its dP/du, dP/dv; flags: its bits).
void cornerTermsOne(const Arrays& a, std::size_t t, const float* frame, std::int8_t orientation, std::uint8_t flags,
                    float* tangents) {
  const std::uint32_t notPositive = orientation > 0 ? 0 : kNotPositiveBit;
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
    slot[3] = bitCast<float>((bitCast<std::uint32_t>(angle) & ~kConeBits) | cone | notPositive);
  }
}

namespace {

// Triangle t's positions and UVs from its first corner in value order, as floats.
struct CornerValuesF {
  F3 p[3];
  float u[3], v[3];
};

inline CornerValuesF loadCorners(const Arrays& a, std::size_t t) {
  const int first = firstCorner(a, t);
  const std::uint32_t* triangle = a.indices + 3 * t;
  const std::uint32_t rotated[5] = {triangle[0], triangle[1], triangle[2], triangle[0], triangle[1]};
  CornerValuesF c;
  for (int k = 0; k < 3; ++k) {
    const std::uint32_t vertex = rotated[first + k];
    c.p[k] = {a.positions[3 * vertex], a.positions[3 * vertex + 1], a.positions[3 * vertex + 2]};
    c.u[k] = a.uvs[2 * vertex];
    c.v[k] = a.uvs[2 * vertex + 1];
  }
  return c;
}

// The edges from the first corner to the other two, in double.
inline void doubleEdges(const CornerValuesF& c, V3& e1, V3& e2) {
  const V3 p[3] = {{c.p[0].x, c.p[0].y, c.p[0].z}, {c.p[1].x, c.p[1].y, c.p[1].z}, {c.p[2].x, c.p[2].y, c.p[2].z}};
  e1 = p[1] - p[0], e2 = p[2] - p[0];
}

// The flags that need no frame: kNonFinite | kGroupWithAny where a value is not finite,
// kFlat where the positions span no area, kCoincident where two are equal. False where the
// triangle has no frame to find (not finite, or coincident).
inline bool screenCorners(const CornerValuesF& c, std::uint8_t& flags) {
  const F3* pf = c.p;
  const float *uf = c.u, *vf = c.v;
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
    return false;
  }
  flags = 0;
  const bool coincident = same(p0, p1) | same(p1, p2) | same(p0, p2);
  V3 e1, e2;
  doubleEdges(c, e1, e2);
  if (!(dot(cross(e1, e2), cross(e1, e2)) > kAreaZero * kAreaZero * dot(e1, e1) * dot(e2, e2))) flags |= kFlat;
  if (coincident) {
    flags |= kCoincident;
    return false;
  }
  return true;
}

// The reference, in float: the frame and orientation where it finds one (true).
inline bool floatFrame(const CornerValuesF& c, float* frame, std::int8_t& orientation) {
  const F3* pf = c.p;
  const float *uf = c.u, *vf = c.v;
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
  if (!usable) return false;
  orientation = signedArea > 0 ? 1 : -1;
  const float values[6] = {vOs.x, vOs.y, vOs.z, vOt.x, vOt.y, vOt.z};
  std::copy(values, values + 6, frame);
  return true;
}

// Where float found nothing: the double frame and orientation (true) where float's terms
// under- or overflowed on a triangle that double resolves; else float is trusted (false).
inline bool doubleFrame(const CornerValuesF& c, float* frame, std::int8_t& orientation) {
  const float *uf = c.u, *vf = c.v;
  V3 e1, e2;
  doubleEdges(c, e1, e2);
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
  if (floatRange || !doubleUsable) return false;
  const double sign = det > 0 ? 1.0 : -1.0;
  orientation = det > 0 ? 1 : -1;
  for (int i = 0; i < 3; ++i) {
    frame[i] = static_cast<float>((&uDirection.x)[i] * (sign / uLength));
    frame[3 + i] = static_cast<float>((&vDirection.x)[i] * (sign / vLength));
  }
  return true;
}

}  // namespace

// Unit dP/du and dP/dv of triangle t (signed by the UV orientation), its orientation and
// flags. The reference's float formulas (eq. 18, 19 of its source) from the triangle's first
// corner in value order; where float under- or overflows on a triangle that double
// arithmetic resolves (denormal or huge coordinates), the double result.
void evaluateTriangle(const Arrays& a, std::size_t t, float* frame, std::int8_t& orientation, std::uint8_t& flags) {
  const CornerValuesF c = loadCorners(a, t);
  std::fill(frame, frame + 6, 0.0f);
  orientation = 0;
  if (!screenCorners(c, flags)) return;
  if (floatFrame(c, frame, orientation) || doubleFrame(c, frame, orientation)) return;
  flags |= kGroupWithAny;
  if (!(flags & kFlat)) flags |= kZeroUv;
}

// One triangle the scalar way, for the lanes' leftovers and tails: its orientation and flags,
// and its corners' parked terms (cornerTermsOne), from a frame that is not kept.
void evaluateAndParkOne(const Arrays& a, std::size_t t, std::int8_t& orientation, std::uint8_t& flags, float* tangents) {
  float frame[6];
  evaluateTriangle(a, t, frame, orientation, flags);
  cornerTermsOne(a, t, frame, orientation, flags, tangents);
}

}  // namespace tangent::detail::mikk
