// SPDX-License-Identifier: MIT
// validateDocument's Validator (validate.hpp): the document checked part by part, each check
// naming the JSON pointer of what it refuses. The parts' checks are in validate.cpp,
// validate_scene.cpp and validate_animations.cpp.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "read/accessors.hpp"
#include "read/animation_rules.hpp"
#include "tangent/gltf.hpp"

namespace tangent::gltf::detail {

using Json = nlohmann::ordered_json;

inline int componentsOf(const std::string& type) {
  static const std::array<std::pair<const char*, int>, 7> types = {
      {{"SCALAR", 1}, {"VEC2", 2}, {"VEC3", 3}, {"VEC4", 4}, {"MAT2", 4}, {"MAT3", 9}, {"MAT4", 16}}};
  for (const auto& [name, n] : types) {
    if (type == name) return n;
  }
  return 0;
}

// Components of a SCALAR or VECn; 0 for the matrices (a MAT2 is not a VEC4).
inline int vectorComponentsOf(const std::string& type) { return type.rfind("MAT", 0) == 0 ? 0 : componentsOf(type); }

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

  // The document's parts, in run()'s order. Top level, buffers, views, accessors: validate.cpp.
  void topLevel();
  void buffers();
  void bufferViews();

  // Bytes [offset, offset + span) must lie inside bufferView `view`.
  void inView(std::int64_t view, std::int64_t offset, std::int64_t span, const std::string& pointer, const char* what) const;

  void accessors();

  // Images, textures, materials, meshes, nodes, scenes, skins: validate_scene.cpp.
  void images();
  void textures();
  void textureInfo(const Json& owner, const char* key, const std::string& pointer);

  // KHR_texture_transform: offset and scale [u, v], rotation in radians, texCoord a UV set.
  void textureTransform(const Json& transform, const std::string& pointer);

  void materials();
  void accessorMap(const Json& map, const std::string& pointer);

  // `weights` of a mesh or node: one number per morph target of the mesh (glTF 2.0 3.7.2.2).
  void morphWeights(const Json& owner, const std::string& pointer, std::size_t mesh) const;

  void meshes();
  void nodes();
  void scenes();
  void skins();

  // Animations: validate_animations.cpp.
  bool extensionUsed(const char* name) const;

  // "accessor 4 is SCALAR UNSIGNED_BYTE" (normalized when so), for messages.
  std::string accessorFormat(std::int64_t a) const;
  static bool normalized(const Json& accessor);

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
  void animations();

  // A sampler's references and interpolation.
  Interpolation animationSampler(const Json& sampler, const std::string& pointer) const;

  // A channel's target; nullopt for a channel whose values nothing checks further
  // (KHR_animation_pointer's "pointer", or a channel without a node, which is ignored).
  std::optional<AnimatedTarget> animationTarget(const Json& channel, const std::string& pointer, bool animationPointer) const;

  void keyframeTimes(const Json& sampler, const std::string& pointer) const;

  // The sampler's output for `target`: its format, and as many values as the input's keyframes need.
  void keyframeValues(const Json& sampler, const std::string& pointer, Interpolation interpolation, const AnimatedTarget& target) const;

  // The morph targets a weights channel animates: those of its node's mesh.
  std::size_t animatedMorphTargets(const AnimatedTarget& target) const;

  const Json& doc_;
  const std::string& label_;
  std::vector<std::int64_t> viewLength_, viewStride_, accessorCount_;
  std::vector<std::size_t> meshTargets_;  // morph targets of each mesh (meshes() fills it)
};

}  // namespace tangent::gltf::detail
