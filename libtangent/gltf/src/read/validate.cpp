// SPDX-License-Identifier: MIT
#include "read/validate.hpp"

#include <array>
#include <cstdint>
#include <deque>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "read/accessors.hpp"
#include "read/animation_rules.hpp"
#include "tangent/gltf.hpp"

namespace tangent::gltf::detail {

using Json = nlohmann::ordered_json;

void checkJsonDepth(std::string_view text, const std::string& label, const char* what) {
  if (text.size() > kMaxJsonBytes)
    throw InputError(label + ": " + what + " is " + std::to_string(text.size()) + " bytes; the limit is " +
                     std::to_string(kMaxJsonBytes));
  std::size_t depth = 0;
  bool inString = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (inString) {
      if (c == '\\') ++i;
      else if (c == '"') inString = false;
      continue;
    }
    if (c == '"') {
      inString = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonDepth)
        throw InputError(label + ": " + what + " nests deeper than " + std::to_string(kMaxJsonDepth) +
                         " levels (at byte " + std::to_string(i) + ")");
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
}

namespace {

// Sizes beyond these are refused before any arithmetic: products of a count (< 2^32) and a
// stride (< 256) then fit 64 bits with room to spare.
constexpr std::int64_t kMaxByteLength = std::int64_t(1) << 40;
constexpr std::int64_t kMaxCount = (std::int64_t(1) << 32) - 1;

int componentBytesOf(std::int64_t componentType) {
  switch (componentType) {
    case 5120: case 5121: return 1;
    case 5122: case 5123: return 2;
    case 5125: case 5126: return 4;
    default: return 0;
  }
}

int componentsOf(const std::string& type) {
  static const std::array<std::pair<const char*, int>, 7> types = {
      {{"SCALAR", 1}, {"VEC2", 2}, {"VEC3", 3}, {"VEC4", 4}, {"MAT2", 4}, {"MAT3", 9}, {"MAT4", 16}}};
  for (const auto& [name, n] : types) {
    if (type == name) return n;
  }
  return 0;
}

// Components of a SCALAR or VECn; 0 for the matrices (a MAT2 is not a VEC4).
int vectorComponentsOf(const std::string& type) { return type.rfind("MAT", 0) == 0 ? 0 : componentsOf(type); }

class Validator {
 public:
  Validator(const Json& doc, const std::string& label) : doc_(doc), label_(label) {}

  void run() {
    topLevel();
    buffers();
    bufferViews();
    accessors();
    images();
    textures();
    materials();
    meshes();
    nodes();
    scenes();
    skins();
    animations();
  }

 private:
  [[noreturn]] void fail(const std::string& pointer, const std::string& what) const {
    throw InputError(label_ + ": " + pointer + ": " + what);
  }
  std::size_t count(const char* array) const {
    auto it = doc_.find(array);
    return it == doc_.end() ? 0 : it->size();
  }
  const Json& at(const char* array, std::int64_t i) const { return doc_[array][static_cast<std::size_t>(i)]; }
  static std::string join(const std::string& pointer, const std::string& key) { return pointer + "/" + key; }

  // An integer member in [min, max]; `fallback` when absent and not required.
  std::int64_t integer(const Json& object, const char* key, const std::string& pointer, std::int64_t min, std::int64_t max,
                       bool required, std::int64_t fallback = 0) const {
    auto it = object.find(key);
    if (it == object.end()) {
      if (required) fail(join(pointer, key), "is required");
      return fallback;
    }
    if (!it->is_number_integer()) fail(join(pointer, key), "must be an integer");
    std::int64_t value;
    if (it->is_number_unsigned()) {
      const std::uint64_t u = it->get<std::uint64_t>();
      value = u > std::uint64_t(std::numeric_limits<std::int64_t>::max()) ? std::numeric_limits<std::int64_t>::max()
                                                                           : static_cast<std::int64_t>(u);
    } else {
      value = it->get<std::int64_t>();
    }
    if (value < min || value > max)
      fail(join(pointer, key), std::string(it->dump()) + " is out of range (allowed: " + std::to_string(min) + " to " +
                                   std::to_string(max) + ")");
    return value;
  }
  // An index into the top-level array `array`; -1 when absent and not required.
  std::int64_t reference(const Json& object, const char* key, const std::string& pointer, const char* array,
                         bool required = false) const {
    auto it = object.find(key);
    if (it == object.end()) {
      if (required) fail(join(pointer, key), "is required");
      return -1;
    }
    referenceValue(*it, join(pointer, key), array);
    return it->get<std::int64_t>();
  }
  void referenceValue(const Json& value, const std::string& pointer, const char* array) const {
    const std::int64_t n = static_cast<std::int64_t>(count(array));
    if (!value.is_number_integer()) fail(pointer, "must be an index into " + std::string(array));
    if ((!value.is_number_unsigned() && value.get<std::int64_t>() < 0) || value.get<std::uint64_t>() >= std::uint64_t(n))
      fail(pointer, "refers to " + std::string(array) + " " + value.dump() + ", which does not exist (the file has " +
                        std::to_string(n) + ")");
  }
  const Json* member(const Json& object, const char* key, const std::string& pointer, bool (Json::*is)() const noexcept,
                     const char* expected) const {
    auto it = object.find(key);
    if (it == object.end()) return nullptr;
    if (!((*it).*is)()) fail(join(pointer, key), std::string("must be ") + expected);
    return &*it;
  }
  const Json* objectMember(const Json& object, const char* key, const std::string& pointer) const {
    return member(object, key, pointer, &Json::is_object, "an object");
  }
  const Json* arrayMember(const Json& object, const char* key, const std::string& pointer) const {
    return member(object, key, pointer, &Json::is_array, "an array");
  }

  void topLevel() {
    if (!doc_.contains("asset") || !doc_["asset"].is_object()) fail("/asset", "is required and must be an object");
    const Json* version = member(doc_["asset"], "version", "/asset", &Json::is_string, "a string");
    if (!version) fail("/asset/version", "is required");
    if (version->get<std::string>().rfind("2.", 0) != 0) fail("/asset/version", "is " + version->dump() + "; only glTF 2.x is read (glTF 1.0 files need converting first)");
    for (const char* key : {"accessors", "animations", "buffers", "bufferViews", "cameras", "images", "materials", "meshes",
                            "nodes", "samplers", "scenes", "skins", "textures"}) {
      auto it = doc_.find(key);
      if (it == doc_.end()) continue;
      if (!it->is_array()) fail(std::string("/") + key, "must be an array");
      for (std::size_t i = 0; i < it->size(); ++i) {
        if (!(*it)[i].is_object()) fail("/" + std::string(key) + "/" + std::to_string(i), "must be an object");
      }
    }
    for (const char* key : {"extensionsUsed", "extensionsRequired"}) {
      auto it = doc_.find(key);
      if (it == doc_.end()) continue;
      if (!it->is_array()) fail(std::string("/") + key, "must be an array");
      for (std::size_t i = 0; i < it->size(); ++i) {
        if (!(*it)[i].is_string()) fail("/" + std::string(key) + "/" + std::to_string(i), "must be a string");
      }
    }
    reference(doc_, "scene", "", "scenes");
  }

  void buffers() {
    for (std::size_t i = 0; i < count("buffers"); ++i) {
      const Json& buffer = doc_["buffers"][i];
      const std::string pointer = "/buffers/" + std::to_string(i);
      integer(buffer, "byteLength", pointer, 1, kMaxByteLength, true);
      member(buffer, "uri", pointer, &Json::is_string, "a string");
    }
  }

  void bufferViews() {
    viewLength_.assign(count("bufferViews"), 0);
    viewStride_.assign(count("bufferViews"), 0);
    for (std::size_t i = 0; i < count("bufferViews"); ++i) {
      const Json& view = doc_["bufferViews"][i];
      const std::string pointer = "/bufferViews/" + std::to_string(i);
      const std::int64_t buffer = reference(view, "buffer", pointer, "buffers", true);
      const std::int64_t offset = integer(view, "byteOffset", pointer, 0, kMaxByteLength, false);
      const std::int64_t length = integer(view, "byteLength", pointer, 1, kMaxByteLength, true);
      const std::int64_t stride = integer(view, "byteStride", pointer, 4, 252, false);
      if (stride % 4 != 0) fail(join(pointer, "byteStride"), std::to_string(stride) + " is not a multiple of 4");
      const std::int64_t bufferLength = at("buffers", buffer).value("byteLength", std::int64_t(0));
      if (offset + length > bufferLength)
        fail(pointer, "byteOffset " + std::to_string(offset) + " + byteLength " + std::to_string(length) +
                          " overruns buffer " + std::to_string(buffer) + " (byteLength " + std::to_string(bufferLength) + ")");
      viewLength_[i] = length;
      viewStride_[i] = stride;
    }
  }

  // Bytes [offset, offset + span) must lie inside bufferView `view`.
  void inView(std::int64_t view, std::int64_t offset, std::int64_t span, const std::string& pointer, const char* what) const {
    if (offset + span > viewLength_[static_cast<std::size_t>(view)])
      fail(pointer, std::string(what) + " need bytes " + std::to_string(offset) + " to " + std::to_string(offset + span) +
                        " of bufferView " + std::to_string(view) + ", which has " +
                        std::to_string(viewLength_[static_cast<std::size_t>(view)]));
  }

  void accessors() {
    accessorCount_.assign(count("accessors"), 0);
    for (std::size_t i = 0; i < count("accessors"); ++i) {
      const Json& accessor = doc_["accessors"][i];
      const std::string pointer = "/accessors/" + std::to_string(i);
      const std::int64_t componentType = integer(accessor, "componentType", pointer, 0, 1 << 16, true);
      const int componentSize = componentBytesOf(componentType);
      if (componentSize == 0)
        fail(join(pointer, "componentType"), std::to_string(componentType) + " is not a glTF component type");
      const Json* type = member(accessor, "type", pointer, &Json::is_string, "a string");
      if (!type) fail(join(pointer, "type"), "is required");
      const int components = componentsOf(type->get<std::string>());
      if (components == 0) fail(join(pointer, "type"), type->dump() + " is not a glTF accessor type");
      const std::int64_t elements = integer(accessor, "count", pointer, 1, kMaxCount, true);
      accessorCount_[i] = elements;
      const std::int64_t elementSize = std::int64_t(componentSize) * components;
      const std::int64_t view = reference(accessor, "bufferView", pointer, "bufferViews");
      const std::int64_t offset = integer(accessor, "byteOffset", pointer, 0, kMaxByteLength, false);
      if (offset % componentSize != 0)
        fail(join(pointer, "byteOffset"), std::to_string(offset) + " is not a multiple of the component size " +
                                              std::to_string(componentSize));
      if (view >= 0) {
        const std::int64_t stride = viewStride_[static_cast<std::size_t>(view)];
        if (stride != 0 && stride < elementSize)
          fail(pointer, "bufferView " + std::to_string(view) + " has byteStride " + std::to_string(stride) + ", less than the " +
                            std::to_string(elementSize) + "-byte elements");
        inView(view, offset, (stride ? stride : elementSize) * (elements - 1) + elementSize, pointer, "its elements");
      }
      if (const Json* sparse = objectMember(accessor, "sparse", pointer)) {
        const std::string sp = join(pointer, "sparse");
        const std::int64_t sparseCount = integer(*sparse, "count", sp, 1, elements, true);
        const Json* indices = objectMember(*sparse, "indices", sp);
        const Json* values = objectMember(*sparse, "values", sp);
        if (!indices) fail(join(sp, "indices"), "is required");
        if (!values) fail(join(sp, "values"), "is required");
        const std::string ip = join(sp, "indices"), vp = join(sp, "values");
        const std::int64_t indexType = integer(*indices, "componentType", ip, 0, 1 << 16, true);
        if (indexType != 5121 && indexType != 5123 && indexType != 5125)
          fail(join(ip, "componentType"), std::to_string(indexType) + " is not an unsigned integer type");
        const std::int64_t indexView = reference(*indices, "bufferView", ip, "bufferViews", true);
        const std::int64_t indexOffset = integer(*indices, "byteOffset", ip, 0, kMaxByteLength, false);
        inView(indexView, indexOffset, sparseCount * componentBytesOf(indexType), ip, "the sparse indices");
        const std::int64_t valueView = reference(*values, "bufferView", vp, "bufferViews", true);
        const std::int64_t valueOffset = integer(*values, "byteOffset", vp, 0, kMaxByteLength, false);
        inView(valueView, valueOffset, sparseCount * elementSize, vp, "the sparse values");
      }
    }
  }

  void images() {
    for (std::size_t i = 0; i < count("images"); ++i) {
      const Json& image = doc_["images"][i];
      const std::string pointer = "/images/" + std::to_string(i);
      member(image, "uri", pointer, &Json::is_string, "a string");
      reference(image, "bufferView", pointer, "bufferViews");
    }
  }

  void textures() {
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

  void textureInfo(const Json& owner, const char* key, const std::string& pointer) {
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
  void textureTransform(const Json& transform, const std::string& pointer) {
    for (const char* key : {"offset", "scale"}) {
      auto it = transform.find(key);
      if (it == transform.end()) continue;
      if (!it->is_array() || it->size() != 2 || !(*it)[0].is_number() || !(*it)[1].is_number())
        fail(join(pointer, key), "must be an array of 2 numbers");
    }
    member(transform, "rotation", pointer, &Json::is_number, "a number");
    integer(transform, "texCoord", pointer, 0, 1 << 20, false);
  }

  void materials() {
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

  void accessorMap(const Json& map, const std::string& pointer) {
    if (!map.is_object()) fail(pointer, "must be an object");
    for (const auto& [name, value] : map.items()) referenceValue(value, pointer + "/" + name, "accessors");
  }

  // `weights` of a mesh or node: one number per morph target of the mesh (glTF 2.0 3.7.2.2).
  void morphWeights(const Json& owner, const std::string& pointer, std::size_t mesh) const {
    const Json* weights = arrayMember(owner, "weights", pointer);
    if (!weights) return;
    for (std::size_t k = 0; k < weights->size(); ++k) {
      if (!(*weights)[k].is_number()) fail(join(pointer, "weights/" + std::to_string(k)), "must be a number");
    }
    if (weights->size() != meshTargets_[mesh])
      fail(join(pointer, "weights"), "has " + std::to_string(weights->size()) + " weight(s); mesh " + std::to_string(mesh) +
                                         " has " + std::to_string(meshTargets_[mesh]) + " morph target(s)");
  }

  void meshes() {
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

  void nodes() {
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

  void scenes() {
    for (std::size_t i = 0; i < count("scenes"); ++i) {
      const std::string pointer = "/scenes/" + std::to_string(i);
      if (const Json* nodes = arrayMember(doc_["scenes"][i], "nodes", pointer)) {
        for (std::size_t k = 0; k < nodes->size(); ++k) referenceValue((*nodes)[k], pointer + "/nodes/" + std::to_string(k), "nodes");
      }
    }
  }

  void skins() {
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

  bool extensionUsed(const char* name) const {
    auto it = doc_.find("extensionsUsed");
    if (it == doc_.end()) return false;
    for (const Json& used : *it) {
      if (used == name) return true;
    }
    return false;
  }

  // "accessor 4 is SCALAR UNSIGNED_BYTE" (normalized when so), for messages.
  std::string accessorFormat(std::int64_t a) const {
    const Json& accessor = at("accessors", a);
    return "accessor " + std::to_string(a) + " is " + accessor["type"].get<std::string>() + " " +
           (normalized(accessor) ? "normalized " : "") + componentTypeName(accessor["componentType"].get<int>());
  }
  static bool normalized(const Json& accessor) {
    auto it = accessor.find("normalized");
    return it != accessor.end() && it->is_boolean() && it->get<bool>();
  }

  // A channel's target node and path, the channel's JSON pointer and its sampler's index.
  struct AnimatedTarget {
    std::int64_t node = -1;
    AnimationPath path = AnimationPath::translation;
    std::string channel;
    std::size_t sampler = 0;
  };

  // glTF 2.0 3.11 (animation_rules.hpp). References and names of every sampler and channel
  // come first, so that a dangling index is reported as such; then the accessors' formats
  // and counts, which need the channels' paths.
  void animations() {
    const bool animationPointer = extensionUsed("KHR_animation_pointer");
    for (std::size_t i = 0; i < count("animations"); ++i) {
      const Json& animation = doc_["animations"][i];
      const std::string pointer = "/animations/" + std::to_string(i);
      const Json* samplers = arrayMember(animation, "samplers", pointer);
      const std::size_t samplerCount = samplers ? samplers->size() : 0;
      std::vector<Interpolation> interpolation(samplerCount);
      for (std::size_t s = 0; s < samplerCount; ++s)
        interpolation[s] = animationSampler((*samplers)[s], pointer + "/samplers/" + std::to_string(s));
      std::vector<AnimatedTarget> targets;
      if (const Json* channels = arrayMember(animation, "channels", pointer)) {
        for (std::size_t c = 0; c < channels->size(); ++c) {
          const std::string cp = pointer + "/channels/" + std::to_string(c);
          if (!(*channels)[c].is_object()) fail(cp, "must be an object");
          const std::int64_t s = integer((*channels)[c], "sampler", cp, 0, static_cast<std::int64_t>(samplerCount) - 1, true);
          std::optional<AnimatedTarget> target = animationTarget((*channels)[c], cp, animationPointer);
          if (!target) continue;
          for (const AnimatedTarget& earlier : targets) {
            if (earlier.node == target->node && earlier.path == target->path)
              fail(join(cp, "target"), "animates the same node and path as " + earlier.channel + " (each target once an animation)");
          }
          target->channel = cp;
          target->sampler = static_cast<std::size_t>(s);
          targets.push_back(*target);
        }
      }
      for (std::size_t s = 0; s < samplerCount; ++s) keyframeTimes((*samplers)[s], pointer + "/samplers/" + std::to_string(s));
      for (const AnimatedTarget& target : targets) {
        const std::string sp = pointer + "/samplers/" + std::to_string(target.sampler);
        keyframeValues((*samplers)[target.sampler], sp, interpolation[target.sampler], target);
      }
    }
  }

  // A sampler's references and interpolation.
  Interpolation animationSampler(const Json& sampler, const std::string& pointer) const {
    if (!sampler.is_object()) fail(pointer, "must be an object");
    reference(sampler, "input", pointer, "accessors", true);
    reference(sampler, "output", pointer, "accessors", true);
    const Json* name = member(sampler, "interpolation", pointer, &Json::is_string, "a string");
    if (!name) return Interpolation::linear;
    const std::optional<Interpolation> interpolation = interpolationOf(name->get<std::string>());
    if (!interpolation) fail(join(pointer, "interpolation"), name->dump() + " is not one of " + kInterpolationNames);
    return *interpolation;
  }

  // A channel's target; nullopt for a channel whose values nothing checks further
  // (KHR_animation_pointer's "pointer", or a channel without a node, which is ignored).
  std::optional<AnimatedTarget> animationTarget(const Json& channel, const std::string& pointer, bool animationPointer) const {
    const Json* target = objectMember(channel, "target", pointer);
    if (!target) fail(join(pointer, "target"), "is required");
    const std::string tp = join(pointer, "target");
    const std::int64_t node = reference(*target, "node", tp, "nodes");
    const Json* name = member(*target, "path", tp, &Json::is_string, "a string");
    if (!name) fail(join(tp, "path"), "is required");
    const std::optional<AnimationPath> path = animationPathOf(name->get<std::string>());
    if (!path) {
      if (animationPointer && *name == "pointer") return std::nullopt;
      fail(join(tp, "path"), name->dump() + " is not one of " + kAnimationPathNames);
    }
    if (node < 0) return std::nullopt;
    AnimatedTarget animated;
    animated.node = node;
    animated.path = *path;
    return animated;
  }

  void keyframeTimes(const Json& sampler, const std::string& pointer) const {
    const std::int64_t input = sampler["input"].get<std::int64_t>();
    const Json& times = at("accessors", input);
    if (!keyframeTimesFormatAllowed(vectorComponentsOf(times["type"].get<std::string>()), times["componentType"].get<int>()))
      fail(join(pointer, "input"), accessorFormat(input) + "; an animation sampler's input (keyframe times) must be SCALAR FLOAT");
    if (!times.contains("min") || !times.contains("max"))
      fail(join(pointer, "input"), "accessor " + std::to_string(input) + " has no min and max, which a sampler's input must have");
  }

  // The sampler's output for `target`: its format, and as many values as the input's keyframes need.
  void keyframeValues(const Json& sampler, const std::string& pointer, Interpolation interpolation, const AnimatedTarget& target) const {
    const std::size_t morphTargets = target.path == AnimationPath::weights ? animatedMorphTargets(target) : 0;
    const std::int64_t input = sampler["input"].get<std::int64_t>(), output = sampler["output"].get<std::int64_t>();
    const Json& values = at("accessors", output);
    const std::string op = join(pointer, "output");
    const std::string channel = std::string(animationPathName(target.path)) + " channel (" + target.channel + ")";
    if (!keyframeValuesFormatAllowed(target.path, vectorComponentsOf(values["type"].get<std::string>()), values["componentType"].get<int>(),
                                     normalized(values)))
      fail(op, accessorFormat(output) + "; a " + channel + " needs " + keyframeValuesFormatNeeded(target.path));
    const std::int64_t keyframes = accessorCount_[static_cast<std::size_t>(input)];
    const std::int64_t stored = accessorCount_[static_cast<std::size_t>(output)];
    const std::uint64_t needed = keyframeValueCount(static_cast<std::uint64_t>(keyframes), interpolation, target.path, morphTargets);
    if (static_cast<std::uint64_t>(stored) != needed)
      fail(op, "accessor " + std::to_string(output) + " has " + std::to_string(stored) + " elements; a " + channel + " with " +
                   std::to_string(keyframes) + " keyframes" +
                   (interpolation == Interpolation::cubicSpline ? " (CUBICSPLINE: 3 each)" : "") +
                   (target.path == AnimationPath::weights ? " of " + std::to_string(morphTargets) + " morph target(s)" : "") +
                   " needs " + std::to_string(needed));
  }

  // The morph targets a weights channel animates: those of its node's mesh.
  std::size_t animatedMorphTargets(const AnimatedTarget& target) const {
    const Json& node = at("nodes", target.node);
    const std::string where = join(target.channel, "target");
    const std::string what = "animates the weights of node " + std::to_string(target.node);
    if (!node.contains("mesh")) fail(where, what + ", which has no mesh");
    const std::size_t mesh = node["mesh"].get<std::size_t>();
    if (meshTargets_[mesh] == 0) fail(where, what + ", whose mesh " + std::to_string(mesh) + " has no morph targets");
    return meshTargets_[mesh];
  }

  const Json& doc_;
  const std::string& label_;
  std::vector<std::int64_t> viewLength_, viewStride_, accessorCount_;
  std::vector<std::size_t> meshTargets_;  // morph targets of each mesh (meshes() fills it)
};

}  // namespace

void validateDocument(const Json& doc, const std::string& label) { Validator(doc, label).run(); }

}  // namespace tangent::gltf::detail
