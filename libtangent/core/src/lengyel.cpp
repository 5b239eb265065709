// SPDX-License-Identifier: MIT
// Methods `lengyel`, `flat` and `meshopt` on packed arrays.
// Source: E. Lengyel, "Computing Tangent Space Basis Vectors for an Arbitrary Mesh", 2001:
// accumulate per-triangle tangents over the corners that will share a vertex, then
// Gram-Schmidt orthogonalize against the normal; handedness w = sign(dot(cross(N, T), B)).
// Corners share a frame when they share position, normal, UV and UV orientation, so mirrored
// islands never average together. `flat` is the same pipeline with one group per triangle;
// `meshopt` the same groups with meshoptimizer's corner weight (projectedEdgeWeight).
//
// Determinism: per-triangle terms start at a canonical corner (triangle_tangent.cpp), groups
// are runs of corners sorted by value, and the terms of a group are summed in an order given
// by their values, so neither face order, corner rotation nor thread count moves a bit.
#include "lengyel.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <functional>
#include <tuple>

namespace tangent::detail {
namespace {

// The non-manifold count's threaded way (countNonManifoldFacesInRanges) from this many
// threads and triangles. On two threads it ran no faster (it adds passes, and the one-thread
// way already runs beside the triangle pass, whose pieces the other thread takes); on small
// meshes its setup costs more than it saves.
constexpr unsigned kThreadedCountThreads = 4;
constexpr std::size_t kThreadedCountTriangles = 1 << 14;

// The open-addressing probe's hash of a position's canonical bits (+0 and -0 alike).
std::uint64_t positionHash(const std::uint32_t bits[3]) {
  std::uint64_t h = bits[0] * 0x9E3779B97F4A7C15ull ^ bits[1] * 0xC2B2AE3D27D4EB4Full ^ bits[2] * 0x165667B19E3779F9ull;
  h ^= h >> 32;
  h *= 0xFF51AFD7ED558CCDull;
  return h ^ (h >> 29);
}

// Each vertex's representative: the smallest vertex with the same position bits (+0 and -0
// alike). Its position is the one every corner at that point is evaluated with. Vertices go
// into an open-addressing table (vertex + 1, 0 empty) in increasing order, so the first of a
// position found there is its smallest; a block's slots are fetched ahead of its probes (the
// table is larger than the caches). Into the workspace: ws.positionRepresentative.
std::span<const std::uint32_t> positionWeld(WorkspaceData& ws, const MeshArrays& mesh) {
  const std::size_t vertexCount = ws.vertexCount;
  std::size_t tableSize = 64;
  while (tableSize < 2 * vertexCount) tableSize *= 2;
  ensureSize(ws.positionTable, tableSize);
  ensureSize(ws.positionRepresentative, vertexCount);
  std::uint32_t* table = ws.positionTable.data();
  std::uint32_t* representative = ws.positionRepresentative.data();
  std::fill(table, table + tableSize, 0u);
  auto bitsAt = [&](std::size_t v, std::uint32_t bits[3]) {
    for (int i = 0; i < 3; ++i) bits[i] = canonicalBits(mesh.positions[3 * v + i]);
  };
  constexpr std::size_t kBlock = 32;
  std::uint64_t slotOf[kBlock];
  for (std::size_t first = 0; first < vertexCount; first += kBlock) {
    const std::size_t count = std::min(kBlock, vertexCount - first);
    for (std::size_t i = 0; i < count; ++i) {
      std::uint32_t bits[3];
      bitsAt(first + i, bits);
      slotOf[i] = positionHash(bits) & (tableSize - 1);
      prefetch(table + slotOf[i]);
    }
    for (std::size_t i = 0; i < count; ++i) {
      const std::size_t v = first + i;
      std::uint32_t bits[3], other[3];
      bitsAt(v, bits);
      for (std::size_t slot = slotOf[i];; slot = (slot + 1) & (tableSize - 1)) {
        if (table[slot] == 0) {
          table[slot] = static_cast<std::uint32_t>(v + 1);
          representative[v] = static_cast<std::uint32_t>(v);
          break;
        }
        bitsAt(table[slot] - 1, other);
        if (std::memcmp(bits, other, sizeof bits) == 0) {
          representative[v] = table[slot] - 1;
          break;
        }
      }
    }
  }
  return {representative, vertexCount};
}

Vec3 vec3At(std::span<const float> values, std::uint32_t vertex) {
  return {values[3 * vertex], values[3 * vertex + 1], values[3 * vertex + 2]};
}

// A corner's term's weight: its weighting's (meshopt: its own), 0 where the triangle is not
// usable or the method weighs all alike (flat).
// `angle`: cornerAngle(positions, k), where the triangle pass's lanes made it already (else
// negative: made here).
double cornerWeight(const Options& options, const std::array<Vec3, 3>& positions, int k, const Vec3& normal,
                    const TriangleTangent& triangle, double angle) {
  if (triangle.kind != TriangleKind::usable || options.method == Method::flat) return 0;
  if (options.method == Method::meshopt) return projectedEdgeWeight(positions, k, normal, triangle.tangent);
  switch (options.weighting) {
    case Weighting::angle: return angle >= 0 ? angle : cornerAngle(positions, k);
    case Weighting::area: return triangle.area;
    case Weighting::uniform: return 1.0;
  }
  return 0;
}

// Each vertex's normal made unit, or marked invalid, once for all its corners
// (ws.vertexUnitNormals, ws.vertexNormalInvalid).
void unitNormalsOfVertices(WorkspaceData& ws, const MeshArrays& mesh) {
  ensureSize(ws.vertexUnitNormals, ws.vertexCount);
  ensureSize(ws.vertexNormalInvalid, ws.vertexCount);
  forRange(ws, ws.vertexCount, 1 << 14, [&](std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) {
      bool invalid = false;
      ws.vertexUnitNormals[v] = unitNormal(vec3At(mesh.normals, static_cast<std::uint32_t>(v)), invalid);
      ws.vertexNormalInvalid[v] = invalid;
    }
  });
}

// Each triangle evaluated at its corners' positions (their representatives') and UVs, each
// corner given its normal and its weighting's term (meshopt: its own), into the workspace's
// arrays; counts into the report. `flat` frames each corner here as well (flatTriangleFrames):
// its frame needs its triangle alone, so the pass writes it while the triangle is in registers.
TriangleData evaluateTriangles(WorkspaceData& ws, const MeshArrays& mesh, std::span<const std::uint32_t> weldOf,
                               const Options& options, const CornerOutputs& outputs, Report& report) {
  const std::size_t triangleCount = ws.cornerCount / 3;
  const bool flat = options.method == Method::flat;
  ensureSize(ws.triangleTerms, triangleCount);
  ensureSize(ws.cornerNormals, 3 * triangleCount);
  if (!flat) ensureSize(ws.cornerWeights, 3 * triangleCount);  // flat weighs every term alike: none read
  ensureSize(ws.invalidNormal, 3 * triangleCount);
  unitNormalsOfVertices(ws, mesh);
  const TriangleData data{{ws.triangleTerms.data(), triangleCount},
                          {ws.cornerNormals.data(), 3 * triangleCount},
                          {flat ? nullptr : ws.cornerWeights.data(), flat ? 0 : 3 * triangleCount},
                          {ws.invalidNormal.data(), 3 * triangleCount},
                          {ws.vertexUnitNormals.data(), ws.vertexCount},
                          mesh.indices};
  if (flat) ensureSize(ws.cornerState, ws.cornerCount);
  // Triangles of each kind, counted by each piece and summed (integers: any order).
  Combinable<std::array<std::uint64_t, 4>> kindCounts;
  // The triangles' arithmetic four at a time in vector registers where the processor has them
  // (triangleTangentsAt: the same bits as one at a time).
  const VectorIsa isa = activeVectorIsa();
#if defined(TANGENT_DOUBLE_LANES4)
  const int lanes = isa == VectorIsa::scalar ? 1 : isa == VectorIsa::avx2 ? 4 : 2;
#else
  const int lanes = isa == VectorIsa::scalar ? 1 : 2;
#endif
  forRange(ws, triangleCount, 1024, [&](std::size_t begin, std::size_t end) {
    float* tangents = outputs.tangents.data();
    std::uint8_t* state = ws.cornerState.data();
    std::array<std::uint64_t, 4> kinds{};
    constexpr int kBlock = 4;
    bool blockInvalid[kBlock][3], wantFaceNormal[kBlock];
    TriangleTangent blockTriangles[kBlock];
    TriangleLanes values{};
    FlatLanes flatLanes{};  // flat on lanes: its lanes past a short block's count stay not usable
    const TriangleSource source{mesh.positions.data(), mesh.uvs.data(), mesh.indices.data(), weldOf.data()};
    values.wantAngles = lanes > 1 && options.method == Method::lengyel && options.weighting == Weighting::angle;
    const bool meshoptLanes = lanes > 1 && options.method == Method::meshopt;
    const bool readsNormals = options.method != Method::lengyel;
    MeshoptLanes meshoptWeights{};
    for (std::size_t block = begin; block < end; block += kBlock) {
      const int count = static_cast<int>(std::min<std::size_t>(kBlock, end - block));
      for (int i = 0; i < count; ++i) {
        for (int k = 0; k < 3; ++k) blockInvalid[i][k] = ws.vertexNormalInvalid[mesh.indices[3 * (block + i) + k]];
        wantFaceNormal[i] = blockInvalid[i][0] || blockInvalid[i][1] || blockInvalid[i][2];
      }
      triangleTangentsAt(source, block, count, wantFaceNormal, lanes, values, blockTriangles);
      for (int i = 0; i < count; ++i) {
        const std::size_t t = block + i;
        const bool(&invalid)[3] = blockInvalid[i];
        const TriangleTangent& triangle = blockTriangles[i];
        std::array<Vec3, 3> positions;  // for the weights of a usable triangle only
        if (!flat && !meshoptLanes && triangle.kind == TriangleKind::usable) {
          for (int k = 0; k < 3; ++k) positions[k] = values.position(i, k);
        }
        // Stored field by field: a TriangleTerms built on the stack and copied was read back in
        // 16-byte pieces its 8-byte stores could not forward to (a stall per triangle).
        TriangleTerms& terms = data.triangles[t];
        terms.tangent = triangle.tangent;
        terms.bitangent = triangle.bitangent;
        terms.orientation = triangle.orientation;
        terms.kind = triangle.kind;
        Vec3 normals[3];
        for (int k = 0; k < 3; ++k) {
          const std::size_t corner = 3 * t + k;
          const std::uint32_t vertex = mesh.indices[corner];
          // lengyel's weights read no normal: a valid one (a vertex's, a cache miss) is loaded
          // for flat's frames and meshopt's weights only.
          if (invalid[k]) {
            normals[k] = replacedNormal(triangle);
            data.cornerNormals[corner] = normals[k];
          } else if (readsNormals) {
            normals[k] = ws.vertexUnitNormals[vertex];
          }
          data.invalidNormal[corner] = invalid[k];
          if (meshoptLanes) {
            for (int a = 0; a < 3; ++a) meshoptWeights.normal[values.laneCorner(i, k)][a][i] = normals[k][a];
          } else if (!flat) {
            const double angle = values.wantAngles ? values.cornerAngle(i, k) : -1.0;
            data.cornerWeights[corner] = cornerWeight(options, positions, k, normals[k], triangle, angle);
          }
        }
        if (meshoptLanes) {
          for (int a = 0; a < 3; ++a) meshoptWeights.tangent[a][i] = triangle.tangent[a];
        }
        if (flat && lanes == 1) flatTriangleFrames(terms, normals, invalid, tangents, state, 3 * t);
        if (flat && lanes > 1) {
          for (int a = 0; a < 3; ++a) {
            flatLanes.tangent[a][i] = terms.tangent[a];
            flatLanes.bitangent[a][i] = terms.bitangent[a];
            for (int k = 0; k < 3; ++k) flatLanes.normal[k][a][i] = normals[k][a];
          }
          flatLanes.usable[i] = terms.kind == TriangleKind::usable;
          flatLanes.uvSide[i] = terms.orientation < 0 ? -1.0 : 1.0;
        }
        if (triangle.kind != TriangleKind::usable) ++kinds[static_cast<std::size_t>(triangle.kind)];  // rare
      }
      if (meshoptLanes) {  // cornerWeight's: 0 where the triangle is not usable
        meshoptWeightLanes(values, meshoptWeights, lanes);
        for (int i = 0; i < count; ++i) {
          const bool usable = blockTriangles[i].kind == TriangleKind::usable;
          for (int k = 0; k < 3; ++k) {
            data.cornerWeights[3 * (block + i) + k] = usable ? meshoptWeights.weight[values.laneCorner(i, k)][i] : 0.0;
          }
        }
      }
      if (flat && lanes > 1) {
        for (int i = count; i < kBlock; ++i) flatLanes.usable[i] = false;
        flatFrameLanes(flatLanes, lanes);
        for (int i = 0; i < count; ++i) {
          for (int k = 0; k < 3; ++k) {
            const std::size_t corner = 3 * (block + i) + k;
            if (flatLanes.framed[k][i]) {
              writeCornerFrame(tangents, corner, Vec3(flatLanes.frame[k][0][i], flatLanes.frame[k][1][i], flatLanes.frame[k][2][i]),
                               flatLanes.w[k][i]);
            }
            state[corner] = static_cast<std::uint8_t>((flatLanes.framed[k][i] ? 0 : kUndefined) |
                                                      (blockInvalid[i][k] ? kInvalidNormal : 0));
          }
        }
      }
    }
    std::array<std::uint64_t, 4>& sum = kindCounts.local();
    for (std::size_t k = 0; k < kinds.size(); ++k) sum[k] += kinds[k];
  });
  kindCounts.combine_each([&](const std::array<std::uint64_t, 4>& kinds) {
    report.degenerateTriangles += kinds[static_cast<std::size_t>(TriangleKind::degenerate)];
    report.zeroUvAreaTriangles += kinds[static_cast<std::size_t>(TriangleKind::zeroUvArea)];
    report.nonFiniteTriangles += kinds[static_cast<std::size_t>(TriangleKind::nonFinite)];
  });
  return data;
}

// Calls each(low, high, t) for the three edges of each triangle t in [begin, end) whose
// corners are at three positions (the ends' representatives, the smaller first); triangles
// with two corners at one position are left out, as the OpenMesh call's weld leaves them out.
template <typename Each>
void forEachEdge(const MeshArrays& mesh, std::span<const std::uint32_t> weldOf, std::size_t begin, std::size_t end,
                 const Each& each) {
  for (std::size_t t = begin; t < end; ++t) {
    std::uint32_t welds[3];
    for (int k = 0; k < 3; ++k) welds[k] = weldOf[mesh.indices[3 * t + k]];
    if (welds[0] == welds[1] || welds[1] == welds[2] || welds[0] == welds[2]) continue;
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = welds[k], b = welds[(k + 1) % 3];
      each(std::min(a, b), std::max(a, b), t);
    }
  }
}

// One position's edges (other end << 32 | triangle), [first, last): sorted, and mark(t) for
// the triangles of each other end that more than two share.
template <typename Mark>
void markSharedEdges(std::uint64_t* first, std::uint64_t* last, const Mark& mark) {
  if (last - first < 3) return;
  std::sort(first, last);
  for (auto i = first; i != last;) {
    auto j = i;
    while (j != last && *j >> 32 == *i >> 32) ++j;
    if (j - i > 2) {
      for (auto k = i; k != j; ++k) mark(static_cast<std::uint32_t>(*k & 0xffffffffu));
    }
    i = j;
  }
}

// From four threads: the edges sorted by ranges of their smaller end (a stable counting sort
// by chunks of triangles), then each range's edges counted out to their positions and each
// position's few sorted and marked, ranges in parallel (a triangle's marks may come from two
// ranges: stores of 1, any order). The same marks as one thread's way, so the same count.
std::uint64_t countNonManifoldFacesInRanges(WorkspaceData& ws, const MeshArrays& mesh, std::span<const std::uint32_t> weldOf) {
  const std::size_t triangleCount = ws.cornerCount / 3, vertexCount = ws.vertexCount;
  const std::size_t threads = std::max(ws.threads, 1u);
  int rangeBits = 8;  // ranges of 2^8 to 2^12 positions, about four a thread (their ends fit 16 bits)
  while (rangeBits < 12 && (std::size_t(2) << rangeBits) * 4 * threads <= vertexCount) ++rangeBits;
  const std::size_t rangeLength = std::size_t(1) << rangeBits;
  const std::size_t ranges = (vertexCount + rangeLength - 1) / rangeLength;
  const std::size_t chunkTriangles = std::clamp<std::size_t>(triangleCount / (4 * threads), 1 << 10, 1 << 15);
  const std::size_t chunks = (triangleCount + chunkTriangles - 1) / chunkTriangles;
  ensureSize(ws.edgeCounts, chunks * ranges + ranges + 1);
  ensureSize(ws.edges, 3 * triangleCount);
  ensureSize(ws.edgeLowInRange, 3 * triangleCount);
  ensureSize(ws.edgeNext, vertexCount);
  ensureSize(ws.onSharedEdge, triangleCount);
  std::uint32_t* rangeStart = ws.edgeCounts.data() + chunks * ranges;
  std::uint64_t* edges = ws.edges.data();
  std::uint16_t* lows = ws.edgeLowInRange.data();
  std::uint8_t* onShared = ws.onSharedEdge.data();
  countingSortInChunks(
      ws, 3 * triangleCount, ranges, chunks,
      [&](std::size_t begin, std::size_t end, std::uint32_t* counter) {
        forEachEdge(mesh, weldOf, begin / 3, end / 3,
                    [&](std::uint32_t low, std::uint32_t, std::size_t) { ++counter[low >> rangeBits]; });
      },
      ws.edgeCounts.data(), rangeStart,
      [&](std::size_t begin, std::size_t end, std::uint32_t* next) {
        std::fill(onShared + begin / 3, onShared + end / 3, std::uint8_t(0));
        forEachEdge(mesh, weldOf, begin / 3, end / 3, [&](std::uint32_t low, std::uint32_t high, std::size_t t) {
          const std::uint32_t slot = next[low >> rangeBits]++;
          edges[slot] = std::uint64_t(high) << 32 | t;
          lows[slot] = static_cast<std::uint16_t>(low & (rangeLength - 1));
        });
      },
      3);
  forRange(ws, ranges, 1, [&](std::size_t begin, std::size_t end) {
    BucketScratch& scratch = ws.scratch.local();
    for (std::size_t r = begin; r < end; ++r) {
      const std::size_t first = r << rangeBits, last = std::min(vertexCount, first + rangeLength);
      const std::uint32_t from = rangeStart[r], n = rangeStart[r + 1] - from;
      std::uint32_t* next = ws.edgeNext.data() + first;  // this range's counts, then cursors
      std::fill(next, next + (last - first), 0u);
      for (std::uint32_t i = from; i < from + n; ++i) ++next[lows[i]];
      std::uint32_t total = from;
      for (std::size_t v = 0; v < last - first; ++v) {
        const std::uint32_t count = next[v];
        next[v] = total;
        total += count;
      }
      if (n == 0) continue;
      ensureSize(scratch.rangeEdges, n);  // grown only
      ensureSize(scratch.rangeLows, n);
      std::memcpy(scratch.rangeEdges.data(), edges + from, n * sizeof(std::uint64_t));
      std::memcpy(scratch.rangeLows.data(), lows + from, n * sizeof(std::uint16_t));
      for (std::uint32_t i = 0; i < n; ++i) edges[next[scratch.rangeLows[i]]++] = scratch.rangeEdges[i];
      // Each cursor has run to the end of its position's edges, where the next one's start.
      std::uint32_t positionStart = from;
      for (std::size_t v = 0; v < last - first; ++v) {
        markSharedEdges(edges + positionStart, edges + next[v], [&](std::uint32_t t) {
          AtomicRef<std::uint8_t>(onShared[t]).store(1, std::memory_order_relaxed);
        });
        positionStart = next[v];
      }
    }
  });
  Combinable<std::uint64_t> faces;
  forRange(ws, triangleCount, 1 << 16, [&](std::size_t begin, std::size_t end) {
    faces.local() += static_cast<std::uint64_t>(std::count(onShared + begin, onShared + end, std::uint8_t(1)));
  });
  return faces.combine(std::plus<>());
}

// Faces on an edge (two distinct positions) that more than two faces share. Each edge's other
// end is counted out to its smaller end (a counting sort, 4 bytes an edge), and each end's few
// other ends are sorted to find one that three or more share: linear time but for those runs.
// Only where such edges exist (none on most meshes) are they listed and the faces on them
// marked, in one more pass over the triangles. From four threads by ranges of positions
// (countNonManifoldFacesInRanges), with the same result. Into the workspace's edgeStart,
// edgeNext, edgeEnds and onSharedEdge.
std::uint64_t countNonManifoldFaces(WorkspaceData& ws, const MeshArrays& mesh, std::span<const std::uint32_t> weldOf) {
  const std::size_t triangleCount = ws.cornerCount / 3;
  if (ws.threads >= kThreadedCountThreads && triangleCount >= kThreadedCountTriangles) return countNonManifoldFacesInRanges(ws, mesh, weldOf);
  ensureSize(ws.edgeStart, ws.vertexCount + 1);
  ensureSize(ws.edgeNext, ws.vertexCount);
  std::uint32_t* start = ws.edgeStart.data();
  std::fill(start, start + ws.vertexCount + 1, 0u);
  forEachEdge(mesh, weldOf, 0, triangleCount, [&](std::uint32_t low, std::uint32_t, std::size_t) { ++start[low + 1]; });
  for (std::size_t v = 0; v < ws.vertexCount; ++v) start[v + 1] += start[v];
  ensureSize(ws.edgeEnds, start[ws.vertexCount]);
  std::uint32_t* ends = ws.edgeEnds.data();
  std::uint32_t* next = ws.edgeNext.data();
  std::copy(start, start + ws.vertexCount, next);
  forEachEdge(mesh, weldOf, 0, triangleCount, [&](std::uint32_t low, std::uint32_t high, std::size_t) { ends[next[low]++] = high; });
  // Each edge that more than two faces share, as low << 32 | high.
  std::vector<std::uint64_t> shared;
  for (std::size_t v = 0; v < ws.vertexCount; ++v) {
    std::uint32_t* first = ends + start[v];
    std::uint32_t* last = ends + start[v + 1];
    if (last - first < 3) continue;
    std::sort(first, last);
    for (std::uint32_t* i = first; i + 2 < last; ++i) {
      if (i[2] != i[0]) continue;
      shared.push_back(std::uint64_t(v) << 32 | i[0]);
      while (i + 1 < last && i[1] == i[0]) ++i;
    }
  }
  if (shared.empty()) return 0;
  // Listed in order of their smaller end, then of their other: sorted already.
  ensureSize(ws.onSharedEdge, triangleCount);
  std::uint8_t* onShared = ws.onSharedEdge.data();
  std::fill(onShared, onShared + triangleCount, std::uint8_t(0));
  forEachEdge(mesh, weldOf, 0, triangleCount, [&](std::uint32_t low, std::uint32_t high, std::size_t t) {
    if (std::binary_search(shared.begin(), shared.end(), std::uint64_t(low) << 32 | high)) onShared[t] = 1;
  });
  return static_cast<std::uint64_t>(std::count(onShared, onShared + triangleCount, std::uint8_t(1)));
}

// Every corner's frame into the output (w on the stored UVs, bottom-left), its source and
// invalid normal into cornerState, no links: what finishOutputs reads.
void writeCorners(WorkspaceData& ws, const TriangleData& data, const CornerGroups& cornerGroups, const CornerOutputs& outputs) {
  ensureSize(ws.cornerState, ws.cornerCount);
  ensureSize(ws.cornerLink, ws.cornerCount);
  float* tangents = outputs.tangents.data();
  forRange(ws, ws.cornerCount, 1 << 14, [&](std::size_t begin, std::size_t end) {
    for (std::size_t c = begin; c < end; ++c) {
      const Group& group = cornerGroups.groups[cornerGroups.cornerGroup[c]];
      writeCornerFrame(tangents, c, group.tangent, group.w);
      ws.cornerState[c] = static_cast<std::uint8_t>(static_cast<std::uint8_t>(group.source) | (data.invalidNormal[c] ? kInvalidNormal : 0));
      ws.cornerLink[c] = kNone;
    }
  });
}

}  // namespace

Report lengyelOnArrays(WorkspaceData& ws, const MeshArrays& mesh, const CornerOutputs& outputs, const Options& options,
                       Grouping grouping) {
  beginCall(ws, mesh);
  Report report;
  report.method = options.method;
  if (options.method == Method::lengyel) report.weighting = options.weighting;
  report.triangles = ws.cornerCount / 3;
  report.corners = ws.cornerCount;
  std::span<const std::uint32_t> weldOf;
  TriangleData data;
  // The weld and buckets serve the vertex split only: beside the method's own first phases
  // (on one thread below four, as mikktspace's kernel runs them).
  ensureSize(ws.cornerLink, ws.cornerCount);
  const unsigned weldThreads = ws.threads < 4 ? 1 : ws.threads;
  invokeBoth(ws, [&] { weldAndBucket(ws, mesh, weldThreads); }, [&] {
    weldOf = positionWeld(ws, mesh);
    // The count (its own arrays) beside the triangle pass, whose pieces the other threads take.
    // invokeBoth offers its first to other threads and runs its second here: the triangle
    // pass here, so that its pieces are there to take at once.
    std::uint64_t nonManifoldFaces = 0;
    invokeBoth(ws, [&] { nonManifoldFaces = countNonManifoldFaces(ws, mesh, weldOf); },
               [&] { data = evaluateTriangles(ws, mesh, weldOf, options, outputs, report); });
    report.nonManifoldFaces = nonManifoldFaces;
  });
  // Read for the last time (setReleaseAsItGoes): the weld's and the count's arrays.
  releaseWhenDone(ws, ws.table, ws.weldCounts, ws.positionTable, ws.edgeStart, ws.edgeNext, ws.edgeEnds, ws.edgeCounts, ws.edges,
                  ws.onSharedEdge, ws.edgeLowInRange);
  // Frames by the shortest way that gives the full grouping's bits: flat's one-corner groups
  // (framed by the triangle pass; the corners it left undefined here), the buckets where they
  // are lengyel's groups, else every corner's key sorted.
  if (grouping == Grouping::perFace) {
    flatFrames(ws, mesh, weldOf, data, outputs);
  } else if (!bucketFrames(ws, mesh, weldOf, data, options.method, outputs)) {
    CornerGroups cornerGroups = groupCorners(ws, mesh, weldOf, data, grouping);
    sumAndOrthonormalize(ws, data, cornerGroups, options.method);
    fillUndefinedGroups(mesh, weldOf, cornerGroups);
    writeCorners(ws, data, cornerGroups, outputs);
  }
  // The triangle pass's results, read for the last time by the frames (setReleaseAsItGoes).
  releaseWhenDone(ws, ws.triangleTerms, ws.cornerNormals, ws.cornerWeights, ws.vertexUnitNormals, ws.invalidNormal,
                  ws.vertexNormalInvalid, ws.positionRepresentative);
  finishOutputs(ws, mesh, outputs, options, report);
  return report;
}

}  // namespace tangent::detail
