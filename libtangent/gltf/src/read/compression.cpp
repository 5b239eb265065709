// SPDX-License-Identifier: MIT
// Which compressions a document and its primitives use, and the bookkeeping of their
// extension declarations. The decoders are in meshopt_decode.cpp and draco_decode.cpp.
#include "read/compression.hpp"

#include <algorithm>

#include "read/primitive.hpp"
#include "tangent/gltf.hpp"

namespace tangent::gltf::detail {

using Json = nlohmann::ordered_json;

namespace {

bool hasExtension(const Json& object, const char* name) {
  if (!object.is_object()) return false;
  auto it = object.find("extensions");
  return it != object.end() && it->is_object() && it->contains(name);
}

bool viewIsMeshopt(const Json& doc, int view) {
  if (view < 0 || !doc.contains("bufferViews") || view >= static_cast<int>(doc["bufferViews"].size())) return false;
  return hasExtension(doc["bufferViews"][view], kMeshoptExtension);
}

bool accessorIsMeshopt(const Json& doc, int accessor) {
  if (accessor < 0 || !doc.contains("accessors") || accessor >= static_cast<int>(doc["accessors"].size())) return false;
  const Json& json = doc["accessors"][accessor];
  if (viewIsMeshopt(doc, accessorOf(json, "bufferView"))) return true;
  if (json.contains("sparse") && json["sparse"].is_object()) {
    const Json& sparse = json["sparse"];
    for (const char* part : {"indices", "values"}) {
      if (sparse.contains(part) && viewIsMeshopt(doc, accessorOf(sparse[part], "bufferView"))) return true;
    }
  }
  return false;
}

void eraseName(Json& doc, const char* list, const std::string& name) {
  if (!doc.contains(list) || !doc[list].is_array()) return;
  Json& names = doc[list];
  names.erase(std::remove(names.begin(), names.end(), Json(name)), names.end());
  if (names.empty()) doc.erase(list);
}

bool declared(const Json& doc, const char* name) {
  for (const char* list : {"extensionsUsed", "extensionsRequired"}) {
    if (!doc.contains(list) || !doc[list].is_array()) continue;
    for (const Json& entry : doc[list]) {
      if (entry == name) return true;
    }
  }
  return false;
}

}  // namespace

PrimitiveCompression primitiveCompression(const Asset& asset, const Json& primitive) {
  const Json& doc = asset.json;
  PrimitiveCompression compression;
  compression.draco = hasExtension(primitive, kDracoExtension);
  auto scan = [&](const Json& map) {
    if (!map.is_object()) return;
    for (const auto& [name, value] : map.items()) {
      if (value.is_number_integer() && accessorIsMeshopt(doc, value.get<int>())) compression.meshopt = true;
    }
  };
  if (primitive.contains("attributes")) scan(primitive["attributes"]);
  if (primitive.contains("targets") && primitive["targets"].is_array()) {
    for (const Json& target : primitive["targets"]) scan(target);
  }
  if (accessorIsMeshopt(doc, accessorOf(primitive, "indices"))) compression.meshopt = true;
  return compression;
}

std::vector<std::string> compressionNames(const PrimitiveCompression& compression) {
  std::vector<std::string> names;
  if (compression.draco) names.push_back(kDracoExtension);
  if (compression.meshopt) names.push_back(kMeshoptExtension);
  return names;
}

bool isMeshoptFallbackBuffer(const Json& buffer) {
  if (!hasExtension(buffer, kMeshoptExtension)) return false;
  const Json& extension = buffer["extensions"][kMeshoptExtension];
  return extension.is_object() && extension.value("fallback", false) == true;
}

bool adaptForLoader(Json& doc) {
  bool changed = false;
  if (doc.contains("buffers") && doc["buffers"].is_array()) {
    for (Json& buffer : doc["buffers"]) {
      if (!buffer.is_object() || buffer.contains("uri") || !isMeshoptFallbackBuffer(buffer)) continue;
      // Its bytes are never read: the views on it are decoded from their compressed source.
      buffer["byteLength"] = 1;
      buffer["uri"] = "data:application/octet-stream;base64,AA==";
      changed = true;
    }
  }
  if (doc.contains("meshes") && doc["meshes"].is_array()) {
    for (Json& mesh : doc["meshes"]) {
      if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
      for (Json& primitive : mesh["primitives"]) {
        if (hasExtension(primitive, kDracoExtension) && primitive.contains("indices")) {
          primitive.erase("indices");
          changed = true;
        }
      }
    }
  }
  return changed;
}

void decodeCompressedData(Asset& asset) {
  // KHR_meshopt_compression (meshoptimizer's newer codec versions) is not decoded: refused by
  // name rather than read as if its views held plain data.
  if (asset.json.contains("extensionsUsed") && asset.json["extensionsUsed"].is_array()) {
    for (const Json& name : asset.json["extensionsUsed"]) {
      if (name == "KHR_meshopt_compression")
        throw InputError(asset.path.string() + ": uses KHR_meshopt_compression, which is not decoded (EXT_meshopt_compression is)");
    }
  }
  decodeMeshoptViews(asset);
  decodeDracoPrimitives(asset);
}

std::vector<std::string> dropUnusedCompressionExtensions(Json& doc) {
  bool dracoUsed = false, meshoptUsed = false;
  if (doc.contains("meshes")) {
    for (const Json& mesh : doc["meshes"]) {
      if (!mesh.contains("primitives")) continue;
      for (const Json& primitive : mesh["primitives"]) dracoUsed = dracoUsed || hasExtension(primitive, kDracoExtension);
    }
  }
  if (doc.contains("bufferViews")) {
    for (const Json& view : doc["bufferViews"]) meshoptUsed = meshoptUsed || hasExtension(view, kMeshoptExtension);
  }
  std::vector<std::string> removed;
  for (const auto& [name, used] : {std::pair{kDracoExtension, dracoUsed}, std::pair{kMeshoptExtension, meshoptUsed}}) {
    if (used || !declared(doc, name)) continue;
    eraseName(doc, "extensionsUsed", name);
    eraseName(doc, "extensionsRequired", name);
    removed.push_back(name);
  }
  return removed;
}

}  // namespace tangent::gltf::detail
