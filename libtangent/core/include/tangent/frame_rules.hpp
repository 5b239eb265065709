// SPDX-License-Identifier: MIT
// Frame rules that callers outside the core apply too, written once here: the glTF layer,
// the command line, the WebAssembly package and Python call these rather than their own.
#pragma once

#include <span>

namespace tangent {

// The tangent of a vertex no triangle uses, and of a corner with no frame to borrow
// (FrameSource::fixed): the coordinate axis least aligned with the unit normal (ties to the
// lower axis), made orthogonal to it and unit; w = +1. A zero or non-finite normal counts as
// +z. Every output TANGENT must be a valid unit vector (the validator and loaders read every
// element), so a vertex the triangles leave out gets this one.
void unusedVertexTangent(std::span<const float, 3> normal, std::span<float, 4> tangent);

}  // namespace tangent
