// SPDX-License-Identifier: MIT
// Shadow mapping for light 0 (orthographic for a directional light, perspective from a spot
// light, viewer/renderer.cpp's lightViewProjection; a cube map for a point light): depth compare
// in a sampler2DShadow or samplerCubeShadow (hardware comparison with bilinear filtering), with
// PCF over (2r+1)x(2r+1) texels (r = 0 off, 1 = 3x3, 2 = 5x5) in (2r)^2 taps. Without SHADOW_PCF
// (radius 0) the tap loops are left out, not skipped at run time: a software rasteriser runs a
// loop's body at least once.
// Against acne and the blotches of low-poly smooth meshes, all judged with the triangle's own
// (geometric) normal, which is what the depth map holds, not the interpolated one:
// - normal offset: the lookup point moves off the surface along the geometric normal by a few
//   shadow-map texels (their world size at the fragment), more the more the face turns from the
//   light (Holbert, "Normal Offset Shadows", 2011);
// - a constant plus slope-scaled depth bias (the slope of the geometric face);
// - the shadow terminator: a face turned away from the light is in its own shadow, a polygonal
//   step where the interpolated normal still faces the light (up to sin of half the facet angle):
//   there the shadow fades out, by how far the interpolated normal is ahead of the face, and N.L
//   of the shading normal darkens it smoothly instead. A flat surface (both normals alike) keeps
//   its whole shadow, at any angle.
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
// A shadow-map texel's world size at the fragment: x + y * its distance from the light (x for a
// directional light's orthographic map, y for a spot light's or a point light's perspective).
uniform vec2 u_shadowTexelWorld;
#ifndef POINT_SHADOWS
uniform mat4 u_lightViewProjection;  // as mesh.vert has it
#endif

// The normal offset, in shadow-map texels, at a face seen edge-on by the light (less as it turns
// towards the light); PCF taps reach further, so the offset grows with the radius.
const float kShadowNormalOffsetTexels = 1.5;
// The geometric N.L over which a face's shadow fades in: below 0 the face is in its own shadow.
const float kShadowTerminatorFade = 0.2;

// The depth bias, in units of the shadow map's depth range: constant plus slope-scaled.
float shadowBias(vec3 normal, vec3 toLight) {
  float cosine = clamp(dot(normal, toLight), 0.0, 1.0);
  float slope = sqrt(1.0 - cosine * cosine) / max(cosine, 0.05);  // tan of the incidence angle
  return u_shadowBiasConstant + u_shadowBiasSlope * min(slope, 10.0);
}

// The triangle's own normal (flat over it, from the position's screen derivatives), on the side
// of `shadingSide` (the interpolated normal as shaded, reversed on back faces).
vec3 shadowFaceNormal(vec3 shadingSide) {
  vec3 face = cross(dFdx(v_positionWorld), dFdy(v_positionWorld));
  float length2 = dot(face, face);
  if (!(length2 > 1e-30)) return shadingSide;  // a degenerate or sub-pixel triangle
  face *= inversesqrt(length2);
  return dot(face, shadingSide) < 0.0 ? -face : face;
}

// Where the shadow is looked up: the fragment moved off its face by the normal offset.
vec3 shadowLookupPosition(vec3 faceNormal, vec3 toLight, float lightDistance) {
  float texel = u_shadowTexelWorld.x + u_shadowTexelWorld.y * lightDistance;
  float cosine = clamp(dot(faceNormal, toLight), 0.0, 1.0);
#ifdef SHADOW_PCF
  float reach = float(u_pcfRadius) + 1.0;
#else
  float reach = 1.0;
#endif
  return v_positionWorld + faceNormal * (kShadowNormalOffsetTexels * reach * texel * (1.0 - cosine));
}

// The shadow, lifted towards 1 where a face turned (nearly) away from the light would shadow
// itself while its interpolated normal faces the light.
float terminatorFade(vec3 faceNormal, vec3 smoothNormal, vec3 toLight, float shadow) {
  float faceCosine = dot(faceNormal, toLight);
  float ahead = clamp((dot(smoothNormal, toLight) - faceCosine) / kShadowTerminatorFade, 0.0, 1.0);
  return mix(shadow, 1.0, ahead * (1.0 - smoothstep(0.0, kShadowTerminatorFade, faceCosine)));
}

#ifdef POINT_SHADOWS
float cubeShadow(vec3 normal, vec3 toLight) {
  vec3 fromLight = shadowLookupPosition(normal, toLight, length(v_positionWorld - u_lightPosition[0].xyz)) - u_lightPosition[0].xyz;
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

// Light 0's shadow at the fragment: 0 shadowed, 1 lit. `faceNormal` is the geometric normal
// (shadowFaceNormal), `smoothNormal` the interpolated one on the same side.
float shadowFactor(vec3 faceNormal, vec3 smoothNormal, vec3 toLight) {
  return terminatorFade(faceNormal, smoothNormal, toLight, cubeShadow(faceNormal, toLight));
}
#else
float mapShadow(vec3 normal, vec3 toLight) {
  // The light's distance matters for a spot light's perspective only (u_shadowTexelWorld.y).
  float lightDistance = u_shadowTexelWorld.y > 0.0 ? length(v_positionWorld - u_lightPosition[0].xyz) : 0.0;
  vec4 shadowCoord = u_lightViewProjection * vec4(shadowLookupPosition(normal, toLight, lightDistance), 1.0);
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

// Light 0's shadow at the fragment: 0 shadowed, 1 lit. `faceNormal` is the geometric normal
// (shadowFaceNormal), `smoothNormal` the interpolated one on the same side.
float shadowFactor(vec3 faceNormal, vec3 smoothNormal, vec3 toLight) {
  return terminatorFade(faceNormal, smoothNormal, toLight, mapShadow(faceNormal, toLight));
}
#endif
#endif
