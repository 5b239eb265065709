#version 330 core
// Mesh fragment stage. Every feature is a define (viewer/shader_features.hpp): a material
// without a feature compiles none of its code.

in vec3 v_positionWorld;
in vec3 v_normalWorld;
in vec4 v_tangentWorld;
in vec2 v_uvNormal;
in vec2 v_uvBase;
in vec4 v_shadowCoord;
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

#include "lighting.glsl"
#include "shadows.glsl"
#include "normal_mapping.glsl"
#include "debug_views.glsl"

#ifdef HAS_BASE_COLOR_MAP
uniform sampler2D u_baseColorMap;
#endif
#ifdef HAS_SPECULAR_MAP
uniform sampler2D u_specularMap;
#endif
#ifdef HAS_SPECULAR_COLOR_MAP
uniform sampler2D u_specularColorMap;
#endif
#ifdef HAS_METALLIC_ROUGHNESS_MAP
uniform sampler2D u_metallicRoughnessMap;
#endif
#ifdef HAS_EMISSIVE_MAP
uniform sampler2D u_emissiveMap;
#endif
#ifdef USE_REFLECTION
uniform sampler2D u_sphereMap;
uniform float u_reflectivity;
#endif

void main() {
#if defined(DEBUG_FACE_ORIENTATION)
  // As Blender's overlay: front faces blue, back faces red (culling is off for this view).
  fragColor = gl_FrontFacing ? vec4(0.15, 0.35, 0.95, 1.0) : vec4(0.90, 0.15, 0.10, 1.0);
  return;
#endif
  vec3 normal = normalize(v_normalWorld);
  vec4 tangent = v_tangentWorld;
  // Only double-sided materials show back faces (the others are culled): lit as seen, with
  // N, T and B all reversed (glTF 2.0 3.9.6).
  if (!gl_FrontFacing) {
    normal = -normal;
    tangent = vec4(-tangent.xyz, -tangent.w);
  }
  vec3 shadingNormal = normal;
#ifdef HAS_NORMAL_MAP
  if (u_useNormalMap) shadingNormal = perturbedNormal(normal, tangent, v_uvNormal);
#endif

#if defined(DEBUG_GEOMETRY_NORMAL)
  fragColor = vec4(signedColor(cross(dFdx(v_positionWorld), dFdy(v_positionWorld))), 1.0);
  return;
#elif defined(DEBUG_TANGENT)
  fragColor = vec4(signedColor(tangent.xyz), 1.0);
  return;
#elif defined(DEBUG_BITANGENT)
  fragColor = vec4(signedColor(cross(normal, tangent.xyz) * tangent.w), 1.0);
  return;
#elif defined(DEBUG_SHADING_NORMAL)
  fragColor = vec4(signedColor(shadingNormal), 1.0);
  return;
#elif defined(DEBUG_UV)
  fragColor = vec4(fract(v_uvNormal), 0.0, 1.0);
  return;
#elif defined(DEBUG_HANDEDNESS)
  fragColor = vec4(handednessColor(v_tangentWorld.w), 1.0);
  return;
#elif defined(DEBUG_TANGENT_ERROR)
  fragColor = vec4(v_cornerProblems > 0.5 ? vec3(1.0, 0.0, 1.0) : heatmap(v_tangentError), 1.0);
  return;
#endif

  vec4 baseColor = u_baseColorFactor;
#ifdef HAS_BASE_COLOR_MAP
  baseColor *= texture(u_baseColorMap, v_uvBase);
#endif
  // Specular: KHR_materials_specular maps; without them a fallback from roughness/metallic.
  vec3 specularColor = u_specularColorFactor;
  float specularStrength = u_specularStrength;
  float roughness = u_roughness;
  float metallic = u_metallic;
#ifdef HAS_METALLIC_ROUGHNESS_MAP
  vec4 mr = texture(u_metallicRoughnessMap, v_uvBase);
  roughness *= mr.g;
  metallic *= mr.b;
#endif
#ifdef HAS_SPECULAR_MAP
  specularStrength *= texture(u_specularMap, v_uvBase).a;
#endif
#ifdef HAS_SPECULAR_COLOR_MAP
  specularColor *= texture(u_specularColorMap, v_uvBase).rgb;
#endif
  float shininess = u_shininess;
  if (u_shininess <= 0.0) {
    float alpha = max(roughness * roughness, 0.02);
    shininess = 2.0 / (alpha * alpha) - 2.0;
    specularStrength *= (1.0 - roughness) * (1.0 - roughness);
    specularColor *= mix(vec3(0.04), baseColor.rgb, metallic) / 0.04;
  }
  if (!u_useSpecular) specularStrength = 0.0;

  vec3 toEye = normalize(u_eyeWorld - v_positionWorld);
  SurfaceLight light = SurfaceLight(vec3(0.0), vec3(0.0), vec3(0.0));
  for (int i = 0; i < u_lightCount; ++i) {
    float shadow = 1.0;
#ifdef USE_SHADOWS
    if (i == 0) {
      vec3 toLight = u_lightPosition[0].w == 0.0 ? normalize(-u_lightPosition[0].xyz) : normalize(u_lightPosition[0].xyz - v_positionWorld);
      shadow = shadowFactor(v_shadowCoord, normal, toLight);
    }
#endif
    addLight(i, v_positionWorld, shadingNormal, toEye, shininess, shadow, light);
  }
  vec3 color = baseColor.rgb * (light.ambient + light.diffuse) + specularColor * specularStrength * light.specular;
#ifdef USE_REFLECTION
  vec3 r = mat3(u_view) * reflect(-toEye, shadingNormal);
  float m = 2.0 * sqrt(r.x * r.x + r.y * r.y + (r.z + 1.0) * (r.z + 1.0));
  color = mix(color, texture(u_sphereMap, r.xy / m + 0.5).rgb, u_reflectivity);
#endif
  color += u_emissiveFactor;
#ifdef HAS_EMISSIVE_MAP
  color += u_emissiveFactor * (texture(u_emissiveMap, v_uvBase).rgb - 1.0);
#endif
  fragColor = vec4(color, baseColor.a);
}
