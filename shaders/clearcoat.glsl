// SPDX-License-Identifier: MIT
// KHR_materials_clearcoat: a coat of ior 1.5 over the material, its own roughness and normal
// (the clearcoat normal texture through the primitive's TANGENT, on its own UV set and
// KHR_texture_transform), layered as the extension's README defines it:
//   coated = mix(material, clearcoat_brdf, clearcoat * fresnel_coat),
//   fresnel_coat = 0.04 + 0.96 (1 - |N_coat . V|)^5, clearcoat_brdf = V_GGX D_GGX (alpha = r^2).
// The coat's factor is clearcoatFactor times its texture's R, its roughness
// clearcoatRoughnessFactor times its texture's G.
// The coat's factor, roughness and normal (clearcoatAt) wherever the variant has the coat: in the
// PBR shading and in the clearcoat-normal view; its lighting in the PBR shading only.
#ifdef MATERIAL_CLEARCOAT
uniform float u_clearcoat;
uniform float u_clearcoatRoughness;
#ifdef HAS_CLEARCOAT_MAP
uniform sampler2D u_clearcoatMap;
uniform int u_clearcoatUvSet;
uniform mat3 u_clearcoatUvTransform;
#endif
#ifdef HAS_CLEARCOAT_ROUGHNESS_MAP
uniform sampler2D u_clearcoatRoughnessMap;
uniform int u_clearcoatRoughnessUvSet;
uniform mat3 u_clearcoatRoughnessUvTransform;
#endif
#ifdef HAS_CLEARCOAT_NORMAL_MAP
uniform sampler2D u_clearcoatNormalMap;
uniform int u_clearcoatNormalUvSet;
uniform mat3 u_clearcoatNormalUvTransform;
uniform float u_clearcoatNormalScale;
#endif

struct Clearcoat {
  float factor;
  float roughness;
  vec3 normal;
};

// normal, t, b: the geometry's frame (T orthogonal to the normal, B as frameBitangent gives it).
Clearcoat clearcoatAt(vec3 normal, vec3 t, vec3 b) {
  Clearcoat c = Clearcoat(u_clearcoat, u_clearcoatRoughness, normal);
#ifdef HAS_CLEARCOAT_MAP
  c.factor *= texture(u_clearcoatMap, textureUv(u_clearcoatUvSet, u_clearcoatUvTransform)).r;
#endif
#ifdef HAS_CLEARCOAT_ROUGHNESS_MAP
  c.roughness *= texture(u_clearcoatRoughnessMap, textureUv(u_clearcoatRoughnessUvSet, u_clearcoatRoughnessUvTransform)).g;
#endif
#ifdef HAS_CLEARCOAT_NORMAL_MAP
  if (u_useNormalMap) {
    vec3 m = texture(u_clearcoatNormalMap, textureUv(u_clearcoatNormalUvSet, u_clearcoatNormalUvTransform)).xyz * 2.0 - 1.0;
    if (u_flipGreen) m.y = -m.y;
    m.xy *= u_clearcoatNormalScale;
    c.normal = normalize(mat3(t, b, normal) * m);
  }
#endif
  c.factor = clamp(c.factor, 0.0, 1.0);
  c.roughness = clamp(c.roughness, 0.0, 1.0);
  return c;
}
#endif

#if defined(SHADING_PBR) && defined(MATERIAL_CLEARCOAT)

float clearcoatFresnel(Clearcoat c, vec3 toEye) { return 0.04 + 0.96 * pow5(1.0 - clamp(abs(dot(c.normal, toEye)), 0.0, 1.0)); }

// The coat's lobe times N.L for one light; its Fresnel is the layering's.
float clearcoatDirect(Clearcoat c, vec3 toEye, vec3 toLight) {
  float nl = dot(c.normal, toLight);
  if (nl <= 0.0) return 0.0;
  vec3 h = normalize(toLight + toEye);
  float nv = max(abs(dot(c.normal, toEye)), 1e-4);
  float alpha = max(c.roughness * c.roughness, 0.0025);
  return visibilityGgx(nl, nv, alpha) * distributionGgx(max(dot(c.normal, h), 0.0), alpha) * nl;
}

// The environment the coat reflects (before its Fresnel): prefiltered for its roughness with
// USE_IBL, else the sky pbrEnvironment uses.
vec3 clearcoatEnvironment(Clearcoat c, vec3 toEye, vec3 ambient) {
  vec3 reflected = reflect(-toEye, c.normal);
#ifdef USE_IBL
  return ambient * u_environmentScale * environmentRadiance(reflected, c.roughness);
#else
  return skyRadiance(normalize(mix(reflected, c.normal, c.roughness * c.roughness)), ambient);
#endif
}
#endif
