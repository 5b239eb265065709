// SPDX-License-Identifier: MIT
// Fresh frames by one of the library's generators, as bake computes them (what check's
// `reference` compares with), and `--identify`: which generator the stored tangents are closest to.
#pragma once

#include <vector>

#include "read/primitive.hpp"
#include "tangent/check.hpp"
#include "tangent/tangent.hpp"

namespace tangent::gltf::detail {

// Frames of `frames` (one per corner, glTF's w) by one generator, as bake computes them: what
// `reference` and `--identify` compare the stored tangents with.
void computeFrames(const PrimitiveGeometry& frames, Method method, Weighting weighting, TangentWorkspace& workspace,
                   std::vector<float>& computed, std::vector<FrameSource>& sources);

// check --identify: the stored tangents (`tangents`, per vertex of the buffer; `used` maps the
// part's vertices to them) against each generator the library has, on the same geometry the
// reference uses (frames: the part, or its flat-normal split); into result.generators and
// result.generator.
void identifyGenerator(const PrimitiveGeometry& frames, const PrimitiveGeometry& part, const UsedVertices& used,
                       const std::vector<float>& tangents, TangentWorkspace& workspace, PrimitiveCheck& result);

}  // namespace tangent::gltf::detail
