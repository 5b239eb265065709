// SPDX-License-Identifier: MIT
// The vertex split of a baked primitive (the core's corner -> output vertex map made into each
// output vertex's source vertex and tangent), and the parallel loop bake runs it on.
#pragma once

#include <cstdint>
#include <vector>

#include "tangent/bulk_buffer.hpp"
#include "tangent/tangent.hpp"

#if !defined(TANGENT_SERIAL)  // the web viewer's build has no oneTBB: its passes run here, in order
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#endif

namespace tangent::gltf::detail {

constexpr std::uint32_t kNoCorner = 0xffffffffu;

// Output vertices as the core split them: input vertex o stays o, copies follow.
struct VertexSplit {
  std::vector<std::uint32_t> source;       // original vertex of each output vertex
  std::vector<std::uint32_t> firstCorner;  // the first corner of each output vertex, kNoCorner if unused
  BulkVector<std::uint32_t> cornerVertex;
  std::vector<float> tangents;             // 4 per output vertex
};

#if defined(TANGENT_SERIAL)
struct Arena {};  // no threads
#else
using Arena = tbb::task_arena;
#endif

// Runs body(begin, end) over [0, n) in chunks of about `grain`, on `arena`'s threads where it
// has more than one (null: here, in one call). The bodies write disjoint elements, so the
// result does not depend on the threads. The core's forRange (core/src/parallel.hpp) does the
// same on a core workspace's threads; it is private to the core (it takes detail::WorkspaceData)
// and this layer runs on an arena of its own, so the glTF layer keeps this one.
template <typename Body>
void inChunks(Arena* arena, std::size_t n, std::size_t grain, const Body& body) {
#if !defined(TANGENT_SERIAL)
  if (arena && n > grain) {
    arena->execute([&] {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, grain),
                        [&](const tbb::blocked_range<std::size_t>& range) { body(range.begin(), range.end()); });
    });
    return;
  }
#endif
  (void)arena;
  (void)grain;
  body(std::size_t(0), n);
}

// Two passes over the core's corner -> output vertex map (CornerOutputs::cornerVertex), each
// in parallel: the first corner of each output vertex (the smallest, kept by an atomic minimum,
// whatever order the chunks run in), then each output vertex's source vertex and tangent from
// it. A vertex no corner uses gets unusedVertexTangent of its normal.
VertexSplit splitVertices(const StridedMesh& mesh, const BulkVector<float>& cornerTangents, BulkVector<std::uint32_t> cornerVertex,
                          std::size_t outputVertices, Arena* arena);

}  // namespace tangent::gltf::detail
