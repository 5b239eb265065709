// SPDX-License-Identifier: MIT
// `tangent info`: meshes, primitives, attributes, and which primitives need tangents and why.
#include "read/asset.hpp"
#include "read/accessors.hpp"
#include "read/compression.hpp"
#include "entry_point.hpp"
#include "read/primitive.hpp"
#include "tangent/gltf.hpp"

namespace tangent::gltf {
namespace {

using Json = nlohmann::ordered_json;

// Each attribute's accessor as "VEC3 FLOAT x24", by attribute name.
Json attributeFormats(const detail::Asset& asset, const Json& primitive) {
  Json attributes = Json::object();
  if (!primitive.contains("attributes")) return attributes;
  for (auto& [name, accessorRef] : primitive["attributes"].items()) {
    const int a = accessorRef.is_number_integer() ? accessorRef.get<int>() : -1;
    if (a >= 0 && a < static_cast<int>(asset.model.accessors.size())) {
      const auto& accessor = asset.model.accessors[a];
      attributes[name] = std::string(detail::typeName(accessor.type)) + " " +
                         detail::componentTypeName(accessor.componentType) + (accessor.normalized ? " normalized" : "") +
                         " x" + std::to_string(accessor.count);
    } else {
      attributes[name] = "invalid accessor " + std::to_string(a);
    }
  }
  return attributes;
}

// The vertices the primitive draws by its counts alone (its indices, else POSITION); 0 where
// neither is a valid accessor. Nothing is read.
std::size_t drawnVertexCount(const detail::Asset& asset, const Json& primitive) {
  const int counted = primitive.contains("indices") && primitive["indices"].is_number_integer()
                          ? primitive["indices"].get<int>()
                          : (primitive.contains("attributes") ? detail::accessorOf(primitive["attributes"], "POSITION") : -1);
  return counted >= 0 && counted < static_cast<int>(asset.model.accessors.size()) ? asset.model.accessors[counted].count : 0;
}

// Every material feature that reads the tangent frame, the one TANGENT follows first.
Json frameConsumers(const detail::PrimitiveNeeds& needs) {
  Json consumers = Json::array();
  for (const detail::ConsumerUse& use : needs.consumers) {
    Json entry = {{"consumer", detail::toString(use.consumer)}, {"texCoord", use.texCoord}, {"texture", use.sampled}};
    if (use.texCoordFromTransform) entry["texCoordFromTransform"] = true;
    consumers.push_back(std::move(entry));
  }
  return consumers;
}

// Primitive `p` of mesh `m`: its mode, material, attributes, compression, and whether and why
// it needs tangents.
Json describePrimitive(const detail::Asset& asset, const std::filesystem::path& input, std::size_t m, std::size_t p) {
  const Json& doc = asset.json;
  const Json& primitive = doc["meshes"][m]["primitives"][p];
  const detail::PrimitiveNeeds needs = detail::primitiveNeeds(doc, primitive, asset.fromMeshFile);
  // What bake refuses, info refuses: a normal texture on a UV set the primitive lacks, or
  // on a primitive without POSITION (the rest bake refuses, loadAsset refused above).
  for (const std::string& problem : {detail::missingUvSet(primitive, needs), detail::missingPosition(primitive, needs)}) {
    if (!problem.empty())
      throw InputError(input.string() + ": " + detail::primitiveLabel(doc, static_cast<int>(m), static_cast<int>(p)) + ": " + problem);
  }
  Json primitiveOut = Json::object();
  primitiveOut["index"] = p;
  primitiveOut["mode"] = primitive.value("mode", 4);
  if (primitive.contains("material")) primitiveOut["material"] = primitive["material"];
  primitiveOut["attributes"] = attributeFormats(asset, primitive);
  if (primitive.contains("targets")) primitiveOut["morphTargets"] = primitive["targets"].size();
  // The extensions the primitive's data was decoded from: [] when stored plainly.
  primitiveOut["compression"] = detail::compressionNames(detail::primitiveCompression(asset, primitive));
  const bool hasTangent = primitive.contains("attributes") && primitive["attributes"].contains("TANGENT");
  // A strip or fan of fewer than three vertices, or a list of fewer than three, draws no
  // triangle: bake leaves it and check passes it.
  const std::size_t vertices = drawnVertexCount(asset, primitive);
  const bool drawsTriangles = vertices >= 3;
  primitiveOut["needsTangents"] = detail::bakesTangents(needs) && drawsTriangles;
  primitiveOut["hasTangents"] = hasTangent;
  if (needs.texCoord >= 0 && needs.hasNormalTexture) primitiveOut["normalTexCoord"] = needs.texCoord;
  primitiveOut["frameConsumers"] = frameConsumers(needs);
  if (!needs.otherFrames.empty()) primitiveOut["frameWarning"] = needs.otherFrames;
  primitiveOut["why"] = needs.triangles && !drawsTriangles
                            ? "draws no triangle (" + std::to_string(vertices) + " vertices); left as it is"
                            : detail::bakeReason(needs, asset.fromMeshFile);
  return primitiveOut;
}

Json describe(const std::filesystem::path& input, const std::filesystem::path& assetRoot) {
  detail::Asset asset = detail::loadAsset(input, assetRoot);
  const Json& doc = asset.json;
  Json out = Json::object();
  out["file"] = input.string();
  out["container"] = asset.fromMeshFile ? "mesh file" : asset.binary ? "glb" : "gltf";
  Json meshes = Json::array();
  const std::size_t meshCount = doc.contains("meshes") ? doc["meshes"].size() : 0;
  for (std::size_t m = 0; m < meshCount; ++m) {
    const Json& mesh = doc["meshes"][m];
    Json meshOut = Json::object();
    meshOut["index"] = m;
    if (mesh.contains("name")) meshOut["name"] = mesh["name"];
    Json primitives = Json::array();
    const std::size_t primitiveCount = mesh.contains("primitives") ? mesh["primitives"].size() : 0;
    for (std::size_t p = 0; p < primitiveCount; ++p) primitives.push_back(describePrimitive(asset, input, m, p));
    meshOut["primitives"] = primitives;
    meshes.push_back(meshOut);
  }
  out["meshes"] = meshes;
  Json warnings = Json::array();
  for (const auto& w : asset.warnings) warnings.push_back(w);
  out["warnings"] = warnings;
  return out;
}

}  // namespace

nlohmann::ordered_json describeFile(const std::filesystem::path& input, const std::filesystem::path& assetRoot) {
  return detail::throwingInputError(input, [&] { return describe(input, assetRoot); });
}

}  // namespace tangent::gltf
