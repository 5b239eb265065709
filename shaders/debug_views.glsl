// SPDX-License-Identifier: MIT
// Validation views: geometry normal (the NORMAL attribute), tangent, bitangent, shading normal,
// UVs, handedness (the file's w, or the world-space w after the node's mirroring: +1 teal,
// -1 orange), the angular error against freshly computed tangents as a heatmap (0 blue,
// 1 deg green, 5 deg yellow, >= 20 deg red; failing corners magenta), and on the same scale the
// per-pixel angle between the file's frames and a compared set's.

vec3 heatmap(float degrees) {
  if (degrees < 1.0) return mix(vec3(0.10, 0.25, 0.90), vec3(0.10, 0.80, 0.20), degrees);
  if (degrees < 5.0) return mix(vec3(0.10, 0.80, 0.20), vec3(0.95, 0.90, 0.10), (degrees - 1.0) / 4.0);
  return mix(vec3(0.95, 0.90, 0.10), vec3(0.90, 0.10, 0.10), clamp((degrees - 5.0) / 15.0, 0.0, 1.0));
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

vec3 handednessColor(float w) { return w < 0.0 ? vec3(0.95, 0.55, 0.10) : vec3(0.10, 0.70, 0.75); }
