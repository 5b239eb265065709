// SPDX-License-Identifier: MIT
// Corner angles: atan2 in double (scalar and two lanes, the same bits) for the full path, in
// float for the triangle pass, and the reference's own acos for the rules that need its
// rounding. Each gives the same bits on every vector width.
#pragma once

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "math.hpp"

namespace tangent::detail::mikk {

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

constexpr float kQuarterPiF = 0.785398163f, kHalfPiF = 1.57079633f, kPiF = 3.14159265f;

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

}  // namespace tangent::detail::mikk
