// SPDX-License-Identifier: MIT
// The methods on the half-edge mesh (`lengyel`, `flat`); `mikktspace` runs on packed arrays
// (mikktspace.cpp, workspace.hpp).
#pragma once

#include <span>

#include "tangent/halfedge_mesh.hpp"

namespace tangent::detail {

Report lengyelTangents(CornerMesh& mesh, const Options& options, std::span<FrameSource> sources);  // and flat

}  // namespace tangent::detail
