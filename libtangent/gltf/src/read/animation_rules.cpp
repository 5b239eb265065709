// SPDX-License-Identifier: MIT
// glTF 2.0 section 3.11 "Animations" and its table of channel paths and accessor formats.
#include "read/animation_rules.hpp"

namespace tangent::gltf::detail {
namespace {

constexpr int kByte = 5120, kUnsignedByte = 5121, kShort = 5122, kUnsignedShort = 5123, kFloat = 5126;

bool floatOrNormalized(int componentType, bool normalized) {
  if (componentType == kFloat) return true;
  const bool small = componentType == kByte || componentType == kUnsignedByte || componentType == kShort ||
                     componentType == kUnsignedShort;
  return small && normalized;
}

}  // namespace

std::optional<AnimationPath> animationPathOf(std::string_view name) {
  if (name == "translation") return AnimationPath::translation;
  if (name == "rotation") return AnimationPath::rotation;
  if (name == "scale") return AnimationPath::scale;
  if (name == "weights") return AnimationPath::weights;
  return std::nullopt;
}

const char* animationPathName(AnimationPath path) {
  switch (path) {
    case AnimationPath::translation: return "translation";
    case AnimationPath::rotation: return "rotation";
    case AnimationPath::scale: return "scale";
    case AnimationPath::weights: return "weights";
  }
  return "";
}

std::optional<Interpolation> interpolationOf(std::string_view name) {
  if (name == "LINEAR") return Interpolation::linear;
  if (name == "STEP") return Interpolation::step;
  if (name == "CUBICSPLINE") return Interpolation::cubicSpline;
  return std::nullopt;
}

bool keyframeTimesFormatAllowed(int components, int componentType) { return components == 1 && componentType == kFloat; }

bool keyframeValuesFormatAllowed(AnimationPath path, int components, int componentType, bool normalized) {
  switch (path) {
    case AnimationPath::translation:
    case AnimationPath::scale: return components == 3 && componentType == kFloat;
    case AnimationPath::rotation: return components == 4 && floatOrNormalized(componentType, normalized);
    case AnimationPath::weights: return components == 1 && floatOrNormalized(componentType, normalized);
  }
  return false;
}

const char* keyframeValuesFormatNeeded(AnimationPath path) {
  switch (path) {
    case AnimationPath::translation:
    case AnimationPath::scale: return "VEC3 FLOAT";
    case AnimationPath::rotation: return "VEC4 FLOAT or normalized BYTE, UNSIGNED_BYTE, SHORT or UNSIGNED_SHORT";
    case AnimationPath::weights: return "SCALAR FLOAT or normalized BYTE, UNSIGNED_BYTE, SHORT or UNSIGNED_SHORT";
  }
  return "";
}

std::uint64_t keyframeValueCount(std::uint64_t keyframes, Interpolation interpolation, AnimationPath path,
                                 std::uint64_t morphTargets) {
  const std::uint64_t perKeyframe = interpolation == Interpolation::cubicSpline ? 3 : 1;
  return keyframes * perKeyframe * (path == AnimationPath::weights ? morphTargets : 1);
}

}  // namespace tangent::gltf::detail
