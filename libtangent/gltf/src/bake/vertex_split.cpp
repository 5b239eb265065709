// SPDX-License-Identifier: MIT
// The vertex split (bake/vertex_split.hpp): two parallel passes, the same bits for any thread count.
#include "bake/vertex_split.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cstring>
#include <span>

#include "tangent/frame_rules.hpp"

namespace tangent::gltf::detail {
namespace {

// The input's index of corner c and normal of vertex v, as the core reads them from `mesh`.
std::uint32_t cornerIndex(const StridedMesh& mesh, std::size_t c) {
  const auto* bytes = static_cast<const std::uint8_t*>(mesh.indices);
  if (mesh.indexType == IndexType::uint16) {
    std::uint16_t index;
    std::memcpy(&index, bytes + 2 * c, sizeof index);
    return index;
  }
  std::uint32_t index;
  std::memcpy(&index, bytes + 4 * c, sizeof index);
  return index;
}

std::array<float, 3> vertexNormal(const StridedMesh& mesh, std::size_t v) {
  std::array<float, 3> normal;
  std::memcpy(normal.data(), static_cast<const std::uint8_t*>(mesh.normals) + v * mesh.normalStride, sizeof normal);
  return normal;
}

// slot = min(slot, value), where other threads may lower it at the same time.
inline void lowerTo(std::uint32_t& slot, std::uint32_t value) {
#if defined(TANGENT_SERIAL)
  slot = std::min(slot, value);
#else
  std::atomic_ref<std::uint32_t> shared(slot);
  std::uint32_t seen = shared.load(std::memory_order_relaxed);
  while (value < seen && !shared.compare_exchange_weak(seen, value, std::memory_order_relaxed)) {
  }
#endif
}

}  // namespace

// Two passes over the core's corner -> output vertex map (CornerOutputs::cornerVertex), each
// in parallel: the first corner of each output vertex (the smallest, kept by an atomic minimum,
// whatever order the chunks run in), then each output vertex's source vertex and tangent from
// it. A vertex no corner uses gets unusedVertexTangent of its normal.
VertexSplit splitVertices(const StridedMesh& mesh, const BulkVector<float>& cornerTangents, BulkVector<std::uint32_t> cornerVertex,
                          std::size_t outputVertices, Arena* arena) {
  VertexSplit split;
  const std::size_t cornerCount = mesh.indexCount;
  split.firstCorner.assign(outputVertices, kNoCorner);
  std::uint32_t* first = split.firstCorner.data();
  const std::uint32_t* vertexOf = cornerVertex.data();
  inChunks(arena, cornerCount, 1 << 16, [&](std::size_t begin, std::size_t end) {
    for (std::size_t c = begin; c < end; ++c) lowerTo(first[vertexOf[c]], static_cast<std::uint32_t>(c));
  });
  split.source.resize(outputVertices);
  split.tangents.resize(outputVertices * 4);
  inChunks(arena, outputVertices, 1 << 15, [&](std::size_t begin, std::size_t end) {
    for (std::size_t o = begin; o < end; ++o) {
      const std::uint32_t c = first[o];
      float* tangent = &split.tangents[4 * o];
      if (c == kNoCorner) {  // only an input vertex no triangle uses: every copy has a corner
        split.source[o] = static_cast<std::uint32_t>(o);
        const std::array<float, 3> normal = vertexNormal(mesh, o);
        unusedVertexTangent(std::span<const float, 3>(normal), std::span<float, 4>(tangent, 4));
        continue;
      }
      split.source[o] = cornerIndex(mesh, c);
      std::memcpy(tangent, &cornerTangents[4 * std::size_t(c)], 4 * sizeof(float));
    }
  });
  split.cornerVertex = std::move(cornerVertex);
  return split;
}

}  // namespace tangent::gltf::detail
