// SPDX-License-Identifier: MIT
// Colour encodings. Textures holding colour are sampled from sRGB8_ALPHA8 storage (decoded to
// linear by the sampler); lighting is linear; the result is encoded once, here, to sRGB
// (IEC 61966-2-1) after clamping to [0, 1], so the same code serves the window and screenshots.
vec3 linearToSrgb(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}
