#version 330 core
// SPDX-License-Identifier: MIT
// Mesh vertex stage: world-space position, normal and tangent frame; shadow-map coordinates.

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec4 a_tangent;         // xyz, w = handedness (glTF convention)
layout(location = 3) in vec2 a_uvNormal;        // the normal texture's UV set, its transform applied
layout(location = 4) in vec2 a_uv0;             // TEXCOORD_0 as stored
layout(location = 5) in vec2 a_uv1;             // TEXCOORD_1 as stored
layout(location = 6) in float a_tangentError;   // degrees from freshly computed tangents
layout(location = 7) in float a_cornerProblems; // tangent check failures (bit mask)

uniform mat4 u_model;
uniform mat3 u_normalMatrix;
uniform mat4 u_viewProjection;
uniform mat4 u_lightViewProjection;
uniform float u_uvScale;
uniform float u_mirror;  // sign of det(u_model): a mirroring transform flips the bitangent

out vec3 v_positionWorld;
out vec3 v_normalWorld;
out vec4 v_tangentWorld;
out vec2 v_uvNormal;
out vec2 v_uv0;
out vec2 v_uv1;
out vec4 v_shadowCoord;
out float v_tangentError;
out float v_cornerProblems;
invariant gl_Position;  // as in shadow_depth.vert: the depth pre-pass writes the same depths

void main() {
  vec4 world = u_model * vec4(a_position, 1.0);  // gl_Position as shadow_depth.vert computes it
  v_positionWorld = world.xyz;
  v_normalWorld = u_normalMatrix * a_normal;
  // B = cross(N, T) * w in object space; in world space cross(M N, M T) carries det(M)'s sign,
  // so w does too.
  v_tangentWorld = vec4(mat3(u_model) * a_tangent.xyz, a_tangent.w * u_mirror);
  v_uvNormal = a_uvNormal * u_uvScale;
  v_uv0 = a_uv0 * u_uvScale;
  v_uv1 = a_uv1 * u_uvScale;
  v_shadowCoord = u_lightViewProjection * world;
  v_tangentError = a_tangentError;
  v_cornerProblems = a_cornerProblems;
  gl_Position = u_viewProjection * world;
}
