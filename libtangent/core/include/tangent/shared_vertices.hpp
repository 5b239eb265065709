// SPDX-License-Identifier: MIT
// De-indexed input (every corner its own vertex, as the npm package's generateTangents and
// glTF-Transform take it) made indexed before the core sees it: corners whose position, normal
// and UV have the same bits share one vertex. The core then welds and buckets a sixth as many vertices on a typical mesh (each
// vertex of a closed triangle mesh has about six corners), and its per-vertex arrays shrink
// alike. Each corner keeps exactly its own bits, and the core's results depend on the corners'
// values only, never on how the vertices are numbered, so its output is the same to the bit:
// values that are equal but not the same bits (+0 and -0) stay apart here and the core welds
// them as it would have; a vertex with a NaN is never shared (NaN equals nothing).
// Use: shareVertices (or a VertexSharer fed in runs), then computeCornerTangents on the shared
// arrays with TangentWorkspace::setWeldOnly(zeroVertices) for that call.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "tangent/bulk_buffer.hpp"

namespace tangent {

// Sized for the worst case (every corner its own vertex) but never zero-filled (BulkVector):
// only the pages the shared vertices use are touched.
struct SharedVertices {
  BulkVector<float> positions, normals, uvs;  // 3, 3, 2 per shared vertex
  BulkVector<std::uint32_t> indices;          // per corner: its shared vertex
  // Open addressing, (vertex + 1, hash) per slot; the slot is the hash's low bits.
  std::vector<std::uint32_t> table;
  // The vertex a hash last found or made, at the hash's top kRecentBits bits: (vertex + 1, hash).
  std::vector<std::uint32_t> recent;
  std::size_t vertexCount = 0;
  // The shared vertices with a value of +0 or -0, in increasing order: the only ones the core
  // can still weld with another (TangentWorkspace::setWeldOnly), since they are distinct by bits.
  std::vector<std::uint32_t> zeroVertices;
  std::uint32_t probeSink = 0;  // the sum of shareVertices' early loads (kept, so not dropped)
  // shareVertices on several threads: per corner its hash, then its first corner of the same
  // bits, then its vertex (reused from call to call, never zero-filled).
  BulkVector<std::uint32_t> cornerHash, firstCorner, cornerVertex;
};

// Shares the corners of one call as they come, a run of corners at a time (the WebAssembly
// package passes the input through a small staging buffer instead of copying all of it into
// the module's memory first). The shared vertices are numbered in order of their first corner.
class VertexSharer {
 public:
  // Starts a call of `cornerCount` corners; `out` is filled by add() and must outlive the call.
  void begin(std::size_t cornerCount, SharedVertices& out);

  // The next `count` corners (positions 3, normals 3, uvs 2 per corner); false when they would
  // run past begin()'s count.
  bool add(const float* positions, const float* normals, const float* uvs, std::size_t count);

  std::size_t added() const { return added_; }

 private:
  void grow();

  SharedVertices* out_ = nullptr;
  std::size_t cornerCount_ = 0, added_ = 0, count_ = 0, capacity_ = 0;
};

// All of `cornerCount` corners at once. On `threads` threads (0: every hardware thread) where
// there are more than one and the build has threads: the same vertices, numbers, indices and
// zero list as one thread's VertexSharer gives, for any thread count.
void shareVertices(const float* positions, const float* normals, const float* uvs, std::size_t cornerCount,
                   SharedVertices& out, unsigned threads = 1);

// The threads shareVertices shares `cornerCount` corners on, given `threads`: 1 (one thread's
// VertexSharer) up to 131,072 corners, in a build without threads, or where `threads` is 1.
// A caller that has the corners in pieces copies them whole only where this is above 1.
unsigned threadsToShareOn(std::size_t cornerCount, unsigned threads = 1);

}  // namespace tangent
