// SPDX-License-Identifier: MIT
// The OpenMesh call: the mesh's corners gathered into packed arrays (in the workspace), the
// array call on them for every method, and the frames written back per halfedge. The same
// bits as the array call on the arrays the mesh was built from.
#include <algorithm>
#include <cstddef>
#include <cstring>
#include <stdexcept>
#include <string>

#include "tangent/openmesh.hpp"
#include "parallel.hpp"

namespace tangent {

Report computeTangents(CornerMesh& cornerMesh, const Options& options, std::span<FrameSource> cornerSources) {
  CachedWorkspace workspace;
  return computeTangents(cornerMesh, options, workspace.get(), cornerSources);
}

Report computeTangents(CornerMesh& cornerMesh, const Options& options, TangentWorkspace& workspace,
                       std::span<FrameSource> cornerSources) {
  const std::size_t cornerCount = cornerMesh.cornerHalfedge.size();
  if (!cornerSources.empty() && cornerSources.size() != cornerCount)
    throw std::invalid_argument("cornerSources: expected one per corner");
  // Below, one index array holds vertex numbers (< cornerCount), corner links counted down
  // from 2^32 - 1 (kNone - 1 - corner) and kNone.
  if (cornerCount >= (std::size_t(1) << 31)) throw std::invalid_argument("mesh: more than 2^31 corners");
  // The array call on the corners' values: the same bits. The corners of
  // one mesh vertex mostly carry the same normal and UV; those share one array vertex, so the
  // weld sees about as many vertices as the array call does (sharing changes no bits: the
  // kernel works on values, and corners share only where every value is equal and not NaN).
  const TriMesh& mesh = cornerMesh.mesh;
  detail::WorkspaceData& ws = workspace.data();
  detail::ensureSize(ws.meshTangents, 4 * cornerCount);
  detail::ensureSize(ws.meshIndices, cornerCount);
  float* tangents = ws.meshTangents.data();
  std::uint32_t* indices = ws.meshIndices.data();
  const auto kLinkFrom = static_cast<std::uint32_t>(detail::kNone - cornerCount);  // links: [kLinkFrom, kNone)
  ws.threads = threadCount(options);
  auto inArena = [&](const auto& body) { detail::onThreads(ws, [&] { detail::forRange(ws, cornerCount, 1 << 14, body); }); };
  using detail::CornerValues;
  static_assert(offsetof(CornerValues, uv) == offsetof(CornerValues, normal) + 3 * sizeof(float), "normal, then UV");
  auto valuesAt = [&](TriMesh::HalfedgeHandle halfedge) {
    const auto& p = mesh.point(mesh.to_vertex_handle(halfedge));
    const auto& n = mesh.normal(halfedge);
    const auto& uv = mesh.texcoord2D(halfedge);
    CornerValues v;
    for (int i = 0; i < 3; ++i) {
      v.position[i] = static_cast<float>(p[i]);
      v.normal[i] = static_cast<float>(n[i]);
    }
    v.uv[0] = static_cast<float>(uv[0]);
    v.uv[1] = static_cast<float>(uv[1]);
    return v;
  };
  // 1. Each corner: its own array vertex (kNone) or that of its mesh vertex's representative
  // (the corner of the face of the vertex's stored halfedge). First each vertex's
  // representative and its values, where they hold no NaN; then the corners in halfedge
  // order, which reads the mesh's per-halfedge normals and UVs front to back (in corner or
  // vertex order those reads land anywhere in arrays of tens of megabytes). Equal bits imply
  // the same NaN-free state.
  inArena([&](std::size_t begin, std::size_t end) { std::fill(indices + begin, indices + end, detail::kNone); });
  const std::size_t meshVertices = mesh.n_vertices();
  detail::ensureSize(ws.meshRepresentative, meshVertices);
  detail::ensureSize(ws.meshRepresentativeValues, meshVertices);
  std::uint32_t* representative = ws.meshRepresentative.data();
  CornerValues* representativeValues = ws.meshRepresentativeValues.data();
  detail::onThreads(ws, [&] {
    detail::forRange(ws, meshVertices, 1 << 12, [&](std::size_t begin, std::size_t end) {
      for (std::size_t v = begin; v < end; ++v) {
        representative[v] = detail::kNone;
        const TriMesh::VertexHandle vertex(static_cast<int>(v));
        const auto out = mesh.halfedge_handle(vertex);
        if (!out.is_valid()) continue;
        const auto in = mesh.is_boundary(out) ? mesh.opposite_halfedge_handle(out) : mesh.prev_halfedge_handle(out);
        const std::uint32_t r = cornerMesh.halfedgeCorner[static_cast<std::size_t>(in.idx())];
        if (r >= cornerCount) continue;  // kNoCorner
        const CornerValues shared = valuesAt(in);  // corner r's halfedge is `in`
        if (!shared.shareable()) continue;
        representative[v] = r;
        representativeValues[v] = shared;
      }
    });
  });
  const std::size_t halfedgeCount = std::min<std::size_t>(mesh.n_halfedges(), cornerMesh.halfedgeCorner.size());
  detail::onThreads(ws, [&] {
    detail::forRange(ws, halfedgeCount, 1 << 14, [&](std::size_t begin, std::size_t end) {
      for (std::size_t h = begin; h < end; ++h) {
        const std::uint32_t c = cornerMesh.halfedgeCorner[h];
        if (c >= cornerCount) continue;  // kNoCorner (a boundary halfedge)
        const TriMesh::HalfedgeHandle halfedge(static_cast<int>(h));
        const auto v = static_cast<std::size_t>(mesh.to_vertex_handle(halfedge).idx());
        const std::uint32_t r = representative[v];
        if (r == detail::kNone || r == c) continue;
        // Corners of one mesh vertex share its point: normal and UV decide.
        const auto& n = mesh.normal(halfedge);
        const auto& uv = mesh.texcoord2D(halfedge);
        const float attributes[5] = {static_cast<float>(n[0]), static_cast<float>(n[1]), static_cast<float>(n[2]),
                                     static_cast<float>(uv[0]), static_cast<float>(uv[1])};
        if (std::memcmp(attributes, representativeValues[v].normal, sizeof attributes) == 0) indices[c] = detail::kNone - 1 - r;
      }
    });
  });
  // 2. Array vertices: the corners that keep their own, numbered in corner order.
  std::vector<std::uint32_t> own;
  detail::onThreads(ws, [&] { own = detail::collectIf(ws, cornerCount, [&](std::size_t c) { return indices[c] == detail::kNone; }); });
  const std::size_t vertexCount = own.size();
  detail::ensureSize(ws.meshPositions, 3 * vertexCount);
  detail::ensureSize(ws.meshNormals, 3 * vertexCount);
  detail::ensureSize(ws.meshUvs, 2 * vertexCount);
  float* positions = ws.meshPositions.data();
  float* normals = ws.meshNormals.data();
  float* uvs = ws.meshUvs.data();
  detail::onThreads(ws, [&] {
    detail::forRange(ws, vertexCount, 1 << 14, [&](std::size_t begin, std::size_t end) {
      for (std::size_t next = begin; next < end; ++next) {
        const std::uint32_t c = own[next];
        // A vertex's representative has its values gathered already (one read, not three).
        const TriMesh::HalfedgeHandle halfedge = cornerMesh.cornerHalfedge[c];
        const auto vertex = static_cast<std::size_t>(mesh.to_vertex_handle(halfedge).idx());
        const CornerValues v = representative[vertex] == c ? representativeValues[vertex] : valuesAt(halfedge);
        std::memcpy(&positions[3 * next], v.position, sizeof v.position);
        std::memcpy(&normals[3 * next], v.normal, sizeof v.normal);
        std::memcpy(&uvs[2 * next], v.uv, sizeof v.uv);
        indices[c] = static_cast<std::uint32_t>(next);  // below cornerCount: told apart from links
      }
    });
  });
  // 3. Links to representatives become their numbers (a representative is always numbered,
  // and this pass writes only links, so no read meets a write).
  inArena([&](std::size_t begin, std::size_t end) {
    for (std::size_t c = begin; c < end; ++c) {
      const std::uint32_t i = indices[c];
      if (i >= kLinkFrom) indices[c] = indices[detail::kNone - 1 - i];
    }
  });
  const MeshArrays arrays{std::span<const float>(positions, 3 * vertexCount), std::span<const float>(normals, 3 * vertexCount),
                          std::span<const float>(uvs, 2 * vertexCount), std::span<const std::uint32_t>(indices, cornerCount)};
  Report report = computeCornerTangents(arrays, CornerOutputs{std::span<float>(tangents, 4 * cornerCount), cornerSources, {}},
                                        options, workspace);
  report.nonManifoldFaces = std::max(report.nonManifoldFaces, cornerMesh.nonManifoldFaces);
  report.splitVertices = 0;  // corners of the half-edge mesh are its vertices here
  report.outputVertices = cornerCount;
  // Frames back into the mesh in halfedge order: its tangent array written front to back.
  detail::onThreads(ws, [&] {
    detail::forRange(ws, halfedgeCount, 1 << 14, [&](std::size_t begin, std::size_t end) {
      for (std::size_t h = begin; h < end; ++h) {
        const std::uint32_t c = cornerMesh.halfedgeCorner[h];
        if (c >= cornerCount) continue;  // kNoCorner
        const float* t = &tangents[4 * std::size_t(c)];
        cornerMesh.mesh.property(cornerMesh.tangent, TriMesh::HalfedgeHandle(static_cast<int>(h))) = TangentVec(t[0], t[1], t[2], t[3]);
      }
    });
  });
  return report;
}

}  // namespace tangent
