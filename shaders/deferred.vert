#version 330 core
// SPDX-License-Identifier: MIT
// The deferred lighting pass's one triangle over the whole viewport (no vertex buffer: the
// corners come from gl_VertexID), clipped to the viewport and to the scissor box.
void main() {
  vec2 corner = vec2(float((gl_VertexID & 1) * 4) - 1.0, float((gl_VertexID & 2) * 2) - 1.0);
  gl_Position = vec4(corner, 0.0, 1.0);
}
