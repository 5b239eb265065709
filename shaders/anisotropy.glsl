// SPDX-License-Identifier: MIT
// KHR_materials_anisotropy: the direction of the anisotropy in the tangent frame and, in pbr.glsl,
// the extension's anisotropic GGX lobe (its README, "Implementation": alpha_t = mix(alpha, 1,
// strength^2) along the direction, alpha_b = alpha across it; D and the height-correlated Smith
// V of Heitz 2014 in their anisotropic forms; as the Khronos glTF Sample Viewer evaluates them).
// The direction is (1, 0) in (T, B), or the texture's RG mapped to [-1, 1], turned by
// anisotropyRotation counter-clockwise from T towards B; the strength is anisotropyStrength times
// the texture's B. The frame is the primitive's TANGENT: a wrong w mirrors the direction.
#ifdef MATERIAL_ANISOTROPY
uniform vec3 u_anisotropy;  // cos(rotation), sin(rotation), strength
#ifdef HAS_ANISOTROPY_MAP
uniform sampler2D u_anisotropyMap;
uniform int u_anisotropyUvSet;
uniform mat3 u_anisotropyUvTransform;
#endif

struct Anisotropy {
  vec3 direction;  // world space, in the surface's (T, B) plane
  vec3 across;     // cross(geometry normal, direction)
  float strength;  // 0..1
};

// t, b: the geometry's tangent frame (T made orthogonal to the normal, B = frameBitangent's).
Anisotropy anisotropyAt(vec3 geometryNormal, vec3 t, vec3 b) {
  vec2 direction = vec2(1.0, 0.0);
  float strength = u_anisotropy.z;
#ifdef HAS_ANISOTROPY_MAP
  vec3 texel = texture(u_anisotropyMap, textureUv(u_anisotropyUvSet, u_anisotropyUvTransform)).rgb;
  direction = texel.rg * 2.0 - 1.0;
  if (dot(direction, direction) < 1e-6) direction = vec2(1.0, 0.0);  // no direction encoded: T's
  strength *= texel.b;
#endif
  direction = mat2(u_anisotropy.x, u_anisotropy.y, -u_anisotropy.y, u_anisotropy.x) * normalize(direction);
  Anisotropy a;
  a.direction = normalize(t * direction.x + b * direction.y);
  a.across = cross(geometryNormal, a.direction);
  a.strength = clamp(strength, 0.0, 1.0);
  return a;
}
#endif
