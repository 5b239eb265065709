// Shadow mapping for light 0: depth compare in a sampler2DShadow, with a constant plus slope
// bias and a (2r+1)x(2r+1) PCF kernel (r = 0 off, 1 = 3x3, 2 = 5x5).
#ifdef USE_SHADOWS
uniform sampler2DShadow u_shadowMap;
uniform int u_pcfRadius;
uniform float u_shadowBiasConstant;
uniform float u_shadowBiasSlope;

float shadowFactor(vec4 shadowCoord, vec3 normal, vec3 toLight) {
  vec3 coord = shadowCoord.xyz / shadowCoord.w * 0.5 + 0.5;
  if (coord.z > 1.0 || any(lessThan(coord.xy, vec2(0.0))) || any(greaterThan(coord.xy, vec2(1.0)))) return 1.0;
  float cosine = clamp(dot(normal, toLight), 0.0, 1.0);
  float slope = sqrt(1.0 - cosine * cosine) / max(cosine, 0.05);  // tan of the incidence angle
  float bias = u_shadowBiasConstant + u_shadowBiasSlope * min(slope, 10.0);
  vec2 texel = 1.0 / vec2(textureSize(u_shadowMap, 0));
  float lit = 0.0;
  int taps = 0;
  for (int y = -u_pcfRadius; y <= u_pcfRadius; ++y) {
    for (int x = -u_pcfRadius; x <= u_pcfRadius; ++x) {
      lit += texture(u_shadowMap, vec3(coord.xy + vec2(x, y) * texel, coord.z - bias));
      ++taps;
    }
  }
  return lit / float(taps);
}
#endif
