// SPDX-License-Identifier: MIT
// `tangent check`'s verdict on each corner: the one rule behind check's findings and counts, the
// triangles its HTML report frames, and the viewer's error view (scene.hpp). Primitives are named
// by their indices in the document, never by a label.
#pragma once

#include <compare>
#include <cstdint>
#include <filesystem>
#include <vector>

#include "tangent/check.hpp"

namespace tangent::gltf {

// meshes[mesh].primitives[primitive] of a document.
struct PrimitiveIndex {
  int mesh = 0;
  int primitive = 0;
  auto operator<=>(const PrimitiveIndex&) const = default;
};

// Bits of CornerVerdict::problems: the checks of `tangent check` that fail at a corner. The
// per-vertex checks (finite, unit, w, orthogonal) mark every corner of a failing vertex;
// handedness marks the corners whose w disagrees with their triangle's UV orientation; reference
// marks the corners it finds too far from the recomputed frame. A check --only/--ignore leaves
// out marks nothing.
enum CornerProblem : std::uint8_t {
  kProblemNotFinite = 1,
  kProblemNotUnit = 2,
  kProblemBadW = 4,
  kProblemNotOrthogonal = 8,
  kProblemHandedness = 16,
  kProblemFarFromReference = 32,
};

// What `reference` made of one corner.
enum class ReferenceVerdict : std::uint8_t {
  notChecked,  // not compared: reference not run, or the stored tangent is not finite
  undefined,   // the generator defines no frame here (FrameSource neighbour or fixed): not compared
  unresolved,  // rounded positions/UVs leave the frame open (the allowance reaches 180 deg, or the
               // triangle's UV orientation is undecided and w differs): not compared
  agrees,      // within the limit (on the angle alone where wUndecided)
  disagrees,   // further than the limit, or w differs
};

struct CornerVerdict {
  ReferenceVerdict reference = ReferenceVerdict::notChecked;
  std::uint8_t problems = 0;   // CornerProblem bits
  bool wUndecided = false;     // compared on the angle alone: rounding leaves its triangle's UV orientation open
  float referenceDegrees = 0;  // angle between the stored and the recomputed tangent where compared, else 0
};

// The corners of one primitive that check judged, in the order of its triangle list (3 per
// triangle, the triangles as the indices and mode give them).
struct PrimitiveVerdicts {
  PrimitiveIndex primitive;
  std::vector<CornerVerdict> corners;
};

// checkFile's verdict per corner on every primitive it checks with `options` (the same method,
// weighting, tolerances, --only/--ignore, all and allowMissing), in checkFile's order. A
// primitive that check skips or that fails present or format has no entry. Throws InputError
// on unreadable input, as checkFile does.
std::vector<PrimitiveVerdicts> checkCorners(const std::filesystem::path& input, const CheckOptions& options);

}  // namespace tangent::gltf
