// SPDX-License-Identifier: MIT
// Method `flat`'s frames without grouping every corner. A usable triangle's three corners are
// at three positions (a triangle with two at one position is not usable), so each is a group
// of its own: its frame is its triangle's terms summed as every group's are (sumTerms). Only
// the corners left without a frame need groups (frameUndefinedCorners), so every bit is the
// one the full grouping gives.
#include "lengyel.hpp"

namespace tangent::detail {

void flatFrames(WorkspaceData& ws, const MeshArrays& mesh, std::span<const std::uint32_t> weldOf,
                const TriangleData& data, const CornerOutputs& outputs) {
  ensureSize(ws.cornerState, ws.cornerCount);
  ensureSize(ws.cornerLink, ws.cornerCount);
  float* tangents = outputs.tangents.data();
  forRange(ws, ws.cornerCount, 1 << 14, [&](std::size_t begin, std::size_t end) {
    for (std::size_t c = begin; c < end; ++c) {
      Contribution term;
      const std::size_t termCount = termOf(data, static_cast<std::uint32_t>(c), Method::flat, term) ? 1 : 0;
      Vec3 tangentSum(0, 0, 0), tangent;
      double w = 1;
      const bool framed = sumTerms({&term, termCount}, data.cornerNormals[c], data.triangles[c / 3].orientation, Method::flat, tangentSum, tangent, w);
      if (framed) writeCornerFrame(tangents, c, tangent, w);
      ws.cornerState[c] = static_cast<std::uint8_t>((framed ? 0 : kUndefined) | (data.invalidNormal[c] ? kInvalidNormal : 0));
      ws.cornerLink[c] = kNone;
    }
  });
  frameUndefinedCorners(ws, mesh, weldOf, data, Grouping::perFace, Method::flat, outputs);
}

}  // namespace tangent::detail
