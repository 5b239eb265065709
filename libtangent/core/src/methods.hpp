// SPDX-License-Identifier: MIT
// The methods on the half-edge mesh (`lengyel`, `flat`); `mikktspace` runs on packed arrays
// (mikktspace/kernel.cpp, workspace.hpp).
#pragma once

#include <span>

#include "tangent/halfedge_mesh.hpp"
#include "workspace.hpp"

namespace tangent::detail {

// Runs on ws's threads: the caller resolves them (threadCount) and enters onThreads(ws).
Report lengyelTangents(const WorkspaceData& ws, CornerMesh& mesh, const Options& options,
                       std::span<FrameSource> sources);  // and flat

}  // namespace tangent::detail
