// The methods, each in its own file; computeTangents() dispatches.
#pragma once

#include <span>

#include "tangent/halfedge_mesh.hpp"

namespace tangent::detail {

Report lengyelTangents(CornerMesh& mesh, const Options& options, std::span<FrameSource> sources);  // and flat
Report mikktspaceTangents(CornerMesh& mesh, const Options& options, std::span<FrameSource> sources);

}  // namespace tangent::detail
