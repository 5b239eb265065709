// SPDX-License-Identifier: MIT
// bake's plan phase: which primitives get tangents and why, which keep the TANGENT they have,
// and which bake together (the same inputs; one vertex buffer with different indices).
#include <string>
#include <unordered_map>

#include "bake/primitive_baker.hpp"
#include "check/check_primitive.hpp"

namespace tangent::gltf::detail {
namespace {
using Json = nlohmann::ordered_json;
}  // namespace

// Every primitive planned, in mesh and primitive order; existing tangents judged.
std::vector<PrimitivePlan> PrimitiveBaker::planAll() {
  std::vector<PrimitivePlan> plans;
  const Json& doc = output_.json();
  const std::size_t meshCount = doc.contains("meshes") ? doc["meshes"].size() : 0;
  for (std::size_t m = 0; m < meshCount; ++m) {
    if (!output_.json()["meshes"][m].contains("primitives")) continue;
    const std::size_t primitiveCount = output_.json()["meshes"][m]["primitives"].size();
    for (std::size_t p = 0; p < primitiveCount; ++p) plans.push_back(planPrimitive(static_cast<int>(m), static_cast<int>(p)));
  }
  decideExisting(plans);
  return plans;
}

// Eligibility (a triangle primitive that needs tangents and has what they are computed from)
// and validity (an existing TANGENT that tangent check passes is kept).
PrimitivePlan PrimitiveBaker::planPrimitive(int meshIndex, int primitiveIndex) {
  const Json& doc = output_.json();
  PrimitivePlan plan;
  plan.mesh = meshIndex;
  plan.primitive = primitiveIndex;
  const Json& primitive = primitiveJson(plan);
  plan.where = asset_.path.string() + ": " + primitiveLabel(doc, meshIndex, primitiveIndex);
  PrimitiveResult& result = plan.result;
  result.mesh = meshIndex;
  result.primitive = primitiveIndex;
  if (doc["meshes"][meshIndex].contains("name")) result.meshName = doc["meshes"][meshIndex]["name"].get<std::string>();
  result.action = PrimitiveAction::skipped;

  const PrimitiveNeeds& needs = plan.needs = primitiveNeeds(doc, primitive, options_.all || asset_.fromMeshFile);
  plan.why = bakeReason(needs, asset_.fromMeshFile);
  result.reason = plan.why;
  if (!bakesTangents(needs)) return plan;
  result.texCoord = needs.texCoord;
  if (!primitive.contains("attributes") || !primitive["attributes"].is_object())
    throw InputError(plan.where + ": has no attributes object");
  const Json& attributes = primitive["attributes"];
  const std::string uvName = "TEXCOORD_" + std::to_string(needs.texCoord);
  if (const std::string problem = missingPosition(primitive, needs); !problem.empty())
    throw InputError(plan.where + ": " + problem);
  if (accessorOf(attributes, "NORMAL") < 0) {
    if (options_.normals == NormalsMode::keep) {
      result.reason = "no NORMAL attribute; tangents need normals, primitive left as it is (--normals keep)";
      return plan;
    }
    plan.generatesNormals = true;
  }
  if (accessorOf(attributes, uvName) < 0) {
    // The material names a UV set the primitive lacks: a broken reference, refused (as check
    // and info do). Without a normal texture (--all) there is simply nothing to bake from.
    if (const std::string problem = missingUvSet(primitive, needs); !problem.empty())
      throw InputError(plan.where + ": " + problem);
    result.reason = needs.why + ", but the primitive has no " + uvName + "; left as it is";
    return plan;
  }
  // An existing TANGENT is judged by decideExisting, once every primitive is planned; one
  // without NORMAL is recomputed with the NORMAL bake writes.
  plan.hasTangent = accessorOf(attributes, "TANGENT") >= 0 && !plan.generatesNormals;
  plan.bake = !plan.hasTangent;
  if (plan.generatesNormals) {
    plan.why += std::string("; no NORMAL: ") + toString(options_.normals) + " normals generated and written";
    plan.replacesTangent = accessorOf(attributes, "TANGENT") >= 0;
    if (plan.replacesTangent) result.reason = plan.why + "; the existing TANGENT recomputed from them";
  }
  return plan;
}

// Keep exactly what `tangent check` passes at its default settings: the same function decides.
void PrimitiveBaker::decideExisting(std::vector<PrimitivePlan>& plans) {
  std::vector<PrimitiveToCheck> toCheck;
  std::vector<std::size_t> planOf;
  for (std::size_t i = 0; i < plans.size(); ++i) {
    if (!plans[i].hasTangent) continue;
    toCheck.push_back({&primitiveJson(plans[i]), plans[i].needs, plans[i].where});
    planOf.push_back(i);
  }
  if (toCheck.empty()) return;
  const std::vector<PrimitiveCheck> verdicts = checkPrimitives(asset_, toCheck, CheckOptions{});
  for (std::size_t k = 0; k < planOf.size(); ++k) {
    PrimitivePlan& plan = plans[planOf[k]];
    PrimitiveResult& result = plan.result;
    const PrimitiveCheck& verdict = verdicts[k];
    if (verdict.findings.empty() && !options_.overwrite) {
      result.action = PrimitiveAction::kept;
      result.reason = "valid TANGENT present: tangent check passes it (use --overwrite to recompute)";
      continue;
    }
    for (const CheckFinding& finding : verdict.findings) result.failedChecks.push_back(finding.check);
    result.reason = verdict.findings.empty() ? "TANGENT recomputed (--overwrite)"
                                             : "existing TANGENT fails tangent check (" + findingsSummary(verdict) + "); recomputed";
    plan.replacesTangent = true;
    plan.bake = true;
  }
}

// The baked plans by input key, and the input keys by the vertex buffer they share: one group
// per vertex key, its first plan of each input key in document order.
PlanGroups PrimitiveBaker::groupPlans(const std::vector<PrimitivePlan>& plans) {
  PlanGroups grouped;
  grouped.inputKeys.resize(plans.size());
  grouped.groupOfPlan.assign(plans.size(), 0);
  std::unordered_map<std::string, std::size_t> groupOfVertexKey;
  std::unordered_map<std::string, std::size_t> firstOfInputKey;
  for (std::size_t i = 0; i < plans.size(); ++i) {
    if (!plans[i].bake) continue;
    const Json& primitive = primitiveJson(plans[i]);
    std::string& inputKey = grouped.inputKeys[i];
    inputKey = sameInputKey(output_.json(), primitive, plans[i].needs);
    // A primitive whose normals are generated is baked alone (its vertices are split by them).
    const std::string vertexKey = plans[i].generatesNormals ? "generated normals " + std::to_string(i)
                                                             : sameVertexKey(output_.json(), primitive, plans[i].needs);
    if (plans[i].generatesNormals) inputKey += " normals " + std::string(toString(options_.normals));
    const auto group = groupOfVertexKey.emplace(vertexKey, grouped.groups.size());
    if (group.second) grouped.groups.emplace_back();
    grouped.groupOfPlan[i] = group.first->second;
    if (firstOfInputKey.emplace(inputKey, i).second) grouped.groups[grouped.groupOfPlan[i]].firstOfInput.push_back(i);
  }
  return grouped;
}

}  // namespace tangent::gltf::detail
