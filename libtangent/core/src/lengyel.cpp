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
#include <algorithm>
#include <bit>
#include <cmath>
#include <tuple>
#include <unordered_map>

#include "tangent/halfedge_mesh.hpp"
#include "triangle_tangent.hpp"

namespace tangent {
namespace {

using detail::TriangleKind;
using detail::TriangleTangent;
using detail::Vec2;
using detail::Vec3;

std::uint64_t bitsOf(double value) { return std::bit_cast<std::uint64_t>(value == 0.0 ? 0.0 : value); }

struct GroupKey {
  std::uint32_t weld = 0;
  std::int32_t orientation = 0;
  std::uint64_t face = 0;  // only for `flat`
  std::uint64_t normal[3] = {};
  std::uint64_t uv[2] = {};
  bool operator==(const GroupKey&) const = default;
};

struct GroupKeyHash {
  std::size_t operator()(const GroupKey& key) const noexcept {
    std::uint64_t h = key.weld * 0x9E3779B97F4A7C15ull ^ static_cast<std::uint64_t>(key.orientation + 7) ^ (key.face << 17);
    for (std::uint64_t v : key.normal) h = (h ^ v) * 0x100000001B3ull + (h >> 29);
    for (std::uint64_t v : key.uv) h = (h ^ v) * 0x100000001B3ull + (h >> 29);
    return static_cast<std::size_t>(h);
  }
};

struct Group {
  GroupKey key;
  Vec3 normal{0, 0, 1};
  Vec3 tangentSum{0, 0, 0};
  Vec3 bitangentSum{0, 0, 0};
  Vec3 tangent{0, 0, 0};
  double w = 1;
  bool defined = false;
};

struct Contribution {
  std::uint32_t group;
  Vec3 tangent;
  Vec3 bitangent;
};

bool contributionLess(const Contribution& a, const Contribution& b) {
  return std::tie(a.group, a.tangent[0], a.tangent[1], a.tangent[2], a.bitangent[0], a.bitangent[1], a.bitangent[2]) <
         std::tie(b.group, b.tangent[0], b.tangent[1], b.tangent[2], b.bitangent[0], b.bitangent[1], b.bitangent[2]);
}

// Gram-Schmidt of `sum` against unit `n`; false when nothing of it lies in the tangent plane.
bool orthonormalize(const Vec3& sum, const Vec3& n, Vec3& out) {
  const double sumLength = sum.norm();
  if (!(sumLength > 0) || !std::isfinite(sumLength)) return false;
  Vec3 t = sum - n * (n | sum);
  const double length = t.norm();
  if (!(length > 1e-12 * sumLength)) return false;
  out = t / length;
  return true;
}

// Frame for a corner no usable triangle reached, from already-defined groups: the one whose
// normal is nearest (then the heaviest, then by value) is copied exactly when its normal is the
// same, else projected onto n. One candidate, not a sum: opposite frames of a mirrored seam
// would cancel. This mirrors MikkTSpace, where degenerate corners copy a good neighbour.
bool frameFromCandidates(const std::vector<const Group*>& candidates, const Group& group, Vec3& tangent, double& w) {
  const Group* best = nullptr;
  auto rank = [&](const Group* g) {
    return std::make_tuple(g->normal | group.normal, g->tangentSum.sqrnorm(), g->tangent[0], g->tangent[1], g->tangent[2], g->w);
  };
  for (const Group* candidate : candidates) {
    if (!best || rank(best) < rank(candidate)) best = candidate;
  }
  if (!best) return false;
  if (std::equal(std::begin(best->key.normal), std::end(best->key.normal), std::begin(group.key.normal))) {
    tangent = best->tangent;
  } else if (!orthonormalize(best->tangent, group.normal, tangent)) {
    return false;
  }
  w = best->w;
  return true;
}

}  // namespace

Report computeTangents(CornerMesh& cornerMesh, const Options& options) {
  TriMesh& mesh = cornerMesh.mesh;
  const std::size_t cornerCount = cornerMesh.cornerHalfedge.size();
  const std::size_t triangleCount = cornerCount / 3;
  const bool flat = options.method == Method::flat;

  Report report;
  report.method = std::string(toString(options.method));
  report.weighting = flat ? "" : std::string(toString(options.weighting));
  report.triangles = triangleCount;
  report.corners = cornerCount;
  report.nonManifoldFaces = cornerMesh.nonManifoldFaces;

  std::vector<TriangleTangent> triangles(triangleCount);
  std::vector<Vec3> cornerNormals(cornerCount);
  std::vector<double> cornerWeights(cornerCount, 0.0);
  for (std::size_t t = 0; t < triangleCount; ++t) {
    std::array<Vec3, 3> positions;
    std::array<Vec2, 3> uvs;
    for (int k = 0; k < 3; ++k) {
      const auto halfedge = cornerMesh.cornerHalfedge[3 * t + k];
      positions[k] = mesh.point(mesh.to_vertex_handle(halfedge));
      uvs[k] = mesh.texcoord2D(halfedge);
    }
    const TriangleTangent& triangle = triangles[t] = detail::triangleTangent(positions, uvs);
    switch (triangle.kind) {
      case TriangleKind::usable: break;
      case TriangleKind::degenerate: ++report.degenerateTriangles; break;
      case TriangleKind::zeroUvArea: ++report.zeroUvAreaTriangles; break;
      case TriangleKind::nonFinite: ++report.nonFiniteTriangles; break;
    }
    for (int k = 0; k < 3; ++k) {
      const std::size_t corner = 3 * t + k;
      const Vec3 n = mesh.normal(cornerMesh.cornerHalfedge[corner]);
      const double length = n.norm();
      if (length > 0 && std::isfinite(length)) {
        cornerNormals[corner] = n / length;
      } else {
        ++report.invalidNormals;
        cornerNormals[corner] = triangle.faceNormal.norm() > 0 ? triangle.faceNormal : Vec3(0, 0, 1);
      }
      if (triangle.kind != TriangleKind::usable) continue;
      switch (options.weighting) {
        case Weighting::angle: cornerWeights[corner] = detail::cornerAngle(positions, k); break;
        case Weighting::area: cornerWeights[corner] = triangle.area; break;
        case Weighting::uniform: cornerWeights[corner] = 1.0; break;
      }
    }
  }

  // Group the corners.
  std::unordered_map<GroupKey, std::uint32_t, GroupKeyHash> groupIndex;
  groupIndex.reserve(cornerCount);
  std::vector<Group> groups;
  std::vector<std::uint32_t> cornerGroup(cornerCount);
  for (std::size_t corner = 0; corner < cornerCount; ++corner) {
    const auto halfedge = cornerMesh.cornerHalfedge[corner];
    GroupKey key;
    key.weld = cornerMesh.weldedVertex[mesh.to_vertex_handle(halfedge).idx()];
    key.orientation = triangles[corner / 3].orientation;
    key.face = flat ? corner / 3 + 1 : 0;
    for (int i = 0; i < 3; ++i) key.normal[i] = bitsOf(cornerNormals[corner][i]);
    const Vec2 uv = mesh.texcoord2D(halfedge);
    key.uv[0] = bitsOf(uv[0]);
    key.uv[1] = bitsOf(uv[1]);
    auto [it, inserted] = groupIndex.try_emplace(key, static_cast<std::uint32_t>(groups.size()));
    if (inserted) {
      Group group;
      group.key = key;
      group.normal = cornerNormals[corner];
      groups.push_back(group);
    }
    cornerGroup[corner] = it->second;
  }

  // Accumulate in value order.
  std::vector<Contribution> contributions;
  contributions.reserve(cornerCount);
  for (std::size_t corner = 0; corner < cornerCount; ++corner) {
    const TriangleTangent& triangle = triangles[corner / 3];
    if (triangle.kind != TriangleKind::usable) continue;
    const double weight = flat ? 1.0 : cornerWeights[corner];
    if (!(weight > 0)) continue;
    contributions.push_back({cornerGroup[corner], triangle.tangent * weight, triangle.bitangent * weight});
  }
  std::sort(contributions.begin(), contributions.end(), contributionLess);
  for (const Contribution& c : contributions) {
    groups[c.group].tangentSum += c.tangent;
    groups[c.group].bitangentSum += c.bitangent;
  }

  for (Group& group : groups) {
    if (!orthonormalize(group.tangentSum, group.normal, group.tangent)) continue;
    const double handedness = (group.normal % group.tangent) | group.bitangentSum;
    group.w = handedness > 0 ? 1.0 : handedness < 0 ? -1.0 : (group.key.orientation < 0 ? -1.0 : 1.0);
    group.defined = true;
  }

  // Corners no usable triangle reached: borrow from the vertex, then from its 1-ring.
  std::vector<std::vector<std::uint32_t>> definedAtWeld(mesh.n_vertices());
  for (std::uint32_t g = 0; g < groups.size(); ++g) {
    if (groups[g].defined) definedAtWeld[groups[g].key.weld].push_back(g);
  }
  std::vector<std::uint64_t> groupCornerCount(groups.size(), 0);
  for (std::uint32_t g : cornerGroup) ++groupCornerCount[g];
  std::vector<const Group*> candidates;
  for (std::uint32_t g = 0; g < groups.size(); ++g) {
    Group& group = groups[g];
    if (group.defined) continue;
    bool found = false;
    // Same normal and UV first (a degenerate corner of a smooth vertex), then any.
    for (int pass = 0; pass < 2 && !found; ++pass) {
      candidates.clear();
      for (std::uint32_t other : definedAtWeld[group.key.weld]) {
        const GroupKey& k = groups[other].key;
        const bool sameAttributes = std::equal(std::begin(k.normal), std::end(k.normal), std::begin(group.key.normal)) &&
                                    std::equal(std::begin(k.uv), std::end(k.uv), std::begin(group.key.uv));
        if (pass == 1 || sameAttributes) candidates.push_back(&groups[other]);
      }
      found = frameFromCandidates(candidates, group, group.tangent, group.w);
    }
    if (!found) {
      candidates.clear();
      const OpenMesh::VertexHandle vertex(static_cast<int>(group.key.weld));
      for (auto neighbour : mesh.vv_range(vertex)) {
        for (std::uint32_t other : definedAtWeld[cornerMesh.weldedVertex[neighbour.idx()]]) candidates.push_back(&groups[other]);
      }
      found = frameFromCandidates(candidates, group, group.tangent, group.w);
    }
    if (found) {
      report.fallbackFromNeighbours += groupCornerCount[g];
    } else {
      group.tangent = detail::fixedPerpendicular(group.normal);
      group.w = group.key.orientation < 0 ? -1.0 : 1.0;
      report.fallbackFixed += groupCornerCount[g];
    }
  }

  const double wSign = options.uvOrigin == UvOrigin::topLeft ? -1.0 : 1.0;
  for (std::size_t corner = 0; corner < cornerCount; ++corner) {
    const Group& group = groups[cornerGroup[corner]];
    const double w = group.w * wSign;
    if (w < 0) ++report.mirroredCorners;
    mesh.property(cornerMesh.tangent, cornerMesh.cornerHalfedge[corner]) =
        TangentVec(group.tangent[0], group.tangent[1], group.tangent[2], w);
  }
  return report;
}

}  // namespace tangent
