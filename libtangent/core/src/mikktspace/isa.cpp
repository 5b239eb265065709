// SPDX-License-Identifier: MIT
// Which vector width the triangle pass uses on this processor (TANGENT_MAX_CPU_ISA caps it).
#include <cstdlib>
#include <string_view>

#include "triangle.hpp"

namespace tangent::detail {

#if defined(__wasm_simd128__)
constexpr VectorIsa kFourLanes = VectorIsa::simd128;
#else
constexpr VectorIsa kFourLanes = VectorIsa::sse2;
#endif

VectorIsa activeVectorIsa() {
#if defined(TANGENT_LANES8)
  static const VectorIsa widest = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") ? VectorIsa::avx2 : VectorIsa::sse2;
  }();
#elif defined(__wasm_simd128__)  // first: the WebAssembly build also has SSE2's intrinsics (-msse2)
  constexpr VectorIsa widest = VectorIsa::simd128;
#elif defined(__SSE2__)
  constexpr VectorIsa widest = VectorIsa::sse2;
#else
  constexpr VectorIsa widest = VectorIsa::scalar;
#endif
  VectorIsa cap = VectorIsa::avx2;
  if (const char* name = std::getenv("TANGENT_MAX_CPU_ISA")) {
    const std::string_view value(name);
    if (value == "scalar") cap = VectorIsa::scalar;
    if (value == "sse2" || value == "simd128") cap = kFourLanes;  // either name: four lanes
  }
  return std::min(widest, cap);
}

}  // namespace tangent::detail
