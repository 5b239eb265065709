// SPDX-License-Identifier: MIT
// The output pass every method ends with: copies for duplicate triangles, the w convention,
// the report's corner counts, and the vertex split (CornerOutputs::cornerVertex).
#include "parallel.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <tuple>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace tangent::detail {

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

// Sort key of a corner in the split: input vertex, then tangent bits, then corner. The bits
// are kept byte-swapped, so that comparing them as numbers orders them as a byte-wise memcmp
// of the little-endian floats did (the order the new vertices are numbered in), without a
// memcmp call per comparison (4% of a `flat` call at 1e6, whose every vertex splits).
struct SplitEntry {
  std::uint32_t vertex;
  std::uint32_t bits[4];
  std::uint32_t corner;
  bool operator<(const SplitEntry& o) const {
    return std::tie(vertex, bits[0], bits[1], bits[2], bits[3], corner) <
           std::tie(o.vertex, o.bits[0], o.bits[1], o.bits[2], o.bits[3], o.corner);
  }
  bool sameTangent(const SplitEntry& o) const {
    return vertex == o.vertex && bits[0] == o.bits[0] && bits[1] == o.bits[1] && bits[2] == o.bits[2] && bits[3] == o.bits[3];
  }
};


constexpr std::uint32_t kExtraFlag = 0x80000000u;  // a corner's new vertex, numbered per bucket

// Duplicates copy their original; w in the output convention; the report's corner counts
// and each corner's source.
void copyAndCount(WorkspaceData& ws, const CornerOutputs& outputs, const Options& options, const KernelOutcome& kernel,
                  Report& report) {
  const std::size_t cornerCount = ws.cornerCount;
  float* tangents = outputs.tangents.data();
  std::uint8_t* state = ws.cornerState.data();
  const std::uint32_t* link = ws.cornerLink.data();
  const float wSign = handedness(1.0f, options.uvOrigin);

  // Duplicates copy their original (never itself a copy); then w convention and counts. Where
  // the kernel counted the mirrored corners (all but the copies) and wrote w in the output
  // convention, the counts pass need not read the tangents, and without copies the copy pass
  // is skipped.
  const bool kernelCounts = kernel.wInOutputConvention;
  Combinable<std::uint64_t> mirroredCopies;
  if (!kernelCounts || kernel.anyCopy) {
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
  report.mirroredCorners = kernelCounts ? kernel.mirroredCorners + mirroredCopies.combine(std::plus<>()) : total.mirrored;
  report.inheritedCorners = total.inherited;
  report.fallbackFromNeighbours = total.neighbour;
  report.fallbackFixed = total.fixed;
  report.invalidNormals = total.invalidNormals;

}

// What the vertex split reads and writes.
struct SplitArrays {
  const std::uint32_t* corners;
  const std::uint32_t* indices;
  const float* tangents;
  std::uint32_t* cornerVertex;  // null where not asked for
};

// A bucket's split without a sort, for buckets of up to kSmallBucket corners (all but a few):
// each corner is compared with the groups of (input vertex, tangent) found so far. The new
// vertices' numbers within a bucket need only be distinct (numberExtraVertices renumbers them
// in order of their first corner), so they follow the groups' order, not the sort's.
constexpr std::uint32_t kSmallBucket = 16;

std::uint32_t splitSmallBucket(const SplitArrays& arrays, std::uint32_t first, std::uint32_t last) {
  const std::uint32_t* corners = arrays.corners;
  const std::uint32_t* indices = arrays.indices;
  const float* tangents = arrays.tangents;
  // Each group: its input vertex, tangent bits (-0 as +0), smallest corner; each corner's group.
  std::uint32_t groupVertex[kSmallBucket], groupBits[kSmallBucket][4], groupFirst[kSmallBucket];
  std::uint32_t groupOf[kSmallBucket];
  std::uint32_t groups = 0;
  for (std::uint32_t i = 0; i < last - first; ++i) {
    const std::uint32_t c = corners[first + i];
    const std::uint32_t vertex = indices[c];
    std::uint32_t bits[4];
    for (int k = 0; k < 4; ++k) bits[k] = canonicalBits(tangents[4 * c + k]);
    std::uint32_t g = 0;
    while (g < groups && !(groupVertex[g] == vertex && groupBits[g][0] == bits[0] && groupBits[g][1] == bits[1] &&
                           groupBits[g][2] == bits[2] && groupBits[g][3] == bits[3]))
      ++g;
    if (g == groups) {
      groupVertex[g] = vertex;
      std::memcpy(groupBits[g], bits, sizeof bits);
      groupFirst[g] = c;
      ++groups;
    } else {
      groupFirst[g] = std::min(groupFirst[g], c);
    }
    groupOf[i] = g;
  }
  // The group holding an input vertex's first corner keeps the vertex; each other is new.
  std::uint32_t groupId[kSmallBucket];
  std::uint32_t extras = 0;
  for (std::uint32_t g = 0; g < groups; ++g) {
    bool keepsVertex = true;
    for (std::uint32_t h = 0; h < groups; ++h)
      keepsVertex = keepsVertex && !(groupVertex[h] == groupVertex[g] && groupFirst[h] < groupFirst[g]);
    groupId[g] = keepsVertex ? groupVertex[g] : (kExtraFlag | extras++);
  }
  if (std::uint32_t* cornerVertex = arrays.cornerVertex) {
    for (std::uint32_t i = 0; i < last - first; ++i) cornerVertex[corners[first + i]] = groupId[groupOf[i]];
  }
  return extras;
}

// One bucket's split (corners[first .. last - 1]): its count of new vertices, and cornerVertex
// for its corners. Out of line, so that the loop over the buckets that need none keeps its
// values in registers.
[[gnu::noinline]] std::uint32_t splitBucket(const SplitArrays& arrays, std::uint32_t first, std::uint32_t last,
                                            std::vector<SplitEntry>& entries) {
  const std::uint32_t* corners = arrays.corners;
  const std::uint32_t* indices = arrays.indices;
  const float* tangents = arrays.tangents;
  std::uint32_t* cornerVertex = arrays.cornerVertex;
  const bool wantVertices = cornerVertex != nullptr;
  // Most buckets: one input vertex, one tangent.
  const std::uint32_t c0 = corners[first];
  bool uniform = true;
  for (std::uint32_t i = first + 1; i < last && uniform; ++i) {
    const std::uint32_t c = corners[i];
    uniform = indices[c] == indices[c0] && std::memcmp(&tangents[4 * c], &tangents[4 * c0], 4 * sizeof(float)) == 0;
  }
  if (uniform) {
    if (wantVertices) {
      for (std::uint32_t i = first; i < last; ++i) cornerVertex[corners[i]] = indices[c0];
    }
    return 0;
  }
  if (last - first <= kSmallBucket) return splitSmallBucket(arrays, first, last);
  entries.clear();
  for (std::uint32_t i = first; i < last; ++i) {
    const std::uint32_t c = corners[i];
    SplitEntry e;
    e.vertex = indices[c];
    for (int k = 0; k < 4; ++k) e.bits[k] = __builtin_bswap32(canonicalBits(tangents[4 * c + k]));  // -0 and +0 alike
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
  return extras;
}

// The vertex split, bucket by bucket: cornerVertex holds the input vertex or kExtraFlag | the
// bucket's own number of the new vertex; bucketExtra each bucket's count of new vertices.
void splitBuckets(WorkspaceData& ws, const MeshArrays& mesh, const CornerOutputs& outputs, const std::uint8_t* knownUniform,
                  bool uniformWritten) {
  // Vertex split, bucket by bucket: the tangent of a vertex's first corner keeps the vertex,
  // each other distinct tangent is one extra vertex.
  const SplitArrays arrays{ws.bucketCorners.data(), mesh.indices.data(), outputs.tangents.data(),
                           outputs.cornerVertex.empty() ? nullptr : outputs.cornerVertex.data()};
  const std::uint32_t* start = ws.bucketStart.data();
  std::uint32_t* extra = ws.bucketExtra.data();
  const bool writeUniform = arrays.cornerVertex && !uniformWritten;
  auto split = [&arrays, start, extra, knownUniform, writeUniform](std::size_t begin, std::size_t end) {
    // Everything in locals: through the closure, every bucket loaded them again (the stores
    // below may alias them, as far as the compiler knows).
    const std::uint32_t* corners = arrays.corners;
    const std::uint32_t* indices = arrays.indices;
    std::uint32_t* cornerVertex = arrays.cornerVertex;
    const std::uint32_t* starts = start;
    std::uint32_t* extras = extra;
    const std::uint8_t* uniformBuckets = knownUniform;
    std::vector<SplitEntry> entries;
    for (std::size_t b = begin; b < end; ++b) {
      const std::uint32_t first = starts[b], last = starts[b + 1];
      // Most buckets: one input vertex, one tangent, known from the kernel.
      if (last - first > 1 && uniformBuckets && (uniformBuckets[b] & kUniformVertex)) {
        if (writeUniform) {
          const std::uint32_t vertex = indices[corners[first]];
          for (std::uint32_t i = first; i < last; ++i) cornerVertex[corners[i]] = vertex;
        }
        extras[b] = 0;
      } else {
        extras[b] = last == first ? 0 : splitBucket(arrays, first, last, entries);
      }
    }
  };
  forRange(ws, ws.vertexCount, 2048, split);
}

// The new vertices numbered from the vertex count up, in order of their first corner.
void numberExtraVertices(WorkspaceData& ws, const MeshArrays& mesh, const CornerOutputs& outputs, Report& report) {
  const std::size_t cornerCount = ws.cornerCount, vertexCount = ws.vertexCount;
  std::uint32_t* extra = ws.bucketExtra.data();
  const std::uint32_t* indices = mesh.indices.data();
  const bool wantVertices = !outputs.cornerVertex.empty();
  std::uint32_t* cornerVertex = wantVertices ? outputs.cornerVertex.data() : nullptr;
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

}  // namespace

void finishOutputs(WorkspaceData& ws, const MeshArrays& mesh, const CornerOutputs& outputs, const Options& options,
                   Report& report, const KernelOutcome& kernel) {
  copyAndCount(ws, outputs, options, kernel, report);
  // Read last by the copies and counts (setReleaseAsItGoes), before the split writes cornerVertex.
  releaseWhenDone(ws, ws.cornerLink, ws.cornerState, ws.triangleFlags, ws.orientation);
  splitBuckets(ws, mesh, outputs, kernel.bucketUniform, kernel.bucketUniform && kernel.uniformVerticesWritten);
  numberExtraVertices(ws, mesh, outputs, report);
}


}  // namespace tangent::detail
