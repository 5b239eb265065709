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

}  // namespace tangent::detail::mikk
