// SPDX-License-Identifier: MIT
// Groups of corners that get one frame (lengyel, flat): sorted by value, summed in value
// order, and the fallbacks for groups no usable triangle reaches.
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <unordered_map>
#include <tuple>

#include "gram_schmidt.hpp"
#include "lengyel.hpp"

namespace tangent::detail {

namespace {

// groupCorners over `cornerCount` corners, the i-th of them cornerAt(i) in increasing order:
// every corner, or a few (groupCornersAt). The groups of a position hold all its corners
// listed, so the caller lists all corners of each position it wants grouped.
template <typename CornerAt>
CornerGroups groupListedCorners(const WorkspaceData& ws, const MeshArrays& mesh, std::span<const std::uint32_t> weldOf,
                                const TriangleData& data, Grouping grouping, std::size_t cornerCount,
                                const CornerAt& cornerAt) {
  const bool everyCorner = cornerCount == mesh.indices.size();
  // The keys in CornerKey order without one sort of them all: each corner's slot is counted
  // out by its weld (the key's first field), corners of one weld in corner order, and then
  // each weld's run (the few corners at one position) is sorted by the whole key. The same
  // order as sorting every key, in linear time but for the runs. A few listed corners
  // (groupCornersAt: the fallbacks' neighbourhoods) are sorted directly instead: the counting
  // costs arrays of every vertex. The key ends with the corner, so both give one order.
  const bool countOut = everyCorner || cornerCount >= ws.vertexCount / 8;
  std::vector<std::uint32_t> slot(cornerCount), runStart(countOut ? ws.vertexCount + 1 : 0, 0);
  if (countOut) {
    for (std::size_t i = 0; i < cornerCount; ++i) ++runStart[weldOf[mesh.indices[cornerAt(i)]] + 1];
    for (std::size_t v = 0; v < ws.vertexCount; ++v) runStart[v + 1] += runStart[v];
    std::vector<std::uint32_t> next(runStart.begin(), runStart.end() - 1);
    for (std::size_t i = 0; i < cornerCount; ++i) slot[i] = next[weldOf[mesh.indices[cornerAt(i)]]]++;
  } else {
    for (std::size_t i = 0; i < cornerCount; ++i) slot[i] = static_cast<std::uint32_t>(i);
  }
  CornerGroups result;
  std::vector<CornerKey>& keys = result.keys;
  keys.resize(cornerCount);
  forRange(ws, cornerCount, 1 << 14, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const std::size_t c = cornerAt(i);
      const TriangleTerms& triangle = data.triangles[c / 3];
      const std::uint32_t vertex = mesh.indices[c];
      CornerKey& key = keys[slot[i]];
      key.weld = weldOf[vertex];
      key.orientation = triangle.kind == TriangleKind::usable ? triangle.orientation : 0;
      key.tag = grouping == Grouping::perFace ? c / 3 + 1 : 0;
      const Vec3& normal = data.cornerNormal(c);
      for (int axis = 0; axis < 3; ++axis) key.normal[axis] = bitsOf(normal[axis]);
      key.uv[0] = bitsOf(mesh.uvs[2 * vertex]);
      key.uv[1] = bitsOf(mesh.uvs[2 * vertex + 1]);
      key.corner = static_cast<std::uint32_t>(c);
    }
  });
  if (countOut) {
    forRange(ws, ws.vertexCount, 1 << 12, [&](std::size_t begin, std::size_t end) {
      for (std::size_t v = begin; v < end; ++v) {
        if (runStart[v + 1] - runStart[v] > 1) std::sort(keys.begin() + runStart[v], keys.begin() + runStart[v + 1]);
      }
    });
  } else {
    std::sort(keys.begin(), keys.end());
  }
  // Runs of equal keys are groups: where each starts, numbered by a scan, then filled in
  // parallel. The first corner of a group is its smallest: it gives the group's normal and
  // whether it may inherit, as the corner met first in corner order did before.
  auto startsGroup = [&](std::size_t i) { return i == 0 || !keys[i].sameGroup(keys[i - 1]); };
  std::vector<std::uint32_t> groupOf(cornerCount);
  forRange(ws, cornerCount, 1 << 14, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) groupOf[i] = startsGroup(i);
  });
  const std::size_t groupCount = exclusiveScan(ws, groupOf.data(), cornerCount);  // groups before i
  result.groups.resize(groupCount);
  result.groupStart.resize(groupCount + 1);
  result.sortedCorners.resize(cornerCount);
  if (everyCorner) result.cornerGroup.resize(cornerCount);
  forRange(ws, cornerCount, 1 << 14, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const CornerKey& key = keys[i];
      const bool first = startsGroup(i);
      const std::uint32_t g = first ? groupOf[i] : groupOf[i] - 1;
      if (first) {
        Group& group = result.groups[g];
        group.key = &key;
        group.normal = data.cornerNormal(key.corner);
        group.mayInherit = data.triangles[key.corner / 3].kind != TriangleKind::usable;
        result.groupStart[g] = static_cast<std::uint32_t>(i);
      }
      result.sortedCorners[i] = key.corner;
      if (everyCorner) result.cornerGroup[key.corner] = g;
    }
  });
  result.groupStart[groupCount] = static_cast<std::uint32_t>(cornerCount);
  return result;
}

}  // namespace

CornerGroups groupCorners(const WorkspaceData& ws, const MeshArrays& mesh, std::span<const std::uint32_t> weldOf,
                          const TriangleData& data, Grouping grouping) {
  return groupListedCorners(ws, mesh, weldOf, data, grouping, mesh.indices.size(), [](std::size_t i) { return i; });
}

CornerGroups groupCornersAt(const WorkspaceData& ws, const MeshArrays& mesh, std::span<const std::uint32_t> weldOf,
                            const TriangleData& data, Grouping grouping, std::span<const std::uint32_t> corners) {
  return groupListedCorners(ws, mesh, weldOf, data, grouping, corners.size(), [&](std::size_t i) { return corners[i]; });
}

namespace {

// Value order (Contribution::operator<). A group is mostly one vertex's fan, a few terms: an
// insertion sort, whose comparisons inline (std::sort's did not: a call per comparison). Terms
// are finite (a usable triangle's unit directions times a positive finite weight), so terms
// that compare equal differ at most in the sign of a zero, which no sum from +0 tells apart,
// and any sort gives the same sums.
void sortTerms(std::span<Contribution> terms) {
  constexpr std::size_t kInsertionAtMost = 16;
  if (terms.size() > kInsertionAtMost) {
    std::sort(terms.begin(), terms.end());
    return;
  }
  for (std::size_t i = 1; i < terms.size(); ++i) {
    if (!(terms[i] < terms[i - 1])) continue;
    const Contribution moving = terms[i];
    std::size_t j = i;
    do {
      terms[j] = terms[j - 1];
      --j;
    } while (j > 0 && moving < terms[j - 1]);
    terms[j] = moving;
  }
}

}  // namespace

bool sumTerms(std::span<Contribution> terms, const Vec3& normal, int orientation, Method method, Vec3& tangentSum,
              Vec3& tangent, double& w) {
  sortTerms(terms);
  Vec3 bitangentSum(0, 0, 0);
  for (const Contribution& term : terms) {
    tangentSum += term.tangent;
    bitangentSum += term.bitangent;
  }
  if (!orthonormalize(tangentSum.data(), normal.data(), tangent.data())) return false;
  const double side = (normal % tangent) | bitangentSum;
  const double uvSide = orientation < 0 ? -1.0 : 1.0;
  w = method == Method::meshopt ? uvSide : side > 0 ? 1.0 : side < 0 ? -1.0 : uvSide;
  return true;
}

void sumAndOrthonormalize(const WorkspaceData& ws, const TriangleData& data, CornerGroups& cornerGroups, Method method) {
  std::vector<Group>& groups = cornerGroups.groups;
  forRange(ws, groups.size(), 1024, [&](std::size_t begin, std::size_t end) {
    std::vector<Contribution> terms;
    for (std::size_t g = begin; g < end; ++g) {
      Group& group = groups[g];
      terms.clear();
      for (std::uint32_t i = cornerGroups.groupStart[g]; i < cornerGroups.groupStart[g + 1]; ++i) {
        addTerm(data, cornerGroups.sortedCorners[i], method, terms);
      }
      group.defined = sumTerms(terms, group.normal, group.key->orientation, method, group.tangentSum, group.tangent, group.w);
    }
  });
}

namespace {

// One candidate, not a sum: opposite frames of a mirrored seam would cancel. The one whose
// normal is nearest wins (then the heaviest, then by value); it is copied exactly when its
// normal is the same, else projected onto ours.
bool frameFromCandidates(const std::vector<const Group*>& candidates, Group& group) {
  const Group* best = nullptr;
  auto rank = [&](const Group* g) {
    return std::make_tuple(g->normal | group.normal, g->tangentSum.sqrnorm(), g->tangent[0], g->tangent[1], g->tangent[2], g->w);
  };
  for (const Group* candidate : candidates) {
    if (!best || rank(best) < rank(candidate)) best = candidate;
  }
  if (!best) return false;
  if (std::equal(std::begin(best->key->normal), std::end(best->key->normal), std::begin(group.key->normal))) {
    group.tangent = best->tangent;
  } else if (!orthonormalize(best->tangent.data(), group.normal.data(), group.tangent.data())) {
    return false;
  }
  group.w = best->w;
  return true;
}

// The positions (welds) that share a triangle with each weld in `wanted`, in triangle order;
// kept for the wanted welds only (few: a list per vertex cost 24 bytes a vertex a call).
using NeighbourRing = std::unordered_map<std::uint32_t, std::vector<std::uint32_t>>;
NeighbourRing neighbourWelds(const MeshArrays& mesh, std::span<const std::uint32_t> weldOf,
                             const std::vector<std::uint8_t>& wanted) {
  NeighbourRing ring;
  for (std::size_t t = 0; 3 * t < mesh.indices.size(); ++t) {
    const std::uint32_t welds[3] = {weldOf[mesh.indices[3 * t]], weldOf[mesh.indices[3 * t + 1]], weldOf[mesh.indices[3 * t + 2]]};
    for (int k = 0; k < 3; ++k) {
      if (!wanted[welds[k]]) continue;
      for (int other : {(k + 1) % 3, (k + 2) % 3}) {
        if (welds[other] != welds[k]) ring[welds[k]].push_back(welds[other]);
      }
    }
  }
  return ring;
}

}  // namespace

namespace {

// The defined groups of each position, listed once: for the i-th position with any, welds[i],
// definedGroups[start[i] .. end[i]). Only positions with groups have an entry (the groups are
// in key order, so by position: a binary search finds one), so that a call with a few
// undefined groups does not pay arrays of every vertex. Where a position's defined groups all
// have one normal and one UV (a smooth vertex), every question ranks them alike but for the
// normal's term, which is then the same for all: only the first of the best (what
// frameFromCandidates would pick among them) is listed.
struct DefinedByPosition {
  std::vector<std::uint32_t> welds, start, end, groups;
  template <class Each>
  void forEach(const std::vector<Group>& all, std::uint32_t weld, Each&& each) const {
    const std::size_t at = find(weld);
    if (at == kAbsent) return;
    for (std::uint32_t i = start[at]; i < end[at]; ++i) each(all[groups[i]]);
  }
  std::size_t count(std::uint32_t weld) const {
    const std::size_t at = find(weld);
    return at == kAbsent ? 0 : end[at] - start[at];
  }

 private:
  static constexpr std::size_t kAbsent = ~std::size_t(0);
  std::size_t find(std::uint32_t weld) const {
    const auto it = std::lower_bound(welds.begin(), welds.end(), weld);
    return it != welds.end() && *it == weld ? static_cast<std::size_t>(it - welds.begin()) : kAbsent;
  }
};

DefinedByPosition definedByPosition(const std::vector<Group>& groups) {
  DefinedByPosition out;
  std::vector<std::uint32_t>& definedGroups = out.groups;
  // The groups of one position are adjacent (the key starts with it): its defined ones, listed
  // once (a position with n groups, none defined, is then not read n times).
  for (std::uint32_t g = 0; g < groups.size(); ++g) {
    if (!groups[g].defined) continue;
    const std::uint32_t weld = groups[g].key->weld;
    if (out.welds.empty() || out.welds.back() != weld) {
      out.welds.push_back(weld);
      out.start.push_back(static_cast<std::uint32_t>(definedGroups.size()));
      out.end.push_back(0);
    }
    definedGroups.push_back(g);
    out.end.back() = static_cast<std::uint32_t>(definedGroups.size());
  }
  for (std::size_t v = 0; v < out.welds.size(); ++v) {
    const std::uint32_t first = out.start[v];
    if (out.end[v] - first < 2) continue;
    const Group& head = groups[definedGroups[first]];
    auto alike = [&](std::uint32_t g) {
      return std::memcmp(groups[g].normal.data(), head.normal.data(), 3 * sizeof(double)) == 0 && groups[g].key->sameAttributes(*head.key);
    };
    if (!std::all_of(&definedGroups[first], &definedGroups[0] + out.end[v], alike)) continue;
    auto rank = [&](std::uint32_t g) {
      const Group& x = groups[g];
      return std::make_tuple(x.tangentSum.sqrnorm(), x.tangent[0], x.tangent[1], x.tangent[2], x.w);
    };
    std::uint32_t best = definedGroups[first];
    for (std::uint32_t i = first + 1; i < out.end[v]; ++i) {
      if (rank(best) < rank(definedGroups[i])) best = definedGroups[i];
    }
    definedGroups[first] = best;
    out.end[v] = first + 1;
  }
  return out;
}

// A group's answer depends only on its position, its normal (and for the first pass its UV)
// and the defined groups, which fillUndefinedGroups does not change. Where a question reads
// many groups it is answered once (the n groups of a vertex of valence n would otherwise each
// read the others: quadratic); where it reads few, reading them again is cheaper.
class FrameQuestions {
 public:
  // Question `kind` (0: same normal and UV, 1: same position, 2: the 1-ring) for `group`, whose
  // candidates `gather` pushes into candidates(); whether a frame was found (then in `group`).
  template <class Gather>
  bool ask(std::uint64_t kind, std::size_t reads, Group& group, Gather&& gather) {
    candidates_.clear();
    if (reads <= kReadAgainAtMost) {
      gather();
      return frameFromCandidates(candidates_, group);
    }
    const CornerKey& k = *group.key;  // the normal as it is, -0 apart from +0 (the key does not tell them)
    const std::array<std::uint64_t, 7> question{kind, k.weld, bitCast<std::uint64_t>(group.normal[0]),
                                               bitCast<std::uint64_t>(group.normal[1]), bitCast<std::uint64_t>(group.normal[2]),
                                               kind == 0 ? k.uv[0] : 0, kind == 0 ? k.uv[1] : 0};
    const auto [at, inserted] = answered_.try_emplace(question);
    if (!inserted) {
      if (at->second.found) group.tangent = at->second.tangent, group.w = at->second.w;
      return at->second.found;
    }
    gather();
    const bool found = frameFromCandidates(candidates_, group);
    at->second = Answer{found, group.tangent, group.w};
    return found;
  }
  std::vector<const Group*>& candidates() { return candidates_; }

 private:
  struct Answer {
    bool found;
    Vec3 tangent;
    double w;
  };
  struct QuestionHash {
    std::size_t operator()(const std::array<std::uint64_t, 7>& q) const {
      std::uint64_t h = 0;
      for (std::uint64_t part : q) h = (h ^ part) * 0x9E3779B97F4A7C15ull;
      return static_cast<std::size_t>(h ^ (h >> 29));
    }
  };
  static constexpr std::size_t kReadAgainAtMost = 32;
  std::unordered_map<std::array<std::uint64_t, 7>, Answer, QuestionHash> answered_;
  std::vector<const Group*> candidates_;
};

}  // namespace

void fillUndefinedGroups(const MeshArrays& mesh, std::span<const std::uint32_t> weldOf, CornerGroups& cornerGroups) {
  std::vector<Group>& groups = cornerGroups.groups;
  // The groups without a frame, in order (few; `flat` has three groups a triangle, and the
  // passes below then read only these instead of every group again).
  std::vector<std::uint32_t> undefined;
  for (std::uint32_t g = 0; g < groups.size(); ++g) {
    if (!groups[g].defined) undefined.push_back(g);
  }
  if (undefined.empty()) return;
  const std::size_t vertexCount = weldOf.size();
  const DefinedByPosition defined = definedByPosition(groups);
  FrameQuestions questions;
  std::vector<const Group*>& candidates = questions.candidates();
  auto definedAt = [&](std::uint32_t weld, auto&& each) { defined.forEach(groups, weld, each); };
  std::vector<std::uint8_t> wantsRing(vertexCount, 0);
  for (const std::uint32_t g : undefined) {
    Group& group = groups[g];
    bool found = false;
    // Same normal and UV first (a degenerate corner of a smooth vertex), then any.
    const std::uint32_t weld = group.key->weld;
    for (int pass = 0; pass < 2 && !found; ++pass) {
      found = questions.ask(pass, defined.count(weld), group, [&] {
        definedAt(weld, [&](const Group& other) {
          if (pass == 1 || other.key->sameAttributes(*group.key)) candidates.push_back(&other);
        });
      });
      if (found) group.source = pass == 0 && group.mayInherit ? FrameSource::inherited : FrameSource::neighbour;
    }
    if (!found) {
      group.source = FrameSource::fixed;  // for now: the 1-ring below may still give one
      wantsRing[group.key->weld] = 1;
    }
  }
  const NeighbourRing ring = neighbourWelds(mesh, weldOf, wantsRing);
  const std::vector<std::uint32_t> noNeighbours;
  for (const std::uint32_t g : undefined) {
    Group& group = groups[g];
    if (group.source != FrameSource::fixed) continue;
    const auto listed = ring.find(group.key->weld);
    const std::vector<std::uint32_t>& neighbours = listed == ring.end() ? noNeighbours : listed->second;
    const bool found = questions.ask(2, neighbours.size(), group, [&] {
      for (std::uint32_t neighbour : neighbours) definedAt(neighbour, [&](const Group& other) { candidates.push_back(&other); });
    });
    if (found) {
      group.source = FrameSource::neighbour;
      continue;
    }
    group.tangent = fixedPerpendicular(group.normal);
    group.w = group.key->orientation < 0 ? -1.0 : 1.0;
  }
}

namespace {

// Every corner of the positions the fallbacks of `undefined` read: each one's own position
// and those that share a triangle with it (a superset of the 1-ring fillUndefinedGroups
// gathers; a position more adds groups no answer reads).
std::vector<std::uint32_t> cornersNearUndefined(const WorkspaceData& ws, const MeshArrays& mesh,
                                                std::span<const std::uint32_t> weldOf,
                                                const std::vector<std::uint32_t>& undefined) {
  enum : std::uint8_t { kFar = 0, kUndefinedHere = 1, kNeighbour = 2 };
  std::vector<std::uint8_t> near(ws.vertexCount, kFar);
  for (const std::uint32_t c : undefined) near[weldOf[mesh.indices[c]]] = kUndefinedHere;
  for (std::size_t t = 0; 3 * t < ws.cornerCount; ++t) {
    const std::uint32_t welds[3] = {weldOf[mesh.indices[3 * t]], weldOf[mesh.indices[3 * t + 1]],
                                    weldOf[mesh.indices[3 * t + 2]]};
    if (near[welds[0]] != kUndefinedHere && near[welds[1]] != kUndefinedHere && near[welds[2]] != kUndefinedHere) continue;
    for (const std::uint32_t weld : welds) {
      if (near[weld] == kFar) near[weld] = kNeighbour;
    }
  }
  return collectIf(ws, ws.cornerCount, [&](std::size_t c) { return near[weldOf[mesh.indices[c]]] != kFar; });
}

}  // namespace

void frameUndefinedCorners(WorkspaceData& ws, const MeshArrays& mesh, std::span<const std::uint32_t> weldOf,
                           const TriangleData& data, Grouping grouping, Method method, const CornerOutputs& outputs) {
  const std::vector<std::uint32_t> undefined = collectFlagged(ws, ws.cornerState.data(), kUndefined, ws.cornerCount,
                                                              [&](std::size_t c) { return (ws.cornerState[c] & kUndefined) != 0; });
  if (undefined.empty()) return;
  // The groups of these positions are the full grouping's (a group's corners are all at one
  // position): the defined ones give the frames they gave, the others are filled in alike.
  const std::vector<std::uint32_t> near = cornersNearUndefined(ws, mesh, weldOf, undefined);
  CornerGroups cornerGroups = groupCornersAt(ws, mesh, weldOf, data, grouping, near);
  sumAndOrthonormalize(ws, data, cornerGroups, method);
  fillUndefinedGroups(mesh, weldOf, cornerGroups);
  float* tangents = outputs.tangents.data();
  for (std::size_t g = 0; g < cornerGroups.groups.size(); ++g) {
    const Group& group = cornerGroups.groups[g];
    if (group.defined) continue;  // framed before
    for (std::uint32_t i = cornerGroups.groupStart[g]; i < cornerGroups.groupStart[g + 1]; ++i) {
      const std::uint32_t c = cornerGroups.sortedCorners[i];
      writeCornerFrame(tangents, c, group.tangent, group.w);
      ws.cornerState[c] = static_cast<std::uint8_t>(static_cast<std::uint8_t>(group.source) | (ws.cornerState[c] & kInvalidNormal));
    }
  }
}

}  // namespace tangent::detail
