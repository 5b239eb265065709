// SPDX-License-Identifier: MIT
// Phase 1 (beside the weld): every triangle evaluated and its corners' terms parked, at the
// widest vector width the processor has; the report's triangle counts.
#include "kernel.hpp"

namespace tangent::detail::mikk {

void Kernel::evaluateTriangles(Report& report) {
  const std::size_t triangleCount = ws_.cornerCount / 3;
  struct Counts {
    std::uint64_t flat = 0, zeroUv = 0, nonFinite = 0, groupWithAny = 0, coincident = 0;
  };
  Combinable<Counts> counts;
  forRange(ws_, triangleCount, 4096, [&](std::size_t begin, std::size_t end) {
    Counts local;
    std::size_t t = begin;
#if defined(TANGENT_LANES8)
    if (isa_ == VectorIsa::avx2) {
      for (; t + 8 <= end; t += 8) {
        evaluateLanes8(a_, t, &ws_.orientation[t], &ws_.triangleFlags[t], tangents_);
      }
    }
#endif
#if defined(TANGENT_LANES4)
    if (isa_ != VectorIsa::scalar) {
      for (; t + 4 <= end; t += 4) {
        evaluateLanes4(a_, t, &ws_.orientation[t], &ws_.triangleFlags[t], tangents_);
      }
    }
#endif
    for (; t < end; ++t) evaluateAndParkOne(a_, t, ws_.orientation[t], ws_.triangleFlags[t], tangents_);
    for (t = begin; t < end; ++t) {
      if (t + 8 <= end) {  // most triangles have no flags: eight at a time where all are 0
        std::uint64_t eight;
        std::memcpy(&eight, &ws_.triangleFlags[t], sizeof eight);
        if (eight == 0) {
          t += 7;
          continue;
        }
      }
      const std::uint8_t flags = ws_.triangleFlags[t];
      local.flat += (flags & (kFlat | kNonFinite)) == kFlat;
      local.zeroUv += (flags & kZeroUv) != 0;
      local.nonFinite += (flags & kNonFinite) != 0;
      local.groupWithAny += (flags & (kGroupWithAny | kCoincident)) == kGroupWithAny;
      local.coincident += (flags & kCoincident) != 0;
    }
    Counts& total = counts.local();
    total.flat += local.flat;
    total.zeroUv += local.zeroUv;
    total.nonFinite += local.nonFinite;
    total.groupWithAny += local.groupWithAny;
    total.coincident += local.coincident;
  });
  counts.combine_each([&](const Counts& c) {
    report.degenerateTriangles += c.flat;
    report.zeroUvAreaTriangles += c.zeroUv;
    report.nonFiniteTriangles += c.nonFinite;
    groupWithAny_ += c.groupWithAny;
    coincident_ += c.coincident;
  });
}

}  // namespace tangent::detail::mikk
