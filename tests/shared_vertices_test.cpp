// SPDX-License-Identifier: MIT
// The WebAssembly package's sharing of de-indexed corners (tangent/shared_vertices.hpp),
// natively: against a plain map from a corner's eight values' bits to its first corner, on
// corners that repeat in random order (the recent table's misses and evictions, +0/-0 and
// NaN), all at once and in runs of every awkward length (the package's staging buffer), and
// on corners that never repeat (the table grown again and again).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <random>
#include <span>
#include <stdexcept>
#include <vector>

#include "tangent/shared_vertices.hpp"
#include "tangent/tangent.hpp"

namespace {

struct Corners {
  std::vector<float> positions, normals, uvs;  // 3, 3, 2 per corner
  std::size_t count() const { return uvs.size() / 2; }
};

// The expected sharing: corners of the same eight bits share the vertex of the first of them,
// numbered in order of first corners; a corner with a NaN is a vertex of its own.
struct Expected {
  std::vector<std::uint32_t> indices;
  std::vector<std::size_t> firstCorner;  // per vertex
};
Expected expectedSharing(const Corners& corners) {
  Expected out;
  std::map<std::array<std::uint32_t, 8>, std::uint32_t> seen;
  for (std::size_t c = 0; c < corners.count(); ++c) {
    const float values[8] = {corners.positions[3 * c], corners.positions[3 * c + 1], corners.positions[3 * c + 2],
                             corners.normals[3 * c],   corners.normals[3 * c + 1],   corners.normals[3 * c + 2],
                             corners.uvs[2 * c],       corners.uvs[2 * c + 1]};
    std::array<std::uint32_t, 8> key;
    bool nan = false;
    for (int i = 0; i < 8; ++i) {
      std::memcpy(&key[i], &values[i], 4);
      nan = nan || std::isnan(values[i]);
    }
    const auto next = static_cast<std::uint32_t>(out.firstCorner.size());
    const auto [it, added] = nan ? std::pair{seen.end(), true} : seen.emplace(key, next);
    out.indices.push_back(added ? next : it->second);
    if (added) out.firstCorner.push_back(c);
  }
  return out;
}

// Each corner one of `pool` vertices picked at random (so that a vertex comes back after any
// number of others), some of whose values are +0 or -0 at random and some NaN.
Corners randomCorners(std::size_t count, std::size_t pool, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> value(-1.0f, 1.0f);
  std::vector<std::array<float, 8>> vertices(pool);
  for (auto& v : vertices) {
    for (float& x : v) x = value(rng);
    if (rng() % 4 == 0) v[rng() % 8] = (rng() % 2) ? 0.0f : -0.0f;
    if (rng() % 50 == 0) v[rng() % 8] = std::numeric_limits<float>::quiet_NaN();
  }
  // Vertices that differ only in the sign of a zero: the hash ignores signs, so they collide.
  for (std::size_t i = 0; i + 1 < pool; i += 16) {
    vertices[i + 1] = vertices[i];
    vertices[i][5] = 0.0f;
    vertices[i + 1][5] = -0.0f;
  }
  Corners out;
  for (std::size_t c = 0; c < count; ++c) {
    const auto& v = vertices[rng() % pool];
    out.positions.insert(out.positions.end(), v.begin(), v.begin() + 3);
    out.normals.insert(out.normals.end(), v.begin() + 3, v.begin() + 6);
    out.uvs.insert(out.uvs.end(), v.begin() + 6, v.end());
  }
  return out;
}

// Shares `corners` in runs of `runLength` (0: all at once), or all at once on `threads`
// threads where that is more than 1 (shareVertices), and checks every output.
void expectSharing(const Corners& corners, std::size_t runLength, unsigned threads = 1) {
  const std::size_t n = corners.count();
  tangent::SharedVertices shared;
  if (threads > 1) {
    tangent::shareVertices(corners.positions.data(), corners.normals.data(), corners.uvs.data(), n, shared, threads);
    runLength = threads;  // named in the messages below
  } else {
    tangent::VertexSharer sharer;
    sharer.begin(n, shared);
    for (std::size_t first = 0; first < n; first += runLength ? runLength : n) {
      const std::size_t count = std::min(n - first, runLength ? runLength : n);
      ASSERT_TRUE(sharer.add(&corners.positions[3 * first], &corners.normals[3 * first], &corners.uvs[2 * first], count));
    }
  }
  const Expected expected = expectedSharing(corners);
  ASSERT_EQ(shared.vertexCount, expected.firstCorner.size()) << "run length " << runLength;
  std::size_t wrongIndices = 0, wrongValues = 0;
  for (std::size_t c = 0; c < n; ++c) wrongIndices += shared.indices[c] != expected.indices[c];
  for (std::size_t v = 0; v < shared.vertexCount; ++v) {
    const std::size_t c = expected.firstCorner[v];
    wrongValues += std::memcmp(&shared.positions[3 * v], &corners.positions[3 * c], 12) != 0 ||
                   std::memcmp(&shared.normals[3 * v], &corners.normals[3 * c], 12) != 0 ||
                   std::memcmp(&shared.uvs[2 * v], &corners.uvs[2 * c], 8) != 0;
  }
  EXPECT_EQ(wrongIndices, 0u) << "run length " << runLength;
  EXPECT_EQ(wrongValues, 0u) << "run length " << runLength;
  // The vertices that may still weld in the core: those with a value of +0 or -0, in order.
  std::vector<std::uint32_t> withZero;
  for (std::size_t v = 0; v < shared.vertexCount; ++v) {
    bool zero = false;
    for (const float x : {shared.positions[3 * v], shared.positions[3 * v + 1], shared.positions[3 * v + 2],
                          shared.normals[3 * v], shared.normals[3 * v + 1], shared.normals[3 * v + 2], shared.uvs[2 * v],
                          shared.uvs[2 * v + 1]})
      zero = zero || x == 0.0f;
    if (zero) withZero.push_back(static_cast<std::uint32_t>(v));
  }
  EXPECT_EQ(shared.zeroVertices, withZero) << "run length " << runLength;
}

TEST(SharedVertices, RepeatedCornersInRandomOrderAndInRuns) {
  // 20,000 vertices: more than the recent table's 4096 entries, so vertices come back after
  // being evicted from it and are found in the large table.
  const Corners corners = randomCorners(120000, 20000, 1);
  for (std::size_t runLength : {std::size_t(0), std::size_t(1), std::size_t(63), std::size_t(64), std::size_t(65),
                                std::size_t(1000), std::size_t(16384)}) {
    expectSharing(corners, runLength);
  }
}

TEST(SharedVertices, ManyVerticesGrowTheTableAndAreFoundAfter) {
  // 50,000 distinct corners (the table, sized for a sixth of 100,000 corners, grows), then
  // the same corners again in another order: each must find its vertex in the grown table.
  Corners corners = randomCorners(50000, 50000, 2);
  for (std::size_t c = 0; c < corners.count(); ++c) corners.uvs[2 * c] = static_cast<float>(c);  // all distinct
  std::vector<std::size_t> order(corners.count());
  for (std::size_t c = 0; c < order.size(); ++c) order[c] = (c * 7919) % order.size();  // 7919: prime, not a factor
  for (std::size_t c : order) {
    corners.positions.insert(corners.positions.end(), {corners.positions[3 * c], corners.positions[3 * c + 1], corners.positions[3 * c + 2]});
    corners.normals.insert(corners.normals.end(), {corners.normals[3 * c], corners.normals[3 * c + 1], corners.normals[3 * c + 2]});
    corners.uvs.insert(corners.uvs.end(), {corners.uvs[2 * c], corners.uvs[2 * c + 1]});
  }
  expectSharing(corners, 0);
  expectSharing(corners, 4096);
}

// On several threads (shareVertices with threads: chunks' recent repeats, the rest grouped by
// hash, the first corners numbered by a scan) the same vertices, numbers and zero list as one
// thread's: on corners that repeat at random (most found by the hash groups) and on a
// triangle strip whose corners repeat a few corners back (most found in each chunk's recent
// table, some across a chunk's start), each past the size from which it runs in parallel.
TEST(SharedVertices, SeveralThreadsShareAsOneThreadDoes) {
  const Corners random = randomCorners(400000, 30000, 6);
  Corners strip;
  std::mt19937 rng(7);
  const std::size_t columns = 700;
  for (std::size_t t = 0; t < 150000; ++t) {
    const std::size_t row = t / (2 * columns), column = (t / 2) % columns;
    const std::size_t a = row * (columns + 1) + column, b = a + 1, c = a + columns + 1, d = c + 1;
    for (const std::size_t v : (t % 2 ? std::array{a, d, b} : std::array{a, c, d})) {
      const float x = static_cast<float>(v % (columns + 1)), y = static_cast<float>(v / (columns + 1));
      strip.positions.insert(strip.positions.end(), {x, y, rng() % 64 == 0 ? -0.0f : 0.0f});
      strip.normals.insert(strip.normals.end(), {0.0f, 0.0f, 1.0f});
      strip.uvs.insert(strip.uvs.end(), {x / columns, rng() % 512 == 0 ? std::numeric_limits<float>::quiet_NaN() : y});
    }
  }
  for (unsigned threads : {2u, 3u, 8u}) {
    expectSharing(random, 0, threads);
    expectSharing(strip, 0, threads);
  }
}

// The shared vertices of `corners` corners as the core's input.
tangent::MeshArrays meshOf(const tangent::SharedVertices& shared, std::size_t corners) {
  const std::size_t vertices = shared.vertexCount;
  return {{shared.positions.data(), 3 * vertices},
          {shared.normals.data(), 3 * vertices},
          {shared.uvs.data(), 2 * vertices},
          {shared.indices.data(), corners}};
}

// The core on the shared vertices, welding only those with a zero (weldOnly, as the package
// calls it), gives the bits it gives on the de-indexed corners themselves and on the shared
// vertices welded in full: corners that differ only in the sign of a zero are separate vertices
// after sharing and must still weld. Random triangles over a pool of vertices (non-manifold
// edges, degenerate and duplicate triangles among them), every method that welds.
TEST(SharedVertices, TheCoreWeldingOnlyVerticesWithAZeroGivesTheSameBits) {
  const Corners corners = randomCorners(3 * 20000, 3000, 4);
  const std::size_t n = corners.count();
  tangent::SharedVertices shared;
  tangent::shareVertices(corners.positions.data(), corners.normals.data(), corners.uvs.data(), n, shared);
  ASSERT_GT(shared.zeroVertices.size(), 0u);
  ASSERT_LT(shared.zeroVertices.size(), shared.vertexCount);
  std::vector<std::uint32_t> sequence(n);
  for (std::size_t c = 0; c < n; ++c) sequence[c] = static_cast<std::uint32_t>(c);
  const tangent::MeshArrays deindexed{corners.positions, corners.normals, corners.uvs, sequence};
  const tangent::MeshArrays sharedMesh = meshOf(shared, n);
  // One thread (the package's) and four (the bucketing by ranges of ids).
  for (const auto& [method, threads] : {std::pair{tangent::Method::mikktspace, 1u}, std::pair{tangent::Method::lengyel, 1u},
                                        std::pair{tangent::Method::mikktspace, 4u}}) {
    tangent::Options options;
    options.method = method;
    options.threads = threads;
    std::vector<float> reference(4 * n), full(4 * n), only(4 * n);
    tangent::TangentWorkspace workspace;
    const tangent::Report expected = tangent::computeCornerTangents(deindexed, tangent::CornerOutputs{std::span<float>(reference)}, options, workspace);
    tangent::computeCornerTangents(sharedMesh, tangent::CornerOutputs{std::span<float>(full)}, options, workspace);
    workspace.setWeldOnly(std::span<const std::uint32_t>(shared.zeroVertices));
    const tangent::Report report = tangent::computeCornerTangents(sharedMesh, tangent::CornerOutputs{std::span<float>(only)}, options, workspace);
    if (method == tangent::Method::mikktspace) {
      // The control: welding none of them gives other bits (the pairs that differ in a zero's
      // sign are not merged), so the list above did its work. (Lengyel's sums here come out
      // the same either way.)
      std::vector<float> none(4 * n);
      workspace.setWeldOnly(std::span<const std::uint32_t>());
      tangent::computeCornerTangents(sharedMesh, tangent::CornerOutputs{std::span<float>(none)}, options, workspace);
      workspace.setWeldOnly(std::nullopt);
      EXPECT_NE(std::memcmp(none.data(), reference.data(), 4 * n * sizeof(float)), 0);
    }
    EXPECT_EQ(std::memcmp(full.data(), reference.data(), 4 * n * sizeof(float)), 0) << tangent::toString(method) << ", " << threads << " threads";
    EXPECT_EQ(std::memcmp(only.data(), reference.data(), 4 * n * sizeof(float)), 0) << tangent::toString(method) << ", " << threads << " threads";
    EXPECT_EQ(report.mirroredCorners, expected.mirroredCorners);
    EXPECT_EQ(report.degenerateTriangles, expected.degenerateTriangles);
  }
}

TEST(SharedVertices, AWeldListOutOfRangeOrOrderIsRefused) {
  const Corners corners = randomCorners(30, 10, 5);
  tangent::SharedVertices shared;
  tangent::shareVertices(corners.positions.data(), corners.normals.data(), corners.uvs.data(), 30, shared);
  const std::size_t vertices = shared.vertexCount;
  const tangent::MeshArrays mesh = meshOf(shared, 30);
  std::vector<float> tangents(4 * 30);
  tangent::TangentWorkspace workspace;
  for (const std::vector<std::uint32_t>& list :
       {std::vector<std::uint32_t>{0, static_cast<std::uint32_t>(vertices)}, std::vector<std::uint32_t>{1, 0}}) {
    workspace.setWeldOnly(std::span<const std::uint32_t>(list));
    EXPECT_THROW(tangent::computeCornerTangents(mesh, tangent::CornerOutputs{std::span<float>(tangents)}, tangent::Options{}, workspace), std::invalid_argument);
  }
}

TEST(SharedVertices, AddPastTheCountIsRefused) {
  const Corners corners = randomCorners(10, 4, 3);
  tangent::SharedVertices shared;
  tangent::VertexSharer sharer;
  sharer.begin(9, shared);
  EXPECT_TRUE(sharer.add(corners.positions.data(), corners.normals.data(), corners.uvs.data(), 5));
  EXPECT_FALSE(sharer.add(&corners.positions[15], &corners.normals[15], &corners.uvs[10], 5));
  EXPECT_EQ(sharer.added(), 5u);
}

}  // namespace
