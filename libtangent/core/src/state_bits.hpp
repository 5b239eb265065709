// SPDX-License-Identifier: MIT
// Every state bit of the array kernel, with its meaning and its lifetime: which phase sets it,
// which phases read it, and when the slot is spent. Phases (mikktspace/kernel.cpp):
//   weld      weldAndBucket (weld.cpp)
//   triangle  the triangle pass (mikktspace/triangle_pass.cpp)
//   pair      pairBucket (mikktspace/pairing.cpp)
//   orient    resolveGroupWithAny (mikktspace/orientation.cpp), only with zero-UV triangles
//   group     groupBucket / fastBucket (mikktspace/grouping.cpp, fan.cpp)
//   fallback  fallbacks (mikktspace/fallbacks.cpp)
//   output    finishOutputs (outputs.cpp)
#pragma once

#include <cstdint>

namespace tangent::detail {

// WorkspaceData::cornerState, one byte per corner. Cleared by `triangle` for every corner
// (lengyel and flat write only kSourceMask, kUndefined in between and kInvalidNormal, before
// `output`).
enum CornerState : std::uint8_t {
  // FrameSource of the corner's frame: set by `group` and `fallback`, read by `fallback`
  // (candidates) and `output` (report counts, CornerOutputs::sources).
  kSourceMask = 3,
  // No frame yet: set by `group` (a group that sums to nothing) and `fallback`'s inheriting,
  // cleared when a frame is written; `fallback` gives every such corner one. flat: set by
  // flatFrames, cleared by frameUndefinedCorners (lengyel_groups.cpp) before `output`.
  kUndefined = 4,
  // Corner of an exact duplicate triangle: set by `pair`; its cornerLink names the original,
  // whose frame `output` copies. Read by `orient`, `group`, `fallback` (such corners take no
  // part) and `output`.
  kCopy = 8,
  // The corner's welded vertex has a zero or non-finite normal, replaced: set by `group`, read
  // by `output` (Report::invalidNormals).
  kInvalidNormal = 16,
  // The corner's outgoing edge is shared by more than two triangles: set by `pair`
  // (pairNonManifold), read once after `pair` to count Report::nonManifoldFaces.
  kNonManifoldEdge = 32,
  // Scratch of `orient` only, cleared again before it returns: the groups that reach this
  // zero-UV corner include one of negative / positive UV orientation.
  kReachedMinus = 64,
  kReachedPlus = 128,
};

// WorkspaceData::triangleFlags, one byte per triangle: set by `triangle`, read by every later
// phase; never changed after it.
enum TriangleFlag : std::uint8_t {
  kCoincident = 1,    // two corners with the same position: the reference's "degenerate";
                      // its corners take part in nothing and inherit a frame
  kGroupWithAny = 2,  // contributes nothing and takes the orientation of its neighbours
  kNonFinite = 4,     // NaN or infinity in a position or UV (report: nonFinite)
  kFlat = 8,          // zero 3D area (report: degenerate)
  kZeroUv = 16,       // zero UV area (report: zeroUvArea)
};

// WorkspaceData::bucketUniform, one byte per welded vertex, holds two things in turn.
// From `pair` to the start of `group` (same bucket): what the pairing found about the bucket's
// links, a value (not bits). `group` reads it, then overwrites the slot with BucketUniform.
enum BucketChain : std::uint8_t {
  kNotOneChain = 0,    // the links do not form one chain through all corners
  kOneChain = 1,       // one chain through all corners, all taking part, none a copy
  kChainUnknown = 2,   // pairing could not tell (the general path ran)
  kOneFan = 3,         // one chain whose triangles have one UV orientation, where orientations
                       // were final at pairing: one group, and its links were not written
};
// From `group` to `output` (the kernel hands the array to `output` in
// KernelOutcome::bucketUniform; lengyel and flat do not): bits.
enum BucketUniform : std::uint8_t {
  // All the bucket's corners got one frame and are one input vertex, and nothing after `group`
  // changes them: `output`'s vertex split need not compare them.
  kUniformVertex = 1,
  // `fan` kept the group weight of all the bucket's corners once, in the bucket's bucketExtra
  // slot (free between the weld and `output`), instead of per corner in cornerLink.
  kBucketWeight = 2,
};

// WorkspaceData::cornerLink, one 32-bit word per corner, in turn:
//   `pair` to `group`: the neighbour corner across the corner's outgoing edge (kNone: none), or
//     for a kCopy corner the original corner; read by `orient` and `group`.
//   `group` to `fallback`: the float bits of the corner's group weight (its angles' sum),
//     which ranks candidate frames (Kernel::weight); kCopy corners keep their original.
//   `output`: the original of each kCopy corner.
// lengyel and flat set every link to kNone before `output`.

}  // namespace tangent::detail
