// SPDX-License-Identifier: MIT
// check's verdict on one primitive, shared with bake: bake keeps an existing TANGENT exactly
// when this finds nothing at default settings, and otherwise says which checks failed.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "read/asset.hpp"
#include "read/primitive.hpp"
#include "tangent/check.hpp"
#include "tangent/verdict.hpp"

namespace tangent::gltf::detail {

// A primitive that needs tangents (triangles, a UV set and NORMAL present), as checkPrimitives
// takes it. `primitive` points into the document; nothing may be inserted into it meanwhile.
struct PrimitiveToCheck {
  const nlohmann::ordered_json* primitive = nullptr;
  PrimitiveNeeds needs;
  std::string where;  // "<file>: mesh M 'name' primitive P", for messages
};

// check's verdict on each of `primitives`, in their order (mesh, primitive, meshName and texCoord
// left to the caller). Primitives with the same inputs and TANGENT (sameInputKey) are checked
// once. Those that draw from one vertex buffer with their own indices and share its TANGENT
// (sameVertexKey and the TANGENT accessor: CAD exporters write 1e4-1e5 of them) read the buffer
// and the stored tangents once; each is judged on the vertices it draws, plus those no primitive
// of the buffer draws (the validator requires them valid too), and on its own triangles, so the
// time is linear in the buffer plus the corners. Throws InputError for malformed accessors.
// `verdicts` (null: not kept) gets, per primitive, its corners' verdicts (empty where present or
// format failed).
std::vector<PrimitiveCheck> checkPrimitives(const Asset& asset, const std::vector<PrimitiveToCheck>& primitives,
                                            const CheckOptions& options, std::vector<std::vector<CornerVerdict>>* verdicts = nullptr);

// checkCorners (tangent/verdict.hpp) on an asset already loaded from `input` (the viewer's).
std::vector<PrimitiveVerdicts> checkCorners(const Asset& asset, const std::filesystem::path& input, const CheckOptions& options);

// "unit: 3 of 24 vertices; reference: 12 of 36 corners": the findings in one line.
std::string findingsSummary(const PrimitiveCheck& check);

}  // namespace tangent::gltf::detail
