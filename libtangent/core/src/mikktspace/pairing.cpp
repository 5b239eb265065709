// SPDX-License-Identifier: MIT
// Phase 2, per welded vertex: neighbours across edges (the reference's adjacency), exact
// duplicate triangles, and the greedy pairing of non-manifold edges in value order.
#include "kernel.hpp"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(TANGENT_LANES8)
#include <immintrin.h>
#endif
#include <bit>
#include <cstring>
#include <utility>
#include <type_traits>
#include <vector>

namespace tangent::detail::mikk {

// Most buckets: at most this many corners (one SIMD compare covers them).
constexpr std::uint32_t kSmall = 16;

// Pairs the half-edges at one welded vertex: a corner's outgoing edge (to its next corner)
// with the incoming edge of a corner whose previous corner has the same identity. Marks exact
// duplicate triangles (same identities, same winding) as copies of the first of them. Leaves
// in bucketUniform what the links say of the bucket (BucketChain, state_bits.hpp).
void Kernel::pairBucket(std::uint32_t bucket, BucketScratch& scratch) {
  const std::uint32_t first = start_[bucket], count = start_[bucket + 1] - first;
  const std::uint32_t* list = corners_ + first;
  if (count < 2) {  // one corner: a chain of one where it takes part
    resetLinks(list, count);
    ws_.bucketUniform[bucket] = count == 1 && participates(list[0]) ? kOneChain : kNotOneChain;
    return;
  }
  ws_.bucketUniform[bucket] = kChainUnknown;
  if (count <= kSmall && pairSmallBucket(bucket, list, count)) return;
  resetLinks(list, count);
  pairSorted(list, count, scratch);
}

// Clears the links of a bucket's corners (their states are clear: the triangle pass).
void Kernel::resetLinks(const std::uint32_t* list, std::uint32_t count) {
  for (std::uint32_t i = 0; i < count; ++i) ws_.cornerLink[list[i]] = kNone;
}

namespace {

// The participating corners of one small bucket (pairSmallBucket) and their links. Where
// every corner takes part, outId, inId and corner point into the buckets' arrays (which
// may be read kBucketIdPadding past a bucket); otherwise into the gathered copies here.
struct SmallBucket {
  const std::uint32_t* outId;  // next and previous identities
  const std::uint32_t* inId;
  const std::uint32_t* corner;
  std::uint32_t n = 0;
  alignas(16) std::uint32_t gatheredOut[kSmall], gatheredIn[kSmall], gatheredCorner[kSmall];
  std::uint8_t successor[kSmall] = {};  // local index of the corner linked from corner[i],
                                        // kSmall where none (zeroed: GCC cannot see that only
                                        // the first n are read)
  std::uint32_t targets = 0;            // local indices some link reaches
  // The corner linked from corner[i], kNone where none.
  std::uint32_t match(std::uint32_t i) const { return successor[i] == kSmall ? kNone : corner[successor[i]]; }
};

// Fills successor and targets from the identities; false where the bucket is not the
// simple case (a next identity repeats, or is the previous identity of two corners).
inline bool linkSmallBucket(SmallBucket& b) {
  const std::uint32_t n = b.n;
#if defined(__SSE2__)
  // Lane masks of equal identities, four lanes a compare (8 or 16 lanes, those past n
  // masked off).
  const std::uint32_t width = n <= 8 ? 8 : 16;
  const std::uint32_t lanes = (std::uint32_t(1) << n) - 1;
  auto masks = [&](auto vectorCount) {
    constexpr int kVectors = decltype(vectorCount)::value;
    // In locals: the byte stores to successor may alias what the lambda captures.
    const std::uint32_t count = n, valid = lanes;
    const std::uint32_t* outId = b.outId;
    std::uint8_t* successor = b.successor;
    __m128i outs[kVectors], ins[kVectors];
    for (int v = 0; v < kVectors; ++v) {
      outs[v] = _mm_loadu_si128(reinterpret_cast<const __m128i*>(outId + 4 * v));
      ins[v] = _mm_loadu_si128(reinterpret_cast<const __m128i*>(b.inId + 4 * v));
    }
    // Next identities all different: a matched one (some previous identity equal to it) and
    // an unmatched one never are equal; two matched ones that were equal would match the same
    // previous identity, and two different ones never do, so the matched ones are all
    // different exactly when no two of them reach the same target. Only the unmatched (the
    // ends of open fans) are compared with the other next identities.
    std::uint32_t bad = 0, targets = 0;
    for (std::uint32_t i = 0; i < count; ++i) {
      const __m128i key = _mm_set1_epi32(static_cast<int>(outId[i]));
      auto laneMask = [&](__m128i lanesOf) {
        return static_cast<std::uint32_t>(_mm_movemask_ps(_mm_castsi128_ps(_mm_cmpeq_epi32(key, lanesOf))));
      };
      std::uint32_t sameIn = 0;
      for (int v = 0; v < kVectors; ++v) sameIn |= laneMask(ins[v]) << (4 * v);
      sameIn &= valid;
      if (sameIn == 0) {
        std::uint32_t sameOut = 0;
        for (int v = 0; v < kVectors; ++v) sameOut |= laneMask(outs[v]) << (4 * v);
        bad |= (sameOut & valid) ^ (std::uint32_t(1) << i);
        successor[i] = kSmall;
        continue;
      }
      bad |= (sameIn & (sameIn - 1)) | (targets & sameIn);
      successor[i] = static_cast<std::uint8_t>(std::countr_zero(sameIn));
      targets |= sameIn;
    }
    b.targets = targets;
    return bad == 0;
  };
  return width == 8 ? masks(std::integral_constant<int, 2>{}) : masks(std::integral_constant<int, 4>{});
#else
  bool simple = true;
  for (std::uint32_t i = 0; i < n; ++i) {
    std::uint32_t sameOut = 0, sameIn = 0;
    b.successor[i] = kSmall;
    for (std::uint32_t j = 0; j < n; ++j) {
      sameOut += b.outId[i] == b.outId[j];
      sameIn += b.outId[i] == b.inId[j];
      b.successor[i] = b.outId[i] == b.inId[j] ? static_cast<std::uint8_t>(j) : b.successor[i];
      b.targets |= b.outId[i] == b.inId[j] ? std::uint32_t(1) << j : 0;
    }
    simple &= (sameOut == 1) & (sameIn <= 1);
  }
  return simple;
#endif
}

#if defined(TANGENT_LANES8)
// Lane i of kRotations[n][k]: (i + k) % n, for n up to 8 lanes (lanes from n: i).
struct Rotations {
  alignas(32) std::int32_t lanes[9][8][8];
};
constexpr Rotations makeRotations() {
  Rotations r{};
  for (int n = 1; n <= 8; ++n)
    for (int k = 0; k < n; ++k)
      for (int i = 0; i < 8; ++i) r.lanes[n][k][i] = i < n ? (i + k) % n : i;
  return r;
}
constexpr Rotations kRotations = makeRotations();

// The common closed fan, eight identities a compare where the processor has AVX2: whether
// each next identity of a bucket's n (2..8) corners is the previous identity of exactly one
// corner, and the links that makes (each corner to that corner) one cycle through all n
// (then they are one to one). There linkSmallBucket and oneSmallChain accept the bucket too
// (they find the same one successor per corner, no heads, the same cycle), and where they
// accept a bucket that is not one to one it is an open fan, for which this says false.
// Comparing next identities with the previous identities rotated by k lanes,
// k = 0 .. n - 1, compares every pair once. Reads 8 identities from each pointer
// (kBucketIdPadding).
template <std::uint32_t n>
__attribute__((target("avx2"))) inline bool closedFanOf(__m256i outs, __m256i ins) {
  __m256i matches = _mm256_setzero_si256(), successor = _mm256_setzero_si256();
#pragma GCC unroll 8
  for (std::uint32_t k = 0; k < n; ++k) {
    const __m256i rotation = _mm256_load_si256(reinterpret_cast<const __m256i*>(kRotations.lanes[n][k]));
    // Lane i: corner i's next identity against corner (i + k) % n's previous.
    const __m256i same = _mm256_cmpeq_epi32(outs, _mm256_permutevar8x32_epi32(ins, rotation));
    matches = _mm256_sub_epi32(matches, same);
    successor = _mm256_or_si256(successor, _mm256_and_si256(same, rotation));
  }
  const __m256i once = _mm256_cmpeq_epi32(matches, _mm256_set1_epi32(1));
  constexpr int kLanes = (1 << n) - 1;
  if ((_mm256_movemask_ps(_mm256_castsi256_ps(once)) & kLanes) != kLanes) return false;
  // The walk from corner 0 back to it: a cycle of n steps holds n corners, all of them.
  alignas(32) std::int32_t next[8];
  _mm256_store_si256(reinterpret_cast<__m256i*>(next), successor);
  std::uint32_t k = 0;
#pragma GCC unroll 8
  for (std::uint32_t step = 1; step < n; ++step) {
    k = static_cast<std::uint32_t>(next[k]);
    if (k == 0) return false;
  }
  return next[k] == 0;
}
// FanAccumulator's sum of the n corners' parked terms (the same operations in the same
// order, so the same bits), four components a step.
template <std::uint32_t n>
__attribute__((target("avx2"))) inline FanSum fanSumOf(const std::uint32_t* list, const float* tangents) {
  const __m256d quantizer = _mm256_set1_pd(kQuantizer);
  const __m128i keep = _mm_setr_epi32(-1, -1, -1, static_cast<int>(~(kConeBits | kNotPositiveBit)));
  __m128i all = _mm_set1_epi32(-1), any = _mm_setzero_si128();
  __m256d sum = _mm256_setzero_pd();
#pragma GCC unroll 8
  for (std::uint32_t i = 0; i < n; ++i) {
    const __m128i bits = _mm_loadu_si128(reinterpret_cast<const __m128i*>(tangents + 4 * std::size_t(list[i])));
    all = _mm_and_si128(all, bits);
    any = _mm_or_si128(any, bits);
    const __m256d terms = _mm256_cvtps_pd(_mm_castsi128_ps(_mm_and_si128(bits, keep)));
    sum = _mm256_add_pd(sum, _mm256_sub_pd(_mm256_add_pd(terms, quantizer), quantizer));
  }
  alignas(32) double lanes[4];
  _mm256_store_pd(lanes, sum);
  const auto allBits = static_cast<std::uint32_t>(_mm_extract_epi32(all, 3));
  const auto anyBits = static_cast<std::uint32_t>(_mm_extract_epi32(any, 3));
  return {lanes[0], lanes[1], lanes[2], lanes[3], kConeBits & allBits, ((allBits ^ anyBits) & kNotPositiveBit) == 0};
}
template <std::uint32_t n>
__attribute__((target("avx2"))) inline bool closedFanSumOf(__m256i outs, __m256i ins, const std::uint32_t* list,
                                                          const float* tangents, FanSum& fan) {
  if (!closedFanOf<n>(outs, ins)) return false;
  fan = fanSumOf<n>(list, tangents);
  return true;
}
// closedFanOf for n (2..8) corners, and where it holds, their parked terms' sum in fan (the
// loops unrolled for each size; inlined into pairAndGroupEight).
__attribute__((target("avx2"), always_inline)) inline bool closedFanEight(const std::uint32_t* outId,
                                                                          const std::uint32_t* inId, std::uint32_t n,
                                                                          const std::uint32_t* list,
                                                                          const float* tangents, FanSum& fan) {
  const __m256i outs = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(outId));
  const __m256i ins = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(inId));
  switch (n) {
    case 2: return closedFanSumOf<2>(outs, ins, list, tangents, fan);
    case 3: return closedFanSumOf<3>(outs, ins, list, tangents, fan);
    case 4: return closedFanSumOf<4>(outs, ins, list, tangents, fan);
    case 5: return closedFanSumOf<5>(outs, ins, list, tangents, fan);
    case 6: return closedFanSumOf<6>(outs, ins, list, tangents, fan);
    case 7: return closedFanSumOf<7>(outs, ins, list, tangents, fan);
    case 8: return closedFanSumOf<8>(outs, ins, list, tangents, fan);
    default: return false;
  }
}
#endif

#if defined(__wasm_simd128__) && !defined(TANGENT_LANES8)
#include "closed_fan_wasm.inc"  // closedFanWasm: closedFanEight in WebAssembly
#endif

// Each corner has at most one successor and one predecessor here, so the links form paths
// and cycles. One chain through every corner: a cycle from corner 0, or the path from the
// one corner that no link reaches (one head: one path; a walk from it that sees every
// corner: no cycle beside it).
inline bool oneSmallChain(const SmallBucket& b) {
  const std::uint32_t n = b.n;
  const std::uint32_t heads = ((std::uint32_t(1) << n) - 1) & ~b.targets;
  if (heads != 0 && (heads & (heads - 1)) != 0) return false;
  const std::uint32_t start = heads == 0 ? 0 : static_cast<std::uint32_t>(std::countr_zero(heads));
  std::uint32_t k = start, seen = 0;
  do {
    k = b.successor[k];
    ++seen;
  } while (k != kSmall && k != start && seen < n);
  return seen == n && (heads == 0 ? k == start : k == kSmall);
}

}  // namespace

// Most buckets: a few corners whose next identities are all different, each of which is
// the previous identity of at most one corner. Then no triangle duplicates another here
// (a duplicate has the same next identity) and no edge has more than one half-edge each
// way: each outgoing edge pairs with the one incoming edge of its identity, if any (what
// the sorted merge of pairSorted finds), with no sort. (Previous identities that no next one
// matches may repeat: the merge links nothing there either.) False where the bucket is not
// that case (then pairSorted pairs it).
bool Kernel::pairSmallBucket(std::uint32_t bucket, const std::uint32_t* list, std::uint32_t count) {
  const std::uint8_t* triangleFlags = ws_.triangleFlags.data();
  const std::int8_t* orientation = ws_.orientation.data();
  const std::int8_t firstOrientation = orientation[list[0] / 3];
  bool oneOrientation = true, all = true;
  for (std::uint32_t i = 0; i < count; ++i) {
    const std::uint32_t c = list[i];
    all &= !(triangleFlags[c / 3] & kCoincident);  // participates(c)
    oneOrientation &= orientation[c / 3] == firstOrientation;
  }
  SmallBucket b;
  if (all) {  // the identities bucketing put beside the corners
    const std::size_t first = static_cast<std::size_t>(list - corners_);
    b.outId = nextIds_ + first, b.inId = previousIds_ + first, b.corner = list;
    b.n = count;
  } else {
    std::uint32_t n = 0;
    for (std::uint32_t i = 0; i < count; ++i) {
      const std::uint32_t c = list[i];
      if (!participates(c)) {
        ws_.cornerLink[c] = kNone;
        continue;
      }
      b.gatheredCorner[n] = c;
      b.gatheredOut[n] = id(nextCorner(c));
      b.gatheredIn[n] = id(previousCorner(c));
      ++n;
    }
    b.outId = b.gatheredOut, b.inId = b.gatheredIn, b.corner = b.gatheredCorner;
    b.n = n;
  }
  if (!linkSmallBucket(b)) return false;
  const bool oneChain = b.n == count && oneSmallChain(b);
  const std::uint8_t chain = !oneChain ? kNotOneChain : (oneOrientation && orientationsFinal_ ? kOneFan : kOneChain);
  ws_.bucketUniform[bucket] = chain;
  // One fan of one orientation is one group whatever its links (groupBucket), and where
  // orientations are final nothing after grouping reads the links of corners that are not
  // copies: those links are not written.
  if (chain != kOneFan) {
    for (std::uint32_t i = 0; i < b.n; ++i) ws_.cornerLink[b.corner[i]] = b.match(i);
  }
  return true;
}

// Phases 2 and 4 of the common bucket at once, where orientations are final when buckets are
// paired: a small bucket whose corners all take part, whose links are the simple case
// (linkSmallBucket) and one chain through every corner (pairSmallBucket's kOneFan), of one
// orientation, and whose parked terms give the fan's frame (fastBucket). Then the same frame,
// states and bucketUniform as pairBucket and groupBucket would write, with one walk over the
// corners' slots and no gathers of identities; false (nothing written but the corners'
// cleared states, which pairBucket clears too) where the bucket is not that case.
bool Kernel::pairOneFan(std::uint32_t bucket, std::uint64_t& mirrored) {
  const std::uint32_t first = start_[bucket], count = start_[bucket + 1] - first;
  if (count < 2 || count > kSmall) return false;
  const std::uint32_t* list = corners_ + first;
  SmallBucket b;
  b.outId = nextIds_ + first, b.inId = previousIds_ + first, b.corner = list;
  b.n = count;
  if (!linkSmallBucket(b) || !oneSmallChain(b)) return false;
  // Every corner takes part and its triangle has one orientation: a coincident triangle's
  // corners park no cone bits (fanFrame asks for some in all), and the orientations are the
  // parked terms' kNotPositiveBit.
  const float* tangents = tangents_;
  FanAccumulator sum;
  for (std::uint32_t i = 0; i < count; ++i) sum.add(&tangents[4 * std::size_t(list[i])]);
  const FanSum fan = sum.result();
  if (!fan.oneOrientation) return false;
  return fanFrame(bucket, list, count, fan, mirrored);
}

// Pairing and grouping at once, bucket by bucket (Kernel::run, where orientations are final
// when buckets are paired): most buckets by pairOneFan, inlined here; the others, and any it
// does not take, the phases one after the other.
void Kernel::pairAndGroup(std::size_t begin, std::size_t end, BucketScratch& scratch, std::uint64_t& mirrored) {
#if defined(TANGENT_LANES8)
  if (isa_ == VectorIsa::avx2) return pairAndGroupEight(begin, end, scratch, mirrored);
#endif
  const bool fast = ws_.fastBuckets;
  for (std::size_t b = begin; b < end; ++b) {
    const auto bucket = static_cast<std::uint32_t>(b);
#if defined(__wasm_simd128__) && !defined(TANGENT_LANES8)
    // As pairAndGroupEight: the common closed fan first (closedFanWasm), then pairOneFan.
    if (fast) {
      const std::uint32_t first = start_[bucket], count = start_[bucket + 1] - first;
      const std::uint32_t* list = corners_ + first;
      FanSum fan;
      if (count >= 2 && count <= 8 && closedFanWasm(nextIds_ + first, previousIds_ + first, count, list, tangents_, fan)) {
        if (fan.oneOrientation && fanFrame(bucket, list, count, fan, mirrored)) continue;
      } else if (pairOneFan(bucket, mirrored)) {
        continue;
      }
    }
#else
    if (fast && pairOneFan(bucket, mirrored)) continue;
#endif
    pairBucket(bucket, scratch);
    groupBucket(bucket, scratch, mirrored);
  }
}

#if defined(TANGENT_LANES8)
// pairAndGroup where the processor has AVX2: a bucket of 2 to 8 corners is first tested for
// the common closed fan, eight identities a compare, which sums its terms as well
// (closedFanEight); where it is not one, pairOneFan tests for an open fan. Everything but
// pairBucket and groupBucket is inlined here.
__attribute__((target("avx2"))) void Kernel::pairAndGroupEight(std::size_t begin, std::size_t end,
                                                               BucketScratch& scratch, std::uint64_t& mirrored) {
  const bool fast = ws_.fastBuckets;
  for (std::size_t b = begin; b < end; ++b) {
    const auto bucket = static_cast<std::uint32_t>(b);
    if (fast) {
      const std::uint32_t first = start_[bucket], count = start_[bucket + 1] - first;
      const std::uint32_t* list = corners_ + first;
      FanSum fan;
      if (count >= 2 && count <= 8 &&
          closedFanEight(nextIds_ + first, previousIds_ + first, count, list, tangents_, fan)) {
        if (fan.oneOrientation && fanFrame(bucket, list, count, fan, mirrored)) continue;
      } else if (pairOneFan(bucket, mirrored)) {
        continue;
      }
    }
    pairBucket(bucket, scratch);
    groupBucket(bucket, scratch, mirrored);
  }
}
#endif

// The general case: outgoing and incoming half-edges sorted by the identity at their other
// end and merged; duplicates marked first; edges with more than one half-edge each way
// paired by pairNonManifold.
void Kernel::pairSorted(const std::uint32_t* list, std::uint32_t count, BucketScratch& scratch) {
  // keys: [0, n) outgoing (next id, corner), [n, 2n) incoming (previous id, corner).
  scratch.keys.resize(2 * count);
  std::uint64_t* outs = scratch.keys.data();
  std::size_t n = 0;
  for (std::uint32_t i = 0; i < count; ++i) {
    const std::uint32_t c = list[i];
    if (!participates(c)) continue;
    outs[n++] = (std::uint64_t(id(nextCorner(c))) << 32) | c;
  }
  std::uint64_t* ins = outs + n;
  for (std::size_t i = 0; i < n; ++i) {
    const auto c = static_cast<std::uint32_t>(outs[i]);
    ins[i] = (std::uint64_t(id(previousCorner(c))) << 32) | c;
  }
  sortSmall(outs, outs + n);
  sortSmall(ins, ins + n);
  markDuplicates(outs, n);
  auto isCopy = [&](std::uint64_t key) { return (ws_.cornerState[static_cast<std::uint32_t>(key)] & kCopy) != 0; };
  std::size_t o = 0, k = 0;
  while (o < n && k < n) {
    const std::uint64_t q = std::min(outs[o] >> 32, ins[k] >> 32);
    std::size_t oEnd = o, kEnd = k;
    while (oEnd < n && (outs[oEnd] >> 32) == q) ++oEnd;
    while (kEnd < n && (ins[kEnd] >> 32) == q) ++kEnd;
    std::size_t outCount = 0, inCount = 0;
    std::uint32_t lastOut = kNone, lastIn = kNone;
    for (std::size_t i = o; i < oEnd; ++i) {
      if (!isCopy(outs[i])) ++outCount, lastOut = static_cast<std::uint32_t>(outs[i]);
    }
    for (std::size_t i = k; i < kEnd; ++i) {
      if (!isCopy(ins[i])) ++inCount, lastIn = static_cast<std::uint32_t>(ins[i]);
    }
    if (outCount == 1 && inCount == 1) {
      ws_.cornerLink[lastOut] = lastIn;
    } else if (outCount > 0 && inCount > 0) {
      scratch.items.clear();
      for (std::size_t i = o; i < oEnd; ++i) {
        if (!isCopy(outs[i])) scratch.items.push_back(static_cast<std::uint32_t>(outs[i]));
      }
      const std::size_t split = scratch.items.size();
      for (std::size_t i = k; i < kEnd; ++i) {
        if (!isCopy(ins[i])) scratch.items.push_back(static_cast<std::uint32_t>(ins[i]));
      }
      const std::uint32_t* items = scratch.items.data();
      pairNonManifold(items, split, items + split, scratch.items.size() - split);
    }
    o = oEnd;
    k = kEnd;
  }
}

// Duplicates among a bucket's outgoing half-edges (sorted by next identity): same next and
// same previous identity. Each becomes a copy (kCopy) of the first that is not one.
void Kernel::markDuplicates(const std::uint64_t* outs, std::size_t n) {
  for (std::size_t i = 0; i < n;) {
    std::size_t j = i + 1;
    while (j < n && (outs[j] >> 32) == (outs[i] >> 32)) ++j;
    for (std::size_t y = i + 1; y < j; ++y) {
      const auto cy = static_cast<std::uint32_t>(outs[y]);
      for (std::size_t x = i; x < y; ++x) {
        const auto cx = static_cast<std::uint32_t>(outs[x]);
        if (!(ws_.cornerState[cx] & kCopy) && id(previousCorner(cx)) == id(previousCorner(cy))) {
          ws_.cornerState[cy] |= kCopy;
          anyCopy_.store(true, std::memory_order_relaxed);
          ws_.cornerLink[cy] = cx;
          break;
        }
      }
    }
    i = j;
  }
}

// The reference's greedy pairing of the half-edges of one edge, in value order of their
// triangles: each unpaired one takes the first later unpaired one running the other way.
void Kernel::pairNonManifold(const std::uint32_t* outs, std::size_t outCount, const std::uint32_t* ins, std::size_t inCount) {
  struct HalfEdge {
    std::uint32_t corner;
    bool outgoing;
    bool paired;
  };
  std::vector<HalfEdge> halfEdges;
  halfEdges.reserve(outCount + inCount);
  for (std::size_t i = 0; i < outCount; ++i) halfEdges.push_back({outs[i], true, false});
  for (std::size_t i = 0; i < inCount; ++i) halfEdges.push_back({ins[i], false, false});
  std::sort(halfEdges.begin(), halfEdges.end(),
            [&](const HalfEdge& x, const HalfEdge& y) { return triangleBefore(a_, x.corner / 3, y.corner / 3); });
  anyNonManifold_.store(true, std::memory_order_relaxed);
  for (std::size_t i = 0; i < halfEdges.size(); ++i) {
    if (halfEdges[i].outgoing) ws_.cornerState[halfEdges[i].corner] |= kNonManifoldEdge;
    if (halfEdges[i].paired) continue;
    for (std::size_t j = i + 1; j < halfEdges.size(); ++j) {
      if (halfEdges[j].paired || halfEdges[j].outgoing == halfEdges[i].outgoing) continue;
      halfEdges[i].paired = halfEdges[j].paired = true;
      const HalfEdge& out = halfEdges[i].outgoing ? halfEdges[i] : halfEdges[j];
      const HalfEdge& in = halfEdges[i].outgoing ? halfEdges[j] : halfEdges[i];
      ws_.cornerLink[out.corner] = in.corner;
      break;
    }
  }
}

}  // namespace tangent::detail::mikk
