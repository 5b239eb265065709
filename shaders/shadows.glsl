// SPDX-License-Identifier: MIT
// Shadow mapping for light 0 (orthographic for a directional light, perspective from a spot
// light, viewer/renderer.cpp's lightViewProjection; a cube map for a point light): depth compare
// in a sampler2DShadow or samplerCubeShadow (hardware comparison with bilinear filtering), with
// a constant plus slope bias and PCF over (2r+1)x(2r+1) texels (r = 0 off, 1 = 3x3, 2 = 5x5) in
// (2r)^2 taps. Without SHADOW_PCF (radius 0) the tap loops are left out, not skipped at run
// time: a software rasteriser runs a loop's body at least once.
#ifdef USE_SHADOWS
#ifdef POINT_SHADOWS
// A point light's depth cube map (viewer/shadow_cube.hpp): each face a 90-degree perspective
// view, read with the fragment's depth in the face its direction falls in.
uniform samplerCubeShadow u_shadowCube;
uniform vec3 u_shadowCubeDepth;  // the faces' near and far planes; the world length the biases are fractions of
#else
uniform sampler2DShadow u_shadowMap;
#endif
#ifdef SHADOW_PCF
uniform int u_pcfRadius;  // 1 = 3x3, 2 = 5x5
#endif
uniform float u_shadowBiasConstant;
uniform float u_shadowBiasSlope;

// The depth bias, in units of the shadow map's depth range: constant plus slope-scaled.
float shadowBias(vec3 normal, vec3 toLight) {
  float cosine = clamp(dot(normal, toLight), 0.0, 1.0);
  float slope = sqrt(1.0 - cosine * cosine) / max(cosine, 0.05);  // tan of the incidence angle
  return u_shadowBiasConstant + u_shadowBiasSlope * min(slope, 10.0);
}

#ifdef POINT_SHADOWS
float shadowFactor(vec4 shadowCoord, vec3 normal, vec3 toLight) {
  vec3 fromLight = v_positionWorld - u_lightPosition[0].xyz;
  float n = u_shadowCubeDepth.x, f = u_shadowCubeDepth.y;
  // The face's eye-space depth, moved towards the light by the bias, as window depth.
  float z = max(abs(fromLight.x), max(abs(fromLight.y), abs(fromLight.z))) - shadowBias(normal, toLight) * u_shadowCubeDepth.z;
  float depth = 0.5 * ((f + n) / (f - n) - 2.0 * f * n / ((f - n) * max(z, n))) + 0.5;
#ifndef SHADOW_PCF
  return texture(u_shadowCube, vec4(fromLight, depth));
#else
  // As the 2D map's PCF: (2r)^2 bilinear taps half a texel off the grid, one texel apart, in
  // the plane across the light's direction (a face texel is 2 z / size wide at depth z).
  vec3 axis = normalize(fromLight);
  vec3 side = normalize(cross(abs(axis.y) < 0.99 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0), axis));
  vec3 up = cross(axis, side);
  float texel = 2.0 * max(z, n) / float(textureSize(u_shadowCube, 0).x);
  float lit = 0.0;
  int taps = 0;
  for (int y = 0; y < 2 * u_pcfRadius; ++y) {
    for (int x = 0; x < 2 * u_pcfRadius; ++x) {
      vec2 offset = vec2(float(x - u_pcfRadius) + 0.5, float(y - u_pcfRadius) + 0.5) * texel;
      lit += texture(u_shadowCube, vec4(fromLight + offset.x * side + offset.y * up, depth));
      ++taps;
    }
  }
  return lit / float(taps);
#endif
}
#else
float shadowFactor(vec4 shadowCoord, vec3 normal, vec3 toLight) {
  if (shadowCoord.w <= 0.0) return 1.0;  // behind a spot light's view
  vec3 coord = shadowCoord.xyz / shadowCoord.w * 0.5 + 0.5;
  if (coord.z > 1.0 || any(lessThan(coord.xy, vec2(0.0))) || any(greaterThan(coord.xy, vec2(1.0)))) return 1.0;
  float bias = shadowBias(normal, toLight);
#ifndef SHADOW_PCF
  return texture(u_shadowMap, vec3(coord.xy, coord.z - bias));
#else
  vec2 texel = 1.0 / vec2(textureSize(u_shadowMap, 0));
  // Each tap is a bilinear blend of four hardware comparisons, so taps half a texel off the
  // texel grid, one texel apart, cover the (2r+1)^2 texels with (2r)^2 taps (4 for 3x3).
  float lit = 0.0;
  int taps = 0;
  for (int y = 0; y < 2 * u_pcfRadius; ++y) {
    for (int x = 0; x < 2 * u_pcfRadius; ++x) {
      vec2 offset = vec2(float(x - u_pcfRadius) + 0.5, float(y - u_pcfRadius) + 0.5);
      lit += texture(u_shadowMap, vec3(coord.xy + offset * texel, coord.z - bias));
      ++taps;
    }
  }
  return lit / float(taps);
#endif
}
#endif
#endif
