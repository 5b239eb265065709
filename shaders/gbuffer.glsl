// SPDX-License-Identifier: MIT
// The deferred lit view's G-buffer (viewer/renderer.cpp, drawDeferred): what the lighting pass
// needs of each pixel's surface, written by mesh.frag with GBUFFER_PASS and read once per pixel
// by deferred.frag. Two colour targets beside the depth texture (the position comes from depth):
//   0, RGBA8:   sqrt(base colour) RGB, metallic
//   1, RGBA32UI: x: shading normal (octahedral, 12 + 12 bits), occlusion (8)
//                y: sqrt(emissive) RGB (8 each), roughness (8)
//                z: sqrt(dielectric F0) RGB (8 each), specular weight (8)
//                w: light 0's shadow slope, tan of its incidence on the geometry normal (8, 0..10)
// Square roots keep the darks' precision in 8 bits, as sRGB does. Two targets, not more: WebGL2
// promises four; one of 16 bytes takes the packing.

uint packUnorm8(float x) { return uint(clamp(x, 0.0, 1.0) * 255.0 + 0.5); }
float unpackUnorm8(uint word, int shift) { return float((word >> uint(shift)) & 0xffu) / 255.0; }
uint packUnorm4x8(vec4 v) { return packUnorm8(v.x) | (packUnorm8(v.y) << 8u) | (packUnorm8(v.z) << 16u) | (packUnorm8(v.w) << 24u); }
vec4 unpackUnorm4x8(uint word) { return vec4(unpackUnorm8(word, 0), unpackUnorm8(word, 8), unpackUnorm8(word, 16), unpackUnorm8(word, 24)); }

// Octahedral unit vectors (Cigolle et al. 2014): 12 bits per axis, under 0.05 degrees off.
vec2 signNotZero(vec2 v) { return vec2(v.x >= 0.0 ? 1.0 : -1.0, v.y >= 0.0 ? 1.0 : -1.0); }
uint packNormal12x2(vec3 n) {
  n /= abs(n.x) + abs(n.y) + abs(n.z);
  vec2 e = n.z >= 0.0 ? n.xy : (1.0 - abs(n.yx)) * signNotZero(n.xy);
  uvec2 q = uvec2(clamp(e * 0.5 + 0.5, 0.0, 1.0) * 4095.0 + 0.5);
  return q.x | (q.y << 12u);
}
vec3 unpackNormal12x2(uint word) {
  vec2 e = vec2(float(word & 0xfffu), float((word >> 12u) & 0xfffu)) / 4095.0 * 2.0 - 1.0;
  vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
  if (n.z < 0.0) n.xy = (1.0 - abs(n.yx)) * signNotZero(n.xy);
  return normalize(n);
}

const float kMaxShadowSlope = 10.0;  // shadows.glsl's limit on the slope-scaled bias

struct GSurface {
  vec3 baseColor;
  float metallic;
  vec3 normal;  // shading normal, world space
  float occlusion;
  vec3 emissive;
  float roughness;
  vec3 dielectricF0;
  float specularWeight;
  float shadowSlope;
};

#ifdef GBUFFER_PASS
void writeGBuffer(GSurface s, out vec4 target0, out uvec4 target1) {
  target0 = vec4(sqrt(clamp(s.baseColor, 0.0, 1.0)), s.metallic);
  target1 = uvec4(packNormal12x2(s.normal) | (packUnorm8(s.occlusion) << 24u),
                  packUnorm4x8(vec4(sqrt(clamp(s.emissive, 0.0, 1.0)), s.roughness)),
                  packUnorm4x8(vec4(sqrt(clamp(s.dielectricF0, 0.0, 1.0)), s.specularWeight)),
                  packUnorm8(s.shadowSlope / kMaxShadowSlope));
}
#endif

GSurface readGBuffer(vec4 target0, uvec4 target1) {
  GSurface s;
  s.baseColor = target0.rgb * target0.rgb;
  s.metallic = target0.a;
  s.normal = unpackNormal12x2(target1.x);
  s.occlusion = unpackUnorm8(target1.x, 24);
  vec4 y = unpackUnorm4x8(target1.y);
  s.emissive = y.rgb * y.rgb;
  s.roughness = y.a;
  vec4 z = unpackUnorm4x8(target1.z);
  s.dielectricF0 = z.rgb * z.rgb;
  s.specularWeight = z.a;
  s.shadowSlope = unpackUnorm8(target1.w, 0) * kMaxShadowSlope;
  return s;
}
