// SPDX-License-Identifier: MIT
// Seeded random triangle meshes that mix the cases tangent generators disagree on: seams,
// mirrored islands, non-manifold edges and vertices, flipped and duplicated faces, zero UV
// area, degenerate and sliver triangles, welded vs shared vertices, and MikkTSpace subgroup
// splits. Deterministic per seed (std::mt19937_64, no platform-dependent distributions).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "support/test_assets.hpp"
#include "tangent/tangent.hpp"

namespace tangent::testing {

enum class MeshFeature : std::uint8_t {
  smoothGrid,         // grid patch on a smooth height field, analytic normals
  flatGrid,           // grid patch in a plane, exact k/8 coordinates
  jitter,             // positions jittered (as a function of position: equal stays equal)
  uvSeam,             // same position and normal, different UV (shifted or rotated chart)
  normalSeam,         // same position and UV, different normal
  mirroredIsland,     // UVs mirrored across a grid column (w flips) or a whole mirrored patch
  weldedCopies,       // vertices duplicated with identical attributes (the reference welds)
  nonManifoldEdge,    // fins: 3+ triangles on one edge
  nonManifoldVertex,  // a second fan touching an existing vertex
  flippedWinding,     // triangles with corners swapped
  duplicatedFace,     // exact copies of triangles
  rotatedDuplicate,   // copies with rotated corners
  identicalUvs,       // triangles whose three UVs are equal
  collinearUvs,       // triangles whose UVs lie on a line
  degenerate,         // two corners with the same position (same or different UV)
  sliver,             // very thin triangles
  subgroupSplit,      // a group around a vertex whose projected tangents are exactly opposite
  count
};
constexpr std::size_t kMeshFeatureCount = static_cast<std::size_t>(MeshFeature::count);

std::string_view toString(MeshFeature feature);

struct RandomMesh {
  std::vector<float> positions, normals, uvs;
  std::vector<std::uint32_t> indices;
  std::array<bool, kMeshFeatureCount> features{};  // which cases this mesh contains
  MeshArrays arrays() const { return {positions, normals, uvs, indices}; }
  std::size_t triangleCount() const { return indices.size() / 3; }
};

// only: the mesh allows just that case (and a grid kind) instead of a random subset, to
// attribute failures to one case.
RandomMesh randomMesh(std::uint64_t seed, std::optional<MeshFeature> only = std::nullopt);
std::optional<MeshFeature> parseMeshFeature(std::string_view name);

// One call's outputs: a tangent per corner (NaN where unwritten), each corner's output vertex,
// the report.
struct CornerRun {
  std::vector<float> tangents;
  std::vector<std::uint32_t> cornerVertex;
  Report report;
};
// computeCornerTangents with the vertex split on `threads` threads with `method`.
CornerRun runCorners(const MeshArrays& mesh, unsigned threads, TangentWorkspace& workspace, Method method = Method::mikktspace);

// Random meshes (randomMesh, seeds 1, 2, ...) side by side until there are `triangles`: every
// hard case at once, large enough that several threads really split every phase of the core.
GridMesh hardMesh(std::size_t triangles = 60000);

}  // namespace tangent::testing
