// SPDX-License-Identifier: MIT
// The triangle pass four triangles at a time in SSE2 registers: lanes.inc's table, and the
// operations it leaves to each instruction set.
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <algorithm>
#include <cstring>
#include <limits>
#include <utility>

#include "triangle.hpp"

namespace tangent::detail::mikk {

#if defined(__SSE2__)
namespace {  // file-local: compiled for SSE2 only, and inlined as in one function
namespace lanes4 {
constexpr int kWidth = 4;
#include "lanes.inc"
inline F root(F x) { return _mm_sqrt_ps(x); }
inline int movemask(F x) { return _mm_movemask_ps(x); }
inline D lowHalf(F x) { return _mm_cvtps_pd(x); }
inline D highHalf(F x) { return _mm_cvtps_pd(_mm_movehl_ps(x, x)); }
#include "triangle_lanes.inc"
}  // namespace lanes4
}  // namespace

void evaluateLanes4(const Arrays& a, std::size_t t, std::int8_t* orientation, std::uint8_t* flags, float* tangents) {
  lanes4::evaluateLanes(a, t, orientation, flags, tangents);
}
#endif

}  // namespace tangent::detail::mikk
