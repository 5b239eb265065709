// SPDX-License-Identifier: MIT
#include "corner_groups.hpp"

#include "gram_schmidt.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <tuple>

namespace tangent::detail {

std::uint64_t bitsOf(double value) { return std::bit_cast<std::uint64_t>(value == 0.0 ? 0.0 : value); }

bool GroupKey::sameAttributes(const GroupKey& other) const {
  return std::equal(std::begin(normal), std::end(normal), std::begin(other.normal)) &&
         std::equal(std::begin(uv), std::end(uv), std::begin(other.uv));
}

std::size_t GroupKeyHash::operator()(const GroupKey& key) const noexcept {
  std::uint64_t h = key.weld * 0x9E3779B97F4A7C15ull ^ static_cast<std::uint64_t>(key.orientation + 7) ^ (key.tag << 17);
  for (std::uint64_t v : key.normal) h = (h ^ v) * 0x100000001B3ull + (h >> 29);
  for (std::uint64_t v : key.uv) h = (h ^ v) * 0x100000001B3ull + (h >> 29);
  return static_cast<std::size_t>(h);
}

GroupKey makeGroupKey(const CornerMesh& cornerMesh, std::size_t corner, const Vec3& normal, int orientation, std::uint64_t tag) {
  const auto halfedge = cornerMesh.cornerHalfedge[corner];
  GroupKey key;
  key.weld = cornerMesh.weldedVertex[cornerMesh.mesh.to_vertex_handle(halfedge).idx()];
  key.orientation = orientation;
  key.tag = tag;
  for (int i = 0; i < 3; ++i) key.normal[i] = bitsOf(normal[i]);
  const Vec2 uv = cornerMesh.mesh.texcoord2D(halfedge);
  key.uv[0] = bitsOf(uv[0]);
  key.uv[1] = bitsOf(uv[1]);
  return key;
}

void sumInValueOrder(std::vector<Contribution>& contributions, std::vector<Group>& groups) {
  // Bucket by group (counting sort), then order each group's few terms by value.
  std::vector<std::uint32_t> start(groups.size() + 1, 0);
  for (const Contribution& c : contributions) ++start[c.group + 1];
  for (std::size_t g = 0; g < groups.size(); ++g) start[g + 1] += start[g];
  std::vector<std::uint32_t> order(contributions.size());
  {
    std::vector<std::uint32_t> next(start.begin(), start.end() - 1);
    for (std::uint32_t i = 0; i < contributions.size(); ++i) order[next[contributions[i].group]++] = i;
  }
  auto less = [&](std::uint32_t x, std::uint32_t y) {
    const Contribution& a = contributions[x];
    const Contribution& b = contributions[y];
    return std::tie(a.tangent[0], a.tangent[1], a.tangent[2], a.bitangent[0], a.bitangent[1], a.bitangent[2]) <
           std::tie(b.tangent[0], b.tangent[1], b.tangent[2], b.bitangent[0], b.bitangent[1], b.bitangent[2]);
  };
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const auto begin = order.begin() + start[g], end = order.begin() + start[g + 1];
    if (end - begin > 1) std::sort(begin, end, less);
    for (auto it = begin; it != end; ++it) {
      groups[g].tangentSum += contributions[*it].tangent;
      groups[g].bitangentSum += contributions[*it].bitangent;
    }
  }
}

bool orthonormalize(const Vec3& sum, const Vec3& n, Vec3& out) {
  return orthonormalize(sum.data(), n.data(), out.data());  // gram_schmidt.hpp
}

void triangleCorners(const CornerMesh& cornerMesh, std::size_t t, std::array<Vec3, 3>& positions, std::array<Vec2, 3>& uvs) {
  const TriMesh& mesh = cornerMesh.mesh;
  for (int k = 0; k < 3; ++k) {
    const auto halfedge = cornerMesh.cornerHalfedge[3 * t + k];
    positions[k] = mesh.point(mesh.to_vertex_handle(halfedge));
    uvs[k] = mesh.texcoord2D(halfedge);
  }
}

Vec3 cornerNormal(const Vec3& stored, const TriangleTangent& triangle, bool& invalid) {
  const double length = stored.norm();
  invalid = !(length > 0 && std::isfinite(length));
  if (!invalid) return stored / length;
  return triangle.faceNormal.norm() > 0 ? triangle.faceNormal : Vec3(0, 0, 1);
}

namespace {

// One candidate, not a sum: opposite frames of a mirrored seam would cancel. The one whose
// normal is nearest wins (then the heaviest, then by value); it is copied exactly when its
// normal is the same, else projected onto ours.
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

void finishCorners(CornerMesh& cornerMesh, std::vector<Group>& groups, const std::vector<std::uint32_t>& cornerGroup,
                   const Options& options, Report& report, std::span<FrameSource> sources) {
  TriMesh& mesh = cornerMesh.mesh;
  // Defined groups per welded vertex, only needed when some group has no frame of its own.
  const bool anyUndefined = std::any_of(groups.begin(), groups.end(), [](const Group& g) { return !g.defined; });
  std::vector<std::vector<std::uint32_t>> definedAtWeld(anyUndefined ? mesh.n_vertices() : 0);
  for (std::uint32_t g = 0; anyUndefined && g < groups.size(); ++g) {
    if (groups[g].defined) definedAtWeld[groups[g].key.weld].push_back(g);
  }
  std::vector<FrameSource> groupSource(groups.size(), FrameSource::computed);
  std::vector<const Group*> candidates;
  for (std::uint32_t g = 0; g < groups.size(); ++g) {
    Group& group = groups[g];
    if (group.defined) continue;
    bool found = false;
    // Same normal and UV first (a degenerate corner of a smooth vertex), then any.
    for (int pass = 0; pass < 2 && !found; ++pass) {
      candidates.clear();
      for (std::uint32_t other : definedAtWeld[group.key.weld]) {
        if (pass == 1 || groups[other].key.sameAttributes(group.key)) candidates.push_back(&groups[other]);
      }
      found = frameFromCandidates(candidates, group, group.tangent, group.w);
      if (found) groupSource[g] = pass == 0 && group.mayInherit ? FrameSource::inherited : FrameSource::neighbour;
    }
    if (!found) {
      candidates.clear();
      const OpenMesh::VertexHandle vertex(static_cast<int>(group.key.weld));
      for (auto neighbour : mesh.vv_range(vertex)) {
        for (std::uint32_t other : definedAtWeld[cornerMesh.weldedVertex[neighbour.idx()]]) candidates.push_back(&groups[other]);
      }
      found = frameFromCandidates(candidates, group, group.tangent, group.w);
      if (found) groupSource[g] = FrameSource::neighbour;
    }
    if (!found) {
      group.tangent = fixedPerpendicular(group.normal);
      group.w = group.key.orientation < 0 ? -1.0 : 1.0;
      groupSource[g] = FrameSource::fixed;
    }
  }

  const double wSign = handedness(1.0, options.uvOrigin);
  for (std::size_t corner = 0; corner < cornerGroup.size(); ++corner) {
    const Group& group = groups[cornerGroup[corner]];
    const double w = group.w * wSign;
    if (w < 0) ++report.mirroredCorners;
    switch (groupSource[cornerGroup[corner]]) {
      case FrameSource::computed: break;
      case FrameSource::inherited: ++report.inheritedCorners; break;
      case FrameSource::neighbour: ++report.fallbackFromNeighbours; break;
      case FrameSource::fixed: ++report.fallbackFixed; break;
    }
    if (!sources.empty()) sources[corner] = groupSource[cornerGroup[corner]];
    mesh.property(cornerMesh.tangent, cornerMesh.cornerHalfedge[corner]) =
        TangentVec(group.tangent[0], group.tangent[1], group.tangent[2], w);
  }
}

}  // namespace tangent::detail
