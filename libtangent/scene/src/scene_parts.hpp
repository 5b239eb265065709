// SPDX-License-Identifier: MIT
// The parts of loadScene (scene.cpp: load, judge, walk the node tree, pose), internal to
// tangent::scene, one file each:
//   materials.cpp    images, texture samplers, materials
//   draw_items.cpp   what a mesh's primitives become: corners, fresh and file tangents, verdicts
//   deformation.cpp  morph targets and skin influences per corner; nodes, skins, animations
//   transforms.cpp   node transforms, the nodes whose transform cannot be used, the roots
//   lights.cpp       KHR_lights_punctual lights placed by their nodes
// Below them, the JSON reading every part shares: a value that is not finite is kept as such,
// for the parts' checks to find.
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "read/asset.hpp"
#include "tangent/gltf.hpp"
#include "tangent/scene.hpp"

namespace tangent::gltf::scene_parts {

using Json = nlohmann::ordered_json;

// A JSON number as a float: NaN for what is not a number, +-infinity past FLT_MAX (1e39), where
// a plain conversion would be undefined. The checks then see what is not finite.
inline float jsonFloat(const Json& value) {
  if (!value.is_number()) return std::numeric_limits<float>::quiet_NaN();
  const double d = value.get<double>();
  if (std::abs(d) <= static_cast<double>(std::numeric_limits<float>::max())) return static_cast<float>(d);
  constexpr float kInfinity = std::numeric_limits<float>::infinity();
  return d > 0 ? kInfinity : d < 0 ? -kInfinity : std::numeric_limits<float>::quiet_NaN();
}

inline float floatValue(const Json& object, const char* key, float otherwise) {
  return object.contains(key) ? jsonFloat(object[key]) : otherwise;
}

template <std::size_t N>
void readFloats(const Json& object, const char* key, std::array<float, N>& out) {
  if (!object.contains(key) || !object[key].is_array() || object[key].size() != N) return;
  for (std::size_t i = 0; i < N; ++i) out[i] = jsonFloat(object[key][i]);
}

template <std::size_t N>
bool allFinite(const std::array<float, N>& values) {
  return std::all_of(values.begin(), values.end(), [](float v) { return std::isfinite(v); });
}

// The first element (a group of `components` values) of `values` with a value that is not
// finite, or -1 when every one is.
inline std::int64_t firstNonFinite(std::span<const float> values, std::size_t components) {
  for (std::size_t i = 0; i < values.size(); ++i)
    if (!std::isfinite(values[i])) return static_cast<std::int64_t>(i / components);
  return -1;
}

// materials.cpp
std::vector<ImageSource> readImages(const detail::Asset& asset);
std::vector<MaterialDesc> readMaterials(const Json& doc);

// draw_items.cpp
// Per-vertex values (components each) spread over the corners.
std::vector<float> perCorner(const std::vector<float>& values, int components, const std::vector<std::uint32_t>& corners);
std::vector<std::int64_t> readMeshItems(const detail::Asset& asset, int meshIndex, const std::vector<PrimitiveVerdicts>& verdicts,
                                        const SceneOptions& options, Scene& scene);
void growBounds(const DrawItem& item, const glm::mat4& world, glm::vec3& lo, glm::vec3& hi);

// deformation.cpp
void readDeformation(const detail::Asset& asset, const Json& primitive, std::size_t vertexCount, const std::vector<std::uint32_t>& corners,
                     const std::string& where, DrawItem& item, std::vector<std::string>& messages);
// Whether anything in the document can move a node or a vertex (animations, skins, morph targets).
bool posable(const Json& doc);
std::vector<SceneNode> readNodes(const Json& doc, const std::vector<char>& unusable, const std::string& file,
                                 std::vector<std::string>& messages);
std::vector<Skin> readSkins(const detail::Asset& asset, std::size_t nodeCount, std::vector<SceneNode>& nodes, std::vector<std::string>& messages);
void dropSkinsPastTheirJoints(Scene& scene, const std::string& file);
std::vector<Animation> readAnimations(const detail::Asset& asset, std::size_t nodeCount, std::vector<std::string>& messages);

// transforms.cpp
glm::mat4 localTransform(const Json& node, bool usable);
std::vector<char> unusableTransforms(const Json& doc, std::size_t nodeCount, const std::string& file, std::vector<std::string>& messages);
std::vector<int> rootNodes(const Json& doc);

// lights.cpp
std::vector<Json> lightDefinitionsOf(const Json& doc);
void addNodeLight(const Json& reference, int nodeIndex, const glm::mat4& world, const std::vector<Json>& lightDefinitions,
                  const std::string& file, Scene& scene);

}  // namespace tangent::gltf::scene_parts
