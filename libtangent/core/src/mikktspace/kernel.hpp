// SPDX-License-Identifier: MIT
// Method `mikktspace`'s kernel: the state one call's phases share and the phases, one file
// each (see kernel.cpp for the rules and the order of the phases).
#pragma once

#include <algorithm>
#include <atomic>
#include <cstring>
#include <type_traits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "../state_bits.hpp"
#include "../parallel.hpp"
#include "angles.hpp"
#include "arrays.hpp"
#include "triangle.hpp"

namespace tangent::detail::mikk {

// Rounds x to a multiple of 2^-40 (|x| < 2^11): sums of up to 2^13 / pi such values are exact
// in double, so they come out the same in any order, with no sort.
constexpr double kQuantizer = 0x1.8p12;
inline double quantized(float x) {
  return (static_cast<double>(x) + kQuantizer) - kQuantizer;
}
constexpr std::uint32_t kMostQuantizedTerms = 2048;

// A fan's parked terms (fan.cpp) summed on the 2^-40 grid (exact in double, so in any order
// the same), with the AND of their cone bits, and whether their triangles have one
// orientation (kNotPositiveBit all set or all clear).
struct FanSum {
  double x, y, z, angleSum;
  std::uint32_t cone;
  bool oneOrientation;
};
class FanAccumulator {
 public:
  void add(const float* slot) {
#if defined(__SSE2__)
    // Two components at a time.
    const __m128d quantizer = _mm_set1_pd(kQuantizer);
    const __m128i keep = _mm_setr_epi32(-1, -1, -1, static_cast<int>(~(kConeBits | kNotPositiveBit)));
    const __m128i bits = _mm_loadu_si128(reinterpret_cast<const __m128i*>(slot));
    bits_ = _mm_and_si128(bits_, bits);
    anyBits_ = _mm_or_si128(anyBits_, bits);
    const __m128 terms = _mm_castsi128_ps(_mm_and_si128(bits, keep));
    xy_ = _mm_add_pd(xy_, _mm_sub_pd(_mm_add_pd(_mm_cvtps_pd(terms), quantizer), quantizer));
    za_ = _mm_add_pd(za_, _mm_sub_pd(_mm_add_pd(_mm_cvtps_pd(_mm_movehl_ps(terms, terms)), quantizer), quantizer));
#else
    const std::uint32_t bits = bitCast<std::uint32_t>(slot[3]);
    all_ &= bits;
    any_ |= bits;
    sum_.x += quantized(slot[0]), sum_.y += quantized(slot[1]), sum_.z += quantized(slot[2]);
    sum_.angleSum += quantized(bitCast<float>(bits & ~(kConeBits | kNotPositiveBit)));
#endif
  }
  FanSum result() const {
#if defined(__SSE2__)
    double lanes[4];
    _mm_storeu_pd(lanes, xy_);
    _mm_storeu_pd(lanes + 2, za_);
    const auto all = static_cast<std::uint32_t>(_mm_cvtsi128_si32(_mm_shuffle_epi32(bits_, 3)));
    const auto any = static_cast<std::uint32_t>(_mm_cvtsi128_si32(_mm_shuffle_epi32(anyBits_, 3)));
    return {lanes[0], lanes[1], lanes[2], lanes[3], kConeBits & all, ((all ^ any) & kNotPositiveBit) == 0};
#else
    FanSum sum = sum_;
    sum.cone = kConeBits & all_;
    sum.oneOrientation = ((all_ ^ any_) & kNotPositiveBit) == 0;
    return sum;
#endif
  }

 private:
#if defined(__SSE2__)
  __m128d xy_ = _mm_setzero_pd(), za_ = _mm_setzero_pd();
  __m128i bits_ = _mm_set1_epi32(-1), anyBits_ = _mm_setzero_si128();
#else
  FanSum sum_{0, 0, 0, 0, 0, true};
  std::uint32_t all_ = ~std::uint32_t(0), any_ = 0;
#endif
};

// Union-find over the corners of one bucket (local indices), the smaller root winning.
class BucketUnionFind {
 public:
  explicit BucketUnionFind(ScratchVector<std::uint32_t>& parent, std::uint32_t count) : parent_(parent) {
    parent_.resize(count);
    for (std::uint32_t i = 0; i < count; ++i) parent_[i] = i;
  }
  std::uint32_t find(std::uint32_t x) {
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
    return x;
  }
  void unite(std::uint32_t a, std::uint32_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }

 private:
  ScratchVector<std::uint32_t>& parent_;
};

// One bucket on the full path (grouping.cpp): what its steps share.
struct FullBucket {
  std::uint32_t bucket;
  const std::uint32_t* list;  // its corners
  std::uint32_t count;
  bool fan;                   // one group of every corner, in list order (no keys)
  V3 n;                       // unit normal (bucketNormal)
  F3 rawNormal;               // the normal as stored, for the reference's float rules
  V3 here;                    // the corners' common position (where a component is zero its
                              // sign may differ between corners, which moves no angle)
  BucketScratch& scratch;     // keys: (root, local index) per member, group by group
  std::size_t memberCount;
  std::uint32_t member(std::size_t m) const {
    return fan ? static_cast<std::uint32_t>(m) : static_cast<std::uint32_t>(scratch.keys[m]);
  }
  std::uint32_t rootOf(std::size_t m) const { return static_cast<std::uint32_t>(scratch.keys[m] >> 32); }
};

// A group's rows (Kernel::groupRows): kRowStride doubles each, and their value order.
constexpr int kRowStride = 10;
struct GroupRows {
  const double* values = nullptr;
  std::size_t contributing = 0;
  const std::uint32_t* sorted = nullptr;
};

class Kernel {
 public:
  Kernel(WorkspaceData& ws, const MeshArrays& mesh, const CornerOutputs& outputs, UvOrigin origin)
      : wSign_(handedness(1.0f, origin)),
        ws_(ws),
        mesh_(mesh),
        a_{mesh.positions.data(), mesh.normals.data(), mesh.uvs.data(), mesh.indices.data(), mesh.positions.size() / 3},
        tangents_(outputs.tangents.data()),
        cornerVertex_(outputs.cornerVertex.empty() ? nullptr : outputs.cornerVertex.data()) {}

  // Welds and buckets (weldAndBucket), then writes the tangents (w in the convention of the
  // call's UV origin, so that the output pass need not rewrite every tangent) and
  // ws.cornerState, and fills the triangle counts of the report. Returns what the output pass
  // may take as done.
  KernelOutcome run(Report& report);

 private:
  std::uint32_t id(std::size_t corner) const { return identity_ ? a_.indices[corner] : vertexId_[a_.indices[corner]]; }
  bool participates(std::size_t corner) const { return !(ws_.triangleFlags[corner / 3] & kCoincident); }
  std::uint32_t localIndex(std::uint32_t bucket, std::uint32_t corner) const {
    const std::uint32_t* begin = corners_ + start_[bucket];
    return static_cast<std::uint32_t>(std::lower_bound(begin, corners_ + start_[bucket + 1], corner) - begin);
  }

  void evaluateTriangles(Report& report);
  void pairBucket(std::uint32_t bucket, BucketScratch& scratch);
  void resetLinks(const std::uint32_t* list, std::uint32_t count);
  bool pairSmallBucket(std::uint32_t bucket, const std::uint32_t* list, std::uint32_t count);
  void pairSorted(const std::uint32_t* list, std::uint32_t count, BucketScratch& scratch);
  void markDuplicates(const std::uint64_t* outs, std::size_t n);
  void pairNonManifold(const std::uint32_t* outs, std::size_t outCount, const std::uint32_t* ins, std::size_t inCount);
  void resolveGroupWithAny();
  bool openForAny(std::size_t t) const;
  std::size_t neighbourTriangle(std::size_t t, int k) const;
  void orientReached(std::vector<std::uint32_t>& pending);
  void markReached(std::uint32_t bucket, ScratchVector<std::uint32_t>& parent, std::vector<std::uint8_t>& reached);
  void orientByNeighbours(std::vector<std::uint32_t>& pending);
  void orientAcrossEdges(std::vector<std::uint32_t> layer, std::vector<std::int8_t>& decided);
  void appendOpenNeighbours(const std::vector<std::uint32_t>& done, std::vector<std::uint32_t>& layer);
  std::vector<std::uint32_t> decideByVotes(std::vector<std::uint32_t>& candidates, bool byVertex,
                                           std::vector<std::int8_t>& decided);
  V3 bucketNormal(std::uint32_t bucket, bool& invalid) const;
  // Adds the bucket's corners with a negative w (as stored) to `mirrored`, copies aside.
  void groupBucket(std::uint32_t bucket, BucketScratch& scratch, std::uint64_t& mirrored);
  void groupMembers(FullBucket& b);
  std::size_t groupRows(FullBucket& b, std::size_t g, std::size_t gEnd);
  V3 subgroupSum(const FullBucket& b, const GroupRows& rows, std::size_t self, double& weights) const;
  bool groupFrames(FullBucket& b, std::size_t g, std::size_t gEnd);
  bool fastBucket(std::uint32_t bucket, const std::uint32_t* list, std::uint32_t count, std::uint64_t& mirrored);
  // The one frame of a fan from its summed terms (fastBucket, pairOneFan); false (nothing
  // written) where the sum does not give it. In the header, so that pairing.cpp's bucket loops
  // inline it.
  [[gnu::always_inline]] bool fanFrame(std::uint32_t bucket, const std::uint32_t* list, std::uint32_t count,
                                       const FanSum& fan, std::uint64_t& mirrored) {
    const std::uint32_t cone = fan.cone;
    const double x = fan.x, y = fan.y, z = fan.z, angleSum = fan.angleSum;
    if (!(cone & 0x3F) || !(cone & (0x3F << 6))) return false;
    // The sum made orthogonal to the raw normal N (as to the unit normal) and normalized: one
    // square root and one division for the bucket.
    const V3 sum{x, y, z}, normal = a_.normal(bucket);
    const double sum2 = dot(sum, sum), normal2 = dot(normal, normal);
    if (!(sum2 >= 0.0025 * angleSum * angleSum) || !(normal2 > 0) || !std::isfinite(normal2)) return false;
    const V3 t = sum - normal * (dot(normal, sum) / normal2);
    const double t2 = dot(t, t);
    if (!(t2 > 1e-24 * sum2)) return false;
    const V3 unit = t * (1.0 / std::sqrt(t2));
    const float w = ws_.orientation[list[0] / 3] > 0 ? 1.0f : -1.0f;
    const float frame[4] = {static_cast<float>(unit.x), static_cast<float>(unit.y), static_cast<float>(unit.z),
                            w * wSign_};
    // storeFrame without its state write: a corner's source and undefined bits are still clear
    // here (pairing cleared them; only its bucket's group pass sets them), and computed is 0.
    static_assert(static_cast<int>(FrameSource::computed) == 0);
    finishOneFrame(bucket, list, count, mirrored, frame);
    ws_.bucketExtra[bucket] = bitCast<std::uint32_t>(static_cast<float>(angleSum));
    ws_.bucketUniform[bucket] |= kBucketWeight;
    return true;
  }
  // Defined in pairing.cpp and inlined into its callers there (pairAndGroup, pairAndGroupEight).
  [[gnu::always_inline]] inline bool pairOneFan(std::uint32_t bucket, std::uint64_t& mirrored);
  void pairAndGroup(std::size_t begin, std::size_t end, BucketScratch& scratch, std::uint64_t& mirrored);
#if defined(TANGENT_LANES8)
  void pairAndGroupEight(std::size_t begin, std::size_t end, BucketScratch& scratch, std::uint64_t& mirrored);  // AVX2
#endif
  // Whether the triangles of a bucket's corners share one UV orientation (with a chain of
  // links through all of them from pairBucket: one group of every corner).
  bool oneOrientation(const std::uint32_t* list, std::uint32_t count) const {
    const std::int8_t orientation = ws_.orientation[list[0] / 3];
    bool same = true;
    for (std::uint32_t i = 1; i < count; ++i) same &= ws_.orientation[list[i] / 3] == orientation;
    return same;
  }
  // Whether the links of a bucket's corners form one cycle through all of them with one UV
  // orientation: the common closed fan around a vertex, one group without a union-find.
  // Links pair distinct half-edges, so a walk of `count` steps back to its start has seen
  // every corner once.
  bool closedFan(const std::uint32_t* list, std::uint32_t count) const {
    const std::uint32_t start = list[0];
    const std::int8_t orientation = ws_.orientation[start / 3];
    std::uint32_t c = start;
    for (std::uint32_t step = 0; step < count; ++step) {
      if (!participates(c) || (ws_.cornerState[c] & kCopy)) return false;
      const std::uint32_t d = ws_.cornerLink[c];
      if (d == kNone || ws_.orientation[d / 3] != orientation) return false;
      c = d;
      if (c == start) return step + 1 == count;
    }
    return false;
  }
  // The best computed frame of a bucket (with w, unless anyW) that a coincident corner copies,
  // kNone where none; inheritFrom writes it, or marks the corner undefined. Coincident corners
  // are never candidates, so one answer serves all of a bucket's.
  std::uint32_t bestComputedInBucket(std::uint32_t bucket, float w, bool anyW) const;
  void inheritFrom(std::uint32_t best, std::uint32_t corner, float w, bool anyW);
  void fallbacks();
  // fallbacks()'s two phases: a coincident triangle's corners take its majority w (from the
  // bucket's best frame with that w); then each undefined corner's frame from its bucket, its
  // triangle, the triangle's other buckets, or a fixed perpendicular.
  void fallbackCoincident();
  void fallbackUndefined();
  // The reference's corner angle (EvalTspace): float projections on the raw normal, float
  // cosine clamped to [-1, 1], acos.
  double referenceAngle(std::size_t corner, F3 rawNormal) const {
    auto at = [&](std::size_t c) { return floatsAt(a_.positions, a_.indices[c]); };
    return referenceAngleOf(at(corner), at(previousCorner(corner)), at(nextCorner(corner)), rawNormal);
  }
  // Once a bucket's groups are built its corners' neighbour links are spent: the same slot
  // then holds the corner's group weight (the sum of its angles), which ranks candidate
  // frames; corners of duplicate triangles keep their link to the original. A fast bucket
  // keeps its one weight per bucket instead (kBucketWeight).
  void setWeight(std::size_t corner, float weight) { ws_.cornerLink[corner] = bitCast<std::uint32_t>(weight); }
  float weight(std::size_t corner) const {
    const std::uint32_t bucket = id(corner);
    return bitCast<float>((ws_.bucketUniform[bucket] & kBucketWeight) ? ws_.bucketExtra[bucket] : ws_.cornerLink[corner]);
  }
  // A frame as stored (xyz, w in the output convention) into the corner's slot, with its source
  // and weight.
  void storeFrame(std::size_t corner, const float (&frame)[4], FrameSource source, float weight) {
    std::memcpy(&tangents_[4 * corner], frame, sizeof frame);
    ws_.cornerState[corner] = static_cast<std::uint8_t>((ws_.cornerState[corner] & ~(kSourceMask | kUndefined)) |
                                                        static_cast<std::uint8_t>(source));
    setWeight(corner, weight);
  }
  void writeCorner(std::size_t corner, V3 tangent, float w, FrameSource source, float weight) {
    const float frame[4] = {static_cast<float>(tangent.x), static_cast<float>(tangent.y), static_cast<float>(tangent.z),
                            w * wSign_};
    storeFrame(corner, frame, source, weight);
  }
  // A bucket whose corners all got one frame: whether they are one input vertex (bucketUniform,
  // so that the vertex split need not compare them), and its mirrored corners counted. Where
  // the call asks for the vertex split, each corner's input vertex goes into cornerVertex here
  // (the split of a one-vertex bucket; the output pass rewrites the corners of any other), so
  // that the split need not visit these corners again.
  // With a frame, it is first stored into every corner's slot (storeFrame without its state
  // and weight writes), in the same walk over the corners.
  [[gnu::always_inline]] void finishOneFrame(std::uint32_t bucket, const std::uint32_t* list, std::uint32_t count,
                                             std::uint64_t& mirrored, const float* frame = nullptr) {
    // Where the weld merged nothing, every corner of the bucket is its input vertex.
    // Members in locals: the stores below may alias them.
    const bool identity = identity_;
    float* tangents = tangents_;
    std::uint32_t* cornerVertex = cornerVertex_;
    const std::uint32_t* indices = a_.indices;
    const std::uint32_t vertex = identity ? bucket : indices[list[0]];
    bool oneVertex = true;
    auto walk = [&](auto withFrame, auto withVertex, auto sameVertex) {
      for (std::uint32_t i = 0; i < count; ++i) {
        const std::uint32_t c = list[i];
        if constexpr (decltype(withFrame)::value) std::memcpy(&tangents[4 * std::size_t(c)], frame, 4 * sizeof(float));
        const std::uint32_t v = decltype(sameVertex)::value ? vertex : indices[c];
        if constexpr (decltype(withVertex)::value) cornerVertex[c] = v;
        if constexpr (!decltype(sameVertex)::value) oneVertex &= v == vertex;
      }
    };
    using Yes = std::true_type;
    using No = std::false_type;
    auto walkWith = [&](auto withFrame, auto withVertex) {
      identity ? walk(withFrame, withVertex, Yes{}) : walk(withFrame, withVertex, No{});
    };
    if (frame) {
      cornerVertex_ ? walkWith(Yes{}, Yes{}) : walkWith(Yes{}, No{});
    } else {
      cornerVertex_ ? walkWith(No{}, Yes{}) : walkWith(No{}, No{});
    }
    ws_.bucketUniform[bucket] = oneVertex ? kUniformVertex : 0;
    if ((frame ? frame[3] : tangents_[4 * list[0] + 3]) < 0) mirrored += count;
  }
  void markUndefined(std::size_t corner, float w) {
    if (!anyUndefined_.load(std::memory_order_relaxed)) anyUndefined_.store(true, std::memory_order_relaxed);
    tangents_[4 * corner + 3] = w * wSign_;
    ws_.cornerState[corner] |= kUndefined;
    setWeight(corner, 0);
  }
  bool defined(std::size_t corner) const {
    const std::uint8_t s = ws_.cornerState[corner];
    if (s & kUndefined) return false;
    const auto source = static_cast<FrameSource>(s & kSourceMask);
    return source == FrameSource::computed || source == FrameSource::inherited;
  }
  // Ranking of a candidate frame: heavier group first, then by value.
  bool betterCandidate(std::size_t a, std::size_t b) const {
    if (weight(a) != weight(b)) return weight(a) > weight(b);
    std::uint32_t bitsA[4], bitsB[4];
    std::memcpy(bitsA, &tangents_[4 * a], 3 * sizeof(float));
    std::memcpy(bitsB, &tangents_[4 * b], 3 * sizeof(float));
    bitsA[3] = bitCast<std::uint32_t>(w(a));
    bitsB[3] = bitCast<std::uint32_t>(w(b));
    return std::lexicographical_compare(bitsB, bitsB + 4, bitsA, bitsA + 4);
  }

  // Every w is stored in the output convention (times wSign_); the rules here compare the
  // reference's own w (bottom-left), read back through w().
  float w(std::size_t corner) const { return tangents_[4 * corner + 3] * wSign_; }

  const float wSign_;
  WorkspaceData& ws_;
  const MeshArrays& mesh_;
  Arrays a_;
  float* tangents_;
  std::uint32_t* cornerVertex_;  // null where the call does not ask for the vertex split
  // The weld's and the buckets' arrays, taken once they are filled.
  const std::uint32_t* vertexId_ = nullptr;
  bool identity_ = false;  // the weld merged nothing: id(corner) is the corner's index
  const std::uint32_t* start_ = nullptr;
  const std::uint32_t* corners_ = nullptr;
  const std::uint32_t* nextIds_ = nullptr;      // beside corners_: each corner's next and
  const std::uint32_t* previousIds_ = nullptr;  // previous identities
  std::uint64_t groupWithAny_ = 0;  // triangles that group with any (not coincident)
  std::uint64_t coincident_ = 0;    // coincident triangles
  // Whether any corner was marked undefined, any edge is non-manifold: where not, the passes
  // that look for them are skipped.
  std::atomic<bool> anyUndefined_{false}, anyNonManifold_{false};
  std::atomic<bool> anyCopy_{false};  // a corner is kCopy (pairing)
  std::uint64_t mirroredCorners_ = 0;  // corners with w < 0, copies aside (group, fallback)
  const VectorIsa isa_ = activeVectorIsa();
  // Whether the UV orientations are final when the buckets are paired (no zero-UV triangle
  // waits for its neighbours'), so that pairing may vouch for one orientation.
  bool orientationsFinal_ = false;
};

}  // namespace tangent::detail::mikk
