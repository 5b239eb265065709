// SPDX-License-Identifier: MIT
// Phase 4's shortcut: a bucket that is one fan of one orientation sums the terms the
// triangle pass parked, in a fixed-point grid, so that no order moves a bit.
#include "kernel.hpp"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace tangent::detail::mikk {

// The common bucket from the terms the triangle pass parked in its corners' slots: one fan
// (closed or open) of one orientation, every corner usable (cornerTermsOne), its dP/du and
// its dP/dv each inside one half-space (no pair the reference could find opposite, so no
// subgroups), a sum that does not nearly cancel, a normal that is neither zero nor infinite.
// Then every corner gets the one shared frame, as the full path would give it. False
// (nothing written) where the bucket is not that case.
bool Kernel::fastBucket(std::uint32_t bucket, const std::uint32_t* list, std::uint32_t count, std::uint64_t& mirrored) {
  std::uint32_t cone = kConeBits;
  double x, y, z, angleSum;
#if defined(__SSE2__)
  // The same exact sums two components at a time.
  const __m128d quantizer = _mm_set1_pd(kQuantizer);
  __m128d xy = _mm_setzero_pd(), za = _mm_setzero_pd();
  const __m128i keep = _mm_setr_epi32(-1, -1, -1, static_cast<int>(~kConeBits));
  __m128i bits = _mm_set1_epi32(-1);
  for (std::uint32_t i = 0; i < count; ++i) {
    const __m128i slot = _mm_loadu_si128(reinterpret_cast<const __m128i*>(&tangents_[4 * std::size_t(list[i])]));
    bits = _mm_and_si128(bits, slot);
    const __m128 terms = _mm_castsi128_ps(_mm_and_si128(slot, keep));
    xy = _mm_add_pd(xy, _mm_sub_pd(_mm_add_pd(_mm_cvtps_pd(terms), quantizer), quantizer));
    za = _mm_add_pd(za, _mm_sub_pd(_mm_add_pd(_mm_cvtps_pd(_mm_movehl_ps(terms, terms)), quantizer), quantizer));
  }
  cone &= static_cast<std::uint32_t>(_mm_cvtsi128_si32(_mm_shuffle_epi32(bits, 3)));
  double lanes[4];
  _mm_storeu_pd(lanes, xy);
  _mm_storeu_pd(lanes + 2, za);
  x = lanes[0], y = lanes[1], z = lanes[2], angleSum = lanes[3];
#else
  x = y = z = angleSum = 0;
  for (std::uint32_t i = 0; i < count; ++i) {
    const float* slot = &tangents_[4 * std::size_t(list[i])];
    const std::uint32_t bits = bitCast<std::uint32_t>(slot[3]);
    cone &= bits;
    x += quantized(slot[0]), y += quantized(slot[1]), z += quantized(slot[2]);
    angleSum += quantized(bitCast<float>(bits & ~kConeBits));
  }
#endif
  if (!(cone & 0x3F) || !(cone & (0x3F << 6))) return false;
  // The sum made orthogonal to the raw normal N (as to the unit normal) and normalized: one
  // square root and one division for the bucket.
  const V3 sum{x, y, z}, normal = a_.normal(bucket);
  const double sum2 = dot(sum, sum), normal2 = dot(normal, normal);
  if (!(sum2 >= 0.0025 * angleSum * angleSum) || !(normal2 > 0) || !std::isfinite(normal2)) return false;
  const V3 t = sum - normal * (dot(normal, sum) / normal2);
  const double t2 = dot(t, t);
  if (!(t2 > 1e-24 * sum2)) return false;
  const V3 unit = t * (1.0 / std::sqrt(t2));
  const float w = ws_.orientation[list[0] / 3] > 0 ? 1.0f : -1.0f;
  const float frame[4] = {static_cast<float>(unit.x), static_cast<float>(unit.y), static_cast<float>(unit.z),
                          w * wSign_};
  // storeFrame without its state write: a corner's source and undefined bits are still clear
  // here (pairing cleared them; only its bucket's group pass sets them), and computed is 0.
  static_assert(static_cast<int>(FrameSource::computed) == 0);
  finishOneFrame(bucket, list, count, mirrored, frame);
  ws_.bucketExtra[bucket] = bitCast<std::uint32_t>(static_cast<float>(angleSum));
  ws_.bucketUniform[bucket] |= kBucketWeight;
  return true;
}

}  // namespace tangent::detail::mikk
