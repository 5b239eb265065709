// SPDX-License-Identifier: MIT
// The peers the benchmarks measure against, on the same arrays in the same process: the
// reference MikkTSpace in C (Mikkelsen, genTangSpaceDefault) and meshoptimizer's
// meshopt_generateTangents in its MikkTSpace-compatible and default modes. Their unmodified
// sources live in ../shared/peers and are compiled only into the benchmark build (never into
// the library); built without them, peers() is empty and peersNote() says why.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "tangent/tangent.hpp"

namespace tangent::bench {

enum class Peer : std::uint8_t {
  referenceMikktspace,  // mikktspace.c, genTangSpaceDefault, face/vertex callbacks
  meshoptCompatible,    // meshopt_generateTangents(..., meshopt_TangentCompatible)
  meshoptDefault,       // meshopt_generateTangents(..., 0)
};

std::string_view toString(Peer peer);  // "mikktspace.c", "meshopt/compatible", "meshopt/default"

// The peers this build has: all three, or none.
const std::vector<Peer>& peers();

// Where the peers came from, or why they are missing (for configure-time-like messages).
std::string peersNote();

// Writes one tangent (x, y, z, w) per corner of mesh.indices into cornerTangents (4 floats per
// corner). w is in MikkTSpace's convention (fSign, bottom-left UV origin): glTF's TANGENT.w
// is its negation, so it equals the library's w with UvOrigin::bottomLeft.
void runPeer(Peer peer, const MeshArrays& mesh, std::span<float> cornerTangents);

}  // namespace tangent::bench
