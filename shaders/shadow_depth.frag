#version 330 core
// SPDX-License-Identifier: MIT
// Depth only. Alpha-tested materials (MASK, and BLEND by the rule in viewer/renderer.cpp)
// discard where the lit pass would: the same base colour factor, texture, UV set, transform
// and cutoff.
#ifdef ALPHA_MASK
#include "texture_uv.glsl"
uniform vec4 u_baseColorFactor;
uniform float u_alphaCutoff;
#ifdef HAS_BASE_COLOR_MAP
uniform sampler2D u_baseColorMap;
uniform int u_baseColorUvSet;
uniform mat3 u_baseColorUvTransform;
#endif
#endif

void main() {
#ifdef ALPHA_MASK
  float alpha = u_baseColorFactor.a;
#ifdef HAS_BASE_COLOR_MAP
  alpha *= texture(u_baseColorMap, textureUv(u_baseColorUvSet, u_baseColorUvTransform)).a;
#endif
  if (alpha < u_alphaCutoff) discard;
#endif
}
