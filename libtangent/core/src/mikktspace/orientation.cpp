// SPDX-License-Identifier: MIT
// Phase 3, only where some triangle has zero UV area: the orientation such a triangle takes
// from the groups that reach it (the reference), else from its neighbours layer by layer.
#include "kernel.hpp"
#include <algorithm>
#include <vector>

namespace tangent::detail::mikk {

// A zero-UV triangle (one that groups with any) whose orientation is still open: not
// coincident, not a copy, not yet decided.
inline bool Kernel::openForAny(std::size_t t) const {
  return ws_.orientation[t] == 0 && (ws_.triangleFlags[t] & (kGroupWithAny | kCoincident)) == kGroupWithAny &&
         !(ws_.cornerState[3 * t] & kCopy);
}

// The triangle across triangle t's edge from corner k, kNone where none.
inline std::size_t Kernel::neighbourTriangle(std::size_t t, int k) const {
  const std::uint32_t link = ws_.cornerLink[3 * t + k];
  return link == kNone ? kNone : link / 3;
}

// Orientation of the triangles that group with any (zero UV area): first as the reference's
// groups give it (orientReached), then, for those no group reaches, from their neighbours
// (orientByNeighbours).
void Kernel::resolveGroupWithAny() {
  const std::size_t triangleCount = ws_.cornerCount / 3;
  std::vector<std::uint32_t> pending = collectIf(ws_, triangleCount, [&](std::size_t t) { return openForAny(t); });
  if (pending.empty()) return;
  orientReached(pending);
  if (pending.empty()) return;
  orientByNeighbours(pending);
}

// The reference: a group starts at an oriented triangle's corner and spreads around that
// one vertex, and the first group to reach a zero-UV triangle gives it its orientation. So
// the groups that can reach one are those of oriented triangles joined to it around one of
// its vertices through zero-UV triangles. Where all of them agree, the reference's answer
// does not depend on face order and we give the same; where they disagree, the majority of
// the triangle's corners (ties +1). Leaves in `pending` the triangles still open.
void Kernel::orientReached(std::vector<std::uint32_t>& pending) {
  std::vector<std::uint32_t> buckets;
  for (std::uint32_t t : pending) {
    for (int k = 0; k < 3; ++k) buckets.push_back(id(3 * t + k));
  }
  std::sort(buckets.begin(), buckets.end());
  buckets.erase(std::unique(buckets.begin(), buckets.end()), buckets.end());
  ScratchVector<std::uint32_t> parent;
  std::vector<std::uint8_t> reached;
  for (std::uint32_t bucket : buckets) markReached(bucket, parent, reached);
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
  std::erase_if(pending, [&](std::uint32_t t) { return !openForAny(t); });
}

// One bucket of orientReached: its open corners joined across edges between open triangles,
// and each such component marked (kReachedPlus, kReachedMinus) with the orientations of the
// oriented triangles across its edges.
void Kernel::markReached(std::uint32_t bucket, ScratchVector<std::uint32_t>& parent, std::vector<std::uint8_t>& reached) {
  const std::uint32_t first = start_[bucket], count = start_[bucket + 1] - first;
  const std::uint32_t* list = corners_ + first;
  reached.assign(count, 0);
  BucketUnionFind components(parent, count);
  auto find = [&](std::uint32_t x) { return components.find(x); };
  for (std::uint32_t i = 0; i < count; ++i) {
    const std::uint32_t c = list[i];
    const std::uint32_t d = ws_.cornerLink[c];
    if (!participates(c) || (ws_.cornerState[c] & kCopy) || d == kNone) continue;
    if (openForAny(c / 3) && openForAny(d / 3)) components.unite(i, localIndex(bucket, d));
  }
  for (std::uint32_t i = 0; i < count; ++i) {
    const std::uint32_t c = list[i];
    const std::uint32_t d = ws_.cornerLink[c];
    if (!participates(c) || (ws_.cornerState[c] & kCopy) || d == kNone) continue;
    const bool openC = openForAny(c / 3), openD = openForAny(d / 3);
    if (openC == openD) continue;
    const std::uint32_t gwa = openC ? i : localIndex(bucket, d);
    const std::int8_t o = ws_.orientation[openC ? d / 3 : c / 3];
    if (o != 0) reached[find(gwa)] |= o > 0 ? kReachedPlus : kReachedMinus;
  }
  for (std::uint32_t i = 0; i < count; ++i) {
    if (openForAny(list[i] / 3)) ws_.cornerState[list[i]] |= reached[find(i)];
  }
}

// Those no group of the reference reaches: outwards from decided triangles, first across
// edges, then by the triangles that share a corner's identity (at most 64 rounds).
void Kernel::orientByNeighbours(std::vector<std::uint32_t>& pending) {
  std::vector<std::int8_t> decided;
  orientAcrossEdges(pending, decided);
  for (int round = 0; round < 64; ++round) {
    std::erase_if(pending, [&](std::uint32_t t) { return !openForAny(t); });
    if (pending.empty()) break;
    std::vector<std::uint32_t> candidates = pending;
    const std::vector<std::uint32_t> done = decideByVotes(candidates, true, decided);
    if (done.empty()) break;
    std::vector<std::uint32_t> layer;
    appendOpenNeighbours(done, layer);
    orientAcrossEdges(std::move(layer), decided);
  }
}

// Layer by layer across edges: decides the layer, then the open neighbours of those decided.
void Kernel::orientAcrossEdges(std::vector<std::uint32_t> layer, std::vector<std::int8_t>& decided) {
  while (!layer.empty()) {
    const std::vector<std::uint32_t> done = decideByVotes(layer, false, decided);
    layer.clear();
    appendOpenNeighbours(done, layer);
  }
}

// Appends to `layer` the open triangles across the edges of the triangles in `done`.
void Kernel::appendOpenNeighbours(const std::vector<std::uint32_t>& done, std::vector<std::uint32_t>& layer) {
  for (std::uint32_t t : done) {
    for (int k = 0; k < 3; ++k) {
      const std::size_t other = neighbourTriangle(t, k);
      if (other != kNone && openForAny(other)) layer.push_back(static_cast<std::uint32_t>(other));
    }
  }
}

// Decides every open triangle of `candidates` (sorted and made unique here) that has a voter,
// all from one snapshot: the sum of the orientations across its edges, or (byVertex) of the
// triangles of its corners' buckets (ties +1). Returns those decided. `decided` is scratch.
std::vector<std::uint32_t> Kernel::decideByVotes(std::vector<std::uint32_t>& candidates, bool byVertex,
                                                 std::vector<std::int8_t>& decided) {
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
  decided.assign(candidates.size(), 0);
  // By vertex, each bucket's votes are counted once (a vertex of valence n would otherwise be
  // read n times: quadratic).
  std::vector<std::uint32_t> buckets;
  std::vector<std::int64_t> bucketVotes, bucketVoters;
  if (byVertex) {
    for (std::uint32_t t : candidates) {
      if (!openForAny(t)) continue;
      for (int k = 0; k < 3; ++k) buckets.push_back(id(3 * t + k));
    }
    std::sort(buckets.begin(), buckets.end());
    buckets.erase(std::unique(buckets.begin(), buckets.end()), buckets.end());
    bucketVotes.assign(buckets.size(), 0);
    bucketVoters.assign(buckets.size(), 0);
    for (std::size_t b = 0; b < buckets.size(); ++b) {
      for (std::uint32_t j = start_[buckets[b]]; j < start_[buckets[b] + 1]; ++j) {
        const std::int8_t o = ws_.orientation[corners_[j] / 3];
        if (o != 0) bucketVotes[b] += o, ++bucketVoters[b];
      }
    }
  }
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    const std::uint32_t t = candidates[i];
    if (!openForAny(t)) continue;
    std::int64_t votes = 0, voters = 0;
    for (int k = 0; k < 3; ++k) {
      if (!byVertex) {
        const std::size_t other = neighbourTriangle(t, k);
        if (other != kNone && ws_.orientation[other] != 0) votes += ws_.orientation[other], ++voters;
        continue;
      }
      const std::size_t b = std::lower_bound(buckets.begin(), buckets.end(), id(3 * t + k)) - buckets.begin();
      votes += bucketVotes[b];
      voters += bucketVoters[b];
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
}

}  // namespace tangent::detail::mikk
