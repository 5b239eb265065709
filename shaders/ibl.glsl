// SPDX-License-Identifier: MIT
// Image-based lighting by the split-sum approximation (Karis 2013), from the maps that
// viewer/environment.cpp prepares at start-up: the environment prefiltered for roughness in a
// cube map's mip levels, the BRDF's scale and bias on F0 in a table over (N.V, roughness), and
// the irradiance in nine spherical-harmonic coefficients. The environment's mean radiance is 1;
// the caller scales it.
#ifdef USE_IBL
uniform samplerCube u_environmentMap;
uniform float u_environmentMaxLod;   // the level prefiltered for roughness 1
uniform sampler2D u_brdfLut;
uniform vec3 u_irradianceSh[9];      // E(n) / pi = sum of u_irradianceSh[i] * basis_i(n)
uniform float u_environmentScale;    // the lights' ambient level to the environment's

// Diffuse: irradiance over pi, a Lambertian surface's outgoing radiance per unit albedo.
vec3 environmentIrradiance(vec3 n) {
  vec3 e = u_irradianceSh[0];
  e += u_irradianceSh[1] * n.y + u_irradianceSh[2] * n.z + u_irradianceSh[3] * n.x;
  e += u_irradianceSh[4] * (n.x * n.y) + u_irradianceSh[5] * (n.y * n.z) + u_irradianceSh[6] * (3.0 * n.z * n.z - 1.0);
  e += u_irradianceSh[7] * (n.x * n.z) + u_irradianceSh[8] * (n.x * n.x - n.y * n.y);
  return max(e, vec3(0.0));
}

// Specular: the environment around the reflection vector, prefiltered for this roughness.
vec3 environmentRadiance(vec3 reflected, float roughness) {
  return textureLod(u_environmentMap, reflected, roughness * u_environmentMaxLod).rgb;
}

// (A, B): the specular lobe's integral is F0 * A + F90 * B.
vec2 environmentBrdf(float nv, float roughness) { return texture(u_brdfLut, vec2(nv, roughness)).rg; }
#endif
