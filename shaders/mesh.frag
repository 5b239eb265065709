#version 330 core
// SPDX-License-Identifier: MIT
// Mesh fragment stage. Every feature is a define (viewer/shader_features.hpp): a material
// without a feature compiles none of its code. Two shading modes: SHADING_PBR, glTF's
// metallic-roughness model (pbr.glsl), or else the tutorials' specular-map mode (Blinn-Phong
// or Phong, lighting.glsl). Lighting is linear; the output is sRGB-encoded (colour.glsl).

in vec3 v_positionWorld;
in vec3 v_normalWorld;
in vec4 v_tangentWorld;
in vec3 v_bitangentWorld;
#ifdef DEBUG_COMPARE_ANGLE
in vec4 v_tangentCompareWorld;
in vec3 v_bitangentCompareWorld;
#endif
in vec2 v_uvNormal;
#ifdef HAS_VERTEX_COLOR
in vec4 v_color;
#endif
in float v_tangentError;
in float v_cornerProblems;

out vec4 fragColor;

uniform vec3 u_eyeWorld;
uniform mat4 u_view;
uniform vec4 u_baseColorFactor;
uniform vec3 u_specularColorFactor;
uniform float u_specularStrength;
uniform float u_shininess;
uniform vec3 u_emissiveFactor;
uniform bool u_useNormalMap;
uniform bool u_useSpecular;
uniform float u_roughness;
uniform float u_metallic;
uniform bool u_blend;          // alphaMode BLEND: the output keeps the base colour's alpha
uniform float u_exposure;      // linear factor on the lit colour before tone mapping
#ifdef DEBUG_HANDEDNESS
uniform float u_mirror;        // sign of det(u_model), as mesh.vert has it
#endif

#include "colour.glsl"
#include "texture_uv.glsl"
#include "lighting.glsl"
#include "anisotropy.glsl"
#include "pbr.glsl"
#include "shadows.glsl"
#include "normal_mapping.glsl"
#include "clearcoat.glsl"
#include "debug_views.glsl"

#ifdef HAS_BASE_COLOR_MAP
uniform sampler2D u_baseColorMap;
uniform int u_baseColorUvSet;
uniform mat3 u_baseColorUvTransform;
#endif
#ifdef HAS_SPECULAR_MAP
uniform sampler2D u_specularMap;
uniform int u_specularUvSet;
uniform mat3 u_specularUvTransform;
#endif
#ifdef HAS_SPECULAR_COLOR_MAP
uniform sampler2D u_specularColorMap;
uniform int u_specularColorUvSet;
uniform mat3 u_specularColorUvTransform;
#endif
#ifdef HAS_METALLIC_ROUGHNESS_MAP
uniform sampler2D u_metallicRoughnessMap;
uniform int u_metallicRoughnessUvSet;
uniform mat3 u_metallicRoughnessUvTransform;
#endif
#ifdef HAS_EMISSIVE_MAP
uniform sampler2D u_emissiveMap;
uniform int u_emissiveUvSet;
uniform mat3 u_emissiveUvTransform;
#endif
#ifdef HAS_OCCLUSION_MAP
uniform sampler2D u_occlusionMap;
uniform int u_occlusionUvSet;
uniform mat3 u_occlusionUvTransform;
#endif
#if defined(HAS_OCCLUSION_MAP) || defined(OCCLUSION_IN_METALLIC_ROUGHNESS_MAP)
uniform float u_occlusionStrength;
#endif
#ifdef ALPHA_MASK
uniform float u_alphaCutoff;
#endif
#ifdef USE_REFLECTION
uniform sampler2D u_sphereMap;
uniform float u_reflectivity;
#endif

void main() {
  vec4 baseColor = u_baseColorFactor;
#ifdef HAS_VERTEX_COLOR
  baseColor *= v_color;  // COLOR_0 (glTF 2.0 3.9.2: multiplies the base colour)
#endif
#ifdef HAS_BASE_COLOR_MAP
  baseColor *= texture(u_baseColorMap, textureUv(u_baseColorUvSet, u_baseColorUvTransform));
#endif
#ifdef ALPHA_MASK
  if (baseColor.a < u_alphaCutoff) discard;
#endif
  float alpha = u_blend ? baseColor.a : 1.0;

#if defined(DEBUG_FACE_ORIENTATION)
  // As Blender's overlay: front faces blue, back faces red (culling is off for this view).
  fragColor = gl_FrontFacing ? vec4(0.15, 0.35, 0.95, 1.0) : vec4(0.90, 0.15, 0.10, 1.0);
  return;
#endif
#if defined(DEBUG_TANGENT) || defined(DEBUG_BITANGENT) || defined(DEBUG_HANDEDNESS) || defined(DEBUG_HANDEDNESS_WORLD) || defined(DEBUG_TANGENT_ERROR) || defined(DEBUG_COMPARE_ANGLE) || defined(DEBUG_ANISOTROPY_DIRECTION)
  if (v_tangentWorld.w == 0.0) { fragColor = vec4(NO_TANGENT, 1.0); return; }  // no frame here: w = gltf::kUndefinedTangentW
#endif
  vec3 normal = normalize(v_normalWorld);
  vec4 tangent = v_tangentWorld;
  // Only double-sided materials show back faces (the others are culled): lit as seen, with
  // N, T and B all reversed (glTF 2.0 3.9.6).
  if (!gl_FrontFacing) {
    normal = -normal;
    tangent = vec4(-tangent.xyz, -tangent.w);
  }
  vec3 bitangent = frameBitangent(normal, tangent, gl_FrontFacing ? v_bitangentWorld : -v_bitangentWorld);
  vec3 shadingNormal = normal;
#ifdef HAS_NORMAL_MAP
  if (u_useNormalMap) shadingNormal = perturbedNormal(normal, tangent, bitangent, v_uvNormal);
#endif
#if defined(MATERIAL_ANISOTROPY) || defined(MATERIAL_CLEARCOAT)
  // The geometry's frame for the extensions that read it: T made orthogonal to the normal.
  vec3 frameTangent = normalize(tangent.xyz - normal * dot(normal, tangent.xyz));
#endif
#ifdef MATERIAL_ANISOTROPY
  Anisotropy anisotropy = anisotropyAt(normal, frameTangent, bitangent);
#endif

#if defined(DEBUG_GEOMETRY_NORMAL)
  // The interpolated NORMAL attribute (world space; reversed on back faces as T and B are).
  fragColor = vec4(signedColor(normal), 1.0);
  return;
#elif defined(DEBUG_TANGENT)
  fragColor = vec4(signedColor(tangent.xyz), 1.0);
  return;
#elif defined(DEBUG_BITANGENT)
  fragColor = vec4(signedColor(bitangent), 1.0);
  return;
#elif defined(DEBUG_SHADING_NORMAL)
  fragColor = vec4(signedColor(shadingNormal), 1.0);
  return;
#elif defined(DEBUG_UV)
  fragColor = vec4(fract(v_uvNormal), 0.0, 1.0);
  return;
#elif defined(DEBUG_HANDEDNESS)
  // The file's w: the world-space sign divided by the node's mirroring again.
  fragColor = vec4(handednessColor(v_tangentWorld.w * u_mirror), 1.0);
  return;
#elif defined(DEBUG_HANDEDNESS_WORLD)
  // w after the node's mirroring: the sign that B = cross(N, T) * w uses in world space.
  fragColor = vec4(handednessColor(v_tangentWorld.w), 1.0);
  return;
#elif defined(DEBUG_TANGENT_ERROR)
  fragColor = vec4(v_cornerProblems > 0.5 ? vec3(1.0, 0.0, 1.0) : heatmap(v_tangentError), 1.0);
  return;
#elif defined(DEBUG_COMPARE_ANGLE)
  // The compare set's frame here, reversed on back faces as the file's is, against the file's.
  vec4 other = gl_FrontFacing ? v_tangentCompareWorld : vec4(-v_tangentCompareWorld.xyz, -v_tangentCompareWorld.w);
  vec3 otherBitangent = frameBitangent(normal, other, gl_FrontFacing ? v_bitangentCompareWorld : -v_bitangentCompareWorld);
  fragColor = vec4(heatmap(frameAngleDegrees(normal, tangent, bitangent, other, otherBitangent)), 1.0);
  return;
#elif defined(DEBUG_ANISOTROPY_DIRECTION)
  // KHR_materials_anisotropy's direction in world space, (x, y, z) * 0.5 + 0.5; the "no tangent"
  // grey on materials without the extension.
#ifdef MATERIAL_ANISOTROPY
  fragColor = vec4(signedColor(anisotropy.direction), 1.0);
#else
  fragColor = vec4(NO_TANGENT, 1.0);
#endif
  return;
#elif defined(DEBUG_CLEARCOAT_NORMAL)
  // KHR_materials_clearcoat's normal in world space: its normal map through the TANGENT frame
  // (the geometry's normal where the coat has no map); grey on materials without a coat, and
  // where the coat's map needs a frame nothing defines.
#ifdef MATERIAL_CLEARCOAT
#ifdef HAS_CLEARCOAT_NORMAL_MAP
  if (v_tangentWorld.w == 0.0) { fragColor = vec4(NO_TANGENT, 1.0); return; }
#endif
  fragColor = vec4(signedColor(clearcoatAt(normal, frameTangent, bitangent).normal), 1.0);
#else
  fragColor = vec4(NO_TANGENT, 1.0);
#endif
  return;
#endif

#ifdef MATERIAL_UNLIT
  // KHR_materials_unlit: the base colour as it is, no lights, no exposure, no tone mapping.
  fragColor = vec4(linearToSrgb(baseColor.rgb), alpha);
  return;
#else
  float roughness = u_roughness;
  float metallic = u_metallic;
#ifdef HAS_METALLIC_ROUGHNESS_MAP
  vec4 mr = texture(u_metallicRoughnessMap, textureUv(u_metallicRoughnessUvSet, u_metallicRoughnessUvTransform));
  roughness *= mr.g;
  metallic *= mr.b;
#endif
  roughness = clamp(roughness, 0.0, 1.0);
  metallic = clamp(metallic, 0.0, 1.0);
  // KHR_materials_specular: strength (A of its texture) and colour.
  vec3 specularColor = u_specularColorFactor;
  float specularStrength = u_specularStrength;
#ifdef HAS_SPECULAR_MAP
  specularStrength *= texture(u_specularMap, textureUv(u_specularUvSet, u_specularUvTransform)).a;
#endif
#ifdef HAS_SPECULAR_COLOR_MAP
  vec4 specularColorTexel = texture(u_specularColorMap, textureUv(u_specularColorUvSet, u_specularColorUvTransform));
  specularColor *= specularColorTexel.rgb;
#ifdef SPECULAR_IN_COLOR_MAP
  specularStrength *= specularColorTexel.a;  // specularTexture is this texture: one fetch
#endif
#endif
  if (!u_useSpecular) specularStrength = 0.0;
  float occlusion = 1.0;
#ifdef HAS_OCCLUSION_MAP
  occlusion = 1.0 + u_occlusionStrength * (texture(u_occlusionMap, textureUv(u_occlusionUvSet, u_occlusionUvTransform)).r - 1.0);
#elif defined(OCCLUSION_IN_METALLIC_ROUGHNESS_MAP) && defined(HAS_METALLIC_ROUGHNESS_MAP)
  occlusion = 1.0 + u_occlusionStrength * (mr.r - 1.0);  // occlusionTexture is this texture: one fetch
#endif

  vec3 toEye = normalize(u_eyeWorld - v_positionWorld);
  vec3 ambient = vec3(0.0);
#ifdef SHADING_PBR
#ifdef MATERIAL_ANISOTROPY
  PbrSurface surface = PbrSurface(baseColor.rgb, metallic, roughness, min(vec3(0.04) * specularColor, vec3(1.0)), specularStrength, anisotropy);
#else
  PbrSurface surface = PbrSurface(baseColor.rgb, metallic, roughness, min(vec3(0.04) * specularColor, vec3(1.0)), specularStrength);
#endif
  vec3 color = vec3(0.0);
#ifdef MATERIAL_CLEARCOAT
  Clearcoat coat = clearcoatAt(normal, frameTangent, bitangent);
  vec3 coatColor = vec3(0.0);
#endif
#else
  // Without KHR_materials_specular, highlights follow roughness and metallic: shininess from
  // the GGX width, metals tint their highlight and lose their diffuse part.
  float shininess = u_shininess;
  vec3 diffuseColor = baseColor.rgb;
  if (u_shininess <= 0.0) {
    float a = max(roughness * roughness, 0.02);
    shininess = 2.0 / (a * a) - 2.0;
    specularStrength *= (1.0 - roughness) * (1.0 - roughness);
    specularColor *= mix(vec3(1.0), baseColor.rgb, metallic);
    diffuseColor *= 1.0 - metallic;
  }
  SurfaceLight light = SurfaceLight(vec3(0.0), vec3(0.0), vec3(0.0));
#endif
  // Light 0's shadow, looked up once outside the loop (which then has no texture fetch).
  float shadow0 = 1.0;
#ifdef USE_SHADOWS
  {
    vec3 toLight;
    lightAt(0, v_positionWorld, toLight);
    shadow0 = shadowFactor(shadowFaceNormal(normal), normal, toLight);
  }
#endif
  // The variant's light count: a constant trip count the compiler can unroll.
  for (int i = 0; i < kLightCount; ++i) {
    float shadow = i == 0 ? shadow0 : 1.0;
#ifdef SHADING_PBR
    vec3 toLight;
    float attenuation = lightAt(i, v_positionWorld, toLight);
    ambient += u_lightAmbient[i] * attenuation;
    color += pbrDirect(surface, shadingNormal, toEye, toLight) * u_lightDiffuse[i] * (kLightToIlluminance * attenuation * shadow);
#ifdef MATERIAL_CLEARCOAT
    coatColor += clearcoatDirect(coat, toEye, toLight) * u_lightDiffuse[i] * (kLightToIlluminance * attenuation * shadow);
#endif
#else
    addLight(i, v_positionWorld, shadingNormal, toEye, shininess, shadow, light);
#endif
  }
#ifdef SHADING_PBR
  color += pbrEnvironment(surface, shadingNormal, toEye, ambient) * occlusion;
#ifdef MATERIAL_CLEARCOAT
  coatColor += clearcoatEnvironment(coat, toEye, ambient) * occlusion;
  float coatWeight = coat.factor * clearcoatFresnel(coat, toEye);
  color = mix(color, coatColor, coatWeight);
#endif
#else
  vec3 color = diffuseColor * (light.ambient * occlusion + light.diffuse) + specularColor * specularStrength * light.specular;
#endif
#ifdef USE_REFLECTION
  vec3 r = mat3(u_view) * reflect(-toEye, shadingNormal);
  float m = 2.0 * sqrt(r.x * r.x + r.y * r.y + (r.z + 1.0) * (r.z + 1.0));
  color = mix(color, texture(u_sphereMap, r.xy / m + 0.5).rgb, u_reflectivity);
#endif
  vec3 emissive = u_emissiveFactor;
#ifdef HAS_EMISSIVE_MAP
  emissive *= texture(u_emissiveMap, textureUv(u_emissiveUvSet, u_emissiveUvTransform)).rgb;
#endif
#if defined(SHADING_PBR) && defined(MATERIAL_CLEARCOAT)
  emissive *= 1.0 - coatWeight;  // the coat lies over the emission too (KHR_materials_clearcoat)
#endif
  fragColor = vec4(linearToSrgb(toneMap((color + emissive) * u_exposure)), alpha);
#endif
}
