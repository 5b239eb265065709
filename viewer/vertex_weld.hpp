// SPDX-License-Identifier: MIT
// Welding a primitive's packed corners into an indexed vertex buffer: corners whose packed
// vertices are equal bit for bit become one vertex. The vertex stage then shades each vertex
// once per run of the GL's post-transform cache instead of once per corner (a software
// rasteriser shades vertices on one thread, before its rasterising threads start), and the
// triangles it draws are the same bits as the corners', in the same order.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <vector>

namespace tangent::viewer {

struct WeldedVertices {
  std::vector<float> vertices;         // the distinct packed vertices, in order of first use
  std::vector<std::uint32_t> indices;  // one per corner, into `vertices`
};

// `count` corners of `floatsPerVertex` floats each, corner c written by pack(c, out) into `out`
// (floatsPerVertex floats; called once per corner, in order): welded as they are packed, so the
// packed corners are never held all at once (26 floats a corner are 3 GB at 10^7 triangles).
// Bitwise equality (not ==), so that -0 and 0, or two NaNs, stay apart exactly when the GL
// could tell them apart.
template <typename Pack>
WeldedVertices weldPackedCorners(std::size_t count, int floatsPerVertex, const Pack& pack) {
  const auto stride = static_cast<std::size_t>(floatsPerVertex);
  WeldedVertices welded;
  if (stride == 0) return welded;
  welded.indices.reserve(count);
  // Open addressing, linear probing: slot -> vertex number + 1 (0 empty), at most half full.
  std::size_t slots = 16;
  while (slots < 2 * count) slots *= 2;
  std::vector<std::uint32_t> table(slots, 0);
  auto hashOf = [&](const float* vertex) {
    std::uint64_t hash = 14695981039346656037ull;  // FNV-1a over the 32-bit words
    for (std::size_t i = 0; i < stride; ++i) {
      std::uint32_t word;
      std::memcpy(&word, vertex + i, sizeof word);
      hash = (hash ^ word) * 1099511628211ull;
    }
    return hash ^ (hash >> 29);
  };
  // A block of corners at a time: packed and hashed, then their slots fetched ahead, then the
  // vertices those slots hold, then probed in order (the table and the vertices are larger than
  // the caches: a miss per corner each, otherwise). The fetches are hints: the same result.
  constexpr std::size_t kBlock = 16;
  std::vector<float> block(kBlock * stride);
  std::uint64_t hashes[kBlock];
  for (std::size_t first = 0; first < count; first += kBlock) {
    const std::size_t n = std::min(kBlock, count - first);
    for (std::size_t i = 0; i < n; ++i) {
      pack(first + i, &block[i * stride]);
      hashes[i] = hashOf(&block[i * stride]);
      __builtin_prefetch(&table[hashes[i] & (slots - 1)]);
    }
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint32_t held = table[hashes[i] & (slots - 1)];
      if (held != 0) __builtin_prefetch(&welded.vertices[(held - 1) * stride]);
    }
    for (std::size_t i = 0; i < n; ++i) {
      const float* corner = &block[i * stride];
      std::size_t slot = hashes[i] & (slots - 1);
      while (table[slot] != 0 && std::memcmp(&welded.vertices[(table[slot] - 1) * stride], corner, stride * sizeof(float)) != 0)
        slot = (slot + 1) & (slots - 1);
      if (table[slot] == 0) {
        welded.vertices.insert(welded.vertices.end(), corner, corner + stride);
        table[slot] = static_cast<std::uint32_t>(welded.vertices.size() / stride);
      }
      welded.indices.push_back(table[slot] - 1);
    }
  }
  return welded;
}

}  // namespace tangent::viewer
