// SPDX-License-Identifier: MIT
// The tutorials' sphere-map reflection: the view-space reflection vector looks a sphere map up,
// mixed into the lit colour by u_reflectivity. Shared by mesh.frag and deferred.frag.
#ifdef USE_REFLECTION
uniform mat4 u_view;
uniform sampler2D u_sphereMap;
uniform float u_reflectivity;

vec3 withReflection(vec3 color, vec3 shadingNormal, vec3 toEye) {
  vec3 r = mat3(u_view) * reflect(-toEye, shadingNormal);
  float m = 2.0 * sqrt(r.x * r.x + r.y * r.y + (r.z + 1.0) * (r.z + 1.0));
  return mix(color, texture(u_sphereMap, r.xy / m + 0.5).rgb, u_reflectivity);
}
#endif
