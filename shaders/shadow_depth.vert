#version 330 core
// SPDX-License-Identifier: MIT
// Depth only: the shadow map from light 0 (u_viewProjection the light's) and the optional
// depth pre-pass (the camera's; gl_Position computed as mesh.vert computes it, and invariant
// there too, so the lit pass's depths equal these). Masked materials pass their UVs on.
layout(location = 0) in vec3 a_position;
#ifdef ALPHA_MASK
layout(location = 4) in vec2 a_uv0;
layout(location = 5) in vec2 a_uv1;
uniform float u_uvScale;
out vec2 v_uv0;
out vec2 v_uv1;
#endif
uniform mat4 u_model;
uniform mat4 u_viewProjection;
invariant gl_Position;
void main() {
#ifdef ALPHA_MASK
  v_uv0 = a_uv0 * u_uvScale;
  v_uv1 = a_uv1 * u_uvScale;
#endif
  vec4 world = u_model * vec4(a_position, 1.0);
  gl_Position = u_viewProjection * world;
}
