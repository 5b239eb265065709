// SPDX-License-Identifier: MIT
// Colour encodings. Textures holding colour are sampled from sRGB8_ALPHA8 storage (decoded to
// linear by the sampler); lighting is linear; the result is encoded once, here, to sRGB
// (IEC 61966-2-1) after clamping to [0, 1], so the same code serves the window and screenshots.
// Above the linear segment, 1.055 c^(1/2.4) - 0.055 is replaced by Ian Taylor's fit in c's
// square, fourth and eighth roots (within 0.25/255 over [0.0031308, 1], so every 8-bit value
// rounds as the exact curve's does to within one level): three square roots cost a software
// rasteriser less than pow's logarithm and exponential.
vec3 linearToSrgb(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  vec3 root2 = sqrt(c), root4 = sqrt(root2), root8 = sqrt(root4);
  vec3 curve = 0.662002687 * root2 + 0.684122060 * root4 - 0.323583601 * root8 - 0.0225411470 * c;
  return mix(c * 12.92, curve, step(vec3(0.0031308), c));
}

// Tone mapping (the Khronos glTF Sample Viewer's choices): the lit colour, exposed, is mapped
// into [0, 1] before the encoding above, so that bright highlights roll off instead of clipping.
#if defined(TONEMAP_KHR_PBR_NEUTRAL)
// Khronos PBR Neutral (KhronosGroup/ToneMapping, PBR_Neutral): identity up to 0.76 apart from a
// small toe, then compresses the peak channel towards 1 and desaturates what it compresses.
vec3 toneMap(vec3 c) {
  const float startCompression = 0.8 - 0.04;
  const float desaturation = 0.15;
  float lowest = min(c.r, min(c.g, c.b));
  c -= lowest < 0.08 ? lowest - 6.25 * lowest * lowest : 0.04;
  float peak = max(c.r, max(c.g, c.b));
  if (peak < startCompression) return c;
  const float d = 1.0 - startCompression;
  float newPeak = 1.0 - d * d / (peak + d - startCompression);
  c *= newPeak / peak;
  float g = 1.0 - 1.0 / (desaturation * (peak - newPeak) + 1.0);
  return mix(c, vec3(newPeak), g);
}
#elif defined(TONEMAP_ACES_NARKOWICZ)
// Narkowicz's 2015 rational fit of the ACES reference rendering and output transforms.
vec3 toneMap(vec3 c) { return clamp(c * (2.51 * c + 0.03) / (c * (2.43 * c + 0.59) + 0.14), 0.0, 1.0); }
#else
vec3 toneMap(vec3 c) { return c; }  // none: values above 1 clip
#endif
