// SPDX-License-Identifier: MIT
// Methods `lengyel`, `flat` and `meshopt` on packed arrays: what their phases share
// (lengyel.cpp runs them, lengyel_groups.cpp groups corners, sums and fills in fallbacks).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <tuple>
#include <vector>

#include "gram_schmidt.hpp"
#include "triangle_tangent.hpp"
#include "parallel.hpp"

namespace tangent::detail {

// Which corners share one frame.
enum class Grouping : std::uint8_t {
  byValue,  // lengyel, meshopt: corners with the same position, normal, UV and UV orientation
  perFace,  // flat: the same, within one triangle only (no smoothing)
};

// The methods' own pipeline, inside the call's arena on checked arrays: beginCall, the weld and
// buckets (for the vertex split), then the phases of lengyel.cpp and finishOutputs.
Report lengyelOnArrays(WorkspaceData& ws, const MeshArrays& mesh, const CornerOutputs& outputs, const Options& options,
                       Grouping grouping);

// The bits of a value, +0 and -0 alike. Inline with the key's comparisons below: called per
// corner and per comparison of the grouping's sorts (out of line they were 8-10% of a call).
inline std::uint64_t bitsOf(double value) { return bitCast<std::uint64_t>(value == 0.0 ? 0.0 : value); }

// Per corner, what the triangle pass found (one entry per corner of `indices`), in the
// workspace's arrays (triangleTerms, cornerNormals, cornerWeights, invalidNormal, vertexUnitNormals).
struct TriangleData {
  std::span<TriangleTerms> triangles;
  std::span<Vec3> cornerNormals;       // where invalidNormal only: its replacement (replacedNormal)
  std::span<double> cornerWeights;     // the weighting's term; 0 where the triangle is not usable
  std::span<std::uint8_t> invalidNormal;
  std::span<const Vec3> vertexUnitNormals;  // per vertex (ws.vertexUnitNormals)
  std::span<const std::uint32_t> indices;
  // A corner's unit normal: its vertex's, or where that is invalid its replacement. Read from
  // the vertex rather than stored per corner (24 bytes a corner written and read again).
  const Vec3& cornerNormal(std::size_t corner) const {
    return invalidNormal[corner] ? cornerNormals[corner] : vertexUnitNormals[indices[corner]];
  }
};

// The corners' key, sorted: equal keys (all but `corner`) are one group.
struct CornerKey {
  std::uint32_t weld = 0;  // the position's representative vertex (positionWeld)
  std::int32_t orientation = 0;
  std::uint64_t tag = 0;   // 0, or for `flat` the triangle + 1
  std::uint64_t normal[3] = {};
  std::uint64_t uv[2] = {};
  std::uint32_t corner = 0;
  bool sameGroup(const CornerKey& o) const {
    return weld == o.weld && orientation == o.orientation && tag == o.tag && sameAttributes(o);
  }
  bool sameAttributes(const CornerKey& o) const {  // normal and UV bits
    return normal[0] == o.normal[0] && normal[1] == o.normal[1] && normal[2] == o.normal[2] && uv[0] == o.uv[0] &&
           uv[1] == o.uv[1];
  }
  bool operator<(const CornerKey& o) const {
    return std::tie(weld, orientation, tag, normal[0], normal[1], normal[2], uv[0], uv[1], corner) <
           std::tie(o.weld, o.orientation, o.tag, o.normal[0], o.normal[1], o.normal[2], o.uv[0], o.uv[1], o.corner);
  }
};

// One per group: at 3 per triangle for `flat`, so kept small (the key is not copied, the
// bitangents' sum lives only while the group is summed).
struct Group {
  const CornerKey* key = nullptr;  // of its first corner (the smallest index), in CornerGroups::keys
  Vec3 normal{0, 0, 1};   // unit: its first corner's
  Vec3 tangentSum{0, 0, 0};
  Vec3 tangent{0, 0, 0};
  double w = 1;           // handedness on the stored UVs (bottom-left convention)
  FrameSource source = FrameSource::computed;
  bool defined = false;
  bool mayInherit = false;  // its first corner's triangle is not usable: copying a corner of
                            // the same attributes is the method's own rule here
};

// The grouped corners: groups in key order; the corners of group g are
// sortedCorners[groupStart[g] .. groupStart[g + 1]).
// Moved, never copied: each Group's key points into `keys`.
struct CornerGroups {
  CornerGroups() = default;
  CornerGroups(CornerGroups&&) = default;
  CornerGroups& operator=(CornerGroups&&) = default;
  CornerGroups(const CornerGroups&) = delete;
  CornerGroups& operator=(const CornerGroups&) = delete;
  std::vector<CornerKey> keys;  // every corner's, sorted
  std::vector<Group> groups;
  std::vector<std::uint32_t> groupStart;
  std::vector<std::uint32_t> sortedCorners;
  std::vector<std::uint32_t> cornerGroup;  // every corner's group (groupCorners only)
};

// Sorts the corners by key (in parallel) and cuts them into groups.
CornerGroups groupCorners(const WorkspaceData& ws, const MeshArrays& mesh, std::span<const std::uint32_t> weldOf,
                          const TriangleData& data, Grouping grouping);
// The same over the listed corners only (increasing; every corner of each position it
// lists): the groups of those positions, as groupCorners makes them; no cornerGroup.
CornerGroups groupCornersAt(const WorkspaceData& ws, const MeshArrays& mesh, std::span<const std::uint32_t> weldOf,
                            const TriangleData& data, Grouping grouping, std::span<const std::uint32_t> corners);

// A corner's weighted terms in its group's sum.
struct Contribution {
  Vec3 tangent;
  Vec3 bitangent;
  bool operator<(const Contribution& o) const {
    return std::tie(tangent.v[0], tangent.v[1], tangent.v[2], bitangent.v[0], bitangent.v[1], bitangent.v[2]) <
           std::tie(o.tangent.v[0], o.tangent.v[1], o.tangent.v[2], o.bitangent.v[0], o.bitangent.v[1], o.bitangent.v[2]);
  }
};

// The corner's weighted terms, where its triangle is usable and its weight positive (`flat`
// weighs every corner alike), appended to `terms`; nothing where it has none.
// Written in place: a Contribution made on the stack and pushed was read back in 16-byte
// pieces its 8-byte stores could not forward to (a stall per corner of the bucket pass).
inline void addTerm(const TriangleData& data, std::uint32_t corner, Method method, std::vector<Contribution>& terms) {
  const TriangleTerms& triangle = data.triangles[corner / 3];
  if (triangle.kind != TriangleKind::usable) return;
  const double weight = method == Method::flat ? 1.0 : data.cornerWeights[corner];
  if (!(weight > 0)) return;
  Contribution& term = terms.emplace_back();
  for (int i = 0; i < 3; ++i) {
    term.tangent[i] = triangle.tangent[i] * weight;
    term.bitangent[i] = triangle.bitangent[i] * weight;
  }
}

// One group's frame from its terms, the one statement of it: summed in value order (`terms`
// sorted here) onto tangentSum (zero on entry), made orthogonal to the group's unit normal, w
// from the bitangents' side (meshopt: from the UV orientation, the group's key). False where
// nothing is left (tangent and w untouched): the group is undefined.
bool sumTerms(std::span<Contribution> terms, const Vec3& normal, int orientation, Method method, Vec3& tangentSum,
              Vec3& tangent, double& w);

// Each group's weighted terms summed in value order (so no order of the input moves a bit),
// then made orthogonal to its normal; w from the bitangents' side (meshopt: from the UV
// orientation, as meshoptimizer signs its frames). `flat` weights every term alike.
void sumAndOrthonormalize(const WorkspaceData& ws, const TriangleData& data, CornerGroups& cornerGroups, Method method);

// Gives every group without a frame one (see FrameSource): a group of its position with the
// same attributes, any group of its position, a group of a neighbouring position, or a fixed
// perpendicular.
void fillUndefinedGroups(const MeshArrays& mesh, std::span<const std::uint32_t> weldOf, CornerGroups& cornerGroups);

// The frames of the corners marked kUndefined in cornerState (their groups have no frame), by
// lengyel's groups and fallbacks over the positions those read only; the mark cleared, the
// source written (lengyel_groups.cpp). The phases that frame groups directly end with it.
void frameUndefinedCorners(WorkspaceData& ws, const MeshArrays& mesh, std::span<const std::uint32_t> weldOf,
                           const TriangleData& data, Grouping grouping, Method method, const CornerOutputs& outputs);

// lengyel's and meshopt's frames and sources as flatFrames writes them, each group read off
// one weld bucket (bucket_frames.cpp); false, writing nothing, where buckets and groups
// differ (an invalid normal; two normals of one position and UV with the same unit bits).
bool bucketFrames(WorkspaceData& ws, const MeshArrays& mesh, std::span<const std::uint32_t> weldOf,
                  const TriangleData& data, Method method, const CornerOutputs& outputs);

// Method `flat`'s links set to kNone (the weld used them, beside the triangle pass that framed
// the corners) and the frames of the corners that pass left kUndefined (flat_frames.cpp):
// groups only where a fallback is needed.
void flatFrames(WorkspaceData& ws, const MeshArrays& mesh, std::span<const std::uint32_t> weldOf,
                const TriangleData& data, const CornerOutputs& outputs);

// A frame into a corner's output slot (x, y, z, w as floats).
inline void writeCornerFrame(float* tangents, std::size_t corner, const Vec3& tangent, double w) {
  for (int i = 0; i < 3; ++i) tangents[4 * corner + i] = static_cast<float>(tangent[i]);
  tangents[4 * corner + 3] = static_cast<float>(w);
}

// Method `flat`'s frames of one triangle's three corners (firstCorner ..) from the triangle
// alone, into their output slots and states (kUndefined where the triangle gives none,
// kInvalidNormal): for each, sumTerms over its one term, inline for the triangle pass. The
// sums start at +0 as sumTerms' do (so a -0 of a term becomes +0 there too), and
// orthonormalize's operations follow in its order, the sum's length once for the three (the
// same sum).
inline void flatTriangleFrames(const TriangleTerms& triangle, const Vec3 (&normals)[3], const bool (&invalidNormal)[3],
                               float* tangents, std::uint8_t* state, std::size_t firstCorner) {
  bool framed[3] = {false, false, false};
  if (triangle.kind == TriangleKind::usable) {
    const Vec3 tangentSum = Vec3(0, 0, 0) + triangle.tangent;
    const Vec3 bitangentSum = Vec3(0, 0, 0) + triangle.bitangent;
    const double* sum = tangentSum.data();
    const double sumLength = std::sqrt(sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]);
    if (sumLength > 0 && std::isfinite(sumLength)) {
      Vec3 inPlane[3];
      double squared[3];
      for (int k = 0; k < 3; ++k) {
        const double* n = normals[k].data();
        const double along = n[0] * sum[0] + n[1] * sum[1] + n[2] * sum[2];
        inPlane[k] = Vec3(sum[0] - n[0] * along, sum[1] - n[1] * along, sum[2] - n[2] * along);
        const double* t = inPlane[k].data();
        squared[k] = t[0] * t[0] + t[1] * t[1] + t[2] * t[2];
      }
      for (int k = 0; k < 3; ++k) {
        const double length = std::sqrt(squared[k]);
        if (!(length > kInPlaneFloor * sumLength)) continue;
        framed[k] = true;
        const Vec3 tangent = inPlane[k] * (1.0 / length);
        const double side = (normals[k] % tangent) | bitangentSum;
        const double uvSide = triangle.orientation < 0 ? -1.0 : 1.0;
        writeCornerFrame(tangents, firstCorner + k, tangent, side > 0 ? 1.0 : side < 0 ? -1.0 : uvSide);
      }
    }
  }
  for (int k = 0; k < 3; ++k)
    state[firstCorner + k] = static_cast<std::uint8_t>((framed[k] ? 0 : kUndefined) | (invalidNormal[k] ? kInvalidNormal : 0));
}

// A stored normal made unit; `invalid` where it is zero or not finite (the result unused).
inline Vec3 unitNormal(const Vec3& stored, bool& invalid) {
  const double length = stored.norm();
  invalid = !(length > 0 && std::isfinite(length));
  return invalid ? stored : stored / length;
}

// What replaces a corner's invalid normal: its triangle's (or +z).
inline Vec3 replacedNormal(const TriangleTangent& triangle) {
  return triangle.faceNormal.norm() > 0 ? triangle.faceNormal : Vec3(0, 0, 1);
}

}  // namespace tangent::detail
