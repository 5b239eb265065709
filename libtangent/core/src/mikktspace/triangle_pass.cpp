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
    // The report's counts, and every corner's state cleared (the phases after this one only
    // set bits).
    auto countFlags = [&](std::uint8_t flags) {
      local.flat += (flags & (kFlat | kNonFinite)) == kFlat;
      local.zeroUv += (flags & kZeroUv) != 0;
      local.nonFinite += (flags & kNonFinite) != 0;
      local.groupWithAny += (flags & (kGroupWithAny | kCoincident)) == kGroupWithAny;
      local.coincident += (flags & kCoincident) != 0;
    };
    std::uint8_t* state = ws_.cornerState.data();
    for (t = begin; t + 8 <= end; t += 8) {  // eight at a time: most triangles have no flags
      const std::uint64_t zero = 0;
      for (int i = 0; i < 3; ++i) std::memcpy(state + 3 * t + 8 * i, &zero, sizeof zero);
      std::uint64_t eight;
      std::memcpy(&eight, &ws_.triangleFlags[t], sizeof eight);
      if (eight != 0) {
        for (std::size_t k = t; k < t + 8; ++k) countFlags(ws_.triangleFlags[k]);
      }
    }
    for (; t < end; ++t) {
      state[3 * t] = state[3 * t + 1] = state[3 * t + 2] = 0;
      countFlags(ws_.triangleFlags[t]);
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
