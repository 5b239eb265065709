// SPDX-License-Identifier: MIT
// Methods `lengyel` and `meshopt`: groups read off the weld's buckets instead of sorting every
// corner's key. A bucket holds the corners of one (position, normal, UV) value in corner order;
// lengyel's group is one position, unit normal, UV and UV orientation. Where every corner's
// normal is valid and no two buckets of one position and UV have normals with the same unit
// bits (normals that differ as floats, such as n and 2n), a group is the corners of one bucket
// with one orientation: its terms, its first corner and so its frame are the full grouping's.
// Elsewhere the caller runs the full grouping.
#include <algorithm>
#include <compare>

#include "lengyel.hpp"

namespace tangent::detail {
namespace {

// The key of a bucket's lengyel group but for the orientation: its position, its UV and its
// unit normal, as canonical bits (+0 and -0 alike); ordered to find equal ones.
struct GroupValue {
  std::uint32_t position = 0;  // the position's representative
  std::uint32_t uv[2] = {};
  std::uint64_t normal[3] = {};
  auto operator<=>(const GroupValue&) const = default;
};

GroupValue groupValueOf(const MeshArrays& mesh, std::span<const std::uint32_t> weldOf, std::uint32_t vertex) {
  GroupValue value;
  value.position = weldOf[vertex];
  value.uv[0] = canonicalBits(mesh.uvs[2 * vertex]);
  value.uv[1] = canonicalBits(mesh.uvs[2 * vertex + 1]);
  const Vec3 stored(mesh.normals[3 * vertex], mesh.normals[3 * vertex + 1], mesh.normals[3 * vertex + 2]);
  const Vec3 unit = stored / stored.norm();  // cornerNormal's operations for a valid normal
  for (int i = 0; i < 3; ++i) value.normal[i] = bitsOf(unit[i]);
  return value;
}

// Whether no two buckets share a GroupValue. Only buckets of a position with more than one
// can (a seam, a crease): counted per position (ws.positionTable, free once the position weld
// is done), and the GroupValues of those few sorted.
bool bucketsHaveDistinctGroupValues(WorkspaceData& ws, const MeshArrays& mesh, std::span<const std::uint32_t> weldOf) {
  ensureSize(ws.positionTable, ws.vertexCount);
  std::uint32_t* bucketsAt = ws.positionTable.data();
  std::fill(bucketsAt, bucketsAt + ws.vertexCount, 0u);
  auto used = [&](std::size_t id) { return ws.bucketStart[id] != ws.bucketStart[id + 1]; };
  for (std::size_t id = 0; id < ws.vertexCount; ++id) {
    if (used(id)) ++bucketsAt[weldOf[id]];
  }
  std::vector<GroupValue> shared;
  for (std::size_t id = 0; id < ws.vertexCount; ++id) {
    // A welded id is its bucket's smallest vertex: its values are the bucket's.
    if (used(id) && bucketsAt[weldOf[id]] > 1) shared.push_back(groupValueOf(mesh, weldOf, static_cast<std::uint32_t>(id)));
  }
  std::sort(shared.begin(), shared.end());
  return std::adjacent_find(shared.begin(), shared.end()) == shared.end();
}

// The key's orientation of a corner: its triangle's where usable, else 0.
int orientationOf(const TriangleData& data, std::uint32_t corner) {
  const TriangleTerms& triangle = data.triangles[corner / 3];
  return triangle.kind == TriangleKind::usable ? triangle.orientation : 0;
}

// The groups of one bucket, one per orientation present: each summed (sumTerms) with its
// first corner's normal, its frame written to its corners, or its corners marked kUndefined.
void frameBucket(WorkspaceData& ws, const TriangleData& data, Method method, std::span<const std::uint32_t> corners,
                 std::vector<Contribution>& terms, float* tangents) {
  unsigned present = 0;  // bit o + 1: a corner of orientation o (most buckets have one)
  for (const std::uint32_t c : corners) present |= 1u << (orientationOf(data, c) + 1);
  const bool one = (present & (present - 1)) == 0;
  for (const int orientation : {-1, 0, 1}) {
    if (!(present & 1u << (orientation + 1))) continue;
    terms.clear();
    std::uint32_t first = kNone;
    for (const std::uint32_t c : corners) {
      if (!one && orientationOf(data, c) != orientation) continue;
      if (first == kNone) first = c;
      addTerm(data, c, method, terms);
    }
    Vec3 tangentSum(0, 0, 0), tangent;
    double w = 1;
    const bool framed = sumTerms(terms, data.cornerNormal(first), orientation, method, tangentSum, tangent, w);
    for (const std::uint32_t c : corners) {
      if (!one && orientationOf(data, c) != orientation) continue;
      if (framed) writeCornerFrame(tangents, c, tangent, w);
      ws.cornerState[c] = framed ? 0 : kUndefined;  // no invalid normals on this path
      ws.cornerLink[c] = kNone;
    }
  }
}

}  // namespace

bool bucketFrames(WorkspaceData& ws, const MeshArrays& mesh, std::span<const std::uint32_t> weldOf,
                  const TriangleData& data, Method method, const CornerOutputs& outputs) {
  if (std::find(data.invalidNormal.begin(), data.invalidNormal.end(), 1) != data.invalidNormal.end()) return false;
  if (!bucketsHaveDistinctGroupValues(ws, mesh, weldOf)) return false;
  ensureSize(ws.cornerState, ws.cornerCount);
  ensureSize(ws.cornerLink, ws.cornerCount);
  float* tangents = outputs.tangents.data();
  forRange(ws, ws.vertexCount, 1 << 12, [&](std::size_t begin, std::size_t end) {
    std::vector<Contribution> terms;
    for (std::size_t id = begin; id < end; ++id) {
      const std::uint32_t* first = ws.bucketCorners.data() + ws.bucketStart[id];
      frameBucket(ws, data, method, {first, ws.bucketStart[id + 1] - ws.bucketStart[id]}, terms, tangents);
    }
  });
  frameUndefinedCorners(ws, mesh, weldOf, data, Grouping::byValue, method, outputs);
  return true;
}

}  // namespace tangent::detail
