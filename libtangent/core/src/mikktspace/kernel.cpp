// SPDX-License-Identifier: MIT
// Method `mikktspace` over packed arrays.
// Source: M. S. Mikkelsen, "Simulation of Wrinkled Surfaces Revisited", MSc thesis, 2008, and
// the rules of the reference implementation (mikktspace.h/.c, 2011):
//  * A corner's identity is its (position, normal, UV) value. Triangles with two corners at
//    one position ("coincident") take part in nothing; their corners copy the frame of a
//    corner with the same identity.
//  * Two triangles are neighbours across an edge when its two ends have the same identities
//    on both sides and the edge runs the opposite way. Where more than two triangles share an
//    edge, half-edges are paired greedily in a fixed order (the reference: face order).
//  * A triangle with zero UV area or zero dP/du or dP/dv "groups with any": it adds nothing
//    and takes the UV orientation of the groups that reach it.
//  * A group is the set of corners around one identity connected through neighbour edges
//    between triangles of the same UV orientation. A corner's tangent is the sum, over the
//    triangles of its group whose dP/du and dP/dv are not exactly opposite to its own (the
//    reference's subgroups at its default 180 degree threshold), of dP/du projected onto the
//    normal, normalized and weighted by the corner angle in the tangent plane.
// Where the reference depends on face order or a triangle's first corner we use rules that
// depend on values only, so that no shuffle changes a bit: each triangle is evaluated from its
// smallest corner; non-manifold edges pair in the order of the triangles' values; a zero-UV
// triangle takes the orientation most of its neighbours have (layer by layer outwards from
// oriented triangles, ties +1); a coincident corner copies the heaviest group of its identity;
// exact duplicate triangles share one frame. One triangle never gets mixed w, and no corner is
// left without a frame: FrameSource says where a frame was borrowed or made up.
//
// Layout: a few passes over packed arrays. Weld by hashing and bucket corners by welded
// vertex (counting sort) beside the triangle pass, which needs no weld; then every phase runs
// per triangle or per bucket in parallel (oneTBB); each item's result depends only on the
// input, so any thread count gives the same bits.
// Two paths per bucket. The triangle pass parks each corner's angle-weighted term in its
// output slot (float, eight or four triangles at a time: triangle_lanes.inc); a bucket that
// is one fan (closed or open) of one UV orientation, with every corner in the common case and
// no pair the subgroup rule could split, sums its parked terms rounded to multiples of 2^-40 (exact double sums, so no
// order moves a bit) and writes one frame (fastBucket). Every other bucket takes the full path
// (groupBucket): double-precision angles, sums in value order, the subgroup test, the
// reference's own float sums where terms cancel.
//
// Files (mikktspace/), in phase order; the state bits they share: ../state_bits.hpp.
//   kernel.cpp         this orchestration (Kernel::run) and the entry mikktspaceOnArrays
//   kernel.hpp         the state of one call and the small rules every phase uses
//   math.hpp           double (V3) and reference float (F3) vector arithmetic, orthonormalize
//   angles.hpp         atan2 in double (scalar, two lanes) and float, the reference's acos
//   arrays.hpp         the input as read, value orders (first corner, triangle order)
//   ../weld.cpp        1a. weld by value, bucket corners by welded vertex
//   triangle_pass.cpp  1b. every triangle, beside the weld (widest ISA: isa.cpp)
//   triangle.cpp       the triangle rules one at a time; lanes4.cpp, lanes8.cpp (lanes.inc,
//                      triangle_lanes.inc) four and eight at a time, the same bits
//   pairing.cpp        2. neighbours, duplicates, non-manifold edges
//   orientation.cpp    3. zero-UV triangles' orientation (only where there are some)
//   fan.cpp            4a. the one-fan shortcut from the parked terms
//   grouping.cpp       4b. groups, subgroups and sums in value order (the full path)
//   normals.cpp        a welded vertex's unit normal and its replacement
//   fallbacks.cpp      5. coincident triangles' w, corners without a frame
//   ../outputs.cpp     6. copies, w convention, counts, the vertex split
#include <functional>

#include "kernel.hpp"

namespace tangent::detail::mikk {

KernelOutcome Kernel::run(Report& report) {
  const std::size_t cornerCount = ws_.cornerCount, triangleCount = cornerCount / 3;
  ensureSize(ws_.orientation, triangleCount);
  ensureSize(ws_.triangleFlags, triangleCount);
  ensureSize(ws_.cornerLink, cornerCount);
  ensureSize(ws_.cornerState, cornerCount);
  ensureSize(ws_.bucketUniform, ws_.vertexCount);
  // The triangle pass needs no weld: on two threads and more it runs beside the weld and the
  // bucketing. Below four threads, those take the one-thread way, the least work: while one
  // thread welds and buckets, the others evaluate triangles, then all finish them. From four,
  // the weld alone would take longer than the triangle pass on the other threads.
  const unsigned weldThreads = ws_.threads < 4 ? 1 : ws_.threads;
  invokeBoth(ws_, [&] { weldAndBucket(ws_, mesh_, weldThreads, true); }, [&] { evaluateTriangles(report); });
  releaseWhenDone(ws_, ws_.table, ws_.weldCounts);  // the weld's (setReleaseAsItGoes)
  vertexId_ = ws_.vertexId.data();
  identity_ = ws_.weldMergedNone;
  start_ = ws_.bucketStart.data();
  corners_ = ws_.bucketCorners.data();
  nextIds_ = ws_.bucketNextId.data();
  previousIds_ = ws_.bucketPreviousId.data();

  const std::size_t bucketCount = ws_.vertexCount;
  // Pairing and grouping touch only the bucket's own corners, except where a zero-UV
  // triangle takes its orientation from its neighbours between them (resolveGroupWithAny):
  // without one, each bucket is paired and grouped at once, while its data is in cache.
  const bool fused = groupWithAny_ == 0;
  orientationsFinal_ = fused;
  Combinable<std::uint64_t> mirrored;
  forRange(ws_, bucketCount, 1024, [&](std::size_t begin, std::size_t end) {
    BucketScratch& scratch = ws_.scratch.local();
    std::uint64_t local = 0;
    if (fused) {
      pairAndGroup(begin, end, scratch, local);
    } else {
      for (std::size_t b = begin; b < end; ++b) pairBucket(static_cast<std::uint32_t>(b), scratch);
    }
    mirrored.local() += local;
  });
  if (anyNonManifold_.load(std::memory_order_relaxed)) {
    Combinable<std::uint64_t> nonManifold;
    forRange(ws_, triangleCount, 1 << 14, [&](std::size_t begin, std::size_t end) {
      std::uint64_t local = 0;
      for (std::size_t t = begin; t < end; ++t)
        local += ((ws_.cornerState[3 * t] | ws_.cornerState[3 * t + 1] | ws_.cornerState[3 * t + 2]) & kNonManifoldEdge) != 0;
      nonManifold.local() += local;
    });
    report.nonManifoldFaces = nonManifold.combine(std::plus<>());
  }
  if (!fused) {
    resolveGroupWithAny();
    forRange(ws_, bucketCount, 1024, [&](std::size_t begin, std::size_t end) {
      BucketScratch& scratch = ws_.scratch.local();
      std::uint64_t local = 0;
      for (std::size_t b = begin; b < end; ++b) groupBucket(static_cast<std::uint32_t>(b), scratch, local);
      mirrored.local() += local;
    });
  }
  mirroredCorners_ = mirrored.combine(std::plus<>());
  releaseWhenDone(ws_, ws_.bucketNextId, ws_.bucketPreviousId);  // the pairing's
  fallbacks();
  return KernelOutcome{true, mirroredCorners_, anyCopy_.load(std::memory_order_relaxed), ws_.bucketUniform.data(), true};
}

}  // namespace tangent::detail::mikk

namespace tangent::detail {

Report mikktspaceOnArrays(WorkspaceData& ws, const MeshArrays& mesh, const CornerOutputs& outputs, const Options& options) {
  Report report;
  beginCall(ws, mesh);
  report.method = Method::mikktspace;
  report.weighting = Weighting::angle;
  report.triangles = ws.cornerCount / 3;
  report.corners = ws.cornerCount;
  const KernelOutcome done = mikk::Kernel(ws, mesh, outputs, options.uvOrigin).run(report);
  finishOutputs(ws, mesh, outputs, options, report, done);
  return report;
}

}  // namespace tangent::detail
