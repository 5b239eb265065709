// SPDX-License-Identifier: MIT
// Shadow mapping for light 0 (orthographic for a directional light, perspective from a point or
// spot light; viewer/renderer.cpp's lightViewProjection): depth compare in a sampler2DShadow (hardware comparison with
// bilinear filtering), with a constant plus slope bias and PCF over (2r+1)x(2r+1) texels
// (r = 0 off, 1 = 3x3, 2 = 5x5) in (2r)^2 taps.
#ifdef USE_SHADOWS
uniform sampler2DShadow u_shadowMap;
uniform int u_pcfRadius;
uniform float u_shadowBiasConstant;
uniform float u_shadowBiasSlope;

float shadowFactor(vec4 shadowCoord, vec3 normal, vec3 toLight) {
  if (shadowCoord.w <= 0.0) return 1.0;  // behind a point or spot light's view
  vec3 coord = shadowCoord.xyz / shadowCoord.w * 0.5 + 0.5;
  if (coord.z > 1.0 || any(lessThan(coord.xy, vec2(0.0))) || any(greaterThan(coord.xy, vec2(1.0)))) return 1.0;
  float cosine = clamp(dot(normal, toLight), 0.0, 1.0);
  float slope = sqrt(1.0 - cosine * cosine) / max(cosine, 0.05);  // tan of the incidence angle
  float bias = u_shadowBiasConstant + u_shadowBiasSlope * min(slope, 10.0);
  vec2 texel = 1.0 / vec2(textureSize(u_shadowMap, 0));
  if (u_pcfRadius == 0) return texture(u_shadowMap, vec3(coord.xy, coord.z - bias));
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
}
#endif
