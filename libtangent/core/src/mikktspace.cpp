// Method `mikktspace`.
// Source: M. S. Mikkelsen, "Simulation of Wrinkled Surfaces Revisited", MSc thesis, 2008, and
// the rules of the reference implementation (mikktspace.h/.c, 2011), reproduced here on the
// half-edge mesh:
//  * A corner's identity is its (position, normal, UV). Two triangles are neighbours across
//    an edge when both ends have the same identity on both sides (and the winding agrees,
//    which opposite halfedges guarantee).
//  * A triangle whose corners share a position is degenerate: it takes part in nothing and
//    its corners copy the frame of a corner with the same identity.
//  * A triangle with zero UV area (or zero tangent) may group with anything: it contributes
//    nothing and takes the UV orientation of the group that reaches it.
//  * A group is the set of corners around one vertex connected through neighbour edges with
//    the same UV orientation. Its tangent is the angle-weighted sum, over its triangles, of
//    the triangle's dP/du projected onto the normal and normalized; the angle is between the
//    triangle's two edges at the corner, projected onto the tangent plane. w is the
//    orientation (+1 where the UV area is positive), negated for top-left UV origins.
//  * With the default 180 degree threshold a group is never split.
// Where the reference leaves a frame zero or arbitrary (a group with no contributing triangle)
// we give a finite unit frame and say so (FrameSource::neighbour / fixed).
//
// Deviations, all order-independent where the reference is not: a zero-UV-area triangle
// takes the orientation most of its neighbours have (the reference: whichever group reaches
// it first); among several same-identity corners a degenerate corner copies the one whose
// group weighs most (the reference: the first in face order). Arithmetic is double; the
// reference's is float.
#include <algorithm>
#include <cmath>
#include <numeric>

#include "corner_groups.hpp"
#include "methods.hpp"
#include "parallel.hpp"

namespace tangent::detail {
namespace {

class UnionFind {
 public:
  explicit UnionFind(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0u); }
  std::uint32_t find(std::uint32_t x) {
    while (parent_[x] != x) {
      parent_[x] = parent_[parent_[x]];
      x = parent_[x];
    }
    return x;
  }
  void unite(std::uint32_t a, std::uint32_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }

 private:
  std::vector<std::uint32_t> parent_;
};

// Angle at `corner` between its two edges projected onto the plane normal to n; a zero
// projected edge counts as perpendicular, as in the reference. atan2 rather than the
// reference's acos of the dot product: acos returns 0 for angles below ~1e-8 rad, which would
// leave a fan of slivers with no weight at all.
double projectedCornerAngle(const std::array<Vec3, 3>& positions, int corner, const Vec3& n) {
  auto projected = [&](const Vec3& edge) {
    Vec3 v = edge - n * (n | edge);
    const double length = v.norm();
    return length > 0 ? v / length : Vec3(0, 0, 0);
  };
  const Vec3 previous = projected(positions[(corner + 2) % 3] - positions[corner]);
  const Vec3 next = projected(positions[(corner + 1) % 3] - positions[corner]);
  if (previous.sqrnorm() == 0 || next.sqrnorm() == 0) return std::acos(0.0);
  return std::atan2((previous % next).norm(), previous | next);
}

}  // namespace

Report mikktspaceTangents(CornerMesh& cornerMesh, const Options& options, std::span<FrameSource> sources) {
  TriMesh& mesh = cornerMesh.mesh;
  const std::size_t cornerCount = cornerMesh.cornerHalfedge.size();
  const std::size_t triangleCount = cornerCount / 3;

  Report report;
  report.method = "mikktspace";
  report.weighting = "angle";
  report.triangles = triangleCount;
  report.corners = cornerCount;
  report.nonManifoldFaces = cornerMesh.nonManifoldFaces;

  std::vector<Contribution> cornerContribution(cornerCount, Contribution{0, Vec3(0, 0, 0), Vec3(0, 0, 0)});
  const TriangleData data = evaluateTriangles(
      cornerMesh, options, report,
      [&](std::size_t corner, int k, const std::array<Vec3, 3>& positions, const TriangleTangent& triangle, const Vec3& n) {
        if (triangle.orientation == 0) return;  // may group with anything; adds nothing
        Vec3 tangent = triangle.tangent - n * (n | triangle.tangent);
        Vec3 bitangent = triangle.bitangent - n * (n | triangle.bitangent);
        const double tangentLength = tangent.norm(), bitangentLength = bitangent.norm();
        if (tangentLength > 0) tangent /= tangentLength;
        if (bitangentLength > 0) bitangent /= bitangentLength;
        const double angle = projectedCornerAngle(positions, k, n);
        cornerContribution[corner] = {0, tangent * angle, bitangent * angle};
      });
  const std::vector<TriangleTangent>& triangles = data.triangles;
  const std::vector<Vec3>& cornerNormals = data.cornerNormals;

  // Neighbours across an edge: both ends with the same normal and UV on both sides.
  auto sameCorner = [&](OpenMesh::HalfedgeHandle a, OpenMesh::HalfedgeHandle b) {
    return mesh.normal(a) == mesh.normal(b) && mesh.texcoord2D(a) == mesh.texcoord2D(b);
  };
  // For the corner at halfedge h (pointing to v), the corners of the neighbour across the edge
  // arriving at v: {corner at v, corner at the edge's other end} in both faces.
  auto neighbourAcross = [&](OpenMesh::HalfedgeHandle h, std::uint32_t (&pairs)[2][2]) {
    const auto opposite = mesh.opposite_halfedge_handle(h);
    if (mesh.is_boundary(opposite)) return false;
    const auto oppositeAtV = mesh.prev_halfedge_handle(opposite);
    const auto atU = mesh.prev_halfedge_handle(h);
    if (!sameCorner(h, oppositeAtV) || !sameCorner(atU, opposite)) return false;
    const auto& corner = cornerMesh.halfedgeCorner;
    pairs[0][0] = corner[h.idx()];
    pairs[0][1] = corner[oppositeAtV.idx()];
    pairs[1][0] = corner[atU.idx()];
    pairs[1][1] = corner[opposite.idx()];
    return true;
  };

  // The neighbour across each corner's incoming edge, looked up once (in parallel): the
  // corner of the neighbouring face at the same vertex and the two corners at the edge's far
  // end (this face's, then the neighbour's); kNone when there is no such neighbour.
  constexpr std::uint32_t kNone = ~std::uint32_t(0);
  std::vector<std::array<std::uint32_t, 3>> across(cornerCount, {kNone, kNone, kNone});
  parallelFor(cornerCount, options.threads, [&](std::size_t begin, std::size_t end) {
    std::uint32_t pairs[2][2];
    for (std::size_t corner = begin; corner < end; ++corner) {
      if (neighbourAcross(cornerMesh.cornerHalfedge[corner], pairs)) across[corner] = {pairs[0][1], pairs[1][0], pairs[1][1]};
    }
  });

  // Orientation of each triangle; zero-UV-area ones take the majority of their neighbours',
  // round by round so that face order does not matter, ties going to +1.
  std::vector<std::int8_t> orientation(triangleCount);
  for (std::size_t t = 0; t < triangleCount; ++t) orientation[t] = static_cast<std::int8_t>(triangles[t].orientation);
  std::vector<std::uint32_t> open;
  for (std::size_t t = 0; t < triangleCount; ++t) {
    if (orientation[t] == 0 && !triangles[t].coincident) open.push_back(static_cast<std::uint32_t>(t));
  }
  while (!open.empty()) {
    std::vector<std::pair<std::uint32_t, int>> decided;
    bool anyTie = false;
    for (std::uint32_t t : open) {
      int votes = 0, voters = 0;
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t neighbour = across[3 * t + k][0];
        if (neighbour == kNone) continue;
        const int other = orientation[neighbour / 3];
        votes += other;
        voters += other != 0;
      }
      if (votes != 0) decided.emplace_back(t, votes > 0 ? 1 : -1);
      else anyTie = anyTie || voters > 0;
    }
    if (decided.empty()) {
      if (!anyTie) break;  // the rest touch no oriented triangle: the reference groups them nowhere
      for (std::uint32_t t : open) {
        for (int k = 0; k < 3; ++k) {
          const std::uint32_t neighbour = across[3 * t + k][0];
          if (neighbour != kNone && orientation[neighbour / 3] != 0) decided.emplace_back(t, 1);
        }
      }
    }
    for (auto [t, sign] : decided) orientation[t] = static_cast<std::int8_t>(sign);
    std::erase_if(open, [&](std::uint32_t t) { return orientation[t] != 0; });
  }

  // Groups: corners joined across neighbour edges between triangles of equal orientation.
  UnionFind components(cornerCount);
  for (std::size_t corner = 0; corner < cornerCount; ++corner) {
    const std::size_t t = corner / 3;
    const auto& [neighbour, farHere, farThere] = across[corner];
    if (orientation[t] == 0 || neighbour == kNone || orientation[neighbour / 3] != orientation[t]) continue;
    components.unite(static_cast<std::uint32_t>(corner), neighbour);
    components.unite(farHere, farThere);
  }

  std::vector<Group> groups;
  std::vector<std::uint32_t> cornerGroup(cornerCount);
  std::vector<std::uint32_t> rootGroup(cornerCount, ~0u);
  for (std::size_t corner = 0; corner < cornerCount; ++corner) {
    const std::uint32_t root = components.find(static_cast<std::uint32_t>(corner));
    if (rootGroup[root] == ~0u) {
      Group group;
      group.key = makeGroupKey(cornerMesh, corner, cornerNormals[corner], orientation[corner / 3], root + 1);
      group.normal = cornerNormals[corner];
      group.mayInherit = triangles[corner / 3].coincident;
      rootGroup[root] = static_cast<std::uint32_t>(groups.size());
      groups.push_back(group);
    }
    cornerGroup[corner] = rootGroup[root];
  }

  // The contributing corners, compacted in place (no second per-corner array).
  std::size_t kept = 0;
  for (std::size_t corner = 0; corner < cornerCount; ++corner) {
    if (triangles[corner / 3].orientation == 0) continue;
    cornerContribution[kept] = cornerContribution[corner];
    cornerContribution[kept].group = cornerGroup[corner];
    ++kept;
  }
  cornerContribution.resize(kept);
  sumInValueOrder(cornerContribution, groups);
  parallelFor(groups.size(), options.threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t g = begin; g < end; ++g) {
      Group& group = groups[g];
      if (group.key.orientation == 0 || !orthonormalize(group.tangentSum, group.normal, group.tangent)) continue;
      group.w = group.key.orientation;
      group.defined = true;
    }
  });
  finishCorners(cornerMesh, groups, cornerGroup, options, report, sources);
  return report;
}

}  // namespace tangent::detail
