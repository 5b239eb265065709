// SPDX-License-Identifier: MIT
// The triangle pass four triangles at a time in SSE2 registers: the operation table that
// triangle_lanes.inc is written against.
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <algorithm>
#include <limits>

#include "triangle.hpp"

namespace tangent::detail::mikk {

#if defined(__SSE2__)
// Four lanes in SSE2 registers.
namespace {  // file-local, so that GCC inlines the lanes' helpers as in one function
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
}  // namespace
#endif

#if defined(__SSE2__)
void evaluateLanes4(const Arrays& a, std::size_t t, std::int8_t* orientation, std::uint8_t* flags, float* tangents) {
  lanes4::evaluateLanes(a, t, orientation, flags, tangents);
}
#endif

}  // namespace tangent::detail::mikk
