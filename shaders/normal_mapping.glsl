// SPDX-License-Identifier: MIT
// Tangent-space normal mapping: the frame (T, B, N) with B = cross(N, T) * w, as glTF defines
// TANGENT; the map's green channel can be flipped for DirectX-convention maps.

// The frame's bitangent (Substance's "compute tangent space per fragment" choice): per fragment,
// B = cross(N, T) * sign(w) from the interpolated N and T, T made orthogonal to N first
// (MikkTSpace's recommendation, the default); or the per-vertex B = cross(N, T) * w, interpolated,
// as bakers that interpolate it expect (BITANGENT_PER_VERTEX; `vertexBitangent`, reversed on
// back faces by the caller). A define, not a uniform: a software rasteriser runs both sides of a
// branch, and the per-fragment variant then interpolates no bitangent.
vec3 frameBitangent(vec3 normal, vec4 tangent, vec3 vertexBitangent) {
#ifdef BITANGENT_PER_VERTEX
  return normalize(vertexBitangent);
#else
  vec3 n = normalize(normal);
  vec3 t = normalize(tangent.xyz - n * dot(n, tangent.xyz));
  return cross(n, t) * (tangent.w < 0.0 ? -1.0 : 1.0);
#endif
}

uniform bool u_flipGreen;  // the normal maps' (the clearcoat's too)

#ifdef HAS_NORMAL_MAP
// w = tangent::handedness(UV orientation, glTF's top-left origin), passed in by the viewer:
// counter-clockwise UVs get w = -1, so cross(N, T) * w points to the image's top (+green).
#if TANGENT_W_CCW_UV != -1
#error normal_mapping.glsl assumes the glTF handedness, w = -1 for counter-clockwise UVs
#endif
uniform sampler2D u_normalMap;
uniform float u_normalScale;

vec3 perturbedNormal(vec3 normal, vec4 tangent, vec3 bitangent, vec2 uv) {
  vec3 n = normalize(normal);
  vec3 t = normalize(tangent.xyz - n * dot(n, tangent.xyz));
  vec3 b = bitangent;  // frameBitangent's
  vec3 m = texture(u_normalMap, uv).xyz * 2.0 - 1.0;
  if (u_flipGreen) m.y = -m.y;
  m.xy *= u_normalScale;
  return normalize(mat3(t, b, n) * m);
}
#endif
