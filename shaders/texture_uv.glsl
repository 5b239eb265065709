// SPDX-License-Identifier: MIT
// Each texture samples its own UV set (texCoord 0 or 1) through its KHR_texture_transform
// (a 3x3 matrix from viewer/renderer.cpp). Shared by the mesh and the depth-only passes, so an
// alpha-tested shadow cuts out exactly what the lit pass cuts out. Without HAS_UV_TRANSFORMS
// every texture of the material reads TEXCOORD_0 as stored, and the selection and the matrix
// are left out (a software rasteriser would run them for every fetch).
in vec2 v_uv0;
#ifdef HAS_UV_TRANSFORMS
in vec2 v_uv1;

vec2 textureUv(int set, mat3 transform) { return (transform * vec3(set == 1 ? v_uv1 : v_uv0, 1.0)).xy; }
#else
vec2 textureUv(int set, mat3 transform) { return v_uv0; }
#endif
