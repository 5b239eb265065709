// SPDX-License-Identifier: MIT
// glTF 2.0 3.11 (animation samplers and their interpolation, Appendix C for CUBICSPLINE),
// 3.7.3 (skins) and 3.7.2.2 (morph targets).
#include "pose.hpp"

#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numeric>

#include "tangent/tangent.hpp"
#include "tangent/text.hpp"

namespace tangent::viewer {
namespace {

using Interpolation = gltf::AnimationSampler::Interpolation;

// A node's local transform parts, so that channels can replace one of them.
struct LocalTransform {
  glm::vec3 translation{0};
  glm::quat rotation{1, 0, 0, 0};
  glm::vec3 scale{1};
  bool animated = false;  // a channel wrote T, R or S: the node's matrix (if any) no longer applies
};

// The sampler's value at `seconds` into out[0..components).
void sample(const gltf::AnimationSampler& sampler, float seconds, std::size_t components, bool quaternion, float* out) {
  const std::vector<float>& times = sampler.times;
  const bool cubic = sampler.interpolation == Interpolation::cubicSpline;
  const std::size_t stride = components * (cubic ? 3 : 1);
  // Value k of the keyframes (the middle of the in-tangent, value, out-tangent triple for cubic).
  auto value = [&](std::size_t k, std::size_t i) { return sampler.values[k * stride + (cubic ? components : 0) + i]; };
  if (seconds <= times.front() || times.size() == 1) {
    for (std::size_t i = 0; i < components; ++i) out[i] = value(0, i);
    return;
  }
  if (seconds >= times.back()) {
    for (std::size_t i = 0; i < components; ++i) out[i] = value(times.size() - 1, i);
    return;
  }
  const std::size_t k = static_cast<std::size_t>(std::upper_bound(times.begin(), times.end(), seconds) - times.begin()) - 1;
  const float delta = times[k + 1] - times[k];
  const float u = (seconds - times[k]) / delta;
  switch (sampler.interpolation) {
    case Interpolation::step:
      for (std::size_t i = 0; i < components; ++i) out[i] = value(k, i);
      return;
    case Interpolation::linear:
      if (quaternion) {
        const glm::quat a(value(k, 3), value(k, 0), value(k, 1), value(k, 2)), b(value(k + 1, 3), value(k + 1, 0), value(k + 1, 1), value(k + 1, 2));
        const glm::quat q = glm::normalize(glm::slerp(glm::normalize(a), glm::normalize(b), u));  // shortest path
        out[0] = q.x, out[1] = q.y, out[2] = q.z, out[3] = q.w;
        return;
      }
      for (std::size_t i = 0; i < components; ++i) out[i] = value(k, i) + (value(k + 1, i) - value(k, i)) * u;
      return;
    case Interpolation::cubicSpline: {
      const float u2 = u * u, u3 = u2 * u;
      for (std::size_t i = 0; i < components; ++i) {
        const float v0 = value(k, i), v1 = value(k + 1, i);
        const float outTangent0 = sampler.values[k * stride + 2 * components + i];
        const float inTangent1 = sampler.values[(k + 1) * stride + i];
        out[i] = (2 * u3 - 3 * u2 + 1) * v0 + (u3 - 2 * u2 + u) * delta * outTangent0 + (-2 * u3 + 3 * u2) * v1 +
                 (u3 - u2) * delta * inTangent1;
      }
      if (quaternion) {
        const glm::quat q = glm::normalize(glm::quat(out[3], out[0], out[1], out[2]));
        out[0] = q.x, out[1] = q.y, out[2] = q.z, out[3] = q.w;
      }
      return;
    }
  }
}

glm::mat4 localMatrix(const gltf::SceneNode& node, const LocalTransform& local) {
  if (node.hasMatrix && !local.animated) return glm::make_mat4(node.matrix.data());
  return glm::translate(glm::mat4(1), local.translation) * glm::mat4_cast(local.rotation) * glm::scale(glm::mat4(1), local.scale);
}

}  // namespace

std::optional<int> findAnimation(const gltf::Scene& scene, const std::string& indexOrName) {
  for (std::size_t a = 0; a < scene.animations.size(); ++a)
    if (scene.animations[a].name == indexOrName) return static_cast<int>(a);
  int index = -1;
  const auto [end, error] = std::from_chars(indexOrName.data(), indexOrName.data() + indexOrName.size(), index);
  if (error == std::errc() && end == indexOrName.data() + indexOrName.size() && index >= 0 && index < static_cast<int>(scene.animations.size()))
    return index;
  return std::nullopt;
}

std::string animationNames(const gltf::Scene& scene) {
  if (scene.animations.empty()) return "none";
  std::string names;
  for (std::size_t a = 0; a < scene.animations.size(); ++a) {
    const std::string& name = scene.animations[a].name;
    names += (a ? ", " : "") + std::to_string(a) + (name.empty() ? "" : " '" + text::quoted(name) + "'");
  }
  return names;
}

ScenePose poseScene(const gltf::Scene& scene, PoseTime time) {
  const std::size_t nodeCount = scene.nodes.size();
  std::vector<LocalTransform> locals(nodeCount);
  ScenePose pose;
  pose.weights.resize(nodeCount);
  for (std::size_t n = 0; n < nodeCount; ++n) {
    const gltf::SceneNode& node = scene.nodes[n];
    locals[n].translation = glm::make_vec3(node.translation.data());
    locals[n].rotation = glm::quat(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
    locals[n].scale = glm::make_vec3(node.scale.data());
    pose.weights[n] = node.weights;
  }
  if (time.animation >= 0 && time.animation < static_cast<int>(scene.animations.size())) {
    const gltf::Animation& animation = scene.animations[time.animation];
    float value[4];
    for (const gltf::AnimationChannel& channel : animation.channels) {
      if (channel.node >= nodeCount) continue;
      const gltf::AnimationSampler& sampler = animation.samplers[channel.sampler];
      LocalTransform& local = locals[channel.node];
      switch (channel.path) {
        case gltf::AnimationChannel::Path::translation:
          sample(sampler, time.seconds, 3, false, value);
          local.translation = glm::make_vec3(value);
          local.animated = true;
          break;
        case gltf::AnimationChannel::Path::rotation:
          sample(sampler, time.seconds, 4, true, value);
          local.rotation = glm::quat(value[3], value[0], value[1], value[2]);
          local.animated = true;
          break;
        case gltf::AnimationChannel::Path::scale:
          sample(sampler, time.seconds, 3, false, value);
          local.scale = glm::make_vec3(value);
          local.animated = true;
          break;
        case gltf::AnimationChannel::Path::weights: {
          const std::size_t keys = sampler.times.size() * (sampler.interpolation == Interpolation::cubicSpline ? 3 : 1);
          const std::size_t targets = sampler.values.size() / keys;
          std::vector<float>& weights = pose.weights[channel.node];
          weights.resize(targets);
          sample(sampler, time.seconds, targets, false, weights.data());
          break;
        }
      }
    }
  }
  // World transforms parent first, with a stack of our own (chains may be long).
  pose.world.assign(nodeCount, glm::mat4(1));
  std::vector<char> done(nodeCount, 0);
  std::vector<std::size_t> chain;
  for (std::size_t n = 0; n < nodeCount; ++n) {
    for (std::size_t at = n; !done[at];) {
      chain.push_back(at);
      const int parent = scene.nodes[at].parent;
      if (parent < 0 || static_cast<std::size_t>(parent) >= nodeCount || chain.size() > nodeCount) break;
      at = static_cast<std::size_t>(parent);
    }
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
      const std::size_t node = *it;
      const int parent = scene.nodes[node].parent;
      const glm::mat4 local = localMatrix(scene.nodes[node], locals[node]);
      pose.world[node] = parent >= 0 && static_cast<std::size_t>(parent) < nodeCount && done[parent] ? pose.world[parent] * local : local;
      done[node] = 1;
    }
    chain.clear();
  }
  return pose;
}

std::vector<glm::mat4> jointMatrices(const gltf::Skin& skin, const ScenePose& pose, std::uint32_t meshNode) {
  const glm::mat4 toMesh = glm::inverse(pose.world[meshNode]);
  std::vector<glm::mat4> joints(skin.joints.size());
  for (std::size_t j = 0; j < skin.joints.size(); ++j)
    joints[j] = toMesh * pose.world[skin.joints[j]] * glm::make_mat4(skin.inverseBindMatrices[j].data());
  return joints;
}

namespace {

// Fresh tangents as the load computed the item's (DrawItem::freshOptions), 4 per corner, for
// the corners' positions and normals and the item's normal-map UVs, each corner its own vertex; `sources` says where each frame came from. The
// frames nothing defines are marked undefined as the load marks the item's computed set
// (gltf::markUndefinedFrames), so a morph does not turn them into a frame the views would show.
void freshCornerTangents(const gltf::DrawItem& item, std::span<const float> positions, std::span<const float> normals, std::vector<float>& fresh,
                         std::vector<FrameSource>& sources) {
  const std::size_t corners = item.positions.size() / 3;
  std::vector<std::uint32_t> identity(corners);
  std::iota(identity.begin(), identity.end(), 0u);
  fresh.assign(corners * 4, 0.0f);
  sources.assign(corners, FrameSource{});
  if (corners == 0) return;
  computeCornerTangents({positions, normals, item.uvNormal, identity}, fresh, item.freshOptions, sources);
  gltf::markUndefinedFrames(sources, fresh);
}

}  // namespace

bool morphs(const gltf::DrawItem& item, std::span<const float> weights) {
  for (std::size_t t = 0; t < item.morphTargets.size() && t < weights.size(); ++t)
    if (weights[t] != 0) return true;
  return false;
}

void deformItem(const gltf::DrawItem& item, std::span<const float> weights, std::span<const glm::mat4> joints, DeformedCorners& out,
                std::span<const float> compareTangents, CompareMorph compareMorph) {
  const std::size_t corners = item.positions.size() / 3;
  out.positions = item.positions;
  out.normals = item.normals;
  out.tangents = item.tangents;
  out.compareTangents.assign(compareTangents.begin(), compareTangents.end());
  const bool compare = out.compareTangents.size() == out.tangents.size();
  // Morph targets: base + sum of weight * delta (TANGENT deltas are xyz; w stays).
  for (std::size_t t = 0; t < item.morphTargets.size() && t < weights.size(); ++t) {
    const float w = weights[t];
    if (w == 0) continue;
    const gltf::MorphTarget& target = item.morphTargets[t];
    if (!target.positions.empty())
      for (std::size_t i = 0; i < 3 * corners; ++i) out.positions[i] += w * target.positions[i];
    if (!target.normals.empty())
      for (std::size_t i = 0; i < 3 * corners; ++i) out.normals[i] += w * target.normals[i];
    if (!target.tangents.empty())
      for (std::size_t c = 0; c < corners; ++c)
        for (int i = 0; i < 3; ++i) {
          out.tangents[4 * c + i] += w * target.tangents[3 * c + i];
          if (compare && compareMorph == CompareMorph::addDeltas) out.compareTangents[4 * c + i] += w * target.tangents[3 * c + i];
        }
  }
  if (compare && compareMorph == CompareMorph::recompute && morphs(item, weights)) {
    std::vector<FrameSource> sources;
    freshCornerTangents(item, out.positions, out.normals, out.compareTangents, sources);
  }
  if (joints.empty() || item.influencesPerCorner == 0) return;
  // Skinning: the weighted sum of the joint matrices per corner; normals by its inverse
  // transpose, tangents (xyz) by the matrix itself.
  const auto influences = static_cast<std::size_t>(item.influencesPerCorner);
  for (std::size_t c = 0; c < corners; ++c) {
    glm::mat4 skin(0.0f);
    float total = 0;
    for (std::size_t k = 0; k < influences; ++k) {
      const float w = item.jointWeights[c * influences + k];
      const std::uint16_t joint = item.joints[c * influences + k];
      if (w == 0 || joint >= joints.size()) continue;
      skin += w * joints[joint];
      total += w;
    }
    if (total == 0) continue;  // no influence: left where it is
    const glm::mat3 linear(skin);
    const glm::vec3 p = glm::vec3(skin * glm::vec4(glm::make_vec3(&out.positions[3 * c]), 1));
    const glm::vec3 n = glm::transpose(glm::inverse(linear)) * glm::make_vec3(&out.normals[3 * c]);
    const glm::vec3 t = linear * glm::make_vec3(&out.tangents[4 * c]);
    std::copy_n(glm::value_ptr(p), 3, &out.positions[3 * c]);
    std::copy_n(glm::value_ptr(n), 3, &out.normals[3 * c]);
    std::copy_n(glm::value_ptr(t), 3, &out.tangents[4 * c]);
    if (compare) {
      const glm::vec3 other = linear * glm::make_vec3(&out.compareTangents[4 * c]);
      std::copy_n(glm::value_ptr(other), 3, &out.compareTangents[4 * c]);
    }
  }
}

std::vector<float> morphedTangentErrors(const gltf::DrawItem& item, std::span<const float> weights) {
  DeformedCorners morphed;
  deformItem(item, weights, {}, morphed);
  const std::size_t corners = item.positions.size() / 3;
  std::vector<float> fresh;
  std::vector<FrameSource> sources;
  std::vector<float> errors(corners, 0.0f);
  if (corners == 0) return errors;
  freshCornerTangents(item, morphed.positions, morphed.normals, fresh, sources);
  for (std::size_t c = 0; c < corners; ++c) {
    if (sources[c] != FrameSource::computed && sources[c] != FrameSource::inherited) continue;
    const glm::vec3 stored = glm::make_vec3(&morphed.tangents[4 * c]), computed = glm::make_vec3(&fresh[4 * c]);
    const float lengths = glm::length(stored) * glm::length(computed);
    if (!(lengths > 0) || !std::isfinite(lengths)) {
      errors[c] = 180.0f;
      continue;
    }
    const float cosine = std::clamp(glm::dot(stored, computed) / lengths, -1.0f, 1.0f);
    errors[c] = (morphed.tangents[4 * c + 3] < 0) != (fresh[4 * c + 3] < 0) ? 180.0f : glm::degrees(std::acos(cosine));
  }
  return errors;
}

}  // namespace tangent::viewer
