// SPDX-License-Identifier: MIT
// What glTF 2.0 (section 3.11 "Animations") allows an animation channel and its sampler: the
// target paths, the interpolations, the formats a path's keyframe values may be stored in and
// how many values a sampler's output holds. validateDocument() applies them to every file bake,
// check, info and the viewer load; the viewer's reader parses the same names with them.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

namespace tangent::gltf::detail {

enum class AnimationPath { translation, rotation, scale, weights };
enum class Interpolation { linear, step, cubicSpline };

// nullopt for any other name ("pointer" of KHR_animation_pointer among them).
std::optional<AnimationPath> animationPathOf(std::string_view name);
std::optional<Interpolation> interpolationOf(std::string_view name);
const char* animationPathName(AnimationPath path);
inline constexpr const char* kAnimationPathNames = "translation, rotation, scale, weights";
inline constexpr const char* kInterpolationNames = "LINEAR, STEP, CUBICSPLINE";

// A sampler's input: keyframe times, SCALAR FLOAT with min and max.
bool keyframeTimesFormatAllowed(int components, int componentType);

// A sampler's output for `path`: translation and scale VEC3 FLOAT; rotation VEC4 and weights
// SCALAR, each FLOAT or normalized BYTE, UNSIGNED_BYTE, SHORT or UNSIGNED_SHORT.
bool keyframeValuesFormatAllowed(AnimationPath path, int components, int componentType, bool normalized);
// The same rule in words, for messages ("VEC3 FLOAT").
const char* keyframeValuesFormatNeeded(AnimationPath path);

// Elements in the output of a sampler with `keyframes` input times: one per keyframe, three
// for CUBICSPLINE (in-tangent, value, out-tangent), times the morph targets for weights.
std::uint64_t keyframeValueCount(std::uint64_t keyframes, Interpolation interpolation, AnimationPath path,
                                 std::uint64_t morphTargets);

}  // namespace tangent::gltf::detail
