// SPDX-License-Identifier: MIT
// Posing a gltf::Scene: node transforms and morph weights at a time of an animation (glTF 2.0
// 3.11: STEP, LINEAR with quaternion slerp, CUBICSPLINE Hermite), skin joint matrices (3.7.3),
// and the corners of a primitive deformed by its morph targets (3.7.2.2) and its skin, on the
// CPU: position, normal and tangent (xyz by the same matrices, w kept).
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "tangent/scene.hpp"

namespace tangent::viewer {

// Which animation, and when. animation < 0: the rest pose, the nodes' own transforms.
struct PoseTime {
  int animation = -1;
  float seconds = 0;
  bool operator==(const PoseTime&) const = default;
};

// An animation named by --animation: its index, or its name; nullopt when there is none such.
std::optional<int> findAnimation(const gltf::Scene& scene, const std::string& indexOrName);
// The animations --animation can name, for its error: "0 'walk', 1 'die'" (index and name, the
// name quoted as file text; index alone where unnamed), or "none".
std::string animationNames(const gltf::Scene& scene);

struct ScenePose {
  std::vector<glm::mat4> world;             // per node (Scene::nodes)
  std::vector<std::vector<float>> weights;  // per node: morph target weights
};

// Every node's world transform and weights at `time` (time clamped to the animation's keys).
ScenePose poseScene(const gltf::Scene& scene, PoseTime time);

// Joint matrices of `skin` for a mesh on node `meshNode`: inverse(world(meshNode)) *
// world(joint) * inverseBindMatrix, so that the node's own transform still applies after them.
std::vector<glm::mat4> jointMatrices(const gltf::Skin& skin, const ScenePose& pose, std::uint32_t meshNode);

struct DeformedCorners {
  std::vector<float> positions;  // 3 per corner
  std::vector<float> normals;    // 3
  std::vector<float> tangents;   // 4, w the item's
  std::vector<float> compareTangents;  // 4: the compare set given to deformItem, deformed alike (empty without one)
};

// How a compare set follows the morph targets: the file's TANGENT deltas added, as the file's
// tangents get them (a set from a file), or the fresh generator's (DrawItem::freshOptions) computed afresh on the morphed corners
// (the set computed at load: fresh tangents of the shape drawn).
enum class CompareMorph : std::uint8_t { addDeltas, recompute };

// The item's corners with morph `weights` (missing ones 0) added, then skinned by `joints`
// (none: unskinned). Writes into `out`, reusing its memory. A `compareTangents` set (4 per
// corner) gets the morph as `compareMorph` says, then the same skinning as the item's tangents.
void deformItem(const gltf::DrawItem& item, std::span<const float> weights, std::span<const glm::mat4> joints, DeformedCorners& out,
                std::span<const float> compareTangents = {}, CompareMorph compareMorph = CompareMorph::addDeltas);

// Whether `weights` move any of the item's morph targets.
bool morphs(const gltf::DrawItem& item, std::span<const float> weights);

// For the error view on a morphing primitive: per corner, the angle in degrees between its
// morphed tangent (the file's TANGENT plus its weighted deltas) and the fresh generator's tangents
// computed afresh on its morphed positions and normals (180 where the handedness differs, 0
// where the fresh frame had no triangle of its own to come from). Skinning moves both alike, so
// it is left out: this is what judges a file's TANGENT deltas.
std::vector<float> morphedTangentErrors(const gltf::DrawItem& item, std::span<const float> weights);

}  // namespace tangent::viewer
