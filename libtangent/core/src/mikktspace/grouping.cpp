// SPDX-License-Identifier: MIT
// Phase 4, the full path: the groups of one welded vertex (the reference's groups and
// subgroups), their sums in value order, and the frames of its corners.
#include "kernel.hpp"
#include <vector>

namespace tangent::detail::mikk {

// Groups of one welded vertex, their sums, and the frames of its corners.
void Kernel::groupBucket(std::uint32_t bucket, BucketScratch& scratch, std::uint64_t& mirrored) {
  const std::uint32_t first = start_[bucket], count = start_[bucket + 1] - first;
  const std::uint8_t chain = ws_.bucketUniform[bucket];
  ws_.bucketUniform[bucket] = 0;
  if (count == 0) return;
  const std::uint32_t* list = corners_ + first;
  // Members of each group, group by group: keys = (root, local index); one chain of links
  // between triangles of one orientation (a fan around the vertex, closed or open) is one
  // group of every corner (what the union-find below finds for it), without keys.
  const bool fan = chain == kOneFan ||
                   (chain == kOneChain ? oneOrientation(list, count) : chain == kChainUnknown && closedFan(list, count));
  if (fan && count <= kMostQuantizedTerms && ws_.fastBuckets && fastBucket(bucket, list, count, mirrored)) return;
  bool invalidNormal = false;
  const V3 n = bucketNormal(bucket, invalidNormal);
  if (invalidNormal) {
    for (std::uint32_t i = 0; i < count; ++i) ws_.cornerState[list[i]] |= kInvalidNormal;
  }

  if (!fan) {
    scratch.keys.clear();
    // Union-find over the bucket's corners through pairs of equal orientation.
    BucketUnionFind components(scratch.parent, count);
    auto find = [&](std::uint32_t x) { return components.find(x); };
    for (std::uint32_t i = 0; i < count; ++i) {
      const std::uint32_t c = list[i];
      if (!participates(c) || (ws_.cornerState[c] & kCopy)) continue;
      const std::uint32_t d = ws_.cornerLink[c];
      if (d == kNone || ws_.orientation[c / 3] != ws_.orientation[d / 3]) continue;
      components.unite(i, localIndex(bucket, d));
    }
    for (std::uint32_t i = 0; i < count; ++i) {
      const std::uint32_t c = list[i];
      if (participates(c) && !(ws_.cornerState[c] & kCopy)) scratch.keys.push_back((std::uint64_t(find(i)) << 32) | i);
    }
    sortSmall(scratch.keys.data(), scratch.keys.data() + scratch.keys.size());
  }
  const std::size_t memberCount = fan ? count : scratch.keys.size();
  auto member = [&](std::size_t m) {
    return fan ? static_cast<std::uint32_t>(m) : static_cast<std::uint32_t>(scratch.keys[m]);
  };
  auto rootOf = [&](std::size_t m) { return static_cast<std::uint32_t>(scratch.keys[m] >> 32); };

  // Per contributing member: weighted tangent (3), dP/du projected as the reference projects
  // it (float arithmetic on the raw normal), the triangle's unit dP/dv (3), angle.
  const F3 rawNormal{a_.normals[3 * bucket], a_.normals[3 * bucket + 1], a_.normals[3 * bucket + 2]};
  constexpr int kStride = 10;
  // The corners' common position (equal values; where a component is zero its sign may
  // differ between corners, which moves no angle: only signs of zero terms follow it).
  const V3 here = a_.position(bucket);
  // Every corner of the bucket given the one shared frame of one group (see bucketUniform).
  bool oneFrame = memberCount == count;
  for (std::size_t g = 0; g < memberCount;) {
    std::size_t gEnd = fan ? memberCount : g + 1;
    while (gEnd < memberCount && rootOf(gEnd) == rootOf(g)) ++gEnd;
    const std::int8_t orientation = ws_.orientation[list[member(g)] / 3];
    const float w = orientation > 0 ? 1.0f : -1.0f;  // reference: fSign = +1 where the UV area is positive
    scratch.values.resize(kStride * (gEnd - g));
    scratch.items.clear();  // contributing members, local indices
    double* values = scratch.values.data();
    // Three passes over the group's contributing corners: their projected edges (y, x of the
    // angle parked in the row's first two slots, whether both edges are non-zero in its
    // third) and directions; the angles two at a time; then the weighted terms.
    for (std::size_t m = g; m < gEnd; ++m) {
      const std::uint32_t c = list[member(m)];
      const std::size_t t = c / 3;
      if (ws_.triangleFlags[t] & kGroupWithAny) continue;
      // The triangle's frame again (the triangle pass keeps none: most buckets take the fan
      // shortcut, which needs only the parked terms); the same function, the same bits.
      float frame[6];
      std::int8_t orientationAgain;
      std::uint8_t flagsAgain;
      evaluateTriangle(a_, t, frame, orientationAgain, flagsAgain);
      const V3 toPrevious = projected(a_.position(a_.indices[previousCorner(c)]) - here, n);
      const V3 toNext = projected(a_.position(a_.indices[nextCorner(c)]) - here, n);
      const F3 referenceS = referenceProjected({frame[0], frame[1], frame[2]}, rawNormal);
      double* row = values + kStride * scratch.items.size();
      const bool edges = !isZero(toPrevious) & !isZero(toNext);
      row[0] = edges ? length(cross(toPrevious, toNext)) : 1.0;
      row[1] = edges ? dot(toPrevious, toNext) : 0.0;
      row[2] = edges ? 1.0 : 0.0;
      // The reference's projected direction, so that sums which (nearly) cancel keep its sign.
      row[3] = referenceS.x, row[4] = referenceS.y, row[5] = referenceS.z;
      row[6] = frame[3], row[7] = frame[4], row[8] = frame[5];  // projected only where needed
      scratch.items.push_back(static_cast<std::uint32_t>(m));
    }
    const std::size_t contributingCorners = scratch.items.size();
    for (std::size_t i = 0; i < contributingCorners; i += 2) {
      double* row = values + kStride * i;
      if (i + 1 < contributingCorners) {
        const double y[2] = {row[0], row[kStride]}, x[2] = {row[1], row[kStride + 1]};
        double angle[2];
        angleBetweenPair(y, x, angle);
        row[9] = angle[0], row[kStride + 9] = angle[1];
      } else {
        row[9] = angleBetween(row[0], row[1]);
      }
    }
    for (std::size_t i = 0; i < contributingCorners; ++i) {
      double* row = values + kStride * i;
      double angle = row[2] != 0 ? row[9] : kHalfPi;  // a zero edge counts as perpendicular, as in the reference
      if (angle < 0.1 || angle > 2 * kHalfPi - 0.1) {
        // Near 0 or pi the reference's float cosine decides (acos(0.99999994) is 3.5e-4, not 0),
        // and its rounding moves small angles by a visible fraction.
        angle = referenceAngle(list[member(scratch.items[i])], rawNormal);
      }
      // A corner whose edges project onto one line has no angle; its direction still counts
      // where nothing else does.
      angle = std::max(angle, 1e-12);
      row[0] = row[3] * angle, row[1] = row[4] * angle, row[2] = row[5] * angle;
      row[9] = angle;
    }
    const std::size_t contributing = scratch.items.size();
    // Sum in value order so that face order cannot change a bit.
    std::vector<std::uint32_t> byValue;
    std::uint32_t byValueSmall[32];
    std::uint32_t* sorted = byValueSmall;
    if (contributing > 32) {
      byValue.resize(contributing);
      sorted = byValue.data();
    }
    for (std::uint32_t i = 0; i < contributing; ++i) sorted[i] = i;
    auto lessByValue = [&](std::uint32_t x, std::uint32_t y) {
      const double* p = values + kStride * x;
      const double* q = values + kStride * y;
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
    // Subgroups: the reference keeps apart two triangles whose projected dP/du or dP/dv have
    // a float dot product of -1 or less. All vectors well inside one half-space (1e-3 from its
    // boundary) proves there is no such pair; otherwise compare pairs as the reference does.
    auto opposite = [&](std::size_t i, std::size_t j) {
      const double* x = values + kStride * i;
      const double* y = values + kStride * j;
      const F3 si{float(x[3]), float(x[4]), float(x[5])}, sj{float(y[3]), float(y[4]), float(y[5])};
      if (!(fdot(si, sj) > -1.0f)) return true;
      const F3 ti = referenceProjected({float(x[6]), float(x[7]), float(x[8])}, rawNormal);
      const F3 tj = referenceProjected({float(y[6]), float(y[7]), float(y[8])}, rawNormal);
      return !(fdot(ti, tj) > -1.0f);
    };
    bool anyOpposite = false;
    if (contributing > 1) {
      V3 sumS, sumT;
      for (std::size_t i = 0; i < contributing; ++i) {
        sumS = sumS + V3{values[kStride * i + 3], values[kStride * i + 4], values[kStride * i + 5]};
        sumT = sumT + V3{values[kStride * i + 6], values[kStride * i + 7], values[kStride * i + 8]};
      }
      // dP/dv unprojected: its dot with a vector in the plane is that of its projection, whose
      // length is at most 1, so the bound holds for the projections too.
      sumT = projected(sumT, n);
      const double lengthS = length(sumS), lengthT = length(sumT);
      bool halfSpace = true;
      for (std::size_t i = 0; i < contributing && halfSpace; ++i) {
        const double* x = values + kStride * i;
        const V3 si{x[3], x[4], x[5]}, ti{x[6], x[7], x[8]};
        halfSpace = (isZero(si) || dot(si, sumS) > 1e-3 * lengthS) && dot(ti, sumT) > 1e-3 * lengthT;
      }
      if (!halfSpace && contributing <= 4096) {
        for (std::size_t i = 0; i < contributing && !anyOpposite; ++i) {
          for (std::size_t j = i + 1; j < contributing && !anyOpposite; ++j) anyOpposite = opposite(i, j);
        }
      }
    }
    // The sum over a corner's subgroup (self: a contributing index, or kNone for all). Where
    // two terms cancel to a twentieth of their weight, rounding moves the direction: then the
    // reference's own float sum (its float angles), which for two terms does not depend on
    // their order. With more terms the reference's float sum does depend on its face order
    // (measured: 0.03 degrees over the orders of a 7-triangle fan) and the double sum is the
    // better estimate of all of them.
    auto sumOver = [&](std::size_t self, double& weights) {
      V3 sum;
      weights = 0;
      std::size_t terms = 0;
      for (std::size_t i = 0; i < contributing; ++i) {
        if (self != kNone && sorted[i] != self && opposite(sorted[i], self)) continue;
        const double* x = values + kStride * sorted[i];
        sum = sum + V3{x[0], x[1], x[2]};
        weights += x[9];
        ++terms;
      }
      if (length(sum) >= 0.05 * weights) return sum;
      // Cancelling terms magnify every difference in their weights: the reference's float angles.
      F3 floatSum;
      V3 doubleSum;
      for (std::size_t i = 0; i < contributing; ++i) {
        if (self != kNone && sorted[i] != self && opposite(sorted[i], self)) continue;
        const double* x = values + kStride * sorted[i];
        const auto angle = static_cast<float>(referenceAngle(list[member(scratch.items[sorted[i]])], rawNormal));
        const F3 term = fscale(angle, F3{float(x[3]), float(x[4]), float(x[5])});
        floatSum = fadd(floatSum, term);
        doubleSum = doubleSum + V3{term.x, term.y, term.z};
      }
      return terms > 2 ? doubleSum : V3{floatSum.x, floatSum.y, floatSum.z};
    };
    // The group's weight (its angles' sum) in value order too, so that no face order moves it.
    // sumOver(kNone), written out for the common case: no subgroup test per term.
    double angleSum = 0;
    V3 all;
    for (std::size_t i = 0; i < contributing; ++i) {
      const double* x = values + kStride * sorted[i];
      all = all + V3{x[0], x[1], x[2]};
      angleSum += x[9];
    }
    if (!(length(all) >= 0.05 * angleSum)) all = sumOver(kNone, angleSum);
    V3 shared;
    const bool sharedDefined = contributing > 0 && orthonormalize(all, n, shared);
    const auto groupWeight = static_cast<float>(angleSum);
    oneFrame = oneFrame && g == 0 && gEnd == memberCount && sharedDefined && !anyOpposite;
    if (contributing > 0 && !anyOpposite && sharedDefined) {
      // The common case: every member gets the shared frame.
      for (std::size_t m = g; m < gEnd; ++m) {
        writeCorner(list[member(m)], shared, w, FrameSource::computed, groupWeight);
      }
      g = gEnd;
      continue;
    }
    std::size_t nextContributing = 0;
    for (std::size_t m = g; m < gEnd; ++m) {
      const std::uint32_t c = list[member(m)];
      std::size_t self = kNone;
      if (nextContributing < contributing && scratch.items[nextContributing] == m) self = nextContributing++;
      if (contributing == 0) {
        markUndefined(c, orientation != 0 ? w : -1.0f);
      } else if (!anyOpposite || self == kNone) {
        if (sharedDefined) writeCorner(c, shared, w, FrameSource::computed, groupWeight);
        else markUndefined(c, w);
      } else {
        V3 own;
        double weights;
        if (orthonormalize(sumOver(self, weights), n, own)) writeCorner(c, own, w, FrameSource::computed, groupWeight);
        else markUndefined(c, w);
      }
    }
    g = gEnd;
  }
  if (oneFrame) {
    finishOneFrame(bucket, list, count, mirrored);
    return;  // no coincident corners here
  }

  // Coincident corners copy the best frame of their identity (the reference: the first).
  for (std::uint32_t i = 0; i < count; ++i) {
    const std::uint32_t c = list[i];
    if (!participates(c)) inheritInBucket(bucket, c, 0, true);
  }
  for (std::uint32_t i = 0; i < count; ++i) {
    const std::uint32_t c = list[i];
    mirrored += !(ws_.cornerState[c] & kCopy) && tangents_[4 * c + 3] < 0;
  }
}

}  // namespace tangent::detail::mikk
