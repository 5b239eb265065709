// SPDX-License-Identifier: MIT
// The triangle pass four triangles at a time: in SSE2 registers on x86, in SIMD128 registers
// in WebAssembly (emscripten with -msimd128). lanes.inc's table, and the operations it leaves
// to each instruction set.
#if defined(__SSE2__)
#include <emmintrin.h>
#elif defined(__wasm_simd128__)
#include <wasm_simd128.h>
#endif

#include <algorithm>
#include <cstring>
#include <limits>
#include <utility>

#include "triangle.hpp"

namespace tangent::detail::mikk {

#if defined(TANGENT_LANES4)
namespace {  // file-local: compiled for this instruction set only, and inlined as in one function
namespace lanes4 {
constexpr int kWidth = 4;
#include "lanes.inc"
#if defined(__SSE2__)
inline F root(F x) { return _mm_sqrt_ps(x); }
inline int movemask(F x) { return _mm_movemask_ps(x); }
inline D lowHalf(F x) { return _mm_cvtps_pd(x); }
inline D highHalf(F x) { return _mm_cvtps_pd(_mm_movehl_ps(x, x)); }
#else
inline v128_t raw(F x) { return reinterpret_cast<v128_t>(x); }
inline F root(F x) { return reinterpret_cast<F>(wasm_f32x4_sqrt(raw(x))); }
inline int movemask(F x) { return static_cast<int>(wasm_i32x4_bitmask(raw(x))); }
inline D lowHalf(F x) { return reinterpret_cast<D>(wasm_f64x2_promote_low_f32x4(raw(x))); }
inline D highHalf(F x) { return lowHalf(__builtin_shufflevector(x, x, 2, 3, 0, 1)); }
#endif
#include "triangle_lanes.inc"
}  // namespace lanes4
}  // namespace

void evaluateLanes4(const Arrays& a, std::size_t t, std::int8_t* orientation, std::uint8_t* flags, float* tangents) {
  lanes4::evaluateLanes(a, t, orientation, flags, tangents);
}
#endif

}  // namespace tangent::detail::mikk
