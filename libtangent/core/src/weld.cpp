// SPDX-License-Identifier: MIT
// Welding vertices by exact value, as the reference identifies corners, and bucketing the
// corners by welded vertex (a parallel counting sort). Shared by every method.
#include "parallel.hpp"
#include "vertex_hash.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace tangent::detail {
namespace {

// The weld's hash of vertex v (vertex_hash.hpp).
std::uint64_t vertexHash(const MeshArrays& mesh, std::size_t v) {
  return detail::vertexHash(&mesh.positions[3 * v], &mesh.normals[3 * v], &mesh.uvs[2 * v]);
}

// The reference's identity of a corner: every value equal as floats (+0 == -0, NaN != NaN).
bool sameVertex(const MeshArrays& mesh, std::size_t a, std::size_t b) {
  for (int i = 0; i < 3; ++i) {
    if (mesh.positions[3 * a + i] != mesh.positions[3 * b + i] || mesh.normals[3 * a + i] != mesh.normals[3 * b + i])
      return false;
  }
  return mesh.uvs[2 * a] == mesh.uvs[2 * b] && mesh.uvs[2 * a + 1] == mesh.uvs[2 * b + 1];
}

// countingSortInChunks (parallel.hpp) by key(i) of each item.
template <typename Key, typename Fill>
void stableCountingSort(const WorkspaceData& ws, std::size_t count, std::size_t keys, std::size_t chunks, const Key& key,
                        std::uint32_t* counters, std::uint32_t* groupStart, const Fill& fill, std::size_t align = 1) {
  countingSortInChunks(
      ws, count, keys, chunks,
      [&](std::size_t begin, std::size_t end, std::uint32_t* counter) {
        for (std::size_t i = begin; i < end; ++i) ++counter[key(i)];
      },
      counters, groupStart, fill, align);
}
template <typename Key>
void stableCountingSort(const WorkspaceData& ws, std::size_t count, std::size_t keys, std::size_t chunks, const Key& key,
                        std::uint32_t* counters, std::uint32_t* groupStart, std::uint32_t* out) {
  stableCountingSort(ws, count, keys, chunks, key, counters, groupStart,
                     [&](std::size_t begin, std::size_t end, std::uint32_t* next) {
                       for (std::size_t i = begin; i < end; ++i) out[next[key(i)]++] = static_cast<std::uint32_t>(i);
                     });
}

// A piece of `count` items for the workspace's threads: about four pieces a thread, at least
// `least` and at most `most` items (so that 16 threads have work at 1e5 triangles, and the
// counters, pieces * keys, stay few at 4e6). The bits do not depend on it.
std::size_t pieceLength(const WorkspaceData& ws, std::size_t count, std::size_t least, std::size_t most) {
  return std::clamp(count / (4 * std::size_t(std::max(ws.threads, 1u))), least, most);
}

// Brings a table slot into cache ahead of its probe: a prefetch where the target has one.
// WebAssembly has none (the builtin compiles to nothing), so there the slot is loaded and its
// value summed into `sink`, which keepSink stores where the compiler cannot drop it: loads
// issued back to back wait for memory together, where a probe's branch on a missing slot
// would wait for each miss in turn.
inline void touchSlot(const std::uint32_t* slot, [[maybe_unused]] std::uint32_t& sink) {
#if defined(__wasm__)
  sink += *slot;
#else
  prefetch(slot);
#endif
}
inline void keepSink([[maybe_unused]] std::uint32_t sink) {
#if defined(__wasm__)
  volatile std::uint32_t kept = sink;
  (void)kept;
#endif
}

// One table, `count` vertices in order (the i-th is vertexAt(i)); the tag is the hash's top
// 32 bits.
template <typename VertexAt, typename Insert>
void weldInOneTable(WorkspaceData& ws, const MeshArrays& mesh, std::size_t count, const VertexAt& vertexAt,
                    const Insert& insert) {
  std::size_t tableSize = 16;
  while (tableSize < 2 * count) tableSize *= 2;
  ensureSize(ws.table, 2 * tableSize);
  std::uint32_t* table = ws.table.data();
  std::fill(table, table + 2 * tableSize, 0u);
  const std::size_t mask = tableSize - 1;
  // The table (megabytes) is probed at random: a batch of vertices is hashed and each one's
  // slot asked for (touchSlot) before the batch's probes, so that the probes find their
  // slots in cache and their misses overlap instead of waiting one after another.
  constexpr std::size_t kBatch = 64;
  std::uint64_t hashes[kBatch];
  std::uint32_t sink = 0;
  for (std::size_t first = 0; first < count; first += kBatch) {
    const std::size_t batch = std::min(kBatch, count - first);
    for (std::size_t i = 0; i < batch; ++i) {
      hashes[i] = vertexHash(mesh, vertexAt(first + i));
      touchSlot(table + 2 * (hashes[i] & mask), sink);
    }
    for (std::size_t i = 0; i < batch; ++i) {
      insert(table, mask, vertexAt(first + i), hashes[i], static_cast<std::uint32_t>(hashes[i] >> 32));
    }
  }
  keepSink(sink);
}

// The vertices split into partitions by their hash, one small table per partition, in parallel.
template <typename Insert>
void weldInPartitions(WorkspaceData& ws, const MeshArrays& mesh, const Insert& insert) {
  const std::size_t vertexCount = ws.vertexCount, cornerCount = ws.cornerCount;
  std::uint32_t* vertexId = ws.vertexId.data();
  // Threads: the vertices split by the top bits of their hash into partitions (a counting
  // sort that keeps vertex order inside each), one small table per partition, partitions
  // in parallel. Equal values share a hash, so each partition welds on its own; no atomics,
  // and the tables stay in cache. The hashes (partition in the top 8 bits, 24 bits of slot),
  // the tags (32 bits of the hash from bit 24) and the order live in the bucket arrays,
  // which are filled only after the weld.
  constexpr int kPartitionBits = 8;
  constexpr std::size_t kPartitions = std::size_t(1) << kPartitionBits;
  const std::size_t chunk = pieceLength(ws, vertexCount, 1 << 12, 1 << 15);
  const std::size_t chunkCount = (vertexCount + chunk - 1) / chunk;
  ensureSize(ws.bucketExtra, vertexCount + 1);
  ensureSize(ws.bucketStart, vertexCount + 1);
  ensureSize(ws.bucketCorners, std::max(cornerCount, vertexCount));
  ensureSize(ws.weldCounts, chunkCount * kPartitions + kPartitions + 1);
  std::uint32_t* hashes = ws.bucketExtra.data();
  std::uint32_t* tags = ws.bucketStart.data();
  std::uint32_t* order = ws.bucketCorners.data();
  std::uint32_t* counts = ws.weldCounts.data();  // [chunk][partition], then partition starts
  std::uint32_t* partitionStart = counts + chunkCount * kPartitions;
  auto partitionOf = [](std::uint32_t hash) { return static_cast<std::size_t>(hash >> (32 - kPartitionBits)); };
  forRange(ws, vertexCount, chunk, [&](std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) {
      const std::uint64_t hash = vertexHash(mesh, v);
      hashes[v] = static_cast<std::uint32_t>(hash >> 32 & 0xFF000000u) | static_cast<std::uint32_t>(hash & 0xFFFFFFu);
      tags[v] = static_cast<std::uint32_t>(hash >> 24);
    }
  });
  stableCountingSort(ws, vertexCount, kPartitions, chunkCount, [&](std::size_t v) { return partitionOf(hashes[v]); }, counts,
                     partitionStart, order);
  // Table of partition p: a power of two of at least twice its vertices, at tableStart[p].
  std::size_t tableSize = 0;
  std::array<std::size_t, kPartitions + 1> tableStart;
  for (std::size_t p = 0; p < kPartitions; ++p) {
    std::size_t size = 16;
    while (size < 2 * std::size_t(partitionStart[p + 1] - partitionStart[p])) size *= 2;
    tableStart[p] = tableSize;
    tableSize += size;
  }
  tableStart[kPartitions] = tableSize;
  ensureSize(ws.table, 2 * tableSize);
  std::uint32_t* table = ws.table.data();
  forRange(ws, kPartitions, 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t p = begin; p < end; ++p) {
      std::uint32_t* part = table + 2 * tableStart[p];
      const std::size_t mask = tableStart[p + 1] - tableStart[p] - 1;
      std::fill(part, part + 2 * (mask + 1), 0u);
      // A partition's vertices lie all over the arrays (every 256th or so): their hash,
      // tag and id are asked for kAhead vertices early.
      constexpr std::uint32_t kAhead = 8;
      auto ask = [&](std::uint32_t v) {
        prefetch(hashes + v);
        prefetch(tags + v);
        prefetch(vertexId + v);
      };
      const std::uint32_t first = partitionStart[p], last = partitionStart[p + 1];
      for (std::uint32_t i = first; i < std::min(last, first + kAhead); ++i) ask(order[i]);
      for (std::uint32_t i = first; i < last; ++i) {
        if (i + kAhead < last) ask(order[i + kAhead]);
        const std::uint32_t v = order[i];
        insert(part, mask, v, hashes[v] & 0xFFFFFFu, tags[v]);
      }
    }
  });
}

// Corners [begin, end) triangle by triangle, each placed with its welded id and its triangle's
// next and previous ids (the edge identities the pairing reads): `place(corner, id, nextId,
// previousId)`. The one order both bucket fills place corners in.
template <typename Id, typename Place>
inline void placeByTriangle(std::size_t begin, std::size_t end, const Id& id, const Place& place) {
  for (std::size_t c = begin; c < end; c += 3) {
    const std::uint32_t v0 = id(c), v1 = id(c + 1), v2 = id(c + 2);
    place(c, v0, v1, v2);
    place(c + 1, v1, v2, v0);
    place(c + 2, v2, v0, v1);
  }
}

// The buckets from four threads on, where slices * vertices counters grow too large: two
// stable passes. First the corners by range of 2^rangeBits welded ids (per-chunk counters,
// small), triangle by triangle, each with its welded id and (with edges) its next and previous
// identities beside it; then each range on its own, its counters in cache, moving what the
// first pass wrote. No atomics: on 16 CPUs, counting and filling through atomic counters then
// sorting each bucket ran 2x faster than one thread at best, a quarter of the call's wall time
// at 1e6 and 4e6 triangles. Nor does the second pass read through the indices again: reading
// each corner's ids there (a gather per corner, the corners of a range lie all over the mesh)
// made this way cost four times the instructions of the one below four threads.
template <bool kEdges, typename Id>
void bucketByRanges(WorkspaceData& ws, const Id& id) {
  const std::size_t vertexCount = ws.vertexCount, cornerCount = ws.cornerCount;
  int rangeBits = 8;  // ranges of 2^8 to 2^12 welded ids, about four a thread
  while (rangeBits < 12 && std::size_t(2) << rangeBits <= pieceLength(ws, vertexCount, 1, vertexCount + 1)) ++rangeBits;
  const std::size_t vertexRange = std::size_t(1) << rangeBits;
  const std::size_t ranges = (vertexCount + vertexRange - 1) / vertexRange;
  const std::size_t cornerChunk = pieceLength(ws, cornerCount, 3 << 10, 3 << 15);
  const std::size_t chunks = (cornerCount + cornerChunk - 1) / cornerChunk;
  ensureSize(ws.weldCounts, chunks * ranges + ranges + 1);
  // The first pass's output lies where the second writes its own (the bucket arrays, range
  // by range), but for the corners: those go in the kernel's per-corner links (the same
  // size, written only later), so that no array grows for them.
  ensureSize(ws.cornerLink, cornerCount);
  std::uint32_t* rangeStart = ws.weldCounts.data() + chunks * ranges;
  std::uint32_t* byCorner = ws.cornerLink.data();
  std::uint32_t* start = ws.bucketStart.data();
  std::uint32_t* cursor = ws.bucketExtra.data();
  std::uint32_t* corners = ws.bucketCorners.data();
  std::uint32_t* nextIds = ws.bucketNextId.data();
  std::uint32_t* previousIds = ws.bucketPreviousId.data();
  std::uint32_t* byId = corners;
  auto fill = [&](std::size_t begin, std::size_t end, std::uint32_t* next) {
    auto place = [&](std::size_t c, std::uint32_t v, std::uint32_t nextId, std::uint32_t previousId) {
      const std::uint32_t slot = next[v >> rangeBits]++;
      byCorner[slot] = static_cast<std::uint32_t>(c);
      byId[slot] = v;
      if constexpr (kEdges) {
        nextIds[slot] = nextId;
        previousIds[slot] = previousId;
      }
    };
    placeByTriangle(begin, end, id, place);
  };
  stableCountingSort(ws, cornerCount, ranges, chunks, [&](std::size_t c) { return id(c) >> rangeBits; },
                     ws.weldCounts.data(), rangeStart, fill, 3);
  forRange(ws, ranges, 1, [&](std::size_t begin, std::size_t end) {
    // A range's ids (and identities) copied aside: the moves below overwrite them.
    ScratchVector<std::uint32_t>& aside = ws.scratch.local().rangeIds;
    for (std::size_t r = begin; r < end; ++r) {
      const std::size_t first = r * vertexRange, last = std::min(vertexCount, first + vertexRange);
      const std::uint32_t from = rangeStart[r], n = rangeStart[r + 1] - from;
      std::uint32_t* count = cursor + first;  // this range's counters, then its cursors
      std::fill(count, count + (last - first), 0u);
      for (std::uint32_t i = from; i < from + n; ++i) ++cursor[byId[i]];
      std::uint32_t total = from;
      for (std::size_t v = first; v < last; ++v) {
        const std::uint32_t k = cursor[v];
        start[v] = cursor[v] = total;
        total += k;
      }
      if (n == 0) continue;
      ensureSize(aside, std::size_t(n) * (kEdges ? 3 : 1));  // grown only: no zeroing per range
      std::uint32_t* ids = aside.data();
      std::memcpy(ids, byId + from, n * sizeof(std::uint32_t));
      if constexpr (kEdges) {
        std::uint32_t* nexts = ids + n;
        std::uint32_t* previouses = ids + 2 * std::size_t(n);
        std::memcpy(nexts, nextIds + from, n * sizeof(std::uint32_t));
        std::memcpy(previouses, previousIds + from, n * sizeof(std::uint32_t));
        for (std::uint32_t i = 0; i < n; ++i) {
          const std::uint32_t slot = cursor[ids[i]]++;
          corners[slot] = byCorner[from + i];
          nextIds[slot] = nexts[i];
          previousIds[slot] = previouses[i];
        }
      } else {
        for (std::uint32_t i = 0; i < n; ++i) corners[cursor[ids[i]]++] = byCorner[from + i];
      }
    }
  });
  start[vertexCount] = static_cast<std::uint32_t>(cornerCount);
}

// Buckets: a counting sort of the corners by welded id; with `edges`, each bucketed corner's
// next and previous identities beside it (bucketNextId, bucketPreviousId).
void bucketCorners(WorkspaceData& ws, const MeshArrays& mesh, unsigned threads, bool edges) {
  const std::size_t vertexCount = ws.vertexCount, cornerCount = ws.cornerCount;
  const std::uint32_t* vertexId = ws.vertexId.data();
  // Buckets: a counting sort of the corners by welded id.
  ensureSize(ws.bucketStart, vertexCount + 1);
  ensureSize(ws.bucketCorners, cornerCount);
  ensureSize(ws.bucketExtra, vertexCount + 1);
  std::uint32_t* start = ws.bucketStart.data();
  std::uint32_t* corners = ws.bucketCorners.data();
  if (edges) {
    ensureSize(ws.bucketNextId, cornerCount + kBucketIdPadding);
    ensureSize(ws.bucketPreviousId, cornerCount + kBucketIdPadding);
  }
  std::uint32_t* nextIds = ws.bucketNextId.data();
  std::uint32_t* previousIds = ws.bucketPreviousId.data();
  const std::uint32_t* indices = mesh.indices.data();
  // Every bucket in corner order, whatever the thread count. Below four threads, each thread
  // counts and fills its own slice of the corners with its own counters (in the weld table,
  // free by now); from four, two stable passes by ranges of welded ids (bucketByRanges).
  // Where the weld merged no vertex, a corner's bucket is its index: one load fewer per corner.
  const bool identity = ws.weldMergedNone;
  if (threads < 4) {
    const std::size_t slices = threads;
    ensureSize(ws.table, slices * vertexCount);
    // With edges, each slice places its corners triangle by triangle: a corner's next and
    // previous identities are its triangle's other two, read once for all three corners.
    auto sort = [&](const auto& id) {
      if (!edges) {
        stableCountingSort(ws, cornerCount, vertexCount, slices, id, ws.table.data(), start, corners);
        return;
      }
      auto fill = [&](std::size_t begin, std::size_t end, std::uint32_t* next) {
        auto place = [&](std::size_t c, std::uint32_t v, std::uint32_t nextId, std::uint32_t previousId) {
          const std::uint32_t slot = next[v]++;
          corners[slot] = static_cast<std::uint32_t>(c);
          nextIds[slot] = nextId;
          previousIds[slot] = previousId;
        };
        placeByTriangle(begin, end, id, place);
      };
      stableCountingSort(ws, cornerCount, vertexCount, slices, id, ws.table.data(), start, fill, 3);
    };
    if (identity)
      sort([&](std::size_t c) { return indices[c]; });
    else
      sort([&](std::size_t c) { return vertexId[indices[c]]; });
  } else {
    auto byRanges = [&](const auto& id) {
      edges ? bucketByRanges<true>(ws, id) : bucketByRanges<false>(ws, id);
    };
    if (identity)
      byRanges([&](std::size_t c) { return indices[c]; });
    else
      byRanges([&](std::size_t c) { return vertexId[indices[c]]; });
  }
}

}  // namespace

// Weld: open-addressing tables of vertex + 1; the smallest vertex of equal values wins. Then
// the buckets.
void weldAndBucket(WorkspaceData& ws, const MeshArrays& mesh, unsigned threads, bool edges) {
  const std::size_t vertexCount = ws.vertexCount;

  // Weld: open-addressing tables of vertex + 1; the smallest vertex of equal values wins.
  ensureSize(ws.vertexId, vertexCount);
  std::uint32_t* vertexId = ws.vertexId.data();
  std::atomic<bool> merged{false};  // a vertex took another's id (stored only then: rare)
  // Each slot of a table holds vertex + 1 and a tag (other bits of the hash than the slot's):
  // a probe that meets another vertex compares tags before that vertex's values, which lie
  // anywhere in the input (a cache miss per collision otherwise). Equal values have equal
  // tags, so the same slots match as without them.
  auto insert = [&](std::uint32_t* table, std::size_t mask, std::size_t v, std::uint64_t slotHash, std::uint32_t tag) {
    for (std::size_t slot = slotHash & mask;; slot = (slot + 1) & mask) {
      std::uint32_t* entry = table + 2 * slot;
      if (entry[0] == 0) {
        entry[0] = static_cast<std::uint32_t>(v + 1);
        entry[1] = tag;
        vertexId[v] = static_cast<std::uint32_t>(v);
        return;
      }
      if (entry[1] == tag && sameVertex(mesh, entry[0] - 1, v)) {
        vertexId[v] = entry[0] - 1;
        merged.store(true, std::memory_order_relaxed);
        return;
      }
    }
  };
  if (ws.weldOnly) {
    // Only the listed vertices can weld (TangentWorkspace::setWeldOnly): every other is its own.
    const std::span<const std::uint32_t> only = *ws.weldOnly;
    for (std::size_t i = 0; i < only.size(); ++i) {
      if (only[i] >= vertexCount || (i > 0 && only[i] <= only[i - 1])) {
        throw std::invalid_argument("weldOnly: entry " + std::to_string(i) + " (" + std::to_string(only[i]) +
                                    ") is out of range or out of order");
      }
    }
    for (std::size_t v = 0; v < vertexCount; ++v) vertexId[v] = static_cast<std::uint32_t>(v);
    weldInOneTable(ws, mesh, only.size(), [&](std::size_t i) { return std::size_t(only[i]); }, insert);
  } else if (threads < 2) {
    weldInOneTable(ws, mesh, vertexCount, [](std::size_t i) { return i; }, insert);
  } else {
    weldInPartitions(ws, mesh, insert);
  }
  ws.weldMergedNone = !merged.load(std::memory_order_relaxed);
  bucketCorners(ws, mesh, threads, edges);
}

}  // namespace tangent::detail
