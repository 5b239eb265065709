// SPDX-License-Identifier: MIT
// The hash of a vertex's eight values (position, normal, UV) that the weld (weld.cpp) and the
// WebAssembly package's sharing of de-indexed corners (wasm/src/shared_vertices.hpp) both use.
// Header-only and free of the workspace, so that the package can include it on its own.
#pragma once

#include <cstdint>
#include <cstring>

namespace tangent::detail {

// The hash of a vertex's values without their sign bits (equal values, +0 and -0 among them,
// equal hashes; values that differ in sign only collide, which costs a comparison). The eight
// values go in as four 64-bit pairs, three of them one load each (neighbours in their
// array), each pair multiplied on its own, then one finishing mix: a chain of three dependent
// multiplies per vertex. Mixing the values one after another made a chain of eight, and its
// latency was most of the weld's time per vertex.
inline std::uint64_t vertexHash(const float* p, const float* n, const float* t) {
  constexpr std::uint64_t kNoSigns = 0x7FFFFFFF7FFFFFFFull;
  auto two = [](const float* x) {
    std::uint64_t bits;
    std::memcpy(&bits, x, sizeof bits);
    return bits & kNoSigns;
  };
  auto one = [](float x) {
    std::uint32_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    return std::uint64_t(bits);
  };
  const std::uint64_t zx = (one(p[2]) | one(n[0]) << 32) & kNoSigns;
  std::uint64_t h = two(p) * 0x9E3779B97F4A7C15ull ^ zx * 0xC2B2AE3D27D4EB4Full ^ two(n + 1) * 0x165667B19E3779F9ull ^
                    two(t) * 0xD6E8FEB86659FD93ull;
  h ^= h >> 32;
  h *= 0xFF51AFD7ED558CCDull;
  h ^= h >> 29;
  h *= 0xC4CEB9FE1A85EC53ull;
  return h ^ (h >> 32);
}

}  // namespace tangent::detail
