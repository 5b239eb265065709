// SPDX-License-Identifier: MIT
// The triangle pass eight triangles at a time in AVX2 registers: the operation table that
// triangle_lanes.inc is written against.
#include <algorithm>
#include <limits>

#include "triangle.hpp"

#if defined(TANGENT_LANES8)
#include <immintrin.h>
#endif

namespace tangent::detail::mikk {

#if defined(TANGENT_LANES8)
// Eight lanes in AVX2 registers: this code only, compiled for AVX2 (no FMA, so no operation
// is fused) and run where the processor has it (vectorIsa).
#pragma GCC push_options
#pragma GCC target("avx2")
// The lambdas here take and return AVX vectors; they are all inlined in this file, so the
// note that such calls pass them differently without AVX does not apply.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"
namespace {  // file-local, so that GCC inlines the lanes' helpers as in one function
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
}  // namespace

// Compiled for AVX2 too, so that the lanes inline into it.
void evaluateLanes8(const Arrays& a, std::size_t t, std::int8_t* orientation, std::uint8_t* flags, float* tangents) {
  lanes8::evaluateLanes(a, t, orientation, flags, tangents);
}
#pragma GCC diagnostic pop
#pragma GCC pop_options
#endif

}  // namespace tangent::detail::mikk
