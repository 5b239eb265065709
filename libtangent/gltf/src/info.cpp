// `tangent info` and the "does this primitive need tangents" rule (glTF 2.0 spec 3.7.2.1:
// tangents come from the UV set the normal texture uses; KHR_texture_transform may override it).
#include "asset.hpp"
#include "accessors.hpp"
#include "primitive.hpp"
#include "tangent/gltf.hpp"

namespace tangent::gltf {
namespace detail {

using Json = nlohmann::ordered_json;

std::string primitiveLabel(const Json& doc, int mesh, int primitive) {
  std::string label = "mesh " + std::to_string(mesh);
  const Json& meshJson = doc["meshes"][mesh];
  if (meshJson.contains("name") && meshJson["name"].is_string()) label += " '" + meshJson["name"].get<std::string>() + "'";
  return label + " primitive " + std::to_string(primitive);
}

PrimitiveNeeds primitiveNeeds(const Json& doc, const Json& primitive, bool all) {
  PrimitiveNeeds needs;
  const int mode = primitive.value("mode", 4);
  needs.triangles = mode == 4 || mode == 5 || mode == 6;
  needs.compressed = primitive.contains("extensions") && primitive["extensions"].contains("KHR_draco_mesh_compression");
  if (primitive.contains("material") && primitive["material"].is_number_integer() && doc.contains("materials")) {
    const int materialIndex = primitive["material"].get<int>();
    if (materialIndex >= 0 && materialIndex < static_cast<int>(doc["materials"].size())) {
      const Json& material = doc["materials"][materialIndex];
      if (material.contains("normalTexture") && material["normalTexture"].is_object()) {
        const Json& normalTexture = material["normalTexture"];
        needs.hasNormalTexture = true;
        needs.texCoord = normalTexture.value("texCoord", 0);
        if (normalTexture.contains("extensions") && normalTexture["extensions"].contains("KHR_texture_transform")) {
          const Json& transform = normalTexture["extensions"]["KHR_texture_transform"];
          if (transform.contains("texCoord") && transform["texCoord"].is_number_integer()) {
            needs.texCoord = transform["texCoord"].get<int>();
            needs.texCoordFromTransform = true;
          }
        }
        needs.why = "material " + std::to_string(materialIndex) + " has a normalTexture on TEXCOORD_" +
                    std::to_string(needs.texCoord) + (needs.texCoordFromTransform ? " (KHR_texture_transform)" : "");
      }
    }
  }
  if (!needs.hasNormalTexture) {
    if (all) {
      needs.texCoord = 0;
      needs.why = "no normalTexture; --all uses TEXCOORD_0";
    } else {
      needs.why = "material has no normalTexture (use --all to bake anyway)";
    }
  }
  if (!needs.triangles) needs.why = "mode " + std::to_string(mode) + " is not triangles";
  if (needs.compressed) needs.why = "KHR_draco_mesh_compression: decompress before baking";
  return needs;
}

}  // namespace detail

nlohmann::ordered_json describeFile(const std::filesystem::path& input) {
  using detail::Json;
  detail::Asset asset = detail::loadAsset(input);
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
    for (std::size_t p = 0; p < primitiveCount; ++p) {
      const Json& primitive = mesh["primitives"][p];
      const detail::PrimitiveNeeds needs = detail::primitiveNeeds(doc, primitive, asset.fromMeshFile);
      Json primitiveOut = Json::object();
      primitiveOut["index"] = p;
      primitiveOut["mode"] = primitive.value("mode", 4);
      if (primitive.contains("material")) primitiveOut["material"] = primitive["material"];
      Json attributes = Json::object();
      if (primitive.contains("attributes")) {
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
      }
      primitiveOut["attributes"] = attributes;
      if (primitive.contains("targets")) primitiveOut["morphTargets"] = primitive["targets"].size();
      const bool hasTangent = primitive.contains("attributes") && primitive["attributes"].contains("TANGENT");
      primitiveOut["needsTangents"] = needs.triangles && !needs.compressed && needs.hasNormalTexture;
      primitiveOut["hasTangents"] = hasTangent;
      if (needs.texCoord >= 0 && needs.hasNormalTexture) primitiveOut["normalTexCoord"] = needs.texCoord;
      primitiveOut["why"] = needs.why;
      primitives.push_back(primitiveOut);
    }
    meshOut["primitives"] = primitives;
    meshes.push_back(meshOut);
  }
  out["meshes"] = meshes;
  Json warnings = Json::array();
  for (const auto& w : asset.warnings) warnings.push_back(w);
  out["warnings"] = warnings;
  return out;
}

}  // namespace tangent::gltf
