// SPDX-License-Identifier: MIT
// Validator (validator.hpp): animations, by glTF 2.0 3.11 (animation_rules.hpp).
#include <optional>
#include <string>

#include "read/validator.hpp"

namespace tangent::gltf::detail {

bool Validator::extensionUsed(const char* name) const {
  auto it = doc_.find("extensionsUsed");
  if (it == doc_.end()) return false;
  for (const Json& used : *it) {
    if (used == name) return true;
  }
  return false;
}

// "accessor 4 is SCALAR UNSIGNED_BYTE" (normalized when so), for messages.
std::string Validator::accessorFormat(std::int64_t a) const {
  const Json& accessor = at("accessors", a);
  return "accessor " + std::to_string(a) + " is " + accessor["type"].get<std::string>() + " " +
         (normalized(accessor) ? "normalized " : "") + componentTypeName(accessor["componentType"].get<int>());
}

bool Validator::normalized(const Json& accessor) {
  auto it = accessor.find("normalized");
  return it != accessor.end() && it->is_boolean() && it->get<bool>();
}

// glTF 2.0 3.11 (animation_rules.hpp). References and names of every sampler and channel
// come first, so that a dangling index is reported as such; then the accessors' formats
// and counts, which need the channels' paths.
void Validator::animations() {
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
Interpolation Validator::animationSampler(const Json& sampler, const std::string& pointer) const {
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
std::optional<Validator::AnimatedTarget> Validator::animationTarget(const Json& channel, const std::string& pointer, bool animationPointer) const {
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

void Validator::keyframeTimes(const Json& sampler, const std::string& pointer) const {
  const std::int64_t input = sampler["input"].get<std::int64_t>();
  const Json& times = at("accessors", input);
  if (!keyframeTimesFormatAllowed(vectorComponentsOf(times["type"].get<std::string>()), times["componentType"].get<int>()))
    fail(join(pointer, "input"), accessorFormat(input) + "; an animation sampler's input (keyframe times) must be SCALAR FLOAT");
  if (!times.contains("min") || !times.contains("max"))
    fail(join(pointer, "input"), "accessor " + std::to_string(input) + " has no min and max, which a sampler's input must have");
}

// The sampler's output for `target`: its format, and as many values as the input's keyframes need.
void Validator::keyframeValues(const Json& sampler, const std::string& pointer, Interpolation interpolation, const AnimatedTarget& target) const {
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
std::size_t Validator::animatedMorphTargets(const AnimatedTarget& target) const {
  const Json& node = at("nodes", target.node);
  const std::string where = join(target.channel, "target");
  const std::string what = "animates the weights of node " + std::to_string(target.node);
  if (!node.contains("mesh")) fail(where, what + ", which has no mesh");
  const std::size_t mesh = node["mesh"].get<std::size_t>();
  if (meshTargets_[mesh] == 0) fail(where, what + ", whose mesh " + std::to_string(mesh) + " has no morph targets");
  return meshTargets_[mesh];
}

}  // namespace tangent::gltf::detail
