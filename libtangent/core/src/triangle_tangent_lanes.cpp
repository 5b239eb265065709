// SPDX-License-Identifier: MIT
// The double triangle pass several triangles at a time (triangle_lanes.inc): triangleTangent's
// arithmetic and lengyel's corner angles (triangleTangentsAt, triangle_tangent.cpp), flat's
// frames (flatFrameLanes) and meshopt's corner weights (meshoptWeightLanes). Two in SSE2 or
// SIMD128 registers (and, where neither is there, two lanes of plain doubles), four in AVX2
// registers where GCC builds for x86-64 and the processor has it (evaluateTriangles in
// lengyel.cpp picks the width per call from activeVectorIsa).
// The AVX2 lanes pass 32-byte vectors only to functions inlined into them (atanSeries from
// triangle_tangent.hpp among them, whose template GCC reports at its own line): no call
// crosses the ABI the note is about.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "gram_schmidt.hpp"
#include "triangle_tangent.hpp"

#if defined(__SSE2__)
#include <emmintrin.h>  // in WebAssembly emscripten's SSE2 on SIMD128 (wasm/build.sh: -msse2)
#endif
#if defined(TANGENT_DOUBLE_LANES4)
#include <immintrin.h>
#endif

namespace tangent::detail {
namespace {

constexpr double kRelativeZero = kTriangleRelativeZero;

namespace lanes2 {
constexpr int kLanes = 2;
using V = double __attribute__((vector_size(16)));
using M = std::int64_t __attribute__((vector_size(16)));
inline V root(V x) {
#if defined(__SSE2__)
  return reinterpret_cast<V>(_mm_sqrt_pd(reinterpret_cast<__m128d>(x)));
#else
  return V{std::sqrt(x[0]), std::sqrt(x[1])};
#endif
}
#include "triangle_lanes.inc"
}  // namespace lanes2

}  // namespace

void evaluateTriangleLanes2(TriangleLanes& lanes, int first, TriangleTangent* out) {
  lanes2::evaluate(lanes, first, out);
}
void flatFrameLanes2(FlatLanes& lanes, int first) { lanes2::flatFrames(lanes, first); }
void meshoptWeightLanes2(const TriangleLanes& values, MeshoptLanes& lanes, int first) {
  lanes2::meshoptWeights(values, lanes, first);
}

#if defined(TANGENT_DOUBLE_LANES4)
// Compiled for AVX2 (no FMA: no operation is fused) and run where the processor has it.
#pragma GCC push_options
#pragma GCC target("avx2")
namespace {
namespace lanes4 {
constexpr int kLanes = 4;
using V = double __attribute__((vector_size(32)));
using M = std::int64_t __attribute__((vector_size(32)));
inline V root(V x) { return reinterpret_cast<V>(_mm256_sqrt_pd(reinterpret_cast<__m256d>(x))); }
#include "triangle_lanes.inc"
}  // namespace lanes4
}  // namespace

void evaluateTriangleLanes4(TriangleLanes& lanes, TriangleTangent* out) { lanes4::evaluate(lanes, 0, out); }
void flatFrameLanes4(FlatLanes& lanes) { lanes4::flatFrames(lanes, 0); }
void meshoptWeightLanes4(const TriangleLanes& values, MeshoptLanes& lanes) { lanes4::meshoptWeights(values, lanes, 0); }
#pragma GCC pop_options
#endif

}  // namespace tangent::detail

namespace tangent::detail {

void flatFrameLanes(FlatLanes& lanes, int width) {
#if defined(TANGENT_DOUBLE_LANES4)
  if (width == 4) {
    flatFrameLanes4(lanes);
    return;
  }
#endif
  flatFrameLanes2(lanes, 0);
  flatFrameLanes2(lanes, 2);
}

void meshoptWeightLanes(const TriangleLanes& values, MeshoptLanes& lanes, int width) {
#if defined(TANGENT_DOUBLE_LANES4)
  if (width == 4) {
    meshoptWeightLanes4(values, lanes);
    return;
  }
#endif
  meshoptWeightLanes2(values, lanes, 0);
  meshoptWeightLanes2(values, lanes, 2);
}

}  // namespace tangent::detail
