#version 330 core
// SPDX-License-Identifier: MIT
// The deferred lit view's lighting pass (viewer/renderer.cpp, drawDeferred): once per pixel, the
// surface that mesh.frag's GBUFFER_PASS wrote (gbuffer.glsl) lit as the forward pass lights it
// (pbr.glsl's pbrLitColor, light 0's shadow looked up once), at the position its depth gives.
// Pixels without a surface keep the clear colour; the depth goes on to the target, for what is
// drawn after (blended materials, unlit ones, the glyphs).

out vec4 fragColor;

uniform sampler2D u_gDepth;
uniform sampler2D u_gBaseColor;   // target 0
uniform highp usampler2D u_gSurface;    // target 1
uniform mat4 u_inverseViewProjection;
uniform mat4 u_lightViewProjection;
uniform vec2 u_viewportSize;
uniform vec3 u_eyeWorld;
uniform float u_exposure;

#include "colour.glsl"
#include "lighting.glsl"
#include "pbr.glsl"
#include "shadows.glsl"
#include "reflection.glsl"
#include "gbuffer.glsl"

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  float depth = texelFetch(u_gDepth, pixel, 0).r;
  if (depth >= 1.0) discard;
  GSurface g = readGBuffer(texelFetch(u_gBaseColor, pixel, 0), texelFetch(u_gSurface, pixel, 0));
  vec4 clip = u_inverseViewProjection * vec4(gl_FragCoord.xy / u_viewportSize * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0);
  vec3 position = clip.xyz / clip.w;
  vec3 toEye = normalize(u_eyeWorld - position);
  float shadow0 = 1.0;
#ifdef USE_SHADOWS
  shadow0 = shadowFactor(u_lightViewProjection * vec4(position, 1.0), position, g.shadowSlope);
#endif
  PbrSurface surface = PbrSurface(g.baseColor, g.metallic, g.roughness, g.dielectricF0, g.specularWeight);
  vec3 color = pbrLitColor(surface, position, g.normal, toEye, g.occlusion, shadow0);
#ifdef USE_REFLECTION
  color = withReflection(color, g.normal, toEye);
#endif
  fragColor = vec4(linearToSrgb(toneMap((color + g.emissive) * u_exposure)), 1.0);
  gl_FragDepth = depth;
}
