// SPDX-License-Identifier: MIT
// Validation views: geometry normal (the NORMAL attribute), tangent, bitangent, shading normal,
// UVs, handedness (the file's w, or the world-space w after the node's mirroring: +1 teal,
// -1 orange) and the angular error against freshly computed tangents as a heatmap (0 blue,
// 1 deg green, 5 deg yellow, >= 20 deg red; failing corners magenta).

vec3 heatmap(float degrees) {
  if (degrees < 1.0) return mix(vec3(0.10, 0.25, 0.90), vec3(0.10, 0.80, 0.20), degrees);
  if (degrees < 5.0) return mix(vec3(0.10, 0.80, 0.20), vec3(0.95, 0.90, 0.10), (degrees - 1.0) / 4.0);
  return mix(vec3(0.95, 0.90, 0.10), vec3(0.90, 0.10, 0.10), clamp((degrees - 5.0) / 15.0, 0.0, 1.0));
}

vec3 signedColor(vec3 v) { return normalize(v) * 0.5 + 0.5; }

vec3 handednessColor(float w) { return w < 0.0 ? vec3(0.95, 0.55, 0.10) : vec3(0.10, 0.70, 0.75); }
