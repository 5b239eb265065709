// SPDX-License-Identifier: MIT
// Welding a primitive's packed corners into an indexed vertex buffer: corners whose packed
// vertices are equal bit for bit become one vertex. The vertex stage then shades each vertex
// once per run of the GL's post-transform cache instead of once per corner (a software
// rasteriser shades vertices on one thread, before its rasterising threads start), and the
// triangles it draws are the same bits as the corners', in the same order.
#pragma once

#include <cstdint>
#include <cstring>
#include <span>
#include <vector>

namespace tangent::viewer {

struct WeldedVertices {
  std::vector<float> vertices;         // the distinct packed vertices, in order of first use
  std::vector<std::uint32_t> indices;  // one per corner, into `vertices`
};

// `corners` holds floatsPerVertex floats per corner. Bitwise equality (not ==), so that -0
// and 0, or two NaNs, stay apart exactly when the GL could tell them apart.
inline WeldedVertices weldVertices(std::span<const float> corners, int floatsPerVertex) {
  const auto stride = static_cast<std::size_t>(floatsPerVertex);
  const std::size_t count = stride > 0 ? corners.size() / stride : 0;
  WeldedVertices welded;
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
  for (std::size_t c = 0; c < count; ++c) {
    const float* corner = corners.data() + c * stride;
    std::size_t slot = hashOf(corner) & (slots - 1);
    while (table[slot] != 0 &&
           std::memcmp(&welded.vertices[(table[slot] - 1) * stride], corner, stride * sizeof(float)) != 0)
      slot = (slot + 1) & (slots - 1);
    if (table[slot] == 0) {
      welded.vertices.insert(welded.vertices.end(), corner, corner + stride);
      table[slot] = static_cast<std::uint32_t>(welded.vertices.size() / stride);
    }
    welded.indices.push_back(table[slot] - 1);
  }
  return welded;
}

}  // namespace tangent::viewer
