// SPDX-License-Identifier: MIT
// glTF 2.0 metallic-roughness BRDF, as the specification's Appendix B writes it:
//   metal_brdf      = specular_brdf(a) * (baseColor + (1 - baseColor) (1 - V.H)^5)
//   dielectric_brdf = fresnel_mix(ior 1.5, diffuse_brdf(baseColor), specular_brdf(a))
//   material        = mix(dielectric_brdf, metal_brdf, metallic),  a = roughness^2
// with specular_brdf = V_GGX (Smith height-correlated, already divided by 4 |N.L| |N.V|) * D_GGX
// and diffuse_brdf = baseColor / pi. KHR_materials_specular scales the dielectric's F0 by its
// colour and its specular lobe by its strength. Plus an environment term: an ambient
// radiance (the lights' ambient colours) through the same split into diffuse and specular,
// with the Fresnel of the view angle (Schlick, roughness-limited) standing in for the
// pre-integrated environment BRDF, from a sky brighter above than below; or, with USE_IBL, the
// built-in environment by the split-sum approximation (ibl.glsl). Occlusion scales the
// environment term only. KHR_materials_anisotropy's lobe: specularLobe (anisotropy.glsl).
#ifdef SHADING_PBR
const float kPi = 3.14159265;
#include "ibl.glsl"

struct PbrSurface {
  vec3 baseColor;
  float metallic;
  float roughness;
  vec3 dielectricF0;      // 0.04 (ior 1.5), times KHR_materials_specular's colour
  float specularWeight;   // KHR_materials_specular strength; 0 turns specular off
#ifdef MATERIAL_ANISOTROPY
  Anisotropy anisotropy;  // anisotropy.glsl
#endif
};

float pow5(float x) {
  float x2 = x * x;
  return x2 * x2 * x;
}

float distributionGgx(float nh, float alpha) {
  float a2 = alpha * alpha;
  float d = nh * nh * (a2 - 1.0) + 1.0;
  return a2 / (kPi * d * d);
}

// V = G / (4 |N.L| |N.V|), Smith height-correlated.
float visibilityGgx(float nl, float nv, float alpha) {
  float a2 = alpha * alpha;
  float l = nl + sqrt(a2 + (1.0 - a2) * nl * nl);
  float v = nv + sqrt(a2 + (1.0 - a2) * nv * nv);
  return 1.0 / (l * v);
}

float maxComponent(vec3 v) { return max(v.r, max(v.g, v.b)); }

#ifdef MATERIAL_ANISOTROPY
// Anisotropic GGX (anisotropy.glsl): 1 / (pi at ab (th^2 / at^2 + bh^2 / ab^2 + nh^2)^2), written
// so that no term divides by a small alpha.
float distributionGgxAnisotropic(float nh, float th, float bh, float at, float ab) {
  float a2 = at * ab;
  vec3 f = vec3(ab * th, at * bh, a2 * nh);
  float w2 = a2 / dot(f, f);
  return a2 * w2 * w2 / kPi;
}

// Smith height-correlated, already divided by 4 |N.L| |N.V|.
float visibilityGgxAnisotropic(float nl, float nv, float tv, float bv, float tl, float bl, float at, float ab) {
  float lambdaV = nl * length(vec3(at * tv, ab * bv, nv));
  float lambdaL = nv * length(vec3(at * tl, ab * bl, nl));
  return 0.5 / (lambdaV + lambdaL);
}
#endif

// The specular lobe V * D for one light: GGX, or with MATERIAL_ANISOTROPY its anisotropic form
// (alpha_t = mix(alpha, 1, strength^2) along the direction, alpha_b = alpha across it).
float specularLobe(PbrSurface s, vec3 n, vec3 toEye, vec3 toLight, vec3 h, float nl, float nv, float alpha) {
#ifdef MATERIAL_ANISOTROPY
  vec3 t = s.anisotropy.direction, b = s.anisotropy.across;
  float at = mix(alpha, 1.0, s.anisotropy.strength * s.anisotropy.strength);
  return visibilityGgxAnisotropic(nl, nv, dot(t, toEye), dot(b, toEye), dot(t, toLight), dot(b, toLight), at, alpha) *
         distributionGgxAnisotropic(max(dot(n, h), 0.0), dot(t, h), dot(b, h), at, alpha);
#else
  return visibilityGgx(nl, nv, alpha) * distributionGgx(max(dot(n, h), 0.0), alpha);
#endif
}

// The normal the environment's specular reflection is taken about: n, or with anisotropy bent
// towards the plane across the direction, as the Sample Viewer's anisotropic IBL bends it.
vec3 reflectionNormal(PbrSurface s, vec3 n, vec3 toEye) {
#ifdef MATERIAL_ANISOTROPY
  vec3 across = cross(s.anisotropy.direction, toEye);
  vec3 anisotropicNormal = cross(across, s.anisotropy.direction);
  float bend = 1.0 - s.anisotropy.strength * (1.0 - s.roughness);
  bend *= bend;
  bend *= bend;
  return dot(anisotropicNormal, anisotropicNormal) > 1e-8 ? normalize(mix(anisotropicNormal, n, bend)) : n;
#else
  return n;
#endif
}

// BRDF times N.L for one light direction.
vec3 pbrDirect(PbrSurface s, vec3 n, vec3 toEye, vec3 toLight) {
  float nl = dot(n, toLight);
  if (nl <= 0.0) return vec3(0.0);
  vec3 h = normalize(toLight + toEye);
  float nv = max(abs(dot(n, toEye)), 1e-4);
  float vh = max(dot(toEye, h), 0.0);
  float alpha = max(s.roughness * s.roughness, 0.0025);  // a mirror would be a single-pixel sparkle
  float specular = specularLobe(s, n, toEye, toLight, h, nl, nv, alpha);
  float fresnelWeight = pow5(1.0 - vh);
  vec3 diffuse = s.baseColor / kPi;
  vec3 dielectricF = s.specularWeight * (s.dielectricF0 + (1.0 - s.dielectricF0) * fresnelWeight);
  vec3 dielectric = diffuse * (1.0 - maxComponent(dielectricF)) + dielectricF * specular;
  vec3 metal = (s.baseColor + (1.0 - s.baseColor) * fresnelWeight) * specular * sign(s.specularWeight);
  return mix(dielectric, metal, s.metallic) * nl;
}

// The environment: a sky brighter above than below (world +y), its mean over the sphere the
// lights' ambient colour, so that normals, and normal maps, show on metals too.
vec3 skyRadiance(vec3 direction, vec3 ambient) { return ambient * (0.2 + 0.8 * (direction.y + 1.0)); }

vec3 pbrEnvironment(PbrSurface s, vec3 n, vec3 toEye, vec3 ambient) {
  float nv = clamp(abs(dot(n, toEye)), 0.0, 1.0);
#ifdef USE_IBL
  // The specular lobe's integral F0 A + F90 B (F90 = 1), KHR_materials_specular's strength
  // scaling the dielectric's; the diffuse part keeps what the dielectric's specular leaves.
  vec2 ab = environmentBrdf(nv, s.roughness);
  vec3 dielectricSpecular = s.specularWeight * (s.dielectricF0 * ab.x + ab.y);
  vec3 metalSpecular = (s.baseColor * ab.x + ab.y) * sign(s.specularWeight);
  vec3 specular = mix(dielectricSpecular, metalSpecular, s.metallic);
  vec3 diffuse = (1.0 - s.metallic) * s.baseColor * (1.0 - maxComponent(dielectricSpecular));
  vec3 level = ambient * u_environmentScale;
  return level * (diffuse * environmentIrradiance(n) + specular * environmentRadiance(reflect(-toEye, reflectionNormal(s, n, toEye)), s.roughness));
#else
  float fresnelWeight = pow5(1.0 - nv);
  vec3 dielectricF0 = s.specularWeight * s.dielectricF0;
  vec3 f0 = mix(dielectricF0, s.baseColor * sign(s.specularWeight), s.metallic);
  vec3 f90 = max(vec3(1.0 - s.roughness), f0) * sign(s.specularWeight);
  vec3 specular = f0 + (f90 - f0) * fresnelWeight;
  vec3 diffuse = (1.0 - s.metallic) * s.baseColor * (1.0 - maxComponent(dielectricF0));
  // Rougher surfaces see the sky blurred towards the normal's direction.
  vec3 reflected = normalize(mix(reflect(-toEye, reflectionNormal(s, n, toEye)), n, s.roughness * s.roughness));
  return diffuse * skyRadiance(n, ambient) + specular * skyRadiance(reflected, ambient);
#endif
}
#endif
