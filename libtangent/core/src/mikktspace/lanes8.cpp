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
#define TANGENT_LANES_OWN_ROWS 1
#include "lanes.inc"
#undef TANGENT_LANES_OWN_ROWS
#undef TANGENT_LANES_OWN_SELECT
// vblendvps takes each lane from x where the mask's sign bit is set: the masks here are all
// ones or all zeros per lane. vmaxps gives y where x > y is false (NaN in either, or equal).
inline F select(F mask, F x, F y) { return _mm256_blendv_ps(y, x, mask); }
inline F maxF(F x, F y) { return _mm256_max_ps(x, y); }
inline F root(F x) { return _mm256_sqrt_ps(x); }
inline int movemask(F x) { return _mm256_movemask_ps(x); }
inline D lowHalf(F x) { return _mm256_cvtps_pd(_mm256_castps256_ps128(x)); }
inline D highHalf(F x) { return _mm256_cvtps_pd(_mm256_extractf128_ps(x, 1)); }
inline int movemaskD(D x) { return _mm256_movemask_pd(x); }
inline F selectSign(F mask, F x, F y) { return _mm256_blendv_ps(y, x, mask); }

// lanes.inc's row loads and stores in 256-bit registers: vertex j in the low half and vertex
// j + 4 in the high half of one register, so that one transpose within the halves serves
// eight lanes.
inline bool vertexRows(const std::uint32_t* triangles, std::size_t vertexCount, std::uint32_t (&three)[3 * kWidth]) {
  __m256i v[3];
#pragma GCC unroll 4
  for (int i = 0; i < 3; ++i) v[i] = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(triangles + 8 * i));
  const __m256i most = _mm256_max_epu32(_mm256_max_epu32(v[0], v[1]), v[2]);
  __m128i half = _mm_max_epu32(_mm256_castsi256_si128(most), _mm256_extracti128_si256(most, 1));
  half = _mm_max_epu32(half, _mm_shuffle_epi32(half, 0x4E));
  half = _mm_max_epu32(half, _mm_shuffle_epi32(half, 0xB1));
  const auto largest = static_cast<std::uint32_t>(_mm_cvtsi128_si32(half));
#pragma GCC unroll 4
  for (int i = 0; i < 3; ++i) {
    _mm256_store_si256(reinterpret_cast<__m256i*>(three + 8 * i), _mm256_add_epi32(_mm256_add_epi32(v[i], v[i]), v[i]));
  }
  // Read back from memory where used (one load an address), not extracted from the vectors
  // and kept in registers, which spills them.
  asm("" : "+m"(three));
  return std::size_t(largest) + 1 < vertexCount && largest < kRowsLimit;
}
inline void loadRows3(const float* base, const std::uint32_t* three, F (&out)[3]) {
  __m256 r[4];
#pragma GCC unroll 4
  for (int j = 0; j < 4; ++j) {
    const __m128 low = _mm_loadu_ps(base + three[3 * j]), high = _mm_loadu_ps(base + three[3 * (j + 4)]);
    r[j] = _mm256_insertf128_ps(_mm256_castps128_ps256(low), high, 1);
  }
  const __m256 l01 = _mm256_unpacklo_ps(r[0], r[1]), h01 = _mm256_unpackhi_ps(r[0], r[1]);  // x0 x1 y0 y1, z0 z1 . .
  const __m256 l23 = _mm256_unpacklo_ps(r[2], r[3]), h23 = _mm256_unpackhi_ps(r[2], r[3]);
  out[0] = _mm256_shuffle_ps(l01, l23, 0x44);
  out[1] = _mm256_shuffle_ps(l01, l23, 0xEE);
  out[2] = _mm256_shuffle_ps(h01, h23, 0x44);
}
inline void loadRows2(const float* base, const std::uint32_t* vertex, F& u, F& v) {
  // u, v of lanes j and j + 1 in one 128-bit register.
  auto pair = [&](int j) {
    const float* first = base + 2 * std::size_t(vertex[3 * j]);
    const float* second = base + 2 * std::size_t(vertex[3 * (j + 1)]);
    const __m128 low = _mm_castpd_ps(_mm_load_sd(reinterpret_cast<const double*>(first)));
    return _mm_loadh_pi(low, reinterpret_cast<const __m64*>(second));
  };
  const __m256 a = _mm256_insertf128_ps(_mm256_castps128_ps256(pair(0)), pair(4), 1);  // lanes 0 1 | 4 5
  const __m256 b = _mm256_insertf128_ps(_mm256_castps128_ps256(pair(2)), pair(6), 1);  // lanes 2 3 | 6 7
  u = _mm256_shuffle_ps(a, b, 0x88);
  v = _mm256_shuffle_ps(a, b, 0xDD);
}
inline void storeSlots(float* tangents, std::size_t t, int s, F c0, F c1, F c2, F c3) {
  const __m256 l01 = _mm256_unpacklo_ps(c0, c1), h01 = _mm256_unpackhi_ps(c0, c1);  // x0 y0 x1 y1, x2 y2 x3 y3
  const __m256 l23 = _mm256_unpacklo_ps(c2, c3), h23 = _mm256_unpackhi_ps(c2, c3);  // z0 w0 z1 w1, z2 w2 z3 w3
  const __m256 rows[4] = {_mm256_shuffle_ps(l01, l23, 0x44), _mm256_shuffle_ps(l01, l23, 0xEE),
                          _mm256_shuffle_ps(h01, h23, 0x44), _mm256_shuffle_ps(h01, h23, 0xEE)};
  float* slot = tangents + 4 * (3 * t + s);
#pragma GCC unroll 4
  for (int j = 0; j < 4; ++j) {
    _mm_storeu_ps(slot + 12 * j, _mm256_castps256_ps128(rows[j]));
    _mm_storeu_ps(slot + 12 * (j + 4), _mm256_extractf128_ps(rows[j], 1));
  }
}
// Orientations and flags: 32-bit lanes packed to bytes with signed saturation (the values
// are -1, 1 and small flags).
inline void storeBytes(F positive, F flat, std::int8_t* orientation, std::uint8_t* flags) {
  const auto o = reinterpret_cast<__m256i>(orientationLanes(positive));
  const auto f = reinterpret_cast<__m256i>(flagLanes(flat));
  const __m128i o16 = _mm_packs_epi32(_mm256_castsi256_si128(o), _mm256_extracti128_si256(o, 1));
  const __m128i f16 = _mm_packs_epi32(_mm256_castsi256_si128(f), _mm256_extracti128_si256(f, 1));
  const __m128i bytes = _mm_packs_epi16(o16, f16);
  _mm_storel_epi64(reinterpret_cast<__m128i*>(orientation), bytes);
  _mm_storel_epi64(reinterpret_cast<__m128i*>(flags), _mm_unpackhi_epi64(bytes, bytes));  // unaligned
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
