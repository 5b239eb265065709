// SPDX-License-Identifier: MIT
// Phase 4, the full path: the groups of one welded vertex (the reference's groups and
// subgroups), their sums in value order, and the frames of its corners.
#include <vector>

#include "kernel.hpp"

namespace tangent::detail::mikk {

// Groups of one welded vertex, their sums, and the frames of its corners.
void Kernel::groupBucket(std::uint32_t bucket, BucketScratch& scratch, std::uint64_t& mirrored) {
  const std::uint32_t first = start_[bucket], count = start_[bucket + 1] - first;
  const std::uint8_t chain = ws_.bucketUniform[bucket];
  ws_.bucketUniform[bucket] = 0;
  if (count == 0) return;
  const std::uint32_t* list = corners_ + first;
  // One chain of links between triangles of one orientation (a fan around the vertex, closed
  // or open) is one group of every corner (what the union-find finds for it), without keys.
  const bool fan = chain == kOneFan ||
                   (chain == kOneChain ? oneOrientation(list, count) : chain == kChainUnknown && closedFan(list, count));
  // 1. The shortcut for one fan, from the terms the triangle pass parked (fan.cpp).
  if (fan && count <= kMostQuantizedTerms && ws_.fastBuckets && fastBucket(bucket, list, count, mirrored)) return;
  // 2. The vertex's normal, replaced where zero or non-finite.
  bool invalidNormal = false;
  const V3 n = bucketNormal(bucket, invalidNormal);
  if (invalidNormal) {
    for (std::uint32_t i = 0; i < count; ++i) ws_.cornerState[list[i]] |= kInvalidNormal;
  }
  FullBucket b{bucket, list, count, fan, n, {a_.normals[3 * bucket], a_.normals[3 * bucket + 1], a_.normals[3 * bucket + 2]},
               a_.position(bucket), scratch, fan ? count : 0};
  // 3. Its groups (member order: group by group).
  if (!fan) groupMembers(b);
  // 4. Each group's sum and its corners' frames.
  bool oneFrame = b.memberCount == count;  // every corner given the one frame of one group
  for (std::size_t g = 0; g < b.memberCount;) {
    std::size_t gEnd = fan ? b.memberCount : g + 1;
    while (gEnd < b.memberCount && b.rootOf(gEnd) == b.rootOf(g)) ++gEnd;
    oneFrame = groupFrames(b, g, gEnd) && oneFrame && g == 0 && gEnd == b.memberCount;
    g = gEnd;
  }
  if (oneFrame) {
    finishOneFrame(bucket, list, count, mirrored);
    return;  // no coincident corners here
  }
  // 5. Coincident corners copy the best frame of their identity (the reference: the first).
  std::uint32_t best = kNone;
  bool bestFound = false;  // looked for once, at the first coincident corner
  for (std::uint32_t i = 0; i < count; ++i) {
    const std::uint32_t c = list[i];
    if (participates(c)) continue;
    if (!bestFound) best = bestComputedInBucket(bucket, 0, true), bestFound = true;
    inheritFrom(best, c, 0, true);
  }
  for (std::uint32_t i = 0; i < count; ++i) {
    const std::uint32_t c = list[i];
    mirrored += !(ws_.cornerState[c] & kCopy) && tangents_[4 * c + 3] < 0;
  }
}

// Members of each group, group by group, in b.scratch.keys = (root, local index): a
// union-find over the bucket's corners through links between triangles of equal orientation.
void Kernel::groupMembers(FullBucket& b) {
  ScratchVector<std::uint64_t>& keys = b.scratch.keys;
  keys.clear();
  BucketUnionFind components(b.scratch.parent, b.count);
  for (std::uint32_t i = 0; i < b.count; ++i) {
    const std::uint32_t c = b.list[i];
    if (!participates(c) || (ws_.cornerState[c] & kCopy)) continue;
    const std::uint32_t d = ws_.cornerLink[c];
    if (d == kNone || ws_.orientation[c / 3] != ws_.orientation[d / 3]) continue;
    components.unite(i, localIndex(b.bucket, d));
  }
  for (std::uint32_t i = 0; i < b.count; ++i) {
    const std::uint32_t c = b.list[i];
    if (participates(c) && !(ws_.cornerState[c] & kCopy)) keys.push_back((std::uint64_t(components.find(i)) << 32) | i);
  }
  sortSmall(keys.data(), keys.data() + keys.size());
  b.memberCount = keys.size();
}

// One row per contributing member of group [g, gEnd) into b.scratch.values (kRowStride each;
// b.scratch.items: their member indices): the weighted tangent (0..2), dP/du projected as the
// reference projects it (3..5, float arithmetic on the raw normal), the triangle's unit dP/dv
// (6..8), the angle (9). Three passes: projected edges (y, x of the angle in the first two
// slots, whether both edges are non-zero in the third) and directions; the angles two at a
// time; then the weighted terms.
std::size_t Kernel::groupRows(FullBucket& b, std::size_t g, std::size_t gEnd) {
  b.scratch.values.resize(kRowStride * (gEnd - g));
  b.scratch.items.clear();
  double* values = b.scratch.values.data();
  for (std::size_t m = g; m < gEnd; ++m) {
    const std::uint32_t c = b.list[b.member(m)];
    const std::size_t t = c / 3;
    if (ws_.triangleFlags[t] & kGroupWithAny) continue;
    // The triangle's frame again (the triangle pass keeps none: most buckets take the fan
    // shortcut, which needs only the parked terms); the same function, the same bits.
    float frame[6];
    std::int8_t orientationAgain;
    std::uint8_t flagsAgain;
    evaluateTriangle(a_, t, frame, orientationAgain, flagsAgain);
    const V3 toPrevious = projected(a_.position(a_.indices[previousCorner(c)]) - b.here, b.n);
    const V3 toNext = projected(a_.position(a_.indices[nextCorner(c)]) - b.here, b.n);
    const F3 referenceS = referenceProjected({frame[0], frame[1], frame[2]}, b.rawNormal);
    double* row = values + kRowStride * b.scratch.items.size();
    const bool edges = !isZero(toPrevious) & !isZero(toNext);
    row[0] = edges ? length(cross(toPrevious, toNext)) : 1.0;
    row[1] = edges ? dot(toPrevious, toNext) : 0.0;
    row[2] = edges ? 1.0 : 0.0;
    // The reference's projected direction, so that sums which (nearly) cancel keep its sign.
    row[3] = referenceS.x, row[4] = referenceS.y, row[5] = referenceS.z;
    row[6] = frame[3], row[7] = frame[4], row[8] = frame[5];  // projected only where needed
    b.scratch.items.push_back(static_cast<std::uint32_t>(m));
  }
  const std::size_t contributing = b.scratch.items.size();
  for (std::size_t i = 0; i < contributing; i += 2) {
    double* row = values + kRowStride * i;
    if (i + 1 < contributing) {
      const double y[2] = {row[0], row[kRowStride]}, x[2] = {row[1], row[kRowStride + 1]};
      double angle[2];
      angleBetweenPair(y, x, angle);
      row[9] = angle[0], row[kRowStride + 9] = angle[1];
    } else {
      row[9] = angleBetween(row[0], row[1]);
    }
  }
  for (std::size_t i = 0; i < contributing; ++i) {
    double* row = values + kRowStride * i;
    double angle = row[2] != 0 ? row[9] : kHalfPi;  // a zero edge counts as perpendicular, as in the reference
    if (angle < 0.1 || angle > 2 * kHalfPi - 0.1) {
      // Near 0 or pi the reference's float cosine decides (acos(0.99999994) is 3.5e-4, not 0),
      // and its rounding moves small angles by a visible fraction.
      angle = referenceAngle(b.list[b.member(b.scratch.items[i])], b.rawNormal);
    }
    // A corner whose edges project onto one line has no angle; its direction still counts
    // where nothing else does.
    angle = std::max(angle, 1e-12);
    row[0] = row[3] * angle, row[1] = row[4] * angle, row[2] = row[5] * angle;
    row[9] = angle;
  }
  return contributing;
}

namespace {

// The rows' indices in value order (weighted tangent, lexicographic), so that face order
// cannot change a bit of a sum: insertion sort up to 32, std::sort beyond.
void sortRowsByValue(const double* values, std::size_t contributing, std::uint32_t* sorted) {
  for (std::uint32_t i = 0; i < contributing; ++i) sorted[i] = i;
  auto lessByValue = [&](std::uint32_t x, std::uint32_t y) {
    const double* p = values + kRowStride * x;
    const double* q = values + kRowStride * y;
    if (p[0] != q[0]) return p[0] < q[0];
    if (p[1] != q[1]) return p[1] < q[1];
    return p[2] < q[2];
  };
  if (contributing <= 32) {
    for (std::uint32_t i = 1; i < contributing; ++i) {
      const std::uint32_t value = sorted[i];
      std::uint32_t j = i;
      for (; j > 0 && lessByValue(value, sorted[j - 1]); --j) sorted[j] = sorted[j - 1];
      sorted[j] = value;
    }
  } else {
    std::sort(sorted, sorted + contributing, lessByValue);
  }
}

// Whether the reference keeps rows i and j apart (subgroups): their projected dP/du or dP/dv
// have a float dot product of -1 or less.
bool rowsOpposite(const double* values, std::size_t i, std::size_t j, F3 rawNormal) {
  const double* x = values + kRowStride * i;
  const double* y = values + kRowStride * j;
  const F3 si{float(x[3]), float(x[4]), float(x[5])}, sj{float(y[3]), float(y[4]), float(y[5])};
  if (!(fdot(si, sj) > -1.0f)) return true;
  const F3 ti = referenceProjected({float(x[6]), float(x[7]), float(x[8])}, rawNormal);
  const F3 tj = referenceProjected({float(y[6]), float(y[7]), float(y[8])}, rawNormal);
  return !(fdot(ti, tj) > -1.0f);
}

// Whether any two rows are opposite (rowsOpposite). All vectors well inside one half-space
// (1e-3 from its boundary) proves there is no such pair; otherwise pairs are compared as the
// reference compares them (up to 4096 rows).
bool anyOppositeRows(const double* values, std::size_t contributing, V3 n, F3 rawNormal) {
  if (contributing <= 1) return false;
  V3 sumS, sumT;
  for (std::size_t i = 0; i < contributing; ++i) {
    sumS = sumS + V3{values[kRowStride * i + 3], values[kRowStride * i + 4], values[kRowStride * i + 5]};
    sumT = sumT + V3{values[kRowStride * i + 6], values[kRowStride * i + 7], values[kRowStride * i + 8]};
  }
  // dP/dv unprojected: its dot with a vector in the plane is that of its projection, whose
  // length is at most 1, so the bound holds for the projections too.
  sumT = projected(sumT, n);
  const double lengthS = length(sumS), lengthT = length(sumT);
  bool halfSpace = true;
  for (std::size_t i = 0; i < contributing && halfSpace; ++i) {
    const double* x = values + kRowStride * i;
    const V3 si{x[3], x[4], x[5]}, ti{x[6], x[7], x[8]};
    halfSpace = (isZero(si) || dot(si, sumS) > 1e-3 * lengthS) && dot(ti, sumT) > 1e-3 * lengthT;
  }
  bool anyOpposite = false;
  if (!halfSpace && contributing <= 4096) {
    for (std::size_t i = 0; i < contributing && !anyOpposite; ++i) {
      for (std::size_t j = i + 1; j < contributing && !anyOpposite; ++j) anyOpposite = rowsOpposite(values, i, j, rawNormal);
    }
  }
  return anyOpposite;
}

}  // namespace

// The sum over a corner's subgroup (self: a contributing row, or kNone for all) and its
// weights. Where two terms cancel to a twentieth of their weight, rounding moves the
// direction: then the reference's own float sum (its float angles), which for two terms does
// not depend on their order. With more terms the reference's float sum does depend on its face
// order (measured: 0.03 degrees over the orders of a 7-triangle fan) and the double sum is the
// better estimate of all of them.
V3 Kernel::subgroupSum(const FullBucket& b, const GroupRows& rows, std::size_t self, double& weights) const {
  auto inSubgroup = [&](std::size_t i) {
    return self == kNone || rows.sorted[i] == self || !rowsOpposite(rows.values, rows.sorted[i], self, b.rawNormal);
  };
  V3 sum;
  weights = 0;
  std::size_t terms = 0;
  for (std::size_t i = 0; i < rows.contributing; ++i) {
    if (!inSubgroup(i)) continue;
    const double* x = rows.values + kRowStride * rows.sorted[i];
    sum = sum + V3{x[0], x[1], x[2]};
    weights += x[9];
    ++terms;
  }
  if (length(sum) >= 0.05 * weights) return sum;
  // Cancelling terms magnify every difference in their weights: the reference's float angles.
  F3 floatSum;
  V3 doubleSum;
  for (std::size_t i = 0; i < rows.contributing; ++i) {
    if (!inSubgroup(i)) continue;
    const double* x = rows.values + kRowStride * rows.sorted[i];
    const auto angle = static_cast<float>(referenceAngle(b.list[b.member(b.scratch.items[rows.sorted[i]])], b.rawNormal));
    const F3 term = fscale(angle, F3{float(x[3]), float(x[4]), float(x[5])});
    floatSum = fadd(floatSum, term);
    doubleSum = doubleSum + V3{term.x, term.y, term.z};
  }
  return terms > 2 ? doubleSum : V3{floatSum.x, floatSum.y, floatSum.z};
}

// The frames of group [g, gEnd)'s corners. True where they all got the group's one frame (a
// defined sum and no subgroups).
bool Kernel::groupFrames(FullBucket& b, std::size_t g, std::size_t gEnd) {
  const std::int8_t orientation = ws_.orientation[b.list[b.member(g)] / 3];
  const float w = orientation > 0 ? 1.0f : -1.0f;  // reference: fSign = +1 where the UV area is positive
  GroupRows rows;
  rows.contributing = groupRows(b, g, gEnd);
  rows.values = b.scratch.values.data();
  std::vector<std::uint32_t> byValue;
  std::uint32_t byValueSmall[32];
  std::uint32_t* sorted = byValueSmall;
  if (rows.contributing > 32) {
    byValue.resize(rows.contributing);
    sorted = byValue.data();
  }
  sortRowsByValue(rows.values, rows.contributing, sorted);
  rows.sorted = sorted;
  const bool anyOpposite = anyOppositeRows(rows.values, rows.contributing, b.n, b.rawNormal);
  // The group's weight (its angles' sum) in value order too, so that no face order moves it.
  // subgroupSum(kNone), written out for the common case: no subgroup test per term.
  double angleSum = 0;
  V3 all;
  for (std::size_t i = 0; i < rows.contributing; ++i) {
    const double* x = rows.values + kRowStride * sorted[i];
    all = all + V3{x[0], x[1], x[2]};
    angleSum += x[9];
  }
  if (!(length(all) >= 0.05 * angleSum)) all = subgroupSum(b, rows, kNone, angleSum);
  V3 shared;
  const bool sharedDefined = rows.contributing > 0 && orthonormalize(all, b.n, shared);
  const auto groupWeight = static_cast<float>(angleSum);
  if (rows.contributing > 0 && !anyOpposite && sharedDefined) {
    // The common case: every member gets the shared frame.
    for (std::size_t m = g; m < gEnd; ++m) writeCorner(b.list[b.member(m)], shared, w, FrameSource::computed, groupWeight);
    return true;
  }
  std::size_t nextContributing = 0;
  for (std::size_t m = g; m < gEnd; ++m) {
    const std::uint32_t c = b.list[b.member(m)];
    std::size_t self = kNone;
    if (nextContributing < rows.contributing && b.scratch.items[nextContributing] == m) self = nextContributing++;
    if (rows.contributing == 0) {
      markUndefined(c, orientation != 0 ? w : -1.0f);
    } else if (!anyOpposite || self == kNone) {
      if (sharedDefined) writeCorner(c, shared, w, FrameSource::computed, groupWeight);
      else markUndefined(c, w);
    } else {
      V3 own;
      double weights;
      if (orthonormalize(subgroupSum(b, rows, self, weights), b.n, own)) writeCorner(c, own, w, FrameSource::computed, groupWeight);
      else markUndefined(c, w);
    }
  }
  return false;
}

}  // namespace tangent::detail::mikk
