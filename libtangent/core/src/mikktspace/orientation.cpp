// SPDX-License-Identifier: MIT
// Phase 3, only where some triangle has zero UV area: the orientation such a triangle takes
// from the groups that reach it (the reference), else from its neighbours layer by layer.
#include "kernel.hpp"
#include <vector>

namespace tangent::detail::mikk {

// Orientation of the triangles that group with any (zero UV area): see below.
void Kernel::resolveGroupWithAny() {
  const std::size_t triangleCount = ws_.cornerCount / 3;
  auto open = [&](std::size_t t) {
    return ws_.orientation[t] == 0 && (ws_.triangleFlags[t] & (kGroupWithAny | kCoincident)) == kGroupWithAny &&
           !(ws_.cornerState[3 * t] & kCopy);
  };
  auto neighbour = [&](std::size_t t, int k) -> std::size_t {
    const std::uint32_t link = ws_.cornerLink[3 * t + k];
    return link == kNone ? kNone : link / 3;
  };
  std::vector<std::uint32_t> pending = collectIf(ws_, triangleCount, open);
  if (pending.empty()) return;

  // The reference: a group starts at an oriented triangle's corner and spreads around that
  // one vertex, and the first group to reach a zero-UV triangle gives it its orientation. So
  // the groups that can reach one are those of oriented triangles joined to it around one of
  // its vertices through zero-UV triangles. Where all of them agree, the reference's answer
  // does not depend on face order and we give the same; where they disagree, the majority of
  // the triangle's corners (ties +1).
  {
    std::vector<std::uint32_t> buckets;
    for (std::uint32_t t : pending) {
      for (int k = 0; k < 3; ++k) buckets.push_back(id(3 * t + k));
    }
    std::sort(buckets.begin(), buckets.end());
    buckets.erase(std::unique(buckets.begin(), buckets.end()), buckets.end());
    ScratchVector<std::uint32_t> parent;
    std::vector<std::uint8_t> reached;
    for (std::uint32_t bucket : buckets) {
      const std::uint32_t first = start_[bucket], count = start_[bucket + 1] - first;
      const std::uint32_t* list = corners_ + first;
      reached.assign(count, 0);
      BucketUnionFind components(parent, count);
      auto find = [&](std::uint32_t x) { return components.find(x); };
      for (std::uint32_t i = 0; i < count; ++i) {
        const std::uint32_t c = list[i];
        const std::uint32_t d = ws_.cornerLink[c];
        if (!participates(c) || (ws_.cornerState[c] & kCopy) || d == kNone) continue;
        if (open(c / 3) && open(d / 3)) components.unite(i, localIndex(bucket, d));
      }
      for (std::uint32_t i = 0; i < count; ++i) {
        const std::uint32_t c = list[i];
        const std::uint32_t d = ws_.cornerLink[c];
        if (!participates(c) || (ws_.cornerState[c] & kCopy) || d == kNone) continue;
        const bool openC = open(c / 3), openD = open(d / 3);
        if (openC == openD) continue;
        const std::uint32_t gwa = openC ? i : localIndex(bucket, d);
        const std::int8_t o = ws_.orientation[openC ? d / 3 : c / 3];
        if (o != 0) reached[find(gwa)] |= o > 0 ? kReachedPlus : kReachedMinus;
      }
      for (std::uint32_t i = 0; i < count; ++i) {
        if (open(list[i] / 3)) ws_.cornerState[list[i]] |= reached[find(i)];
      }
    }
    std::vector<std::int8_t> orientations(pending.size(), 0);
    for (std::size_t i = 0; i < pending.size(); ++i) {
      int plus = 0, minus = 0;
      for (int k = 0; k < 3; ++k) {
        std::uint8_t& state = ws_.cornerState[3 * pending[i] + k];
        plus += (state & kReachedPlus) != 0;
        minus += (state & kReachedMinus) != 0;
        state &= static_cast<std::uint8_t>(~(kReachedPlus | kReachedMinus));
      }
      if (plus + minus > 0) orientations[i] = minus > plus ? -1 : 1;
    }
    for (std::size_t i = 0; i < pending.size(); ++i) {
      if (orientations[i] != 0) ws_.orientation[pending[i]] = orientations[i];
    }
    std::erase_if(pending, [&](std::uint32_t t) { return !open(t); });
    if (pending.empty()) return;
  }

  // Those no group of the reference reaches: outwards from decided triangles, first across
  // edges, then by the triangles that share a corner's identity.
  // Decides every triangle of `candidates` that has a voter, all from one snapshot.
  std::vector<std::int8_t> decided;
  auto decide = [&](std::vector<std::uint32_t>& candidates, bool byVertex) {
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    decided.assign(candidates.size(), 0);
    for (std::size_t i = 0; i < candidates.size(); ++i) {
      const std::uint32_t t = candidates[i];
      if (!open(t)) continue;
      int votes = 0, voters = 0;
      for (int k = 0; k < 3; ++k) {
        if (!byVertex) {
          const std::size_t other = neighbour(t, k);
          if (other != kNone && ws_.orientation[other] != 0) votes += ws_.orientation[other], ++voters;
          continue;
        }
        const std::uint32_t bucket = id(3 * t + k);
        for (std::uint32_t j = start_[bucket]; j < start_[bucket + 1]; ++j) {
          const std::int8_t o = ws_.orientation[corners_[j] / 3];
          if (o != 0) votes += o, ++voters;
        }
      }
      if (voters > 0) decided[i] = votes < 0 ? -1 : 1;
    }
    std::vector<std::uint32_t> done;
    for (std::size_t i = 0; i < candidates.size(); ++i) {
      if (decided[i] != 0) {
        ws_.orientation[candidates[i]] = decided[i];
        done.push_back(candidates[i]);
      }
    }
    return done;
  };
  auto edgeLayers = [&](std::vector<std::uint32_t> layer) {
    while (!layer.empty()) {
      const std::vector<std::uint32_t> done = decide(layer, false);
      layer.clear();
      for (std::uint32_t t : done) {
        for (int k = 0; k < 3; ++k) {
          const std::size_t other = neighbour(t, k);
          if (other != kNone && open(other)) layer.push_back(static_cast<std::uint32_t>(other));
        }
      }
    }
  };
  edgeLayers(pending);
  for (int round = 0; round < 64; ++round) {
    std::erase_if(pending, [&](std::uint32_t t) { return !open(t); });
    if (pending.empty()) break;
    std::vector<std::uint32_t> candidates = pending;
    const std::vector<std::uint32_t> done = decide(candidates, true);
    if (done.empty()) break;
    std::vector<std::uint32_t> layer;
    for (std::uint32_t t : done) {
      for (int k = 0; k < 3; ++k) {
        const std::size_t other = neighbour(t, k);
        if (other != kNone && open(other)) layer.push_back(static_cast<std::uint32_t>(other));
      }
    }
    edgeLayers(std::move(layer));
  }
}

}  // namespace tangent::detail::mikk
