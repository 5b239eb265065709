// SPDX-License-Identifier: MIT
// libtangent for OpenMesh users (target tangent::openmesh; the core, tangent::core, needs no
// OpenMesh): a triangle mesh welded by position, with normal, UV and tangent stored per
// halfedge (that is, per face corner). The corner of face f at vertex v is the halfedge of f
// that points to v, as OpenMesh's own readers use it. computeTangents() gathers the corners
// into packed arrays and calls computeCornerTangents(), so every method gives the array
// call's bits.
#pragma once

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <cstdint>
#include <span>
#include <vector>

#include "tangent/tangent.hpp"

namespace tangent {

struct CornerMeshTraits : OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
  using TexCoord2D = OpenMesh::Vec2d;
  VertexAttributes(OpenMesh::Attributes::None);
  HalfedgeAttributes(OpenMesh::Attributes::PrevHalfedge | OpenMesh::Attributes::Normal |
                     OpenMesh::Attributes::TexCoord2D);
  EdgeAttributes(OpenMesh::Attributes::None);
  FaceAttributes(OpenMesh::Attributes::None);
};

using TriMesh = OpenMesh::TriMesh_ArrayKernelT<CornerMeshTraits>;
using TangentVec = OpenMesh::Vec4d;

// A welded mesh plus what maps it back to the caller's corners.
struct CornerMesh {
  TriMesh mesh;
  // Tangent per halfedge (xyz, w); filled by computeTangents().
  OpenMesh::HPropHandleT<TangentVec> tangent;
  // Halfedge of each input corner (3 per input triangle). Face i is input triangle i.
  std::vector<OpenMesh::HalfedgeHandle> cornerHalfedge;
  // Input corner of each halfedge (kNoCorner for boundary halfedges).
  static constexpr std::uint32_t kNoCorner = ~std::uint32_t(0);
  std::vector<std::uint32_t> halfedgeCorner;
  // Canonical welded vertex of each mesh vertex: faces refused as non-manifold (or with a
  // repeated vertex) are stored on duplicated vertices, which point back here.
  std::vector<std::uint32_t> weldedVertex;
  std::uint64_t nonManifoldFaces = 0;

  CornerMesh();
  CornerMesh(CornerMesh&&) noexcept;
  CornerMesh& operator=(CornerMesh&&) noexcept;
  CornerMesh(const CornerMesh&) = delete;
  CornerMesh& operator=(const CornerMesh&) = delete;
  ~CornerMesh();
};

// Builds a CornerMesh from plain arrays: vertices welded by exact position (+0 and -0 equal),
// normals and UVs copied to the corners' halfedges. Never drops a face. Which faces OpenMesh
// refuses does not depend on the order of the triangles. The arrays are checked as the array
// call checks them (checkMeshArrays).
CornerMesh buildCornerMesh(const MeshArrays& arrays);

// Computes the tangent of every corner into mesh.tangent, for any options.method, with the
// bits computeCornerTangents() gives on the arrays the mesh was built from. w follows
// options.uvOrigin. cornerSources, when not empty, receives one FrameSource per input corner.
Report computeTangents(CornerMesh& mesh, const Options& options = {}, std::span<FrameSource> cornerSources = {});
// The same with a workspace that repeated calls reuse (see TangentWorkspace).
Report computeTangents(CornerMesh& mesh, const Options& options, TangentWorkspace& workspace,
                       std::span<FrameSource> cornerSources = {});

}  // namespace tangent
