// SPDX-License-Identifier: MIT
// The reference MikkTSpace in C (../shared/peers/mikktspace, compiled by the test build only)
// called on plain arrays, with the triangles handed over in any order and with their corners
// rotated, the results mapped back to the original corners.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "tangent/tangent.hpp"

namespace tangent::testing {

// One reference result per corner: the tangent and fSign as setTSpaceBasic gives them
// (fSign in MikkTSpace's bottom-left convention: glTF's w is -fSign).
struct ReferenceFrame {
  float tangent[3] = {0, 0, 0};
  float sign = 0;
  bool written = false;  // setTSpaceBasic was called for this corner
  // setTSpace gave exactly the space the reference starts every corner with (tangent (1,0,0),
  // bitangent (0,1,0), both magnitudes 1, not orientation preserving): likely no group reached
  // it (a computed space can be the same; see applyReferenceRule).
  bool initialSpace = false;
};

// How the triangles are handed to the reference: face f of the call is original triangle
// triangleOrder[f], and its corner k is the triangle's corner (k + cornerRotation[f]) % 3.
// Both empty: the original order, unrotated.
struct FaceOrder {
  std::vector<std::uint32_t> triangleOrder;
  std::vector<std::uint8_t> cornerRotation;
};

// Runs genTangSpaceDefault; the result is indexed by original corner (3 per triangle).
// Returns an empty vector when the reference reports failure.
std::vector<ReferenceFrame> referenceCornerFrames(const MeshArrays& mesh, const FaceOrder& order = {});

}  // namespace tangent::testing
