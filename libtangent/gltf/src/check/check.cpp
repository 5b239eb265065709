// SPDX-License-Identifier: MIT
// `tangent check`: are the stored tangents present, well formed, orthogonal, of the right
// handedness for the normal texture's UV set, and close to freshly computed ones? This file
// finds the primitives to check, groups those that share a vertex buffer, and runs the gates
// (present, format) and the per-vertex checks; the phases on a primitive's triangles are in
// drawn_part.cpp.
#include "tangent/check.hpp"

#include <algorithm>
#include <cmath>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <unordered_map>

#include "read/accessors.hpp"
#include "read/asset.hpp"
#include "read/primitive.hpp"
#include "check/check_phases.hpp"
#include "check/check_primitive.hpp"
#include "check/generators.hpp"
#include "entry_point.hpp"
#include "check/tangent_rules.hpp"
#include "read/validate.hpp"
#include "tangent/gltf.hpp"
#include "tangent/text.hpp"
#include "tangent/verdict.hpp"

namespace tangent::gltf {
namespace {

using namespace detail;

using Json = nlohmann::ordered_json;

// The vertices each member of a vertex group draws (in member order), and those none draws.
struct GroupParts {
  std::vector<UsedVertices> drawn;     // per member
  std::vector<std::uint32_t> undrawn;  // ascending
};

// Each member's corners read and its vertices found; its result counts the vertices it draws
// plus the undrawn ones, and its triangles.
GroupParts drawnParts(const Asset& asset, const std::vector<PrimitiveToCheck>& primitives, const std::vector<std::size_t>& members,
                      std::size_t vertexCount, std::vector<PrimitiveCheck>& results) {
  GroupParts parts;
  parts.drawn.reserve(members.size());
  std::vector<std::uint32_t> slotOf(vertexCount, kNoSlot);
  std::vector<char> drawnByAny(vertexCount, 0);
  for (const std::size_t member : members) {
    PrimitiveGeometry drawn;
    drawn.vertexCount = vertexCount;
    readCorners(asset, *primitives[member].primitive, primitives[member].where, drawn);
    parts.drawn.push_back(usedVertices(drawn.corners, slotOf));
    for (const std::uint32_t v : parts.drawn.back().vertices) drawnByAny[v] = 1;
  }
  const std::size_t undrawnCount = static_cast<std::size_t>(std::count(drawnByAny.begin(), drawnByAny.end(), 0));
  for (std::size_t k = 0; k < members.size(); ++k) {
    results[members[k]].vertices = parts.drawn[k].vertices.size() + undrawnCount;
    results[members[k]].triangles = parts.drawn[k].corners.size() / 3;
  }
  for (std::uint32_t v = 0; v < vertexCount; ++v) {
    if (!drawnByAny[v]) parts.undrawn.push_back(v);
  }
  return parts;
}

// The `present` gate where the group has no TANGENT: failed by each member that draws a
// triangle; the later checks not run.
void reportMissingTangent(const std::vector<std::size_t>& members, const GroupParts& parts, const CheckOptions& options,
                          std::vector<PrimitiveCheck>& results) {
  for (std::size_t k = 0; k < members.size(); ++k) {
    const std::size_t member = members[k];
    if (parts.drawn[k].corners.empty()) {
      // No triangle is drawn (a strip of two indices): nothing is shaded with the normal
      // texture, and bake leaves such a primitive as it is.
      (options.runs(CheckId::present) ? results[member].passed : results[member].ignored).push_back("present");
      skipFrom(CheckId::format, options, results[member]);
      continue;
    }
    FindingBuilder present(CheckId::present, "primitive", 1, "none", 0, options);
    present.fail(0, 1, "no TANGENT attribute");
    present.finish(results[member], "TANGENT is missing: the material's normal texture needs it (run tangent bake, or pass "
                                    "--allow-missing when clients compute MikkTSpace)");
    skipFrom(CheckId::format, options, results[member]);
  }
}

// The `format` gate failed by every member: TANGENT is not VEC4 of an allowed component type
// with one element per vertex; the later checks not run.
void reportBadFormat(const AccessorData& data, int tangentAccessor, std::size_t vertexCount, const std::vector<std::size_t>& members,
                     const CheckOptions& options, std::vector<PrimitiveCheck>& results) {
  for (const std::size_t member : members) {
    FindingBuilder formatCheck(CheckId::format, "primitive", 1, "none", 0, options);
    formatCheck.fail(0, 1, format("%s of %s%s, %zu elements", typeName(data.type), componentTypeName(data.componentType),
                                  data.normalized ? " normalized" : "", data.count));
    formatCheck.finish(results[member], format("TANGENT (accessor %d) must be VEC4 of FLOAT or normalized BYTE/SHORT with one "
                                               "element per vertex (%zu)", tangentAccessor, vertexCount));
    skipFrom(CheckId::finite, options, results[member]);
  }
}

// The component type NORMAL is stored in; without NORMAL the spec's flat normals are used:
// exact floats.
std::optional<StoredComponent> normalComponentOf(const Asset& asset, const Json& attributes) {
  const int normalAccessor = accessorOf(attributes, "NORMAL");
  return normalAccessor < 0 ? std::optional<StoredComponent>(StoredComponent::float32)
                            : storedComponentOf(asset.json["accessors"][normalAccessor].value("componentType", 0),
                                                asset.json["accessors"][normalAccessor].value("normalized", false));
}

// The stored tangents, with the limits their and NORMAL's component types give.
StoredTangents readStoredTangents(const AccessorData& data, StoredComponent tangentComponent,
                                  std::optional<StoredComponent> normalComponent, const CheckOptions& options) {
  StoredTangents stored;
  stored.limits = storedTangentLimits(tangentComponent, normalComponent.value_or(StoredComponent::float32));
  stored.orthogonalLimit = orthogonalLimitDegrees(stored.limits, options.orthogonalToleranceDegrees);
  stored.referenceLimit = referenceLimitDegrees(stored.limits, options.referenceToleranceDegrees, 0);
  stored.component = toString(tangentComponent);
  stored.values = toFloats(data);
  return stored;
}

// A member's result once `format` passed: the limits it is judged by, the NORMAL lengths as
// read, and a warning where those are beyond NORMAL's rounding.
void recordLimits(const NormalLengths& normalLengths, std::optional<StoredComponent> normalComponent, const StoredTangents& stored,
                  const CheckOptions& options, PrimitiveCheck& result) {
  const double normalLimit = normalLengthWarningLimit(normalComponent.value_or(StoredComponent::float32));
  result.normalsNormalized = normalLengths.normalized;
  result.worstNormalLength = normalLengths.worstLength;
  result.normalLengthLimit = normalLimit;
  if (normalLengths.worstDeviation() > normalLimit)
    result.warnings.push_back(format("NORMAL is not unit length: worst %.6g, beyond the %.3g of %s rounding; %llu normals normalized "
                                     "first, as glTF readers do",
                                     normalLengths.worstLength, normalLimit, toString(normalComponent.value_or(StoredComponent::float32)),
                                     static_cast<unsigned long long>(normalLengths.normalized)));
  (options.runs(CheckId::format) ? result.passed : result.ignored).push_back("format");
  result.tangentComponent = stored.component;
  result.normalComponent = normalComponent ? toString(*normalComponent) : "";
  result.unitLimit = stored.limits.unitDeviation;
  result.orthogonalLimitDegrees = stored.orthogonalLimit;
  result.referenceLimitDegrees = stored.referenceLimit;
}

// The primitives `members` of `primitives`, which share their vertex attributes and TANGENT
// (sameVertexKey and the TANGENT accessor): the buffer and the stored tangents are read once;
// the vertices no member draws are checked once and count for every member. `verdicts` (null:
// not kept) is indexed as `results` and gets each checked member's corner verdicts.
void checkVertexGroup(const Asset& asset, const std::vector<PrimitiveToCheck>& primitives, const std::vector<std::size_t>& members,
                      const CheckOptions& options, TangentWorkspace& workspace, std::vector<PrimitiveCheck>& results,
                      std::vector<std::vector<CornerVerdict>>* verdicts) {
  auto verdictsOf = [&](std::size_t member) { return verdicts ? &(*verdicts)[member] : nullptr; };
  const PrimitiveToCheck& first = primitives[members.front()];
  PrimitiveGeometry buffer = readVertices(asset, *first.primitive, first.needs, first.where, /*normalOptional=*/true);
  GroupParts parts = drawnParts(asset, primitives, members, buffer.vertexCount, results);

  // The gates: present, format.
  const Json& attributes = (*first.primitive)["attributes"];
  const int tangentAccessor = accessorOf(attributes, "TANGENT");
  if (tangentAccessor < 0) {
    reportMissingTangent(members, parts, options, results);
    return;
  }
  for (const std::size_t member : members) (options.runs(CheckId::present) ? results[member].passed : results[member].ignored).push_back("present");
  const AccessorData data = readAccessor(asset.model, tangentAccessor, first.where + ": TANGENT");
  const std::optional<StoredComponent> tangentComponent = storedComponentOf(data.componentType, data.normalized);
  const std::optional<StoredComponent> normalComponent = normalComponentOf(asset, attributes);
  if (data.type != TINYGLTF_TYPE_VEC4 || !tangentComponent || data.count != buffer.vertexCount) {
    reportBadFormat(data, tangentAccessor, buffer.vertexCount, members, options, results);
    return;
  }
  const StoredTangents stored = readStoredTangents(data, *tangentComponent, normalComponent, options);
  for (const std::size_t member : members) recordLimits(buffer.normalLengths, normalComponent, stored, options, results[member]);

  // The vertices no member draws, once for all; then each member's own part.
  VertexFindings undrawn(0, stored, options);
  for (const std::uint32_t v : parts.undrawn) undrawn.check(v, stored);
  const InputRounding rounding = inputRounding(asset, *first.primitive, first.needs.texCoord, first.needs.hasNormalTexture);
  if (members.size() == 1) {
    // The usual single primitive: the buffer, kept to the vertices it draws in place, is its
    // part (no gathered copy of every attribute).
    keepUsedVertices(buffer, parts.drawn[0]);
    checkDrawnPart(parts.drawn[0], buffer, stored, undrawn, rounding, options, workspace, results[members[0]], verdictsOf(members[0]));
    return;
  }
  for (std::size_t k = 0; k < members.size(); ++k)
    checkDrawnPart(parts.drawn[k], gatherGeometry(buffer, parts.drawn[k]), stored, undrawn, rounding, options, workspace,
                   results[members[k]], verdictsOf(members[k]));
}

}  // namespace

namespace detail {

std::vector<PrimitiveCheck> checkPrimitives(const Asset& asset, const std::vector<PrimitiveToCheck>& primitives,
                                            const CheckOptions& options, std::vector<std::vector<CornerVerdict>>* verdicts) {
  std::vector<PrimitiveCheck> results(primitives.size());
  if (verdicts) verdicts->assign(primitives.size(), {});
  // One verdict per set of inputs and TANGENT; those sets grouped by vertex buffer and TANGENT.
  std::vector<std::size_t> sameAs(primitives.size());
  std::vector<std::vector<std::size_t>> groups;
  {
    std::unordered_map<std::string, std::size_t> firstOfInput, groupOfVertices;
    for (std::size_t i = 0; i < primitives.size(); ++i) {
      const PrimitiveToCheck& p = primitives[i];
      const std::string tangent = " TANGENT " + std::to_string(accessorOf((*p.primitive)["attributes"], "TANGENT"));
      const auto input = firstOfInput.emplace(sameInputKey(asset.json, *p.primitive, p.needs) + tangent, i);
      sameAs[i] = input.first->second;
      if (!input.second) continue;
      const auto group = groupOfVertices.emplace(sameVertexKey(asset.json, *p.primitive, p.needs) + tangent, groups.size());
      if (group.second) groups.emplace_back();
      groups[group.first->second].push_back(i);
    }
  }
  CachedWorkspace workspace;  // the thread's cached workspace (tangent.hpp)
  for (const std::vector<std::size_t>& members : groups)
    checkVertexGroup(asset, primitives, members, options, workspace.get(), results, verdicts);
  for (std::size_t i = 0; i < primitives.size(); ++i) {
    if (sameAs[i] == i) continue;
    results[i] = results[sameAs[i]];
    if (verdicts) (*verdicts)[i] = (*verdicts)[sameAs[i]];
  }
  return results;
}

}  // namespace detail

namespace {

// The images[] index of the primitive's material's normal texture, or -1.
long normalTextureImage(const Json& doc, const Json& primitive) {
  auto index = [&doc](const Json& object, const char* key, const char* array) -> long {
    if (!object.is_object() || !object.contains(key) || !object[key].is_number_unsigned()) return -1;
    const std::size_t i = object[key].get<std::size_t>();
    return doc.contains(array) && doc[array].is_array() && i < doc[array].size() ? long(i) : -1;
  };
  const long material = index(primitive, "material", "materials");
  if (material < 0 || !doc["materials"][material].contains("normalTexture")) return -1;
  const long texture = index(doc["materials"][material]["normalTexture"], "index", "textures");
  return texture < 0 ? -1 : index(doc["textures"][texture], "source", "images");
}

// The primitives of `asset` (loaded from `input`) that need tangents, checked into `result`;
// `corners` (null: not kept) gets the verdicts per corner of those that reached the per-corner
// checks, keyed by their indices.
void checkLoaded(const detail::Asset& asset, const std::filesystem::path& input, const CheckOptions& options, FileCheck& result,
                 std::vector<PrimitiveVerdicts>* corners) {
  const Json& doc = asset.json;
  std::vector<detail::PrimitiveToCheck> pending;  // primitives to check, and their slots in result.primitives
  std::vector<std::size_t> pendingSlot;
  const std::size_t meshCount = doc.contains("meshes") ? doc["meshes"].size() : 0;
  for (std::size_t m = 0; m < meshCount; ++m) {
    const Json& mesh = doc["meshes"][m];
    for (std::size_t p = 0; p < mesh["primitives"].size(); ++p) {
      const Json& primitive = mesh["primitives"][p];
      const std::string label = detail::primitiveLabel(doc, static_cast<int>(m), static_cast<int>(p));
      const detail::PrimitiveNeeds needs = detail::primitiveNeeds(doc, primitive, options.all || asset.fromMeshFile);
      const bool hasUv = detail::accessorOf(primitive["attributes"], "TEXCOORD_" + std::to_string(needs.texCoord)) >= 0;
      auto newCheck = [&] {
        PrimitiveCheck check;
        check.mesh = static_cast<int>(m);
        check.primitive = static_cast<int>(p);
        check.texCoord = needs.texCoord;
        if (mesh.contains("name") && mesh["name"].is_string()) check.meshName = mesh["name"].get<std::string>();
        return check;
      };
      if (const std::string problem = detail::missingUvSet(primitive, needs); !problem.empty()) {
        // A normal texture sampling a UV set the primitive lacks: a broken file, not a skip.
        PrimitiveCheck check = newCheck();
        FindingBuilder formatCheck(CheckId::format, "primitive", 1, "none", 0, options);
        formatCheck.fail(0, 1, problem);
        formatCheck.finish(check, problem);
        skipFrom(CheckId::finite, options, check);
        result.primitives.push_back(std::move(check));
        continue;
      }
      // A primitive without NORMAL is checked against the spec's flat normals (checkDrawnPart).
      if (!detail::bakesTangents(needs) || !hasUv) {
        std::string why = needs.why;
        if (detail::bakesTangents(needs)) why = "no TEXCOORD_" + std::to_string(needs.texCoord) + " attribute";
        result.skipped.push_back(label + ": " + why);
        continue;
      }
      if (options.allowMissing && detail::accessorOf(primitive["attributes"], "TANGENT") < 0) {
        result.skipped.push_back(label + ": no TANGENT, allowed (--allow-missing: clients compute MikkTSpace from TEXCOORD_" +
                                 std::to_string(needs.texCoord) + ")");
        continue;
      }
      // Checked below, all together: primitives that share inputs or a vertex buffer share work.
      pendingSlot.push_back(result.primitives.size());
      pending.push_back({&primitive, needs, input.string() + ": " + label});
      result.primitives.push_back(newCheck());
    }
  }
  std::vector<std::vector<CornerVerdict>> cornerVerdicts;
  std::vector<PrimitiveCheck> verdicts = detail::checkPrimitives(asset, pending, options, corners ? &cornerVerdicts : nullptr);
  for (std::size_t i = 0; i < pending.size(); ++i) {
    PrimitiveCheck& named = result.primitives[pendingSlot[i]];
    PrimitiveCheck& verdict = verdicts[i];
    verdict.mesh = named.mesh;
    verdict.primitive = named.primitive;
    verdict.meshName = std::move(named.meshName);
    verdict.texCoord = named.texCoord;
    named = std::move(verdict);
    // Consumers of the frame on other UV sets: the one TANGENT cannot serve them all.
    if (!pending[i].needs.otherFrames.empty()) named.warnings.push_back(pending[i].needs.otherFrames);
    // A normal texture whose image holds no data (neither uri nor bufferView; the loader
    // warned): the tangents are checked all the same.
    const long image = normalTextureImage(doc, *pending[i].primitive);
    if (image >= 0 && doc["images"][image].is_object() && !doc["images"][image].contains("uri") && !doc["images"][image].contains("bufferView"))
      named.warnings.push_back(format("its normal texture's image, images[%ld], has neither uri nor bufferView (no image data)", image));
    if (corners && !cornerVerdicts[i].empty())
      corners->push_back({PrimitiveIndex{named.mesh, named.primitive}, std::move(cornerVerdicts[i])});
  }
}

FileCheck checkAsset(const std::filesystem::path& input, const CheckOptions& options) {
  FileCheck result;
  result.file = input.string();
  const auto started = std::chrono::steady_clock::now();
  checkLoaded(detail::loadAsset(input, options.assetRoot), input, options, result, nullptr);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return result;
}

}  // namespace

FileCheck checkFile(const std::filesystem::path& input, const CheckOptions& options) {
  return detail::throwingInputError(input, [&] { return checkAsset(input, options); });
}

std::vector<PrimitiveVerdicts> detail::checkCorners(const Asset& asset, const std::filesystem::path& input, const CheckOptions& options) {
  FileCheck discarded;
  std::vector<PrimitiveVerdicts> corners;
  checkLoaded(asset, input, options, discarded, &corners);
  return corners;
}

std::vector<PrimitiveVerdicts> checkCorners(const std::filesystem::path& input, const CheckOptions& options) {
  return detail::throwingInputError(
      input, [&] { return detail::checkCorners(detail::loadAsset(input, options.assetRoot), input, options); });
}

}  // namespace tangent::gltf
