// SPDX-License-Identifier: MIT
// check's verdict on one primitive, shared with bake: bake keeps an existing TANGENT exactly
// when this finds nothing at default settings, and otherwise says which checks failed.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "asset.hpp"
#include "primitive.hpp"
#include "tangent/check.hpp"

namespace tangent::gltf::detail {

// `primitive` needs tangents (triangles, a UV set and NORMAL present). Throws InputError for
// malformed accessors.
void checkPrimitiveTangents(const Asset& asset, const nlohmann::ordered_json& primitive, const PrimitiveNeeds& needs,
                            const std::string& where, const CheckOptions& options, PrimitiveCheck& result);

// "unit: 3 of 24 vertices; reference: 12 of 36 corners": the findings in one line.
std::string findingsSummary(const PrimitiveCheck& check);

}  // namespace tangent::gltf::detail
