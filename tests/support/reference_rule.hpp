// SPDX-License-Identifier: MIT
// The differential rule against the reference C MikkTSpace (from the issue "randomized
// differential test against the reference C MikkTSpace"):
//  * the reference runs on the original triangle order and on kShuffles shuffles of it with
//    randomly rotated corners (the first shuffle reverses the order), the results mapped back
//    to the original corners; a corner is stable when all runs agree (within kStableDegrees
//    and the same sign). The issue asks for at least 3 shuffles; where more than two
//    triangles share an edge the reference pairs them greedily in face order, and 3 shuffles
//    often miss the orders that change a pairing, so we take 12;
//  * a corner is undefined where the reference frame is not a unit vector orthogonal to the
//    corner's unit normal within kDefinedTolerance (the reference leaves (1,0,0) where no
//    group reaches); a corner is "reference mixed w" when the reference's sign differs
//    between the corners of its triangle;
//  * on stable, defined corners of triangles with uniform reference w, ours must be within
//    kAgreeDegrees and have w == -fSign (glTF's convention); every other corner must be
//    finite, unit (within kUnitTolerance), have w exactly +-1, and every triangle of ours
//    must have one w.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "support/mikktspace_c.hpp"
#include "tangent/tangent.hpp"

namespace tangent::testing {

inline constexpr double kAgreeDegrees = 0.01;
inline constexpr double kStableDegrees = kAgreeDegrees / 4;  // see sameFrame() in reference_rule.cpp
inline constexpr double kDefinedTolerance = 1e-3;
inline constexpr double kUnitTolerance = 1e-5;
inline constexpr int kShuffles = 12;

// Classes are exclusive, in this order of precedence.
enum class CornerClass : std::uint8_t {
  compared,         // stable, defined, uniform reference w: ours must match
  undefined,        // reference frame not unit or not orthogonal to the unit normal (original order),
                    // or the reference's untouched initial space (see ReferenceFrame::initialSpace)
  unstable,         // the 4 reference runs disagree
  referenceMixedW,  // the reference's w differs between the corners of the triangle
};

struct RuleCounts {
  std::uint64_t meshes = 0, triangles = 0, corners = 0;
  std::uint64_t compared = 0, undefined = 0, unstable = 0, referenceMixedW = 0;
  std::uint64_t unreached = 0;  // of the undefined: unit and orthogonal, but the initial space
  // Failures of ours.
  std::uint64_t angleFailures = 0;      // compared corners further than kAgreeDegrees
  std::uint64_t wFailures = 0;          // compared corners with w != -fSign
  std::uint64_t invalidCorners = 0;     // not finite, not unit or w not exactly +-1 (any class)
  std::uint64_t mixedWTriangles = 0;    // our triangles whose corners have different w
  std::uint64_t referenceFailures = 0;  // genTangSpaceDefault returned false or skipped a corner
  double maxDegrees = 0;                // over compared corners

  std::uint64_t failures() const {
    return angleFailures + wFailures + invalidCorners + mixedWTriangles + referenceFailures;
  }
  void add(const RuleCounts& other);
  std::string describe() const;
};

struct RuleResult {
  RuleCounts counts;
  std::vector<CornerClass> classes;                    // per corner
  std::vector<std::vector<ReferenceFrame>> reference;  // per run (0: original order), per corner
  std::vector<double> degrees;                         // ours vs reference run 0, per corner
  std::vector<bool> failed;                            // per corner: ours broke the rule there
};

// ours: x, y, z, w per corner in glTF's convention. shuffleSeed picks the 3 shuffles.
RuleResult applyReferenceRule(const MeshArrays& mesh, std::span<const float> ours, std::uint64_t shuffleSeed);

// One line per corner (class, the reference runs, ours, the angle), for replaying a seed.
std::string describeCorners(const MeshArrays& mesh, std::span<const float> ours, const RuleResult& result);

std::string_view toString(CornerClass cornerClass);

}  // namespace tangent::testing
