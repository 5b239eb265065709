#version 330 core
// SPDX-License-Identifier: MIT
// Mesh vertex stage: world-space position, normal and tangent frame (shadows.glsl finds the
// shadow map's coordinates per fragment, after its normal offset).

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec4 a_tangent;         // xyz, w = handedness (glTF convention)
layout(location = 3) in vec2 a_uvNormal;        // the normal texture's UV set, its transform applied
layout(location = 4) in vec2 a_uv0;             // TEXCOORD_0 as stored
layout(location = 5) in vec2 a_uv1;             // TEXCOORD_1 as stored
layout(location = 6) in float a_tangentError;   // degrees from freshly computed tangents
layout(location = 7) in float a_cornerProblems; // tangent check failures (bit mask)
layout(location = 8) in vec4 a_tangentCompare;  // the set compared with the file's (split and compare-angle views)
layout(location = 9) in vec4 a_color;           // COLOR_0 as RGBA (white where the primitive has none)

uniform mat4 u_model;
uniform mat3 u_normalMatrix;
uniform mat4 u_viewProjection;
uniform float u_uvScale;
uniform float u_mirror;  // sign of det(u_model): a mirroring transform flips the bitangent
uniform bool u_compareSide;  // shade with a_tangentCompare instead of a_tangent (the split view's right side)

out vec3 v_positionWorld;
out vec3 v_normalWorld;
out vec4 v_tangentWorld;
out vec3 v_bitangentWorld;  // B = cross(N, T) * w at the vertex, for the per-vertex bitangent mode
#ifdef DEBUG_COMPARE_ANGLE
out vec4 v_tangentCompareWorld;
out vec3 v_bitangentCompareWorld;
#endif
out vec2 v_uvNormal;
#ifdef HAS_VERTEX_COLOR
out vec4 v_color;
#endif
out vec2 v_uv0;
out vec2 v_uv1;
out float v_tangentError;
out float v_cornerProblems;
invariant gl_Position;  // as in shadow_depth.vert: the depth pre-pass writes the same depths

// A tangent (xyz, w) in world space: xyz by the model matrix; B = cross(N, T) * w in object space
// turns into cross(M N, M T) in world space, which carries det(M)'s sign, so w does too.
vec4 tangentToWorld(vec4 tangent) { return vec4(mat3(u_model) * tangent.xyz, tangent.w * u_mirror); }
vec3 vertexBitangent(vec3 normalWorld, vec4 tangentWorld) {
  return cross(normalize(normalWorld), normalize(tangentWorld.xyz)) * (tangentWorld.w < 0.0 ? -1.0 : 1.0);
}

void main() {
  vec4 world = u_model * vec4(a_position, 1.0);  // gl_Position as shadow_depth.vert computes it
  v_positionWorld = world.xyz;
  v_normalWorld = u_normalMatrix * a_normal;
  v_tangentWorld = tangentToWorld(u_compareSide ? a_tangentCompare : a_tangent);
  v_bitangentWorld = vertexBitangent(v_normalWorld, v_tangentWorld);
#ifdef DEBUG_COMPARE_ANGLE
  v_tangentCompareWorld = tangentToWorld(a_tangentCompare);
  v_bitangentCompareWorld = vertexBitangent(v_normalWorld, v_tangentCompareWorld);
#endif
  v_uvNormal = a_uvNormal * u_uvScale;
#ifdef HAS_VERTEX_COLOR
  v_color = a_color;
#endif
  v_uv0 = a_uv0 * u_uvScale;
  v_uv1 = a_uv1 * u_uvScale;
  v_tangentError = a_tangentError;
  v_cornerProblems = a_cornerProblems;
  gl_Position = u_viewProjection * world;
}
