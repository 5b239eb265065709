// SPDX-License-Identifier: MIT
// Validator (validator.hpp): images, textures, materials (and the material extensions whose
// textures are read), meshes and their morph targets, the node hierarchy, scenes and skins.
#include <deque>
#include <string>

#include "read/validator.hpp"

namespace tangent::gltf::detail {

void Validator::images() {
  for (std::size_t i = 0; i < count("images"); ++i) {
    const Json& image = doc_["images"][i];
    const std::string pointer = "/images/" + std::to_string(i);
    member(image, "uri", pointer, &Json::is_string, "a string");
    reference(image, "bufferView", pointer, "bufferViews");
  }
}

void Validator::textures() {
  for (std::size_t i = 0; i < count("textures"); ++i) {
    const Json& texture = doc_["textures"][i];
    const std::string pointer = "/textures/" + std::to_string(i);
    reference(texture, "source", pointer, "images");
    reference(texture, "sampler", pointer, "samplers");
    if (const Json* extensions = objectMember(texture, "extensions", pointer)) {
      for (const auto& [name, extension] : extensions->items()) {
        if (extension.is_object()) reference(extension, "source", pointer + "/extensions/" + name, "images");
      }
    }
  }
}

void Validator::textureInfo(const Json& owner, const char* key, const std::string& pointer) {
  const Json* info = objectMember(owner, key, pointer);
  if (!info) return;
  const std::string p = join(pointer, key);
  reference(*info, "index", p, "textures", true);
  integer(*info, "texCoord", p, 0, 1 << 20, false);
  if (const Json* extensions = objectMember(*info, "extensions", p)) {
    if (const Json* transform = objectMember(*extensions, "KHR_texture_transform", join(p, "extensions")))
      textureTransform(*transform, join(p, "extensions/KHR_texture_transform"));
  }
}

// KHR_texture_transform: offset and scale [u, v], rotation in radians, texCoord a UV set.
void Validator::textureTransform(const Json& transform, const std::string& pointer) {
  for (const char* key : {"offset", "scale"}) {
    auto it = transform.find(key);
    if (it == transform.end()) continue;
    if (!it->is_array() || it->size() != 2 || !(*it)[0].is_number() || !(*it)[1].is_number())
      fail(join(pointer, key), "must be an array of 2 numbers");
  }
  member(transform, "rotation", pointer, &Json::is_number, "a number");
  integer(transform, "texCoord", pointer, 0, 1 << 20, false);
}

void Validator::materials() {
  for (std::size_t i = 0; i < count("materials"); ++i) {
    const Json& material = doc_["materials"][i];
    const std::string pointer = "/materials/" + std::to_string(i);
    for (const char* key : {"normalTexture", "occlusionTexture", "emissiveTexture"}) textureInfo(material, key, pointer);
    if (const Json* pbr = objectMember(material, "pbrMetallicRoughness", pointer)) {
      for (const char* key : {"baseColorTexture", "metallicRoughnessTexture"})
        textureInfo(*pbr, key, join(pointer, "pbrMetallicRoughness"));
    }
    // The material extensions whose textures the viewer reads or that read the tangent frame
    // (clearcoat's normal texture, anisotropy: tangent_rules' consumers), with their transforms.
    if (const Json* extensions = objectMember(material, "extensions", pointer)) {
      const std::string ep = join(pointer, "extensions");
      if (const Json* specular = objectMember(*extensions, "KHR_materials_specular", ep)) {
        for (const char* key : {"specularTexture", "specularColorTexture"})
          textureInfo(*specular, key, join(ep, "KHR_materials_specular"));
      }
      if (const Json* clearcoat = objectMember(*extensions, "KHR_materials_clearcoat", ep)) {
        const std::string cp = join(ep, "KHR_materials_clearcoat");
        for (const char* key : {"clearcoatFactor", "clearcoatRoughnessFactor"}) member(*clearcoat, key, cp, &Json::is_number, "a number");
        for (const char* key : {"clearcoatTexture", "clearcoatRoughnessTexture", "clearcoatNormalTexture"}) textureInfo(*clearcoat, key, cp);
      }
      if (const Json* anisotropy = objectMember(*extensions, "KHR_materials_anisotropy", ep)) {
        const std::string ap = join(ep, "KHR_materials_anisotropy");
        for (const char* key : {"anisotropyStrength", "anisotropyRotation"}) member(*anisotropy, key, ap, &Json::is_number, "a number");
        textureInfo(*anisotropy, "anisotropyTexture", ap);
      }
    }
  }
}

void Validator::accessorMap(const Json& map, const std::string& pointer) {
  if (!map.is_object()) fail(pointer, "must be an object");
  for (const auto& [name, value] : map.items()) referenceValue(value, pointer + "/" + name, "accessors");
}

// `weights` of a mesh or node: one number per morph target of the mesh (glTF 2.0 3.7.2.2).
void Validator::morphWeights(const Json& owner, const std::string& pointer, std::size_t mesh) const {
  const Json* weights = arrayMember(owner, "weights", pointer);
  if (!weights) return;
  for (std::size_t k = 0; k < weights->size(); ++k) {
    if (!(*weights)[k].is_number()) fail(join(pointer, "weights/" + std::to_string(k)), "must be a number");
  }
  if (weights->size() != meshTargets_[mesh])
    fail(join(pointer, "weights"), "has " + std::to_string(weights->size()) + " weight(s); mesh " + std::to_string(mesh) +
                                       " has " + std::to_string(meshTargets_[mesh]) + " morph target(s)");
}

void Validator::meshes() {
  meshTargets_.assign(count("meshes"), 0);
  for (std::size_t m = 0; m < count("meshes"); ++m) {
    const Json& mesh = doc_["meshes"][m];
    const std::string meshPointer = "/meshes/" + std::to_string(m);
    const Json* primitives = arrayMember(mesh, "primitives", meshPointer);
    if (!primitives || primitives->empty()) fail(join(meshPointer, "primitives"), "is required and must not be empty");
    for (std::size_t p = 0; p < primitives->size(); ++p) {
      const Json& primitive = (*primitives)[p];
      const std::string pointer = meshPointer + "/primitives/" + std::to_string(p);
      if (!primitive.is_object()) fail(pointer, "must be an object");
      if (!primitive.contains("attributes")) fail(join(pointer, "attributes"), "is required");
      accessorMap(primitive["attributes"], join(pointer, "attributes"));
      const std::int64_t indices = reference(primitive, "indices", pointer, "accessors");
      reference(primitive, "material", pointer, "materials");
      const std::int64_t mode = integer(primitive, "mode", pointer, 0, 6, false, 4);
      const Json* targets = arrayMember(primitive, "targets", pointer);
      if (targets) {
        for (std::size_t t = 0; t < targets->size(); ++t) accessorMap((*targets)[t], pointer + "/targets/" + std::to_string(t));
      }
      // glTF 2.0 3.7.2.2: every primitive of a mesh has the same number of morph targets.
      const std::size_t targetCount = targets ? targets->size() : 0;
      if (p == 0) meshTargets_[m] = targetCount;
      else if (targetCount != meshTargets_[m])
        fail(join(pointer, "targets"), "has " + std::to_string(targetCount) + " morph target(s); primitive 0 of the mesh has " +
                                           std::to_string(meshTargets_[m]) + " (every primitive of a mesh must have as many)");
      // glTF 2.0 3.7.2.1: TRIANGLES draw count / 3 triangles; a remainder is invalid.
      std::int64_t vertices = -1;
      if (indices >= 0) vertices = accessorCount_[static_cast<std::size_t>(indices)];
      else if (primitive["attributes"].contains("POSITION"))
        vertices = accessorCount_[primitive["attributes"]["POSITION"].get<std::size_t>()];
      if (mode == 4 && vertices >= 0 && vertices % 3 != 0)
        fail(pointer, std::string(indices >= 0 ? "indices" : "vertex") + " count " + std::to_string(vertices) +
                          " is not a multiple of 3, as mode 4 (TRIANGLES) requires");
    }
    morphWeights(mesh, meshPointer, m);
  }
}

void Validator::nodes() {
  const std::size_t n = count("nodes");
  std::vector<std::int64_t> parent(n, -1);
  for (std::size_t i = 0; i < n; ++i) {
    const Json& node = doc_["nodes"][i];
    const std::string pointer = "/nodes/" + std::to_string(i);
    const std::int64_t mesh = reference(node, "mesh", pointer, "meshes");
    if (mesh >= 0) morphWeights(node, pointer, static_cast<std::size_t>(mesh));
    else if (node.contains("weights")) fail(join(pointer, "weights"), "needs a mesh (the node has none)");
    reference(node, "skin", pointer, "skins");
    reference(node, "camera", pointer, "cameras");
    if (const Json* children = arrayMember(node, "children", pointer)) {
      for (std::size_t c = 0; c < children->size(); ++c) {
        const std::string cp = pointer + "/children/" + std::to_string(c);
        referenceValue((*children)[c], cp, "nodes");
        const std::size_t child = (*children)[c].get<std::size_t>();
        if (parent[child] >= 0) fail(cp, "node " + std::to_string(child) + " has two parents (nodes " +
                                             std::to_string(parent[child]) + " and " + std::to_string(i) + ")");
        parent[child] = static_cast<std::int64_t>(i);
      }
    }
  }
  // With one parent each, a node that no walk from the roots reaches sits on a cycle.
  std::vector<char> reached(n, 0);
  std::deque<std::size_t> queue;
  for (std::size_t i = 0; i < n; ++i) {
    if (parent[i] < 0) queue.push_back(i), reached[i] = 1;
  }
  while (!queue.empty()) {
    const std::size_t i = queue.front();
    queue.pop_front();
    const Json& node = doc_["nodes"][i];
    if (!node.contains("children")) continue;
    for (const Json& child : node["children"]) {
      const std::size_t c = child.get<std::size_t>();
      if (!reached[c]) reached[c] = 1, queue.push_back(c);
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!reached[i]) fail("/nodes/" + std::to_string(i), "is its own ancestor (the node hierarchy has a cycle)");
  }
}

void Validator::scenes() {
  for (std::size_t i = 0; i < count("scenes"); ++i) {
    const std::string pointer = "/scenes/" + std::to_string(i);
    if (const Json* nodes = arrayMember(doc_["scenes"][i], "nodes", pointer)) {
      for (std::size_t k = 0; k < nodes->size(); ++k) referenceValue((*nodes)[k], pointer + "/nodes/" + std::to_string(k), "nodes");
    }
  }
}

void Validator::skins() {
  for (std::size_t i = 0; i < count("skins"); ++i) {
    const Json& skin = doc_["skins"][i];
    const std::string pointer = "/skins/" + std::to_string(i);
    reference(skin, "inverseBindMatrices", pointer, "accessors");
    reference(skin, "skeleton", pointer, "nodes");
    if (const Json* joints = arrayMember(skin, "joints", pointer)) {
      for (std::size_t k = 0; k < joints->size(); ++k) referenceValue((*joints)[k], pointer + "/joints/" + std::to_string(k), "nodes");
    }
  }
}

}  // namespace tangent::gltf::detail
