// SPDX-License-Identifier: MIT
// Phase 5: corners without a frame of their own, after every group is done.
#include "kernel.hpp"
#include <unordered_map>
#include <vector>

namespace tangent::detail::mikk {

std::uint32_t Kernel::bestComputedInBucket(std::uint32_t bucket, float w, bool anyW) const {
  std::uint32_t best = kNone;
  for (std::uint32_t i = start_[bucket]; i < start_[bucket + 1]; ++i) {
    const std::uint32_t c = corners_[i];
    if (!participates(c) || (ws_.cornerState[c] & kCopy) || (ws_.cornerState[c] & kUndefined)) continue;
    if (static_cast<FrameSource>(ws_.cornerState[c] & kSourceMask) != FrameSource::computed) continue;
    if (!anyW && this->w(c) != w) continue;
    if (best == kNone || betterCandidate(c, best)) best = c;
  }
  return best;
}

void Kernel::inheritFrom(std::uint32_t best, std::uint32_t corner, float w, bool anyW) {
  if (best == kNone) {
    markUndefined(corner, anyW ? -1.0f : w);
    return;
  }
  const float* from = &tangents_[4 * best];
  writeCorner(corner, {from[0], from[1], from[2]}, this->w(best), FrameSource::inherited, weight(best));
}

// The rare corners without a frame of their own, after every group is done: one w per
// coincident triangle, then frames borrowed from the vertex, the triangle or its 1-ring.
void Kernel::fallbackCoincident() {
  const std::size_t triangleCount = ws_.cornerCount / 3;
  const std::vector<std::uint32_t> coincident =
      coincident_ == 0 ? std::vector<std::uint32_t>{}
                       : collectFlagged(ws_, ws_.triangleFlags.data(), kCoincident, triangleCount,
                                        [&](std::size_t t) { return (ws_.triangleFlags[t] & kCoincident) != 0; });
  // The corners written here are coincident, never candidates: one answer per bucket and w.
  std::unordered_map<std::uint64_t, std::uint32_t> bestOfBucket;
  auto bestIn = [&](std::uint32_t bucket, float w) {
    const auto [at, inserted] = bestOfBucket.try_emplace((std::uint64_t{bucket} << 32) | bitCast<std::uint32_t>(w), kNone);
    if (inserted) at->second = bestComputedInBucket(bucket, w, false);
    return at->second;
  };
  for (std::uint32_t t : coincident) {
    int plus = 0, minus = 0;
    for (int k = 0; k < 3; ++k) {
      const std::size_t c = 3 * t + k;
      if (ws_.cornerState[c] & kUndefined) continue;
      (this->w(c) > 0 ? plus : minus) += 1;
    }
    const float w = plus + minus == 0 ? -1.0f : (minus > plus ? -1.0f : 1.0f);
    for (int k = 0; k < 3; ++k) {
      const std::size_t c = 3 * t + k;  // never a copy: coincident triangles pair with nothing
      const bool wasMirrored = tangents_[4 * c + 3] < 0;
      if (ws_.cornerState[c] & kUndefined) tangents_[4 * c + 3] = w * wSign_;
      else if (this->w(c) != w) inheritFrom(bestIn(id(c), w), static_cast<std::uint32_t>(c), w, false);
      mirroredCorners_ += (tangents_[4 * c + 3] < 0) - static_cast<int>(wasMirrored);
    }
  }
}

void Kernel::fallbackUndefined() {
  const std::vector<std::uint32_t> undefined =
      collectFlagged(ws_, ws_.cornerState.data(), kUndefined, ws_.cornerCount, [&](std::size_t c) {
        return (ws_.cornerState[c] & kUndefined) && !(ws_.cornerState[c] & kCopy);
      });
  // Each borrows only from frames that were there before this loop: decide all, then write.
  struct Decision {
    std::uint32_t corner;
    V3 tangent;
    FrameSource source;
  };
  std::vector<Decision> decisions;
  decisions.reserve(undefined.size());
  // The best defined corner of a bucket with a given w, read once per bucket and w (a vertex of
  // valence n with n corners undefined would otherwise be read n times: quadratic). Nothing is
  // written before every corner has decided, so the answer does not change during the loop.
  std::unordered_map<std::uint64_t, std::uint32_t> bestDefined;
  auto bestDefinedIn = [&](std::uint32_t bucket, float w) {
    const std::uint64_t key = (std::uint64_t{bucket} << 32) | bitCast<std::uint32_t>(w);
    const auto [at, inserted] = bestDefined.try_emplace(key, kNone);
    if (!inserted) return at->second;
    std::uint32_t best = kNone;
    for (std::uint32_t i = start_[bucket]; i < start_[bucket + 1]; ++i) {
      const std::uint32_t d = corners_[i];
      if (defined(d) && !(ws_.cornerState[d] & kCopy) && this->w(d) == w && (best == kNone || betterCandidate(d, best))) best = d;
    }
    return at->second = best;
  };
  for (std::uint32_t c : undefined) {
    const float w = this->w(c);
    const std::uint32_t bucket = id(c);
    bool invalid;
    const V3 n = bucketNormal(bucket, invalid);
    const bool isCoincident = (ws_.triangleFlags[c / 3] & kCoincident) != 0;
    // 1. Same identity, same w (c itself is undefined, so never its own candidate).
    std::uint32_t best = bestDefinedIn(bucket, w);
    if (best != kNone) {
      const float* from = &tangents_[4 * best];
      decisions.push_back({c, {from[0], from[1], from[2]}, isCoincident ? FrameSource::inherited : FrameSource::neighbour});
      continue;
    }
    // 2. The triangle's other corners, then 3. the corners at its other two vertices.
    for (int pass = 0; pass < 2 && best == kNone; ++pass) {
      for (int k = 1; k < 3; ++k) {
        const std::size_t other = 3 * (c / 3) + (c % 3 + k) % 3;
        if (pass == 0) {
          if (defined(other) && !(ws_.cornerState[other] & kCopy) && this->w(other) == w && (best == kNone || betterCandidate(other, best)))
            best = static_cast<std::uint32_t>(other);
          continue;
        }
        // The first best of the two buckets in scan order, as one scan over both would give.
        const std::uint32_t d = bestDefinedIn(id(other), w);
        if (d != kNone && (best == kNone || betterCandidate(d, best))) best = d;
      }
    }
    V3 tangent;
    if (best != kNone && orthonormalize({tangents_[4 * best], tangents_[4 * best + 1], tangents_[4 * best + 2]}, n, tangent)) {
      decisions.push_back({c, tangent, FrameSource::neighbour});
      continue;
    }
    // 4. A fixed unit vector perpendicular to the normal.
    axisPerpendicular(&n.x, &tangent.x);
    decisions.push_back({c, tangent, FrameSource::fixed});
  }
  for (const Decision& d : decisions) writeCorner(d.corner, d.tangent, w(d.corner), d.source, 0);
}

void Kernel::fallbacks() {
  fallbackCoincident();
  if (!anyUndefined_.load(std::memory_order_relaxed)) return;
  fallbackUndefined();
}

}  // namespace tangent::detail::mikk
