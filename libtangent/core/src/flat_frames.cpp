// SPDX-License-Identifier: MIT
// Method `flat`'s frames without grouping every corner. A usable triangle's three corners are
// at three positions (a triangle with two at one position is not usable), so each is a group
// of its own: its frame is its triangle's terms made orthogonal to its normal, the operations
// sumAndOrthonormalize applies to a group of one corner. Only the corners left without a frame
// need groups, and only those of the positions the fallbacks read (theirs and their
// neighbours'): grouped, summed and filled in by lengyel's phases, so every bit is the one the
// full grouping gives.
#include "gram_schmidt.hpp"
#include "lengyel.hpp"

namespace tangent::detail {
namespace {

// A one-corner group's frame as sumAndOrthonormalize computes it for `flat` (weight 1, sums
// from zero, w from the bitangent's side); false where the group would be left undefined.
bool oneCornerFrame(const TriangleTangent& triangle, const Vec3& normal, Vec3& tangent, double& w) {
  if (triangle.kind != TriangleKind::usable) return false;
  Vec3 tangentSum(0, 0, 0), bitangentSum(0, 0, 0);
  tangentSum += triangle.tangent * 1.0;
  bitangentSum += triangle.bitangent * 1.0;
  if (!orthonormalize(tangentSum.data(), normal.data(), tangent.data())) return false;
  const double side = (normal % tangent) | bitangentSum;
  const double uvSide = triangle.orientation < 0 ? -1.0 : 1.0;
  w = side > 0 ? 1.0 : side < 0 ? -1.0 : uvSide;
  return true;
}

void writeFrame(float* tangents, std::size_t corner, const Vec3& tangent, double w) {
  for (int i = 0; i < 3; ++i) tangents[4 * corner + i] = static_cast<float>(tangent[i]);
  tangents[4 * corner + 3] = static_cast<float>(w);
}

// Every corner of the positions the fallbacks of `undefined` read: each one's own position
// and those that share a triangle with it (a superset of the 1-ring fillUndefinedGroups
// gathers; a position more adds groups no answer reads).
std::vector<std::uint32_t> cornersNearUndefined(const WorkspaceData& ws, const MeshArrays& mesh,
                                                std::span<const std::uint32_t> weldOf,
                                                const std::vector<std::uint32_t>& undefined) {
  enum : std::uint8_t { kFar = 0, kUndefinedHere = 1, kNeighbour = 2 };
  std::vector<std::uint8_t> near(ws.vertexCount, kFar);
  for (const std::uint32_t c : undefined) near[weldOf[mesh.indices[c]]] = kUndefinedHere;
  for (std::size_t t = 0; 3 * t < ws.cornerCount; ++t) {
    const std::uint32_t welds[3] = {weldOf[mesh.indices[3 * t]], weldOf[mesh.indices[3 * t + 1]],
                                    weldOf[mesh.indices[3 * t + 2]]};
    if (near[welds[0]] != kUndefinedHere && near[welds[1]] != kUndefinedHere && near[welds[2]] != kUndefinedHere) continue;
    for (const std::uint32_t weld : welds) {
      if (near[weld] == kFar) near[weld] = kNeighbour;
    }
  }
  return collectIf(ws, ws.cornerCount, [&](std::size_t c) { return near[weldOf[mesh.indices[c]]] != kFar; });
}

}  // namespace

void flatFrames(WorkspaceData& ws, const MeshArrays& mesh, std::span<const std::uint32_t> weldOf,
                const TriangleData& data, const CornerOutputs& outputs) {
  ensureSize(ws.cornerState, ws.cornerCount);
  ensureSize(ws.cornerLink, ws.cornerCount);
  float* tangents = outputs.tangents.data();
  forRange(ws, ws.cornerCount, 1 << 14, [&](std::size_t begin, std::size_t end) {
    for (std::size_t c = begin; c < end; ++c) {
      Vec3 tangent;
      double w = 1;
      const bool framed = oneCornerFrame(data.triangles[c / 3], data.cornerNormals[c], tangent, w);
      if (framed) writeFrame(tangents, c, tangent, w);
      ws.cornerState[c] = static_cast<std::uint8_t>((framed ? 0 : kUndefined) | (data.invalidNormal[c] ? kInvalidNormal : 0));
      ws.cornerLink[c] = kNone;
    }
  });
  const std::vector<std::uint32_t> undefined =
      collectFlagged(ws, ws.cornerState.data(), kUndefined, ws.cornerCount, [&](std::size_t c) { return (ws.cornerState[c] & kUndefined) != 0; });
  if (undefined.empty()) return;
  const std::vector<std::uint32_t> near = cornersNearUndefined(ws, mesh, weldOf, undefined);
  CornerGroups cornerGroups = groupCornersAt(ws, mesh, weldOf, data, Grouping::perFace, near);
  sumAndOrthonormalize(ws, data, cornerGroups, Method::flat);
  fillUndefinedGroups(mesh, weldOf, cornerGroups);
  // The groups still not `defined` are the fallbacks' (the frames of the others were written).
  for (std::size_t g = 0; g < cornerGroups.groups.size(); ++g) {
    const Group& group = cornerGroups.groups[g];
    if (group.defined) continue;
    for (std::uint32_t i = cornerGroups.groupStart[g]; i < cornerGroups.groupStart[g + 1]; ++i) {
      const std::uint32_t c = cornerGroups.sortedCorners[i];
      writeFrame(tangents, c, group.tangent, group.w);
      ws.cornerState[c] = static_cast<std::uint8_t>(static_cast<std::uint8_t>(group.source) | (ws.cornerState[c] & kInvalidNormal));
    }
  }
}

}  // namespace tangent::detail
