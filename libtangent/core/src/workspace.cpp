// SPDX-License-Identifier: MIT
// The phases every method shares: argument checks, welding by value, corner buckets, and
// the output pass (duplicates, w convention, counts, vertex split).
#include "workspace.hpp"

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

namespace tangent {
namespace detail {
namespace {

// The hash of a vertex's values, -0 taken as +0 (equal values, equal hashes). The eight
// values go in as four pairs, each multiplied on its own, then one finishing mix: a chain of
// three dependent multiplies per vertex. Mixing the values one after another made a chain of
// eight, and its latency was most of the weld's time per vertex.
std::uint64_t vertexHash(const MeshArrays& mesh, std::size_t v) {
  auto pair = [](float a, float b) { return std::uint64_t(canonicalBits(a)) | std::uint64_t(canonicalBits(b)) << 32; };
  const float* p = &mesh.positions[3 * v];
  const float* n = &mesh.normals[3 * v];
  const float* t = &mesh.uvs[2 * v];
  std::uint64_t h = pair(p[0], p[1]) * 0x9E3779B97F4A7C15ull ^ pair(p[2], n[0]) * 0xC2B2AE3D27D4EB4Full ^
                    pair(n[1], n[2]) * 0x165667B19E3779F9ull ^ pair(t[0], t[1]) * 0xD6E8FEB86659FD93ull;
  h ^= h >> 32;
  h *= 0xFF51AFD7ED558CCDull;
  h ^= h >> 29;
  h *= 0xC4CEB9FE1A85EC53ull;
  return h ^ (h >> 32);
}

// The reference's identity of a corner: every value equal as floats (+0 == -0, NaN != NaN).
bool sameVertex(const MeshArrays& mesh, std::size_t a, std::size_t b) {
  for (int i = 0; i < 3; ++i) {
    if (mesh.positions[3 * a + i] != mesh.positions[3 * b + i] || mesh.normals[3 * a + i] != mesh.normals[3 * b + i])
      return false;
  }
  return mesh.uvs[2 * a] == mesh.uvs[2 * b] && mesh.uvs[2 * a + 1] == mesh.uvs[2 * b + 1];
}

}  // namespace

std::size_t WorkspaceData::bytes() const {
  auto size = [](const auto& v) { return v.capacity() * sizeof(v[0]); };
  return size(table) + size(weldCounts) + size(vertexId) + size(bucketStart) + size(bucketCorners) +
         size(orientation) + size(triangleFlags) + size(cornerLink) + size(cornerState) + size(meshPositions) + size(meshNormals) + size(meshUvs) + size(meshTangents) + size(meshIndices) +
         size(meshRepresentative) + size(meshRepresentativeValues) +
         size(bucketExtra) + size(bucketUniform);
}

void checkArrays(const MeshArrays& mesh, const CornerOutputs& outputs) {
  auto fail = [](const std::string& what) { throw std::invalid_argument(what); };
  if (mesh.positions.size() % 3 != 0) fail("positions: size " + std::to_string(mesh.positions.size()) + " is not a multiple of 3");
  const std::size_t vertexCount = mesh.positions.size() / 3;
  if (vertexCount >= kNone) fail("positions: more than 2^32 - 2 vertices");
  if (mesh.normals.size() != vertexCount * 3)
    fail("normals: expected " + std::to_string(vertexCount * 3) + " floats, got " + std::to_string(mesh.normals.size()));
  if (mesh.uvs.size() != vertexCount * 2)
    fail("uvs: expected " + std::to_string(vertexCount * 2) + " floats, got " + std::to_string(mesh.uvs.size()));
  if (mesh.indices.size() % 3 != 0) fail("indices: size " + std::to_string(mesh.indices.size()) + " is not a multiple of 3");
  const std::size_t cornerCount = mesh.indices.size();
  if (cornerCount >= kNone) fail("indices: more than 2^32 - 2 corners");
  if (outputs.tangents.size() != cornerCount * 4)
    fail("tangents: expected " + std::to_string(cornerCount * 4) + " floats (4 per corner), got " +
         std::to_string(outputs.tangents.size()));
  if (!outputs.sources.empty() && outputs.sources.size() != cornerCount)
    fail("sources: expected " + std::to_string(cornerCount) + " entries (one per corner), got " +
         std::to_string(outputs.sources.size()));
  if (!outputs.cornerVertex.empty() && outputs.cornerVertex.size() != cornerCount)
    fail("cornerVertex: expected " + std::to_string(cornerCount) + " entries (one per corner), got " +
         std::to_string(outputs.cornerVertex.size()));
}

namespace {

// Whether any of indices[begin, end) is count or more (0 < count < 2^32). Written out in
// SSE2: at -O2, GCC left the plain loop scalar (0.6 ns an index, 2% of the call at 1e5).
bool anyAtLeast(const std::uint32_t* indices, std::size_t begin, std::size_t end, std::uint32_t count) {
  std::size_t i = begin;
  bool any = false;
#if defined(__SSE2__)
  // Unsigned x > count - 1 as a signed compare, both sides with the top bit flipped.
  const __m128i flip = _mm_set1_epi32(INT32_MIN);
  const __m128i last = _mm_set1_epi32(static_cast<std::int32_t>((count - 1) ^ 0x80000000u));
  __m128i over = _mm_setzero_si128();
  for (; i + 16 <= end; i += 16) {
    for (std::size_t k = 0; k < 16; k += 4) {
      const __m128i x = _mm_loadu_si128(reinterpret_cast<const __m128i*>(indices + i + k));
      over = _mm_or_si128(over, _mm_cmpgt_epi32(_mm_xor_si128(x, flip), last));
    }
  }
  any = _mm_movemask_epi8(over) != 0;
#endif
  for (; i < end; ++i) any |= indices[i] >= count;
  return any;
}

// Whether every index is in range, in parallel (a pass over the whole index array: serial,
// it was 8% of the call's wall time on 16 CPUs); only where one is not, the first such
// index, named.
void checkIndices(const WorkspaceData& ws, const MeshArrays& mesh) {
  const std::uint32_t* indices = mesh.indices.data();
  const std::size_t cornerCount = mesh.indices.size(), vertexCount = mesh.positions.size() / 3;
  if (vertexCount > std::numeric_limits<std::uint32_t>::max()) return;  // every 32-bit index is in range
  std::atomic<bool> outOfRange{vertexCount == 0 && cornerCount > 0};
  if (vertexCount > 0) {
    forRange(ws, cornerCount, 1 << 16, [&](std::size_t begin, std::size_t end) {
      if (anyAtLeast(indices, begin, end, static_cast<std::uint32_t>(vertexCount))) outOfRange.store(true, std::memory_order_relaxed);
    });
  }
  if (!outOfRange.load(std::memory_order_relaxed)) return;
  for (std::size_t i = 0; i < cornerCount; ++i) {
    if (indices[i] >= vertexCount)
      throw std::invalid_argument("indices[" + std::to_string(i) + "] = " + std::to_string(indices[i]) +
                                  " is out of range (vertex count " + std::to_string(vertexCount) + ")");
  }
}

}  // namespace

namespace {

// A stable counting sort in parallel: the items [0, count), cut into `chunks` equal runs, each
// counted and scattered by one task with its own counters (counters: chunks * keys), so that
// out holds the items grouped by key, each group in item order; groupStart (keys + 1) gets
// the groups' starts.
template <typename Key>
void stableCountingSort(const WorkspaceData& ws, std::size_t count, std::size_t keys, std::size_t chunks, const Key& key,
                        std::uint32_t* counters, std::uint32_t* groupStart, std::uint32_t* out) {
  const std::size_t length = chunks == 0 ? 0 : (count + chunks - 1) / chunks;
  forRange(ws, chunks, 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) {
      std::uint32_t* counter = counters + k * keys;
      std::fill(counter, counter + keys, 0u);
      for (std::size_t i = k * length; i < std::min(count, (k + 1) * length); ++i) ++counter[key(i)];
    }
  });
  // Key-major offsets: each group's items chunk by chunk. In blocks of keys, so that the
  // scan runs in parallel too (one thread scanning a vertex's worth of keys per corner bucket
  // was most of the bucketing's serial time): each block's total, the blocks' starts, then
  // each block's offsets from its start.
  constexpr std::size_t kKeyBlock = 1 << 14;
  const std::size_t blocks = (keys + kKeyBlock - 1) / kKeyBlock;
  const std::vector<std::uint32_t> blockStart = blockStarts<std::uint32_t>(ws, blocks, [&](std::size_t b) {
    std::uint32_t n = 0;
    for (std::size_t k = 0; k < chunks; ++k) {
      const std::uint32_t* counter = counters + k * keys;
      for (std::size_t g = b * kKeyBlock; g < std::min(keys, (b + 1) * kKeyBlock); ++g) n += counter[g];
    }
    return n;
  });
  forRange(ws, blocks, 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t b = begin; b < end; ++b) {
      std::uint32_t total = blockStart[b];
      for (std::size_t g = b * kKeyBlock; g < std::min(keys, (b + 1) * kKeyBlock); ++g) {
        groupStart[g] = total;
        for (std::size_t k = 0; k < chunks; ++k) {
          const std::uint32_t n = counters[k * keys + g];
          counters[k * keys + g] = total;
          total += n;
        }
      }
    }
  });
  groupStart[keys] = blockStart[blocks];
  forRange(ws, chunks, 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) {
      std::uint32_t* next = counters + k * keys;
      for (std::size_t i = k * length; i < std::min(count, (k + 1) * length); ++i) out[next[key(i)]++] = static_cast<std::uint32_t>(i);
    }
  });
}

}  // namespace

void beginCall(WorkspaceData& ws, const MeshArrays& mesh) {
  ws.vertexCount = mesh.positions.size() / 3;
  ws.cornerCount = mesh.indices.size();
  ws.bucketUniformKnown = false;
  ws.wInOutputConvention = false;
  ws.anyCopy.store(false, std::memory_order_relaxed);
  checkIndices(ws, mesh);
}

void weldAndBucket(WorkspaceData& ws, const MeshArrays& mesh, unsigned threads) {
  const std::size_t vertexCount = ws.vertexCount, cornerCount = ws.cornerCount;

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
  if (threads < 2) {
    // One table, vertices in order; the tag is the hash's top 32 bits.
    std::size_t tableSize = 16;
    while (tableSize < 2 * vertexCount) tableSize *= 2;
    ensureSize(ws.table, 2 * tableSize);
    std::uint32_t* table = ws.table.data();
    std::fill(table, table + 2 * tableSize, 0u);
    const std::size_t mask = tableSize - 1;
    // The table (megabytes) is probed at random: each vertex's hash is worked out kAhead
    // vertices early and its slot prefetched, so that the probe finds it in cache.
    constexpr std::size_t kAhead = 16;
    std::uint64_t ahead[kAhead];
    for (std::size_t v = 0; v < std::min(kAhead, vertexCount); ++v) {
      ahead[v] = vertexHash(mesh, v);
      prefetch(table + 2 * (ahead[v] & mask));
    }
    for (std::size_t v = 0; v < vertexCount; ++v) {
      const std::uint64_t hash = ahead[v % kAhead];
      if (v + kAhead < vertexCount) {
        const std::uint64_t later = vertexHash(mesh, v + kAhead);
        ahead[v % kAhead] = later;
        prefetch(table + 2 * (later & mask));
      }
      insert(table, mask, v, hash, static_cast<std::uint32_t>(hash >> 32));
    }
  } else {
    // Threads: the vertices split by the top bits of their hash into partitions (a counting
    // sort that keeps vertex order inside each), one small table per partition, partitions
    // in parallel. Equal values share a hash, so each partition welds on its own; no atomics,
    // and the tables stay in cache. The hashes (partition in the top 8 bits, 24 bits of slot),
    // the tags (32 bits of the hash from bit 24) and the order live in the bucket arrays,
    // which are filled only after the weld.
    constexpr int kPartitionBits = 8;
    constexpr std::size_t kPartitions = std::size_t(1) << kPartitionBits, kChunk = 1 << 15;
    const std::size_t chunkCount = (vertexCount + kChunk - 1) / kChunk;
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
    forRange(ws, vertexCount, kChunk, [&](std::size_t begin, std::size_t end) {
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

  ws.weldMergedNone = !merged.load(std::memory_order_relaxed);
  // Buckets: a counting sort of the corners by welded id.
  ensureSize(ws.bucketStart, vertexCount + 1);
  ensureSize(ws.bucketCorners, cornerCount);
  ensureSize(ws.bucketExtra, vertexCount + 1);
  std::uint32_t* start = ws.bucketStart.data();
  std::uint32_t* cursor = ws.bucketExtra.data();
  std::uint32_t* corners = ws.bucketCorners.data();
  const std::uint32_t* indices = mesh.indices.data();
  // Every bucket in corner order, whatever the thread count. Below four threads, each thread
  // counts and fills its own slice of the corners with its own counters (in the weld table,
  // free by now). From four, slices * vertices counters grow too large, so two stable passes:
  // the corners by range of kVertexRange welded ids (per-chunk counters, small), then each
  // range on its own, its counters in cache. No atomics: on 16 CPUs, counting and filling
  // through atomic counters then sorting each bucket ran 2x faster than one thread at best,
  // a quarter of the call's wall time at 1e6 and 4e6 triangles.
  // Where the weld merged no vertex, a corner's bucket is its index: one load fewer per corner.
  const bool identity = ws.weldMergedNone;
  auto bucketOf = [&](std::size_t c) { return identity ? indices[c] : vertexId[indices[c]]; };
  if (threads < 4) {
    const std::size_t slices = threads;
    ensureSize(ws.table, slices * vertexCount);
    if (identity)
      stableCountingSort(ws, cornerCount, vertexCount, slices, [&](std::size_t c) { return indices[c]; }, ws.table.data(), start, corners);
    else
      stableCountingSort(ws, cornerCount, vertexCount, slices, [&](std::size_t c) { return vertexId[indices[c]]; }, ws.table.data(), start, corners);
  } else {
    constexpr std::size_t kVertexRange = 1 << 12, kCornerChunk = 1 << 16;
    const std::size_t ranges = (vertexCount + kVertexRange - 1) / kVertexRange;
    const std::size_t chunks = (cornerCount + kCornerChunk - 1) / kCornerChunk;
    ensureSize(ws.weldCounts, chunks * ranges + ranges + 1);
    // The corners by range go in the kernel's per-corner links (the same size, written only
    // later), so that no array grows for them.
    ensureSize(ws.cornerLink, cornerCount);
    std::uint32_t* rangeStart = ws.weldCounts.data() + chunks * ranges;
    std::uint32_t* byRange = ws.cornerLink.data();
    stableCountingSort(ws, cornerCount, ranges, chunks, [&](std::size_t c) { return bucketOf(c) / kVertexRange; },
                       ws.weldCounts.data(), rangeStart, byRange);
    forRange(ws, ranges, 1, [&](std::size_t begin, std::size_t end) {
      for (std::size_t r = begin; r < end; ++r) {
        const std::size_t first = r * kVertexRange, last = std::min(vertexCount, first + kVertexRange);
        std::uint32_t* next = cursor + first;  // this range's counters, then its cursors
        std::fill(next, next + (last - first), 0u);
        for (std::uint32_t i = rangeStart[r]; i < rangeStart[r + 1]; ++i) ++next[bucketOf(byRange[i]) - first];
        std::uint32_t total = rangeStart[r];
        for (std::size_t v = first; v < last; ++v) {
          const std::uint32_t n = cursor[v];
          start[v] = cursor[v] = total;
          total += n;
        }
        for (std::uint32_t i = rangeStart[r]; i < rangeStart[r + 1]; ++i) {
          const std::uint32_t c = byRange[i];
          corners[cursor[bucketOf(c)]++] = c;
        }
      }
    });
    start[vertexCount] = static_cast<std::uint32_t>(cornerCount);
  }
}

namespace {

struct Counts {
  std::uint64_t mirrored = 0, inherited = 0, neighbour = 0, fixed = 0, invalidNormals = 0;
  void add(const Counts& o) {
    mirrored += o.mirrored;
    inherited += o.inherited;
    neighbour += o.neighbour;
    fixed += o.fixed;
    invalidNormals += o.invalidNormals;
  }
};

// Sort key of a corner in the split: input vertex, then tangent bits, then corner.
struct SplitEntry {
  std::uint32_t vertex;
  std::uint32_t bits[4];
  std::uint32_t corner;
  bool operator<(const SplitEntry& o) const {
    if (vertex != o.vertex) return vertex < o.vertex;
    const int c = std::memcmp(bits, o.bits, sizeof bits);
    if (c != 0) return c < 0;
    return corner < o.corner;
  }
  bool sameTangent(const SplitEntry& o) const { return vertex == o.vertex && std::memcmp(bits, o.bits, sizeof bits) == 0; }
};

}  // namespace

void finishOutputs(WorkspaceData& ws, const MeshArrays& mesh, const CornerOutputs& outputs, const Options& options,
                   Report& report) {
  const std::size_t cornerCount = ws.cornerCount, vertexCount = ws.vertexCount;
  float* tangents = outputs.tangents.data();
  std::uint8_t* state = ws.cornerState.data();
  const std::uint32_t* link = ws.cornerLink.data();
  const float wSign = handedness(1.0f, options.uvOrigin);

  // Duplicates copy their original (never itself a copy); then w convention and counts. Where
  // the kernel counted the mirrored corners (all but the copies) and wrote w in the output
  // convention, the counts pass need not read the tangents, and without copies the copy pass
  // is skipped.
  const bool kernelCounts = ws.wInOutputConvention;
  Combinable<std::uint64_t> mirroredCopies;
  if (!kernelCounts || ws.anyCopy.load(std::memory_order_relaxed)) {
    forRange(ws, cornerCount, 1 << 14, [&](std::size_t begin, std::size_t end) {
      std::uint64_t local = 0;
      for (std::size_t c = begin; c < end; ++c) {
        if (!(state[c] & kCopy)) continue;
        const std::uint32_t original = link[c];
        std::memcpy(&tangents[4 * c], &tangents[4 * original], 4 * sizeof(float));
        state[c] = static_cast<std::uint8_t>((state[c] & ~kSourceMask) | (state[original] & kSourceMask));
        local += tangents[4 * c + 3] < 0;
      }
      mirroredCopies.local() += local;
    });
  }
  Combinable<Counts> counts;
  // Where the kernel counted and no sources are asked for, only corners not computed or with
  // an invalid normal count: runs of eight without either are skipped (all but a few).
  const bool skipCommon = kernelCounts && outputs.sources.empty();
  forRange(ws, cornerCount, 1 << 14, [&](std::size_t begin, std::size_t end) {
    Counts local;
    auto all = [](std::size_t) { return true; };
    scanKept(skipCommon ? state : nullptr, kSourceMask | kInvalidNormal, begin, end, all, [&](std::size_t c) {
      const std::uint8_t s = state[c];
      if (!kernelCounts) {
        tangents[4 * c + 3] *= wSign;
        local.mirrored += tangents[4 * c + 3] < 0;
      }
      switch (static_cast<FrameSource>(s & kSourceMask)) {
        case FrameSource::computed: break;
        case FrameSource::inherited: ++local.inherited; break;
        case FrameSource::neighbour: ++local.neighbour; break;
        case FrameSource::fixed: ++local.fixed; break;
      }
      local.invalidNormals += (s & kInvalidNormal) != 0;
      if (!outputs.sources.empty()) outputs.sources[c] = static_cast<FrameSource>(s & kSourceMask);
    });
    counts.local().add(local);
  });
  Counts total;
  counts.combine_each([&](const Counts& c) { total.add(c); });
  report.mirroredCorners = kernelCounts ? ws.mirroredCorners + mirroredCopies.combine(std::plus<>()) : total.mirrored;
  report.inheritedCorners = total.inherited;
  report.fallbackFromNeighbours = total.neighbour;
  report.fallbackFixed = total.fixed;
  report.invalidNormals = total.invalidNormals;

  // Vertex split, bucket by bucket: the tangent of a vertex's first corner keeps the vertex,
  // each other distinct tangent is one extra vertex.
  const std::uint32_t* start = ws.bucketStart.data();
  const std::uint32_t* corners = ws.bucketCorners.data();
  const std::uint32_t* indices = mesh.indices.data();
  std::uint32_t* extra = ws.bucketExtra.data();
  const std::uint8_t* knownUniform = ws.bucketUniformKnown ? ws.bucketUniform.data() : nullptr;
  const bool wantVertices = !outputs.cornerVertex.empty();
  std::uint32_t* cornerVertex = wantVertices ? outputs.cornerVertex.data() : nullptr;
  constexpr std::uint32_t kExtraFlag = 0x80000000u;
  forRange(ws, vertexCount, 2048, [&](std::size_t begin, std::size_t end) {
    std::vector<SplitEntry> entries;
    for (std::size_t b = begin; b < end; ++b) {
      const std::uint32_t first = start[b], last = start[b + 1];
      extra[b] = 0;
      if (last - first == 0) continue;
      if (last - first == 1) {
        if (wantVertices) cornerVertex[corners[first]] = indices[corners[first]];
        continue;
      }
      // Most buckets: one input vertex, one tangent (known from the kernel for most of those).
      const std::uint32_t c0 = corners[first];
      bool uniform = true;
      if (knownUniform && (knownUniform[b] & 1)) {
        if (wantVertices) {
          const std::uint32_t vertex = indices[c0];
          for (std::uint32_t i = first; i < last; ++i) cornerVertex[corners[i]] = vertex;
        }
        continue;
      }
      for (std::uint32_t i = first + 1; i < last && uniform; ++i) {
        const std::uint32_t c = corners[i];
        uniform = indices[c] == indices[c0] && std::memcmp(&tangents[4 * c], &tangents[4 * c0], 4 * sizeof(float)) == 0;
      }
      if (uniform) {
        if (wantVertices) {
          for (std::uint32_t i = first; i < last; ++i) cornerVertex[corners[i]] = indices[c0];
        }
        continue;
      }
      entries.clear();
      for (std::uint32_t i = first; i < last; ++i) {
        const std::uint32_t c = corners[i];
        SplitEntry e;
        e.vertex = indices[c];
        for (int k = 0; k < 4; ++k) e.bits[k] = canonicalBits(tangents[4 * c + k]);  // -0 and +0 alike
        e.corner = c;
        entries.push_back(e);
      }
      std::sort(entries.begin(), entries.end());
      std::uint32_t extras = 0;
      for (std::size_t i = 0; i < entries.size();) {
        // One input vertex: find the tangent of its first corner.
        std::size_t j = i;
        std::uint32_t firstCorner = entries[i].corner;
        std::size_t firstAt = i;
        while (j < entries.size() && entries[j].vertex == entries[i].vertex) {
          if (entries[j].corner < firstCorner) firstCorner = entries[j].corner, firstAt = j;
          ++j;
        }
        for (std::size_t k = i; k < j;) {
          std::size_t l = k;
          while (l < j && entries[l].sameTangent(entries[k])) ++l;
          const bool keepsVertex = entries[k].sameTangent(entries[firstAt]);
          const std::uint32_t id = keepsVertex ? entries[k].vertex : (kExtraFlag | extras++);
          if (wantVertices) {
            for (std::size_t m = k; m < l; ++m) cornerVertex[entries[m].corner] = id;
          }
          k = l;
        }
        i = j;
      }
      extra[b] = extras;
    }
  });
  // Each bucket's first extra vertex (serial, this prefix sum was 2% of the call's wall time on
  // 16 CPUs).
  const std::uint64_t splits = exclusiveScan(ws, extra, vertexCount);
  if (vertexCount + splits >= kExtraFlag) throw std::invalid_argument("indices: the vertex split needs more than 2^31 vertices");
  report.splitVertices = splits;
  report.outputVertices = vertexCount + splits;
  if (wantVertices && splits > 0) {
    const std::uint32_t* vertexId = ws.vertexId.data();
    const bool identity = ws.weldMergedNone;
    forRange(ws, cornerCount, 1 << 14, [&](std::size_t begin, std::size_t end) {
      for (std::size_t c = begin; c < end; ++c) {
        if (cornerVertex[c] & kExtraFlag)
          cornerVertex[c] = static_cast<std::uint32_t>(vertexCount) + extra[identity ? indices[c] : vertexId[indices[c]]] +
                            (cornerVertex[c] & ~kExtraFlag);
      }
    });
    // The numbering CornerOutputs documents: new vertices in order of their first corner (the
    // buckets above number them by welded vertex, then by tangent bits). One serial pass: a
    // new vertex is renumbered where its first corner is met. The weld table is free by now.
    ensureSize(ws.table, splits);
    std::uint32_t* renumbered = ws.table.data();
    std::fill(renumbered, renumbered + splits, 0u);  // 0: not met yet (a new vertex is >= vertexCount > 0)
    auto next = static_cast<std::uint32_t>(vertexCount);
    for (std::size_t c = 0; c < cornerCount; ++c) {
      const std::uint32_t v = cornerVertex[c];
      if (v < vertexCount) continue;
      std::uint32_t& to = renumbered[v - vertexCount];
      if (to == 0) to = next++;
      cornerVertex[c] = to;
    }
  }
}

}  // namespace detail

TangentWorkspace::TangentWorkspace() : data_(std::make_unique<detail::WorkspaceData>()) {}
TangentWorkspace::~TangentWorkspace() = default;
TangentWorkspace::TangentWorkspace(TangentWorkspace&&) noexcept = default;
TangentWorkspace& TangentWorkspace::operator=(TangentWorkspace&&) noexcept = default;
std::size_t TangentWorkspace::bytesReserved() const { return data_->bytes(); }

}  // namespace tangent
