// SPDX-License-Identifier: MIT
// Validation views: geometry normal (the NORMAL attribute), tangent, bitangent, shading normal,
// UVs, handedness (the file's w, or the world-space w after the node's mirroring: +1 teal,
// -1 orange), the angular error against freshly computed tangents as a heatmap (0 blue,
// 1 deg green, 5 deg yellow, >= 20 deg red; failing corners magenta), and on the same scale the
// per-pixel angle between the file's frames and a compared set's. The colours and the heatmap's
// stops are defines from viewer/debug_colours.hpp, which the panel's legends draw too.

vec3 heatmap(float degrees) {
  if (degrees < HEATMAP_DEGREES_1)
    return mix(HEATMAP_COLOUR_0, HEATMAP_COLOUR_1, (degrees - HEATMAP_DEGREES_0) / (HEATMAP_DEGREES_1 - HEATMAP_DEGREES_0));
  if (degrees < HEATMAP_DEGREES_2)
    return mix(HEATMAP_COLOUR_1, HEATMAP_COLOUR_2, (degrees - HEATMAP_DEGREES_1) / (HEATMAP_DEGREES_2 - HEATMAP_DEGREES_1));
  return mix(HEATMAP_COLOUR_2, HEATMAP_COLOUR_3, clamp((degrees - HEATMAP_DEGREES_2) / (HEATMAP_DEGREES_3 - HEATMAP_DEGREES_2), 0.0, 1.0));
}

// The angle between two tangent frames at a fragment as shading sees them: the larger of the
// angles between the tangents (each made orthogonal to the normal) and between the bitangents,
// so that frames of opposite handedness differ by 180 degrees.
float angleDegrees(vec3 a, vec3 b) { return degrees(acos(clamp(dot(normalize(a), normalize(b)), -1.0, 1.0))); }
float frameAngleDegrees(vec3 normal, vec4 tangent, vec3 bitangent, vec4 otherTangent, vec3 otherBitangent) {
  vec3 n = normalize(normal);
  float tangents = angleDegrees(tangent.xyz - n * dot(n, tangent.xyz), otherTangent.xyz - n * dot(n, otherTangent.xyz));
  return max(tangents, angleDegrees(bitangent, otherBitangent));
}

vec3 signedColor(vec3 v) { return normalize(v) * 0.5 + 0.5; }

vec3 handednessColor(float w) { return w < 0.0 ? HANDEDNESS_NEGATIVE : HANDEDNESS_POSITIVE; }
