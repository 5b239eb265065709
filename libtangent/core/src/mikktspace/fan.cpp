// SPDX-License-Identifier: MIT
// Phase 4's shortcut: a bucket that is one fan of one orientation sums the terms the
// triangle pass parked, in a fixed-point grid, so that no order moves a bit.
#include "kernel.hpp"

namespace tangent::detail::mikk {

// The common bucket from the terms the triangle pass parked in its corners' slots: one fan
// (closed or open) of one orientation, every corner usable (cornerTermsOne), its dP/du and
// its dP/dv each inside one half-space (no pair the reference could find opposite, so no
// subgroups), a sum that does not nearly cancel, a normal that is neither zero nor infinite.
// Then every corner gets the one shared frame, as the full path would give it. False
// (nothing written) where the bucket is not that case.
bool Kernel::fastBucket(std::uint32_t bucket, const std::uint32_t* list, std::uint32_t count, std::uint64_t& mirrored) {
  FanAccumulator sum;
  for (std::uint32_t i = 0; i < count; ++i) sum.add(&tangents_[4 * std::size_t(list[i])]);
  return fanFrame(bucket, list, count, sum.result(), mirrored);
}

// The one frame of a fan from its summed terms (fastBucket, pairOneFan); false (nothing
// written) where the sum does not give it.
bool Kernel::fanFrame(std::uint32_t bucket, const std::uint32_t* list, std::uint32_t count, const FanSum& fan,
                      std::uint64_t& mirrored) {
  const std::uint32_t cone = fan.cone;
  const double x = fan.x, y = fan.y, z = fan.z, angleSum = fan.angleSum;
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
