// SPDX-License-Identifier: MIT
// The triangle pass four triangles at a time in WebAssembly SIMD128 registers (emscripten
// with -msimd128): lanes.inc's table, and the operations it leaves to each instruction set.
#include <algorithm>
#include <cstring>
#include <limits>
#include <utility>

#include "triangle.hpp"

#if defined(__wasm_simd128__)
#include <wasm_simd128.h>
#endif

namespace tangent::detail::mikk {

#if defined(__wasm_simd128__)
namespace {  // file-local, and inlined as in one function
namespace lanes4 {
constexpr int kWidth = 4;
#include "lanes.inc"
inline F root(F x) { return reinterpret_cast<F>(wasm_f32x4_sqrt(reinterpret_cast<v128_t>(x))); }
inline int movemask(F x) { return static_cast<int>(wasm_i32x4_bitmask(reinterpret_cast<v128_t>(x))); }
inline D lowHalf(F x) { return reinterpret_cast<D>(wasm_f64x2_promote_low_f32x4(reinterpret_cast<v128_t>(x))); }
inline D highHalf(F x) { return lowHalf(__builtin_shufflevector(x, x, 2, 3, 0, 1)); }
#include "triangle_lanes.inc"
}  // namespace lanes4
}  // namespace

void evaluateLanes4(const Arrays& a, std::size_t t, std::int8_t* orientation, std::uint8_t* flags, float* tangents) {
  lanes4::evaluateLanes(a, t, orientation, flags, tangents);
}
#endif

}  // namespace tangent::detail::mikk
