// SPDX-License-Identifier: MIT
// What moves a mesh: morph targets and skin influences per corner, nodes, skins and animations
// (glTF 2.0 3.5, 3.7.2.2, 3.7.3, 3.11).
#include "scene_parts.hpp"

#include <algorithm>
#include <optional>

#include "read/accessors.hpp"
#include "read/animation_rules.hpp"
#include "read/primitive.hpp"

namespace tangent::gltf::scene_parts {
namespace {

// Morph targets (POSITION, NORMAL, TANGENT deltas) per corner into item.morphTargets; TANGENT
// only where the item shows the file's tangents.
void readMorphTargets(const detail::Asset& asset, const Json& primitive, std::size_t vertexCount, const std::vector<std::uint32_t>& corners,
                      const std::string& where, DrawItem& item) {
  if (!primitive.contains("targets") || !primitive["targets"].is_array()) return;
  for (std::size_t t = 0; t < primitive["targets"].size(); ++t) {
    const Json& target = primitive["targets"][t];
    MorphTarget morph;
    const std::string prefix = where + ": morph target " + std::to_string(t) + " ";
    // The deltas of one attribute, per corner; a value that is not finite would carry every
    // corner it moves to NaN, so it is refused by element.
    auto deltas = [&](int accessor, const char* attribute) {
      const std::vector<float> values = detail::readVectors(asset.model, accessor, 3, vertexCount, prefix + attribute);
      if (const std::int64_t bad = firstNonFinite(values, 3); bad >= 0)
        throw InputError(prefix + attribute + " element " + std::to_string(bad) + " is not finite");
      return perCorner(values, 3, corners);
    };
    if (const int a = detail::accessorOf(target, "POSITION"); a >= 0) morph.positions = deltas(a, "POSITION");
    if (const int a = detail::accessorOf(target, "NORMAL"); a >= 0) morph.normals = deltas(a, "NORMAL");
    if (const int a = detail::accessorOf(target, "TANGENT"); a >= 0 && item.tangentsFromFile) morph.tangents = deltas(a, "TANGENT");
    item.morphTargets.push_back(std::move(morph));
  }
}

// Skin influences, every JOINTS_n / WEIGHTS_n pair, per corner into item.joints and
// item.jointWeights (influencesPerCorner each).
void readSkinInfluences(const detail::Asset& asset, const Json& primitive, std::size_t vertexCount, const std::vector<std::uint32_t>& corners,
                        const std::string& where, DrawItem& item) {
  const Json& attributes = primitive["attributes"];
  std::vector<std::vector<float>> joints, weights;
  for (int set = 0;; ++set) {
    const int j = detail::accessorOf(attributes, "JOINTS_" + std::to_string(set));
    const int w = detail::accessorOf(attributes, "WEIGHTS_" + std::to_string(set));
    if (j < 0 || w < 0) break;
    joints.push_back(detail::readVectors(asset.model, j, 4, vertexCount, where + ": JOINTS_" + std::to_string(set)));
    weights.push_back(detail::readVectors(asset.model, w, 4, vertexCount, where + ": WEIGHTS_" + std::to_string(set)));
    // A weight that is not finite would make the corner's skin matrix, and so the corner, NaN.
    if (const std::int64_t bad = firstNonFinite(weights.back(), 4); bad >= 0)
      throw InputError(where + ": WEIGHTS_" + std::to_string(set) + " element " + std::to_string(bad) + " is not finite");
  }
  const int sets = static_cast<int>(joints.size());
  item.influencesPerCorner = 4 * sets;
  item.joints.resize(corners.size() * item.influencesPerCorner);
  item.jointWeights.resize(corners.size() * item.influencesPerCorner);
  for (std::size_t c = 0; c < corners.size(); ++c) {
    for (int set = 0; set < sets; ++set) {
      for (int k = 0; k < 4; ++k) {
        const std::size_t out = c * item.influencesPerCorner + 4 * set + k;
        const float joint = joints[set][4 * corners[c] + k];
        item.joints[out] = static_cast<std::uint16_t>(std::clamp(joint, 0.0f, 65535.0f));
        item.jointWeights[out] = weights[set][4 * corners[c] + k];
      }
    }
  }
}

}  // namespace

// Morph targets and skin influences of a primitive, per corner. A malformed one is left out with
// a message: the primitive is still shown, undeformed.
void readDeformation(const detail::Asset& asset, const Json& primitive, std::size_t vertexCount, const std::vector<std::uint32_t>& corners,
                     const std::string& where, DrawItem& item, std::vector<std::string>& messages) {
  try {
    readMorphTargets(asset, primitive, vertexCount, corners, where, item);
  } catch (const InputError& e) {
    item.morphTargets.clear();
    messages.push_back(std::string(e.what()) + "; morph targets not applied");
  }
  try {
    readSkinInfluences(asset, primitive, vertexCount, corners, where, item);
  } catch (const InputError& e) {
    item.influencesPerCorner = 0;
    item.joints.clear();
    item.jointWeights.clear();
    messages.push_back(std::string(e.what()) + "; skin not applied");
  }
}

bool posable(const Json& doc) {
  auto nonEmpty = [&](const char* key) { return doc.contains(key) && doc[key].is_array() && !doc[key].empty(); };
  if (nonEmpty("animations") || nonEmpty("skins")) return true;
  if (!nonEmpty("meshes")) return false;
  for (const Json& mesh : doc["meshes"]) {
    for (const Json& primitive : mesh.value("primitives", Json::array()))
      if (primitive.contains("targets") && !primitive["targets"].empty()) return true;
  }
  return false;
}

// Every node's parent, local transform, morph weights and skin (glTF 2.0 3.5). A node whose
// transform is unusable (`unusable`, which flattenScene has reported) keeps the identity; a morph
// weight that is not finite is 0, with a message naming the node.
std::vector<SceneNode> readNodes(const Json& doc, const std::vector<char>& unusable, const std::string& file,
                                 std::vector<std::string>& messages) {
  const std::size_t nodeCount = doc["nodes"].size();
  std::vector<SceneNode> nodes(nodeCount);
  for (std::size_t n = 0; n < nodeCount; ++n) {
    const Json& node = doc["nodes"][n];
    SceneNode& out = nodes[n];
    if (!unusable[n]) {  // else the identity: SceneNode's defaults
      if (node.contains("matrix") && node["matrix"].is_array() && node["matrix"].size() == 16) {
        out.hasMatrix = true;
        readFloats(node, "matrix", out.matrix);
      }
      readFloats(node, "translation", out.translation);
      readFloats(node, "rotation", out.rotation);
      readFloats(node, "scale", out.scale);
    }
    out.skin = node.value("skin", -1);
    const Json* weights = nullptr;
    if (node.contains("weights") && node["weights"].is_array()) weights = &node["weights"];
    else if (node.contains("mesh") && node["mesh"].is_number_integer() && doc.contains("meshes")) {
      const int mesh = node["mesh"].get<int>();
      if (mesh >= 0 && mesh < static_cast<int>(doc["meshes"].size()) && doc["meshes"][mesh].contains("weights"))
        weights = &doc["meshes"][mesh]["weights"];
    }
    if (weights) {
      for (const Json& w : *weights) {
        const float weight = jsonFloat(w);
        if (!std::isfinite(weight))
          messages.push_back(file + ": node " + std::to_string(n) + ": morph weight " + std::to_string(out.weights.size()) +
                             " is not finite; treated as 0");
        out.weights.push_back(std::isfinite(weight) ? weight : 0.0f);
      }
    }
    for (const Json& child : node.value("children", Json::array())) {
      const auto c = child.get<std::size_t>();
      if (c < nodeCount) nodes[c].parent = static_cast<int>(n);
    }
  }
  return nodes;
}

std::vector<Skin> readSkins(const detail::Asset& asset, std::size_t nodeCount, std::vector<SceneNode>& nodes, std::vector<std::string>& messages) {
  const Json& doc = asset.json;
  std::vector<Skin> skins;
  if (!doc.contains("skins")) return skins;
  for (std::size_t s = 0; s < doc["skins"].size(); ++s) {
    const Json& json = doc["skins"][s];
    const std::string where = asset.path.string() + ": skin " + std::to_string(s);
    Skin skin;
    try {
      for (const Json& joint : json.value("joints", Json::array())) {
        const auto node = joint.get<std::int64_t>();
        if (node < 0 || static_cast<std::size_t>(node) >= nodeCount) throw InputError(where + ": joint " + std::to_string(node) + " is not a node");
        skin.joints.push_back(static_cast<std::uint32_t>(node));
      }
      const std::array<float, 16> identity{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
      skin.inverseBindMatrices.assign(skin.joints.size(), identity);
      if (const int a = detail::accessorOf(json, "inverseBindMatrices"); a >= 0) {
        const std::vector<float> matrices = detail::readVectors(asset.model, a, 16, skin.joints.size(), where + ": inverseBindMatrices");
        if (const std::int64_t bad = firstNonFinite(matrices, 16); bad >= 0)
          throw InputError(where + ": inverseBindMatrices element " + std::to_string(bad) + " is not finite");
        for (std::size_t j = 0; j < skin.joints.size(); ++j) std::copy_n(&matrices[16 * j], 16, skin.inverseBindMatrices[j].begin());
      }
    } catch (const InputError& e) {
      messages.push_back(std::string(e.what()) + "; meshes with this skin shown unskinned");
      skin = Skin{};
    }
    skins.push_back(std::move(skin));
  }
  for (SceneNode& node : nodes)
    if (node.skin >= static_cast<int>(skins.size()) || (node.skin >= 0 && skins[node.skin].joints.empty())) node.skin = -1;
  return skins;
}

// glTF 2.0 3.7.3.1: a JOINTS value is an index into the skin's joints. A node whose skin has
// fewer joints than one of its primitives names (with a weight) is drawn unskinned, with a
// message naming the node, the primitive and the joint; the rest of its skinning would be a guess.
void dropSkinsPastTheirJoints(Scene& scene, const std::string& file) {
  for (const DrawInstance& instance : scene.instances) {
    if (instance.node >= scene.nodes.size()) continue;
    SceneNode& node = scene.nodes[instance.node];
    if (node.skin < 0) continue;
    const DrawItem& item = scene.items[instance.item];
    const std::size_t jointCount = scene.skins[static_cast<std::size_t>(node.skin)].joints.size();
    for (std::size_t i = 0; i < item.joints.size(); ++i) {
      if (item.jointWeights[i] == 0 || item.joints[i] < jointCount) continue;
      const auto influences = static_cast<std::size_t>(item.influencesPerCorner);
      scene.messages.push_back(file + ": node " + std::to_string(instance.node) + ": " + item.label + ": JOINTS_" +
                               std::to_string(i % influences / 4) + " at corner " + std::to_string(i / influences) + " names joint " +
                               std::to_string(item.joints[i]) + ", past the " + std::to_string(jointCount) + " joint(s) of skin " +
                               std::to_string(node.skin) + "; the node drawn unskinned");
      node.skin = -1;
      break;
    }
  }
}

namespace {

// One animation sampler into `sampler`: its interpolation, keyframe times and values. Throws
// InputError where it cannot be used (no input or output, no keyframes, a value that is not
// finite, times that do not increase), `sampler` then holds what was read before.
void readSampler(const detail::Asset& asset, const Json& json, std::size_t s, const std::string& where, AnimationSampler& sampler) {
  // loadAsset's validation checked the name (animation_rules.hpp); absent is LINEAR.
  switch (detail::interpolationOf(json.value("interpolation", "LINEAR")).value_or(detail::Interpolation::linear)) {
    case detail::Interpolation::step: sampler.interpolation = AnimationSampler::Interpolation::step; break;
    case detail::Interpolation::cubicSpline: sampler.interpolation = AnimationSampler::Interpolation::cubicSpline; break;
    case detail::Interpolation::linear: sampler.interpolation = AnimationSampler::Interpolation::linear; break;
  }
  const int input = detail::accessorOf(json, "input"), output = detail::accessorOf(json, "output");
  if (input < 0 || output < 0) throw InputError(where + ": sampler " + std::to_string(s) + " lacks input or output");
  sampler.times = detail::readVectors(asset.model, input, 1, 0, where + ": sampler " + std::to_string(s) + " input");
  detail::AccessorData header;
  sampler.values = detail::readFloats(asset.model, output, where + ": sampler " + std::to_string(s) + " output", header);
  if (sampler.times.empty()) throw InputError(where + ": sampler " + std::to_string(s) + " has no keyframes");
  if (const std::int64_t bad = firstNonFinite(sampler.times, 1); bad >= 0)
    throw InputError(where + ": sampler " + std::to_string(s) + " input element " + std::to_string(bad) + " is not finite");
  if (const std::int64_t bad = firstNonFinite(sampler.values, 1); bad >= 0)
    throw InputError(where + ": sampler " + std::to_string(s) + " output value " + std::to_string(bad) + " is not finite");
  for (std::size_t k = 1; k < sampler.times.size(); ++k)
    if (!(sampler.times[k] > sampler.times[k - 1]))
      throw InputError(where + ": sampler " + std::to_string(s) + " input times do not increase");
}

// A channel that targets a node's transform or weights through a usable sampler, or nothing.
std::optional<AnimationChannel> channelOf(const Json& channel, const std::vector<int>& usable, std::size_t nodeCount) {
  const int sampler = channel.value("sampler", -1);
  const Json target = channel.value("target", Json::object());
  const int node = target.value("node", -1);
  const std::string path = target.value("path", "");
  AnimationChannel out;
  const std::optional<detail::AnimationPath> parsed = detail::animationPathOf(path);
  if (!parsed) return std::nullopt;  // pointer (KHR_animation_pointer) is not shown
  switch (*parsed) {
    case detail::AnimationPath::translation: out.path = AnimationChannel::Path::translation; break;
    case detail::AnimationPath::rotation: out.path = AnimationChannel::Path::rotation; break;
    case detail::AnimationPath::scale: out.path = AnimationChannel::Path::scale; break;
    case detail::AnimationPath::weights: out.path = AnimationChannel::Path::weights; break;
  }
  // Validation checked the output's format and count against the input's keyframes
  // (keyframeValueCount); what is left is data: times that do not increase.
  if (sampler < 0 || sampler >= static_cast<int>(usable.size()) || !usable[sampler] || node < 0 || node >= static_cast<int>(nodeCount))
    return std::nullopt;
  out.node = static_cast<std::uint32_t>(node);
  out.sampler = static_cast<std::uint32_t>(sampler);
  return out;
}

}  // namespace

// glTF 2.0 3.11. A channel or sampler that cannot be used is left out with a message.
std::vector<Animation> readAnimations(const detail::Asset& asset, std::size_t nodeCount, std::vector<std::string>& messages) {
  const Json& doc = asset.json;
  std::vector<Animation> animations;
  if (!doc.contains("animations")) return animations;
  for (std::size_t a = 0; a < doc["animations"].size(); ++a) {
    const Json& json = doc["animations"][a];
    const std::string where = asset.path.string() + ": animation " + std::to_string(a);
    Animation animation;
    animation.name = json.value("name", "");
    const Json samplers = json.value("samplers", Json::array());
    std::vector<int> usable(samplers.size(), 0);
    for (std::size_t s = 0; s < samplers.size(); ++s) {
      AnimationSampler sampler;
      try {
        readSampler(asset, samplers[s], s, where, sampler);
        animation.duration = std::max(animation.duration, sampler.times.back());
        usable[s] = 1;
      } catch (const InputError& e) {
        messages.push_back(std::string(e.what()) + "; its channels left out");
      }
      animation.samplers.push_back(std::move(sampler));
    }
    for (const Json& channel : json.value("channels", Json::array()))
      if (const std::optional<AnimationChannel> out = channelOf(channel, usable, nodeCount)) animation.channels.push_back(*out);
    animations.push_back(std::move(animation));
  }
  return animations;
}

}  // namespace tangent::gltf::scene_parts
