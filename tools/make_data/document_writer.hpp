// SPDX-License-Identifier: MIT
// DocumentWriter: one glTF document (.gltf + .bin) built mesh by mesh; the JSON pieces several
// generated files share.
#pragma once

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "shapes.hpp"
#include "tangent/output.hpp"

namespace make_data {

using Json = nlohmann::ordered_json;

// Accumulates meshes, nodes and buffer data of one glTF document, written as .gltf + .bin.
class DocumentWriter {
 public:
  struct Placement {
    std::string name;
    float translation[3] = {0, 0, 0};
  };

  // Adds a mesh with POSITION, NORMAL, TEXCOORD_0 and uint16 (or uint32) indices, and a node for it.
  void addMesh(const MeshData& mesh, const std::string& name, int material, const float (&translation)[3]) {
    const std::size_t n = mesh.positions.size() / 3;
    float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
      lo[i % 3] = std::min(lo[i % 3], mesh.positions[i]);
      hi[i % 3] = std::max(hi[i % 3], mesh.positions[i]);
    }
    const std::size_t first = accessors_.size();
    accessors_.push_back({{"bufferView", addView(mesh.positions.data(), n * 12, 34962)}, {"componentType", 5126}, {"count", n},
                          {"type", "VEC3"}, {"min", {lo[0], lo[1], lo[2]}}, {"max", {hi[0], hi[1], hi[2]}}});
    accessors_.push_back({{"bufferView", addView(mesh.normals.data(), n * 12, 34962)}, {"componentType", 5126}, {"count", n}, {"type", "VEC3"}});
    accessors_.push_back({{"bufferView", addView(mesh.uvs.data(), n * 8, 34962)}, {"componentType", 5126}, {"count", n}, {"type", "VEC2"}});
    if (mesh.indices32.empty())
      accessors_.push_back({{"bufferView", addView(mesh.indices.data(), mesh.indices.size() * 2, 34963)}, {"componentType", 5123},
                            {"count", mesh.indices.size()}, {"type", "SCALAR"}});
    else
      accessors_.push_back({{"bufferView", addView(mesh.indices32.data(), mesh.indices32.size() * 4, 34963)}, {"componentType", 5125},
                            {"count", mesh.indices32.size()}, {"type", "SCALAR"}});
    Json primitive = Json::object();
    primitive["attributes"] = {{"POSITION", first}, {"NORMAL", first + 1}, {"TEXCOORD_0", first + 2}};
    primitive["indices"] = first + 3;
    if (!mesh.tangents.empty())
      primitive["attributes"]["TANGENT"] = addAccessor(mesh.tangents.data(), mesh.tangents.size() / 4, 5126, "VEC4", 34962);
    primitive["material"] = material;
    meshes_.push_back({{"name", name}, {"primitives", Json::array({primitive})}});
    Json node = {{"name", name}, {"mesh", meshes_.size() - 1}};
    if (translation[0] != 0 || translation[1] != 0 || translation[2] != 0) node["translation"] = {translation[0], translation[1], translation[2]};
    nodes_.push_back(node);
  }
  void addNode(Json node) { nodes_.push_back(std::move(node)); }
  Json& node(std::size_t index) { return nodes_[index]; }
  Json& accessor(std::size_t index) { return accessors_[index]; }
  // The primitive of the mesh added last, to give more attributes or morph targets.
  Json& lastPrimitive() { return meshes_.back()["primitives"][0]; }
  Json& lastMesh() { return meshes_.back(); }
  // An accessor over `count` elements of `type` (SCALAR, VEC3, ...) of float (5126), unsigned
  // short (5123) or unsigned byte (5121) components; its index.
  std::size_t addAccessor(const void* data, std::size_t count, int componentType, const std::string& type, int target = 0) {
    const int components = type == "SCALAR" ? 1 : type == "MAT4" ? 16 : type.back() - '0';
    const std::size_t bytes = count * components * (componentType == 5126 ? 4 : componentType == 5121 ? 1 : 2);
    const std::size_t view = target ? addView(data, bytes, target) : addView(data, bytes);
    accessors_.push_back({{"bufferView", view}, {"componentType", componentType}, {"count", count}, {"type", type}});
    if (type == "SCALAR" && componentType == 5126 && count > 0) {  // animation inputs need min and max
      const auto* values = static_cast<const float*>(data);
      accessors_.back()["min"] = {*std::min_element(values, values + count)};
      accessors_.back()["max"] = {*std::max_element(values, values + count)};
    }
    return accessors_.size() - 1;
  }

  // Writes dir/stem.gltf and dir/stem.bin; `extra` holds materials, textures and the rest.
  void write(const std::filesystem::path& dir, const std::string& stem, Json extra) const {
    std::vector<std::uint8_t> bin = bin_;
    while (bin.size() % 4) bin.push_back(0);
    // The scene's roots: every node that is no other node's child.
    std::vector<bool> isChild(nodes_.size(), false);
    for (const Json& node : nodes_)
      if (node.contains("children"))
        for (const Json& child : node["children"]) isChild[child.get<std::size_t>()] = true;
    Json sceneNodes = Json::array();
    for (std::size_t i = 0; i < nodes_.size(); ++i)
      if (!isChild[i]) sceneNodes.push_back(i);
    Json doc = {{"asset", {{"version", "2.0"}, {"generator", "libtangent tangent-make-data"}, {"copyright", "libtangent authors, CC0"}}}};
    if (extra.contains("extensionsUsed")) doc["extensionsUsed"] = extra["extensionsUsed"];
    doc["scene"] = 0;
    doc["scenes"] = {{{"name", stem}, {"nodes", sceneNodes}}};
    doc["nodes"] = nodes_;
    doc["meshes"] = meshes_;
    for (auto& [key, value] : extra.items()) {
      if (key != "extensionsUsed") doc[key] = value;
    }
    doc["accessors"] = accessors_;
    doc["bufferViews"] = views_;
    doc["buffers"] = {{{"uri", stem + ".bin"}, {"byteLength", bin.size()}}};
    // As every output of the project (tangent/output.hpp): atomically, a failure (a full disk)
    // thrown naming the file; the .bin first, so that the .gltf never names a missing one.
    tangent::output::writeFileAtomic(dir / (stem + ".bin"), {std::span<const std::uint8_t>(bin.data(), bin.size())});
    tangent::output::writeFileAtomic(dir / (stem + ".gltf"), doc.dump(2) + "\n");
  }

 private:
  std::size_t addView(const void* data, std::size_t bytes, int target = 0) {
    while (bin_.size() % 4) bin_.push_back(0);
    views_.push_back({{"buffer", 0}, {"byteOffset", bin_.size()}, {"byteLength", bytes}});
    if (target) views_.back()["target"] = target;
    const auto* p = static_cast<const std::uint8_t*>(data);
    bin_.insert(bin_.end(), p, p + bytes);
    return views_.size() - 1;
  }

  std::vector<std::uint8_t> bin_;
  Json accessors_ = Json::array(), views_ = Json::array(), meshes_ = Json::array(), nodes_ = Json::array();
};

// Materials and textures shared by the scene and the primitives; image URIs relative to
// `imagePrefix` ("" or "../").
Json sharedMaterials(const std::string& imagePrefix);
// A directional light shining along `direction` (KHR_lights_punctual lights shine along their
// node's -z; the rotation turns -z onto it: q = normalize(1 + dot(a, b), cross(a, b))).
Json sunNode(const std::string& name, const double (&direction)[3]);
// KHR_lights_punctual's document extension: one white directional light named Sun.
Json oneSun(double intensity);

}  // namespace make_data
