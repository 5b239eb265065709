// SPDX-License-Identifier: MIT
// Methods `lengyel` and `flat`.
// Source: E. Lengyel, "Computing Tangent Space Basis Vectors for an Arbitrary Mesh", 2001:
// accumulate per-triangle tangents over the corners that will share a vertex, then
// Gram-Schmidt orthogonalize against the normal; handedness w = sign(dot(cross(N, T), B)).
// Corners share a frame when they share position, normal, UV and UV orientation, so mirrored
// islands never average together. `flat` is the same pipeline with one group per corner.
//
// Determinism: per-triangle terms start at a canonical corner (triangle_tangent.cpp) and the
// terms of a group are summed in an order given by their values, so neither face order nor
// corner rotation changes a bit of the output.
#include <unordered_map>

#include "corner_groups.hpp"
#include "methods.hpp"

namespace tangent::detail {

Report lengyelTangents(const WorkspaceData& ws, CornerMesh& cornerMesh, const Options& options,
                       std::span<FrameSource> sources) {
  const std::size_t cornerCount = cornerMesh.cornerHalfedge.size();
  const std::size_t triangleCount = cornerCount / 3;
  const bool flat = options.method == Method::flat;

  Report report;
  report.method = options.method;
  if (!flat) report.weighting = options.weighting;
  report.triangles = triangleCount;
  report.corners = cornerCount;
  report.nonManifoldFaces = cornerMesh.nonManifoldFaces;

  std::vector<double> cornerWeights(cornerCount, 0.0);
  TriangleData data = evaluateTriangles(ws, cornerMesh, report,
                                        [&](std::size_t corner, int k, const std::array<Vec3, 3>& positions,
                                            const TriangleTangent& triangle, const Vec3&) {
                                          if (triangle.kind != TriangleKind::usable) return;
                                          switch (options.weighting) {
                                            case Weighting::angle: cornerWeights[corner] = cornerAngle(positions, k); break;
                                            case Weighting::area: cornerWeights[corner] = triangle.area; break;
                                            case Weighting::uniform: cornerWeights[corner] = 1.0; break;
                                          }
                                        });
  const std::vector<TriangleTangent>& triangles = data.triangles;
  const std::vector<Vec3>& cornerNormals = data.cornerNormals;

  // Group the corners by value.
  std::unordered_map<GroupKey, std::uint32_t, GroupKeyHash> groupIndex;
  groupIndex.reserve(cornerCount);
  std::vector<Group> groups;
  std::vector<std::uint32_t> cornerGroup(cornerCount);
  for (std::size_t corner = 0; corner < cornerCount; ++corner) {
    const TriangleTangent& triangle = triangles[corner / 3];
    const int orientation = triangle.kind == TriangleKind::usable ? triangle.orientation : 0;
    const GroupKey key = makeGroupKey(cornerMesh, corner, cornerNormals[corner], orientation, flat ? corner / 3 + 1 : 0);
    auto [it, inserted] = groupIndex.try_emplace(key, static_cast<std::uint32_t>(groups.size()));
    if (inserted) {
      Group group;
      group.key = key;
      group.normal = cornerNormals[corner];
      group.mayInherit = triangle.kind != TriangleKind::usable;
      groups.push_back(group);
    }
    cornerGroup[corner] = it->second;
  }

  std::vector<Contribution> contributions;
  contributions.reserve(cornerCount);
  for (std::size_t corner = 0; corner < cornerCount; ++corner) {
    const TriangleTangent& triangle = triangles[corner / 3];
    if (triangle.kind != TriangleKind::usable) continue;
    const double weight = flat ? 1.0 : cornerWeights[corner];
    if (!(weight > 0)) continue;
    contributions.push_back({cornerGroup[corner], triangle.tangent * weight, triangle.bitangent * weight});
  }
  sumInValueOrder(contributions, groups);

  for (Group& group : groups) {
    if (!orthonormalize(group.tangentSum, group.normal, group.tangent)) continue;
    const double handedness = (group.normal % group.tangent) | group.bitangentSum;
    group.w = handedness > 0 ? 1.0 : handedness < 0 ? -1.0 : (group.key.orientation < 0 ? -1.0 : 1.0);
    group.defined = true;
  }
  finishCorners(cornerMesh, groups, cornerGroup, options, report, sources);
  return report;
}

}  // namespace tangent::detail
