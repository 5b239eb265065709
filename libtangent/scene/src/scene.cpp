// SPDX-License-Identifier: MIT
// Flattening a glTF document for display (see tangent/scene.hpp): load, judge (check's verdicts),
// walk the node tree placing lights and instances, then what poses it. The parts each phase
// reads are in the files scene_parts.hpp lists.
#include "tangent/scene.hpp"

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "check/check_primitive.hpp"
#include "entry_point.hpp"
#include "scene_parts.hpp"

namespace tangent::gltf {
namespace {

using namespace scene_parts;

// check's verdict on every corner it judges (checkCorners with options.check): what the error
// view shows. A file check cannot judge is still shown, without verdicts, and a message says why.
std::vector<PrimitiveVerdicts> judgeCorners(const detail::Asset& asset, const std::filesystem::path& input, const SceneOptions& options,
                                            std::vector<std::string>& messages) {
  try {
    return detail::checkCorners(asset, input, options.check);
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {
    messages.push_back(std::string(e.what()) + "; tangent check cannot judge it, so the error view shows no verdict");
    return {};
  }
}

// Each mesh's items, read on the mesh's first instance (readMeshItems) and shared by the rest,
// and the box of the instances placed so far.
struct Instancing {
  const detail::Asset& asset;
  const std::vector<PrimitiveVerdicts>& verdicts;
  const SceneOptions& options;
  std::vector<std::optional<std::vector<std::int64_t>>> meshItems;
  glm::vec3 lo = glm::vec3(std::numeric_limits<float>::max()), hi = glm::vec3(-std::numeric_limits<float>::max());
};

// A node's world transform: its parent's times its own. Where each is finite but their product
// is not (scales of 1e30 under 1e30), the parent's alone, with a message.
glm::mat4 worldTransform(const Json& node, int nodeIndex, const glm::mat4& parent, bool usable, const std::string& file,
                         std::vector<std::string>& messages) {
  const glm::mat4 world = parent * localTransform(node, usable);
  const auto finite = [](float v) { return std::isfinite(v); };
  if (usable && !std::all_of(glm::value_ptr(world), glm::value_ptr(world) + 16, finite)) {
    messages.push_back(file + ": node " + std::to_string(nodeIndex) +
                       ": world transform not finite (its transforms' product overflows); its own treated as identity");
    return parent;
  }
  return world;
}

// A node's mesh drawn under `world`: a DrawInstance per primitive shown, each growing the box.
void instanceMesh(const Json& node, int nodeIndex, const glm::mat4& world, Instancing& instancing, Scene& scene) {
  if (!node.contains("mesh")) return;
  const int meshIndex = node["mesh"].get<int>();
  auto& meshItems = instancing.meshItems;
  if (meshIndex < 0 || meshIndex >= static_cast<int>(meshItems.size())) return;
  if (!meshItems[meshIndex]) meshItems[meshIndex] = readMeshItems(instancing.asset, meshIndex, instancing.verdicts, instancing.options, scene);
  for (const std::int64_t item : *meshItems[meshIndex]) {
    if (item < 0) continue;
    DrawInstance instance;
    instance.item = static_cast<std::uint32_t>(item);
    instance.node = static_cast<std::uint32_t>(nodeIndex);
    std::copy(glm::value_ptr(world), glm::value_ptr(world) + 16, instance.world.begin());
    growBounds(scene.items[static_cast<std::size_t>(item)], world, instancing.lo, instancing.hi);
    scene.instances.push_back(instance);
  }
}

// The default scene's nodes, each placed once: its world transform, its light, its mesh's
// instances. Depth first with a stack of its own, so that a chain of a million nodes needs no
// call stack. loadAsset's validation leaves each node one parent at most and no cycle; a node
// that the scene lists twice, or lists beside an ancestor, is shown once, so each node costs one
// visit. Returns how many times a node was reached again.
std::size_t walkNodes(const Json& doc, const std::vector<char>& unusableTransform, const std::vector<Json>& lightDefinitions,
                      const std::string& file, Instancing& instancing, Scene& scene) {
  const std::size_t nodeCount = unusableTransform.size();
  std::vector<char> visited(nodeCount, 0);
  std::size_t reachedAgain = 0;
  std::vector<std::pair<int, glm::mat4>> stack;
  const std::vector<int> roots = rootNodes(doc);
  for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.emplace_back(*it, glm::mat4(1));
  while (!stack.empty()) {
    const auto [nodeIndex, parent] = stack.back();
    stack.pop_back();
    if (nodeIndex < 0 || nodeIndex >= static_cast<int>(nodeCount)) continue;
    if (visited[nodeIndex]) {
      ++reachedAgain;
      continue;
    }
    visited[nodeIndex] = 1;
    const Json& node = doc["nodes"][nodeIndex];
    const glm::mat4 world = worldTransform(node, nodeIndex, parent, !unusableTransform[nodeIndex], file, scene.messages);
    // Pushed in reverse so that nodes are visited in document order (depth first).
    if (node.contains("children")) {
      const Json& children = node["children"];
      for (auto it = children.rbegin(); it != children.rend(); ++it) stack.emplace_back(it->get<int>(), world);
    }
    if (node.contains("extensions") && node["extensions"].contains("KHR_lights_punctual"))
      addNodeLight(node["extensions"]["KHR_lights_punctual"], nodeIndex, world, lightDefinitions, file, scene);
    instanceMesh(node, nodeIndex, world, instancing, scene);
  }
  return reachedAgain;
}

Scene flattenScene(const std::filesystem::path& input, const SceneOptions& options) {
  const detail::Asset asset = detail::loadAsset(input, options.assetRoot);
  const Json& doc = asset.json;
  const std::string file = input.string();
  Scene scene;
  scene.messages = asset.warnings;
  scene.images = readImages(asset);
  scene.materials = readMaterials(doc);
  const std::vector<PrimitiveVerdicts> verdicts =
      options.judge ? judgeCorners(asset, input, options, scene.messages) : std::vector<PrimitiveVerdicts>{};
  const std::vector<Json> lightDefinitions = lightDefinitionsOf(doc);
  const std::size_t nodeCount = doc.contains("nodes") ? doc["nodes"].size() : 0;
  const std::vector<char> unusableTransform = unusableTransforms(doc, nodeCount, file, scene.messages);

  Instancing instancing{asset, verdicts, options, {}};
  instancing.meshItems.resize(doc.contains("meshes") ? doc["meshes"].size() : 0);
  const std::size_t reachedAgain = walkNodes(doc, unusableTransform, lightDefinitions, file, instancing, scene);

  if (nodeCount > 0 && posable(doc)) {
    scene.nodes = readNodes(doc, unusableTransform, file, scene.messages);
    scene.skins = readSkins(asset, nodeCount, scene.nodes, scene.messages);
    dropSkinsPastTheirJoints(scene, file);
    scene.animations = readAnimations(asset, nodeCount, scene.messages);
  }
  if (reachedAgain > 0)
    scene.messages.push_back(file + ": " + std::to_string(reachedAgain) +
                             " node(s) reached again from the scene's roots (listed twice, or beside an ancestor); each shown once");
  if (instancing.lo.x <= instancing.hi.x) {
    scene.boundsMin = {instancing.lo.x, instancing.lo.y, instancing.lo.z};
    scene.boundsMax = {instancing.hi.x, instancing.hi.y, instancing.hi.z};
  }
  return scene;
}

}  // namespace

Scene loadScene(const std::filesystem::path& input, const SceneOptions& options) {
  return detail::throwingInputError(input, [&] { return flattenScene(input, options); });
}

}  // namespace tangent::gltf
