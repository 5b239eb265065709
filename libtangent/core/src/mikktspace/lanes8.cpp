// SPDX-License-Identifier: MIT
// The triangle pass eight triangles at a time in AVX2 registers: lanes.inc's table, and the
// operations it leaves to each instruction set.
#include <algorithm>
#include <cstring>
#include <limits>
#include <utility>

#include "triangle.hpp"

#if defined(TANGENT_LANES8)
#include <immintrin.h>
#endif

namespace tangent::detail::mikk {

#if defined(TANGENT_LANES8)
// This code only is compiled for AVX2 (no FMA, so no operation is fused) and run where the
// processor has it (vectorIsa).
#pragma GCC push_options
#pragma GCC target("avx2")
// The functions here take and return AVX vectors; they are all inlined in this file, so the
// note that such calls pass them differently without AVX does not apply.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"
namespace {  // file-local: compiled for AVX2 only, and inlined as in one function
namespace lanes8 {
constexpr int kWidth = 8;
#define TANGENT_LANES_OWN_SELECT 1
#include "lanes.inc"
#undef TANGENT_LANES_OWN_SELECT
// vblendvps takes each lane from x where the mask's sign bit is set: the masks here are all
// ones or all zeros per lane. vmaxps gives y where x > y is false (NaN in either, or equal).
inline F select(F mask, F x, F y) { return _mm256_blendv_ps(y, x, mask); }
inline F maxF(F x, F y) { return _mm256_max_ps(x, y); }
inline F root(F x) { return _mm256_sqrt_ps(x); }
inline int movemask(F x) { return _mm256_movemask_ps(x); }
inline D lowHalf(F x) { return _mm256_cvtps_pd(_mm256_castps256_ps128(x)); }
inline D highHalf(F x) { return _mm256_cvtps_pd(_mm256_extractf128_ps(x, 1)); }
#include "triangle_lanes.inc"
}  // namespace lanes8
}  // namespace

// Compiled for AVX2 too, so that the lanes inline into it.
void evaluateLanes8(const Arrays& a, std::size_t t, std::int8_t* orientation, std::uint8_t* flags, float* tangents) {
  lanes8::evaluateLanes(a, t, orientation, flags, tangents);
}
#pragma GCC diagnostic pop
#pragma GCC pop_options
#endif

}  // namespace tangent::detail::mikk
