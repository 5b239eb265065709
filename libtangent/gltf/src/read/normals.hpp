// SPDX-License-Identifier: MIT
// NORMAL as glTF readers treat it, before the core sees it (bake, check's `reference`, the
// viewer's scene): glTF 2.0 (3.7.2.1) requires unit normals, and readers normalize what they
// are given (the Khronos Sample Viewer and three.js in their shaders, engines on import).
// Pipelines do store other lengths: gltfpack -vn 10/12 writes b-bit normals into normalized
// SHORT without rescaling (|N| = 2047/32767 at 12 bits), and morphed normals are sums.
//
// The core projects onto the plane of the normal as the reference MikkTSpace C does, with the
// raw normal (v - (N.v)N, a projection only when |N| = 1), so that it keeps the reference's
// bits. A normal further than kNormalLengthKept from unit length is therefore divided by its
// length here; one within it is left exactly as stored.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace tangent::gltf::detail {

struct PrimitiveGeometry;

// The largest | |N| - 1 | left as stored. Float rounding of a normalized vector is ~1e-7; DCC
// exporters that hold normals in 16-bit integers and write them as floats leave a few 1e-5 (the
// Blender export NormalTangentMirrorTest.glb: 4.4e-5). Within this the core keeps the reference
// C's bits, and the raw projection leaves a tangent at most 2 * 5e-5 rad (0.006 deg) times the
// ratio of dP/du's normal to its tangential part out of the plane. Beyond it that tilt grows
// with the length (9.3 deg on a character through gltfpack -vn 12, issue 37), so such normals
// are normalized; the tests' 1 +- 1e-4 is normalized with a factor 2 to spare. Every existing
// bake of the shared and generated assets keeps its bits. A normal of zero length keeps the
// core's documented fallback (its faces' normals).
inline constexpr double kNormalLengthKept = 5e-5;

// The one rule: does a normal of this length get normalized before the core sees it?
bool normalNeedsNormalizing(double length);

// What unitNormals found.
struct NormalLengths {
  std::uint64_t normalized = 0;  // normals divided by their length (normalNeedsNormalizing)
  std::uint64_t zero = 0;        // zero or non-finite normals, left for the core's fallback
  double worstLength = 1;        // the stored length furthest from 1 among the nonzero finite ones
  double worstDeviation() const;  // | worstLength - 1 |
};

// Normalizes, in place, the normals (3 floats each) that normalNeedsNormalizing selects: each
// divided by its length in double, then rounded to float.
NormalLengths unitNormals(std::span<float> normals);

// ---- NORMAL where a primitive has none (bake --normals) ----

// glTF 2.0 (3.7.2.1): "When normals are not specified, client implementations MUST calculate
// flat normals". Flat: each corner takes its triangle's unit normal, cross(p1 - p0, p2 - p0)
// (counter-clockwise front faces). A triangle without area draws nothing: its corners get +Z,
// which keeps the accessor valid (the validator requires unit normals). Smooth: each corner
// takes the sum of the unit normals of the triangles that meet at its position (welded: within
// 1e-6 of the bounding box's diagonal) within creaseAngleDegrees of its own triangle's, each
// weighted by that triangle's corner angle there (Thuermer and Wuethrich 1998), normalized; the
// corners of a triangle without area take every triangle at their position. A vertex whose
// corners get different normals is split: the result is a new vertex list.
struct GeneratedNormals {
  std::vector<std::uint32_t> source;   // input vertex of each new vertex
  std::vector<float> normals;          // 3 per new vertex
  std::vector<std::uint32_t> corners;  // the triangle list over the new vertices
};
GeneratedNormals generateNormals(std::span<const float> positions, std::span<const std::uint32_t> corners, bool smooth,
                                 double creaseAngleDegrees);

// The geometry the core sees for a primitive without NORMAL, in bake and in check's `reference`:
// generateNormals' vertices with their positions and UVs copied from their input vertex, the
// generated normals and triangle list, mode 4 and the input's index component type.
// `sourceVertex` gets the input vertex of each vertex of the result.
PrimitiveGeometry withGeneratedNormals(const PrimitiveGeometry& geometry, bool smooth, double creaseAngleDegrees,
                                       std::vector<std::uint32_t>& sourceVertex);

}  // namespace tangent::gltf::detail
