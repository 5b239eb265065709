// SPDX-License-Identifier: MIT
// What the methods share once triangles are computed: groups of corners that get one frame,
// value-ordered sums, fallbacks for corners no usable triangle reaches, and the output.
#pragma once

#include <span>
#include <vector>

#include "tangent/halfedge_mesh.hpp"
#include "triangle_tangent.hpp"
#include "workspace.hpp"

namespace tangent::detail {

std::uint64_t bitsOf(double value);  // +0 and -0 alike

struct GroupKey {
  std::uint32_t weld = 0;
  std::int32_t orientation = 0;
  std::uint64_t tag = 0;  // extra identity (face for `flat`, component for `mikktspace`)
  std::uint64_t normal[3] = {};
  std::uint64_t uv[2] = {};
  bool operator==(const GroupKey&) const = default;
  bool sameAttributes(const GroupKey& other) const;  // normal and UV bits
};

struct GroupKeyHash {
  std::size_t operator()(const GroupKey& key) const noexcept;
};

GroupKey makeGroupKey(const CornerMesh& mesh, std::size_t corner, const Vec3& normal, int orientation, std::uint64_t tag);

struct Group {
  GroupKey key;
  Vec3 normal{0, 0, 1};  // unit
  Vec3 tangentSum{0, 0, 0};
  Vec3 bitangentSum{0, 0, 0};
  Vec3 tangent{0, 0, 0};
  double w = 1;         // handedness on the stored UVs (bottom-left convention)
  bool defined = false;
  bool mayInherit = false;  // copying a same-attribute corner is the method's own rule here
};

struct Contribution {
  std::uint32_t group;
  Vec3 tangent;
  Vec3 bitangent;
};

// Adds each contribution to its group, summing every group's terms in value order.
void sumInValueOrder(std::vector<Contribution>& contributions, std::vector<Group>& groups);

// Gram-Schmidt of `sum` against unit `n`; false when nothing of it lies in the tangent plane.
bool orthonormalize(const Vec3& sum, const Vec3& n, Vec3& out);

// Positions and UVs of input triangle t, in its input corner order.
void triangleCorners(const CornerMesh& mesh, std::size_t t, std::array<Vec3, 3>& positions, std::array<Vec2, 3>& uvs);

// The unit normal a corner works with: its own, or when that is zero or not finite the
// triangle's (or +z); `invalid` tells which.
Vec3 cornerNormal(const Vec3& stored, const TriangleTangent& triangle, bool& invalid);

struct TriangleData {
  std::vector<TriangleTangent> triangles;
  std::vector<Vec3> cornerNormals;  // unit (see cornerNormal)
};

// The pass every method starts with, in parallel on the workspace's threads (inside the call's
// onThreads): each triangle evaluated, each corner given its normal; perCorner(corner, k,
// positions, triangle, normal) adds the method's own term. Counts degenerate, zero-UV,
// non-finite triangles and invalid normals into the report.
template <typename PerCorner>
TriangleData evaluateTriangles(const WorkspaceData& ws, const CornerMesh& cornerMesh, Report& report, const PerCorner& perCorner) {
  const std::size_t triangleCount = cornerMesh.cornerHalfedge.size() / 3;
  TriangleData data;
  data.triangles.resize(triangleCount);
  data.cornerNormals.resize(triangleCount * 3);
  std::vector<std::uint8_t> invalidNormal(triangleCount * 3, 0);
  forRange(ws, triangleCount, 1024, [&](std::size_t begin, std::size_t end) {
    for (std::size_t t = begin; t < end; ++t) {
      std::array<Vec3, 3> positions;
      std::array<Vec2, 3> uvs;
      triangleCorners(cornerMesh, t, positions, uvs);
      const TriangleTangent& triangle = data.triangles[t] = triangleTangent(positions, uvs);
      for (int k = 0; k < 3; ++k) {
        const std::size_t corner = 3 * t + k;
        bool invalid = false;
        data.cornerNormals[corner] = cornerNormal(cornerMesh.mesh.normal(cornerMesh.cornerHalfedge[corner]), triangle, invalid);
        invalidNormal[corner] = invalid;
        perCorner(corner, k, positions, triangle, data.cornerNormals[corner]);
      }
    }
  });
  for (const TriangleTangent& triangle : data.triangles) {
    switch (triangle.kind) {
      case TriangleKind::usable: break;
      case TriangleKind::degenerate: ++report.degenerateTriangles; break;
      case TriangleKind::zeroUvArea: ++report.zeroUvAreaTriangles; break;
      case TriangleKind::nonFinite: ++report.nonFiniteTriangles; break;
    }
  }
  for (std::uint8_t invalid : invalidNormal) report.invalidNormals += invalid;
  return data;
}

// Gives undefined groups a frame (see FrameSource), writes every corner's tangent into the
// mesh with w in options.uvOrigin's convention, and fills the report's corner counts.
void finishCorners(CornerMesh& mesh, std::vector<Group>& groups, const std::vector<std::uint32_t>& cornerGroup,
                   const Options& options, Report& report, std::span<FrameSource> sources);

}  // namespace tangent::detail
