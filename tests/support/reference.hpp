// SPDX-License-Identifier: MIT
// The reference MikkTSpace (npm `mikktspace`, WebAssembly) run on de-indexed meshes, and the
// per-corner comparison against it.
#pragma once

#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "tangent/tangent.hpp"

namespace tangent::testing {

// One entry per corner.
struct CornerArrays {
  std::string name;
  std::vector<float> positions, normals, uvs;
};

CornerArrays deindex(const std::string& name, const MeshArrays& mesh);

// Tangents per corner (xyzw) as the reference returns them: bottom-left UV convention.
// Fails the calling test and returns no vectors at all (callers assert the count before
// indexing) when node or the package is missing or the reference answers short.
std::vector<std::vector<float>> referenceTangents(const std::vector<CornerArrays>& meshes);

struct Agreement {
  std::size_t corners = 0;
  std::size_t compared = 0;         // where the reference frame is finite and non-zero and ours computed/inherited
  std::size_t referenceZero = 0;    // reference frame zero or not finite: not compared
  std::size_t ourFallback = 0;      // we substituted a frame where the reference has an arbitrary one
  std::size_t fallbackDisagreeing = 0;  // of those, how many differ from the reference's arbitrary frame
  std::size_t wMismatches = 0;
  double medianDegrees = 0, p99Degrees = 0, maxDegrees = 0;
  std::string describe() const;
};

// ours: xyzw per corner; sources may be empty (then every corner is compared); negateW
// compares against the reference with its w negated (glTF's convention).
Agreement compareWithReference(std::span<const float> ours, std::span<const float> reference,
                               std::span<const FrameSource> sources, bool negateW);

}  // namespace tangent::testing
