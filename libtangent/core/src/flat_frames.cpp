// SPDX-License-Identifier: MIT
// Method `flat`'s frames without grouping every corner. A usable triangle's three corners are
// at three positions (a triangle with two at one position is not usable), so each is a group
// of its own: its frame is its triangle's terms summed as every group's are (sumTerms with one
// term, flatTriangleFrames in lengyel.hpp, which the triangle pass calls). Only the corners left
// without a frame need groups (frameUndefinedCorners, here), so every bit is the one the full
// grouping gives.
#include "lengyel.hpp"

#include <algorithm>

namespace tangent::detail {

void flatFrames(WorkspaceData& ws, const MeshArrays& mesh, std::span<const std::uint32_t> weldOf,
                const TriangleData& data, const CornerOutputs& outputs) {
  ensureSize(ws.cornerLink, ws.cornerCount);
  forRange(ws, ws.cornerCount, 1 << 16, [&](std::size_t begin, std::size_t end) {
    std::fill(ws.cornerLink.data() + begin, ws.cornerLink.data() + end, kNone);
  });
  frameUndefinedCorners(ws, mesh, weldOf, data, Grouping::perFace, Method::flat, outputs);
}

}  // namespace tangent::detail
