// SPDX-License-Identifier: MIT
// De-indexed input (every corner its own vertex, as generateTangents takes it) made indexed
// before the core sees it: corners whose position, normal and UV have the same bits share one
// vertex. The core then welds and buckets a sixth as many vertices on a typical mesh (each
// vertex of a closed triangle mesh has about six corners), and its per-vertex arrays shrink
// alike. Each corner keeps exactly its own bits, and the core's results depend on the corners'
// values only, never on how the vertices are numbered, so its output is the same to the bit:
// values that are equal but not the same bits (+0 and -0) stay apart here and the core welds
// them as it would have; a vertex with a NaN is never shared (NaN equals nothing).
// Header-only and free of emscripten so that a native build can time it against the core.
#pragma once

#include <cstdint>
#include <cstring>
#include <vector>

#include "tangent/bulk_buffer.hpp"

namespace tangent::wasm {

// Sized for the worst case (every corner its own vertex) but never zero-filled (BulkVector):
// only the pages the shared vertices use are touched.
struct SharedVertices {
  BulkVector<float> positions, normals, uvs;  // 3, 3, 2 per shared vertex
  BulkVector<std::uint32_t> indices;          // per corner: its shared vertex
  std::vector<std::uint32_t> table;           // open addressing: (hash, vertex + 1) per slot
  std::size_t vertexCount = 0;
};

namespace detail {

inline std::uint32_t floatBits(float x) {
  std::uint32_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  return bits;
}

// A vertex's 32-byte key: its eight floats' bits.
struct VertexKey {
  std::uint32_t bits[8];
};

inline VertexKey keyOf(const float* p, const float* n, const float* t) {
  const float values[8] = {p[0], p[1], p[2], n[0], n[1], n[2], t[0], t[1]};
  VertexKey key;
  for (int i = 0; i < 8; ++i) key.bits[i] = floatBits(values[i]);
  return key;
}

// Four independent 64-bit multiplies, then one finishing mix; the top 32 bits are used.
inline std::uint32_t hashOf(const VertexKey& key) {
  auto pair = [&](int i) { return std::uint64_t(key.bits[i]) | std::uint64_t(key.bits[i + 1]) << 32; };
  std::uint64_t h = pair(0) * 0x9E3779B97F4A7C15ull ^ pair(2) * 0xC2B2AE3D27D4EB4Full ^ pair(4) * 0x165667B19E3779F9ull ^
                    pair(6) * 0xD6E8FEB86659FD93ull;
  h ^= h >> 29;
  h *= 0xFF51AFD7ED558CCDull;
  return static_cast<std::uint32_t>(h >> 32);
}

// Whether `count` floats have the same bits (no call to memcmp: WebAssembly has no inline one).
inline bool sameBits(const float* a, const float* b, int count) {
  std::uint32_t differ = 0;
  for (int i = 0; i < count; ++i) differ |= floatBits(a[i]) ^ floatBits(b[i]);
  return differ == 0;
}

}  // namespace detail

// Fills `out` from `cornerCount` de-indexed corners (positions 3, normals 3, uvs 2 per corner).
// The shared vertices are numbered in order of their first corner.
inline void shareVertices(const float* positions, const float* normals, const float* uvs, std::size_t cornerCount,
                          SharedVertices& out) {
  // Sized for about a sixth as many vertices as corners, at most half full; grown (rehashed
  // from the stored hashes) where a mesh shares less.
  std::size_t capacity = 64;
  while (capacity < cornerCount / 3) capacity *= 2;
  out.table.assign(2 * capacity, 0u);
  if (out.positions.size() < 3 * cornerCount) {
    out.positions.resize(3 * cornerCount);
    out.normals.resize(3 * cornerCount);
    out.uvs.resize(2 * cornerCount);
  }
  out.indices.resize(cornerCount);
  float* P = out.positions.data();
  float* N = out.normals.data();
  float* T = out.uvs.data();
  std::uint32_t* table = out.table.data();
  std::size_t mask = capacity - 1, count = 0;
  for (std::size_t c = 0; c < cornerCount; ++c) {
    const float* p = positions + 3 * c;
    const float* n = normals + 3 * c;
    const float* t = uvs + 2 * c;
    const bool hasNaN = p[0] != p[0] || p[1] != p[1] || p[2] != p[2] || n[0] != n[0] || n[1] != n[1] || n[2] != n[2] ||
                        t[0] != t[0] || t[1] != t[1];
    auto same = [&](std::uint32_t v) {
      return detail::sameBits(P + 3 * v, p, 3) && detail::sameBits(N + 3 * v, n, 3) && detail::sameBits(T + 2 * v, t, 2);
    };
    std::uint32_t vertex = static_cast<std::uint32_t>(count);
    if (!hasNaN) {
      const std::uint32_t hash = detail::hashOf(detail::keyOf(p, n, t));
      for (std::size_t slot = hash & mask;; slot = (slot + 1) & mask) {
        std::uint32_t* entry = table + 2 * slot;
        if (entry[1] == 0) {
          entry[0] = hash;
          entry[1] = vertex + 1;
          break;
        }
        if (entry[0] == hash && same(entry[1] - 1)) {
          vertex = entry[1] - 1;
          break;
        }
      }
    }
    out.indices[c] = vertex;
    if (vertex != count) continue;
    std::memcpy(P + 3 * count, p, 12);
    std::memcpy(N + 3 * count, n, 12);
    std::memcpy(T + 2 * count, t, 8);
    ++count;
    if (2 * count > capacity) {  // more than half full: twice the slots
      std::vector<std::uint32_t> old(std::move(out.table));
      capacity *= 2;
      mask = capacity - 1;
      out.table.assign(2 * capacity, 0u);
      table = out.table.data();
      for (std::size_t s = 0; s < old.size(); s += 2) {
        if (old[s + 1] == 0) continue;
        std::size_t slot = old[s] & mask;
        while (table[2 * slot + 1] != 0) slot = (slot + 1) & mask;
        table[2 * slot] = old[s];
        table[2 * slot + 1] = old[s + 1];
      }
    }
  }
  out.vertexCount = count;
}

}  // namespace tangent::wasm
