// SPDX-License-Identifier: MIT
// Lights: directional (position.w = 0, xyz = direction the light travels) and positional
// (position.w = 1) with ambient, diffuse and specular colours, attenuation 1/(k0 + k1 d + k2 d^2)
// and an optional spot cone. Both shading modes read them: the specular-map mode
// (Blinn-Phong with the half vector or Phong with the reflection vector, as the tutorials teach)
// and the metallic-roughness mode (pbr.glsl), where lights from KHR_lights_punctual are in its
// physical units (LIGHTS_PHYSICAL) and the others' diffuse colour is what a white Lambertian
// surface facing them shows, as in the specular-map mode.

const int kMaxLights = 4;
// The number of lights, 0 to kMaxLights, defined per variant (ShaderLibrary::mesh): the light loop
// runs exactly that many times. With a uniform count, a software rasteriser would run the trip
// that breaks out too, or every trip up to kMaxLights.
const int kLightCount = LIGHT_COUNT;
uniform vec4 u_lightPosition[kMaxLights];
uniform vec3 u_lightAmbient[kMaxLights];
uniform vec3 u_lightDiffuse[kMaxLights];
uniform vec3 u_lightSpecular[kMaxLights];
uniform vec3 u_lightAttenuation[kMaxLights];   // k0, k1, k2
uniform vec3 u_lightSpotDirection[kMaxLights];
uniform vec2 u_lightSpotCos[kMaxLights];       // cos(inner), cos(outer); outer = -2: no cone
uniform int u_specularModel;                   // 0 Blinn-Phong, 1 Phong
#ifdef LIGHTS_PHYSICAL
// In physical units (PBR mode with the file's lights): u_lightDiffuse is colour times intensity,
// lux for directional lights, candela for point and spot lights, whose illuminance at distance d
// is that over d^2; u_lightAmbient the same scaled by the ambient share.
uniform float u_lightRange[kMaxLights];        // 0: infinite
const float kLightToIlluminance = 1.0;
#else
// Otherwise a light's diffuse colour is what a white Lambertian surface facing it shows:
// illuminance pi times that colour.
const float kLightToIlluminance = 3.14159265;
#endif

// Direction to light i from a surface point and the light's attenuation there (distance, cone).
// With LIGHTS_DIRECTIONAL every light is directional (u_lightPosition[i].xyz unit length) and
// the positional code is left out: a software rasteriser runs both sides of a branch.
float lightAt(int i, vec3 position, out vec3 toLight) {
#ifdef LIGHTS_DIRECTIONAL
  toLight = -u_lightPosition[i].xyz;
  return 1.0;
#else
  if (u_lightPosition[i].w == 0.0) {
    toLight = normalize(-u_lightPosition[i].xyz);
    return 1.0;
  }
  vec3 offset = u_lightPosition[i].xyz - position;
  float d = length(offset);
  toLight = offset / max(d, 1e-6);
  float c = dot(-toLight, normalize(u_lightSpotDirection[i]));
#ifdef LIGHTS_PHYSICAL
  // KHR_lights_punctual: inverse-square falloff, windowed to 0 at `range` as the extension
  // recommends, max(min(1 - (d / range)^4, 1), 0) / d^2 (range 0: none), and the spot cone
  // blended between the outer and inner angles' cosines, squared.
  float range = u_lightRange[i];
  float attenuation = 1.0 / max(d * d, 1e-8);
  if (range > 0.0) attenuation *= clamp(1.0 - pow(d / range, 4.0), 0.0, 1.0);
  if (u_lightSpotCos[i].y > -1.5) {
    float cone = clamp((c - u_lightSpotCos[i].y) / max(u_lightSpotCos[i].x - u_lightSpotCos[i].y, 1e-3), 0.0, 1.0);
    attenuation *= cone * cone;
  }
#else
  vec3 k = u_lightAttenuation[i];
  float attenuation = 1.0 / max(k.x + k.y * d + k.z * d * d, 1e-6);
  if (u_lightSpotCos[i].y > -1.5) attenuation *= smoothstep(u_lightSpotCos[i].y, u_lightSpotCos[i].x, c);
#endif
  return attenuation;
#endif
}

#ifndef SHADING_PBR
struct SurfaceLight {
  vec3 ambient;
  vec3 diffuse;
  vec3 specular;
};

// Light i at a surface point, specular-map mode; `shadow` scales its direct part.
void addLight(int i, vec3 position, vec3 normal, vec3 toEye, float shininess, float shadow, inout SurfaceLight total) {
  vec3 toLight;
  float attenuation = lightAt(i, position, toLight);
  total.ambient += u_lightAmbient[i] * attenuation;
  float lambert = max(dot(normal, toLight), 0.0);
  if (lambert <= 0.0) return;
  total.diffuse += u_lightDiffuse[i] * lambert * attenuation * shadow;
  float highlight;
  if (u_specularModel == 1) {
    highlight = max(dot(reflect(-toLight, normal), toEye), 0.0);
  } else {
    highlight = max(dot(normal, normalize(toLight + toEye)), 0.0);
  }
  total.specular += u_lightSpecular[i] * pow(highlight, shininess) * attenuation * shadow;
}
#endif
