// SPDX-License-Identifier: MIT
// The debug views' colours, written once: debug_views.glsl gets them as defines
// (debugColourDefines, added by ShaderLibrary) and the panel's legends draw them.
#pragma once

#include <array>
#include <cstdio>
#include <string>

namespace tangent::viewer {

using Rgb = std::array<float, 3>;

// The error and compare-angle views' heatmap: linear in degrees between these stops, the last
// colour beyond the last stop.
struct HeatmapStop {
  float degrees;
  const char* label;
  Rgb colour;
};
inline constexpr std::array<HeatmapStop, 4> kHeatmapStops{{
    {0, "0", {0.10f, 0.25f, 0.90f}},
    {1, "1 deg", {0.10f, 0.80f, 0.20f}},
    {5, "5 deg", {0.95f, 0.90f, 0.10f}},
    {20, ">= 20 deg", {0.90f, 0.10f, 0.10f}},
}};

// The handedness views: w = +1 and w = -1.
inline constexpr Rgb kHandednessPositive{0.10f, 0.70f, 0.75f};  // teal
inline constexpr Rgb kHandednessNegative{0.95f, 0.55f, 0.10f};  // orange

// Every view of the tangent frame (tangent, bitangent, handedness, error, compare-angle) where
// the corner has none (gltf::kUndefinedTangentW): mid grey, which no direction shows as
// (x, y, z) * 0.5 + 0.5 (a unit vector has a component of at least 1/sqrt 3) and no heatmap or
// handedness colour is.
inline constexpr Rgb kNoTangent{0.5f, 0.5f, 0.5f};

// "#define HEATMAP_COLOUR_i vec3(...)", "#define HEATMAP_DEGREES_i ...",
// "#define HANDEDNESS_POSITIVE/NEGATIVE vec3(...)" and "#define NO_TANGENT vec3(...)" lines.
inline std::string debugColourDefines() {
  auto vec3 = [](const Rgb& c) {
    char text[64];
    std::snprintf(text, sizeof text, "vec3(%.4f, %.4f, %.4f)", static_cast<double>(c[0]), static_cast<double>(c[1]), static_cast<double>(c[2]));
    return std::string(text);
  };
  std::string defines;
  for (std::size_t i = 0; i < kHeatmapStops.size(); ++i) {
    char degrees[32];
    std::snprintf(degrees, sizeof degrees, "%.4f", static_cast<double>(kHeatmapStops[i].degrees));
    defines += "#define HEATMAP_COLOUR_" + std::to_string(i) + " " + vec3(kHeatmapStops[i].colour) + "\n";
    defines += "#define HEATMAP_DEGREES_" + std::to_string(i) + " " + degrees + "\n";
  }
  defines += "#define HANDEDNESS_POSITIVE " + vec3(kHandednessPositive) + "\n";
  defines += "#define HANDEDNESS_NEGATIVE " + vec3(kHandednessNegative) + "\n";
  defines += "#define NO_TANGENT " + vec3(kNoTangent) + "\n";
  return defines;
}

}  // namespace tangent::viewer
