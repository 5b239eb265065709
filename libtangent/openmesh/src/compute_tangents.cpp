// SPDX-License-Identifier: MIT
// The OpenMesh call: the mesh's corners gathered into packed arrays (in the workspace), the
// array call on them for every method, and the frames written back per halfedge. The same
// bits as the array call on the arrays the mesh was built from.
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <stdexcept>
#include <string>

#include "tangent/openmesh.hpp"

namespace tangent {
namespace {

constexpr std::uint32_t kNone = ~std::uint32_t(0);

// Runs body(begin, end) over [0, count) on `threads` threads (in one piece on one); each pass
// below writes only its own elements, so the split changes no result.
template <typename Body>
void forRange(unsigned threads, std::size_t count, std::size_t grain, const Body& body) {
  if (threads <= 1 || count <= grain) {
    if (count > 0) body(std::size_t(0), count);
    return;
  }
  // No more slots than the process may run threads (the pool would only warn).
  const std::size_t limit = tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
  tbb::task_arena arena(static_cast<int>(std::min<std::size_t>(threads, std::max<std::size_t>(limit, 1))));
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, grain),
                      [&](const tbb::blocked_range<std::size_t>& range) { body(range.begin(), range.end()); });
  });
}

// A corner's values in the array call's order: position, normal, UV.
struct CornerValues {
  float values[8];
  bool shareable() const {  // no NaN: the core's weld never joins a NaN vertex with another
    for (float x : values)
      if (x != x) return false;
    return true;
  }
};

}  // namespace
Report computeTangents(CornerMesh& cornerMesh, const Options& options, std::span<FrameSource> cornerSources) {
  CachedWorkspace workspace;
  return computeTangents(cornerMesh, options, workspace.get(), cornerSources);
}

namespace {

// The OpenMesh call's phases: the mesh's corners gathered into the array call's inputs (in the
// workspace's adapter buffers), then the frames written back per halfedge. The corners of one
// mesh vertex mostly carry the same normal and UV; those share one array vertex, so the core's
// weld sees about as many vertices as the array call does. Sharing changes no bits: the kernel
// works on values, and corners share only where every value is equal and not NaN.
// One index array holds array vertex numbers (< cornerCount), links to a representative corner
// counted down from 2^32 - 1 (kNone - 1 - corner) and kNone.
class CornerGather {
 public:
  CornerGather(CornerMesh& cornerMesh, TangentWorkspace::AdapterBuffers& buffers, unsigned threads)
      : cornerMesh_(cornerMesh), mesh_(cornerMesh.mesh), buffers_(buffers), threads_(threads),
        cornerCount_(cornerMesh.cornerHalfedge.size()),
        halfedgeCount_(std::min<std::size_t>(mesh_.n_halfedges(), cornerMesh.halfedgeCorner.size())) {}

  // Phases 1-4; the arrays for the call.
  MeshArrays gather() {
    growTo(buffers_.tangents, 4 * cornerCount_);
    growTo(buffers_.indices, cornerCount_);
    indices_ = buffers_.indices.data();
    forRange(threads_, cornerCount_, 1 << 14, [&](std::size_t begin, std::size_t end) { std::fill(indices_ + begin, indices_ + end, kNone); });
    chooseRepresentatives();
    linkToRepresentatives();
    const std::size_t vertexCount = numberOwnVertices();
    resolveLinks();
    return MeshArrays{std::span<const float>(buffers_.positions.data(), 3 * vertexCount),
                      std::span<const float>(buffers_.normals.data(), 3 * vertexCount),
                      std::span<const float>(buffers_.uvs.data(), 2 * vertexCount),
                      std::span<const std::uint32_t>(indices_, cornerCount_)};
  }

  std::span<float> tangents() { return {buffers_.tangents.data(), 4 * cornerCount_}; }

  // Frames back into the mesh in halfedge order: its tangent array written front to back.
  void writeBack() {
    const float* tangents = buffers_.tangents.data();
    forRange(threads_, halfedgeCount_, 1 << 14, [&](std::size_t begin, std::size_t end) {
      for (std::size_t h = begin; h < end; ++h) {
        const std::uint32_t c = cornerMesh_.halfedgeCorner[h];
        if (c >= cornerCount_) continue;  // kNoCorner
        const float* t = &tangents[4 * std::size_t(c)];
        mesh_.property(cornerMesh_.tangent, TriMesh::HalfedgeHandle(static_cast<int>(h))) = TangentVec(t[0], t[1], t[2], t[3]);
      }
    });
  }

 private:
  template <typename Vector>
  static void growTo(Vector& v, std::size_t n) {
    if (v.size() < n) v.resize(n);
  }

  CornerValues valuesAt(TriMesh::HalfedgeHandle halfedge) const {
    const auto& p = mesh_.point(mesh_.to_vertex_handle(halfedge));
    const auto& n = mesh_.normal(halfedge);
    const auto& uv = mesh_.texcoord2D(halfedge);
    return CornerValues{{static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2]), static_cast<float>(n[0]),
                         static_cast<float>(n[1]), static_cast<float>(n[2]), static_cast<float>(uv[0]), static_cast<float>(uv[1])}};
  }

  // 1. Each mesh vertex's representative: the corner of the face of its stored halfedge, with
  // its values, where they hold no NaN (else kNone).
  void chooseRepresentatives() {
    const std::size_t meshVertices = mesh_.n_vertices();
    growTo(buffers_.vertexCorner, meshVertices);
    growTo(buffers_.vertexValues, 8 * meshVertices);
    std::uint32_t* representative = buffers_.vertexCorner.data();
    float* values = buffers_.vertexValues.data();
    forRange(threads_, meshVertices, 1 << 12, [&](std::size_t begin, std::size_t end) {
      for (std::size_t v = begin; v < end; ++v) {
        representative[v] = kNone;
        const auto out = mesh_.halfedge_handle(TriMesh::VertexHandle(static_cast<int>(v)));
        if (!out.is_valid()) continue;
        const auto in = mesh_.is_boundary(out) ? mesh_.opposite_halfedge_handle(out) : mesh_.prev_halfedge_handle(out);
        const std::uint32_t r = cornerMesh_.halfedgeCorner[static_cast<std::size_t>(in.idx())];
        if (r >= cornerCount_) continue;  // kNoCorner
        const CornerValues shared = valuesAt(in);  // corner r's halfedge is `in`
        if (!shared.shareable()) continue;
        representative[v] = r;
        std::memcpy(&values[8 * v], shared.values, sizeof shared.values);
      }
    });
  }

  // 2. Each other corner of a vertex with a representative links to it where its normal and UV
  // have the same bits (the corners of one mesh vertex share its point). In halfedge order,
  // which reads the mesh's per-halfedge normals and UVs front to back (in corner or vertex order
  // those reads land anywhere in arrays of tens of megabytes).
  void linkToRepresentatives() {
    const std::uint32_t* representative = buffers_.vertexCorner.data();
    const float* values = buffers_.vertexValues.data();
    forRange(threads_, halfedgeCount_, 1 << 14, [&](std::size_t begin, std::size_t end) {
      for (std::size_t h = begin; h < end; ++h) {
        const std::uint32_t c = cornerMesh_.halfedgeCorner[h];
        if (c >= cornerCount_) continue;  // kNoCorner (a boundary halfedge)
        const TriMesh::HalfedgeHandle halfedge(static_cast<int>(h));
        const auto v = static_cast<std::size_t>(mesh_.to_vertex_handle(halfedge).idx());
        const std::uint32_t r = representative[v];
        if (r == kNone || r == c) continue;
        const auto& n = mesh_.normal(halfedge);
        const auto& uv = mesh_.texcoord2D(halfedge);
        const float attributes[5] = {static_cast<float>(n[0]), static_cast<float>(n[1]), static_cast<float>(n[2]),
                                     static_cast<float>(uv[0]), static_cast<float>(uv[1])};
        if (std::memcmp(attributes, &values[8 * v + 3], sizeof attributes) == 0) indices_[c] = kNone - 1 - r;
      }
    });
  }

  // 3. Array vertices: the corners that keep their own, numbered in corner order (fixed chunks
  // counted, then listed at their offsets), with their values.
  std::size_t numberOwnVertices() {
    constexpr std::size_t kChunk = std::size_t(1) << 16;
    const std::size_t chunks = (cornerCount_ + kChunk - 1) / kChunk;
    std::vector<std::size_t> start(chunks + 1, 0);
    forRange(threads_, chunks, 1, [&](std::size_t begin, std::size_t end) {
      for (std::size_t k = begin; k < end; ++k)
        start[k + 1] = static_cast<std::size_t>(
            std::count(indices_ + k * kChunk, indices_ + std::min(cornerCount_, (k + 1) * kChunk), kNone));
    });
    for (std::size_t k = 0; k < chunks; ++k) start[k + 1] += start[k];
    const std::size_t vertexCount = start[chunks];
    growTo(buffers_.list, vertexCount);
    std::uint32_t* own = buffers_.list.data();
    forRange(threads_, chunks, 1, [&](std::size_t begin, std::size_t end) {
      for (std::size_t k = begin; k < end; ++k) {
        std::size_t next = start[k];
        for (std::size_t c = k * kChunk; c < std::min(cornerCount_, (k + 1) * kChunk); ++c)
          if (indices_[c] == kNone) own[next++] = static_cast<std::uint32_t>(c);
      }
    });
    gatherValues(own, vertexCount);
    return vertexCount;
  }

  void gatherValues(const std::uint32_t* own, std::size_t vertexCount) {
    growTo(buffers_.positions, 3 * vertexCount);
    growTo(buffers_.normals, 3 * vertexCount);
    growTo(buffers_.uvs, 2 * vertexCount);
    float *positions = buffers_.positions.data(), *normals = buffers_.normals.data(), *uvs = buffers_.uvs.data();
    const std::uint32_t* representative = buffers_.vertexCorner.data();
    const float* values = buffers_.vertexValues.data();
    forRange(threads_, vertexCount, 1 << 14, [&](std::size_t begin, std::size_t end) {
      for (std::size_t next = begin; next < end; ++next) {
        const std::uint32_t c = own[next];
        // A vertex's representative has its values gathered already (one read, not three).
        const TriMesh::HalfedgeHandle halfedge = cornerMesh_.cornerHalfedge[c];
        const auto vertex = static_cast<std::size_t>(mesh_.to_vertex_handle(halfedge).idx());
        CornerValues v;
        if (representative[vertex] == c) std::memcpy(v.values, &values[8 * vertex], sizeof v.values);
        else v = valuesAt(halfedge);
        std::memcpy(&positions[3 * next], &v.values[0], 3 * sizeof(float));
        std::memcpy(&normals[3 * next], &v.values[3], 3 * sizeof(float));
        std::memcpy(&uvs[2 * next], &v.values[6], 2 * sizeof(float));
        indices_[c] = static_cast<std::uint32_t>(next);  // below cornerCount: told apart from links
      }
    });
  }

  // 4. Links to representatives become their numbers (a representative is always numbered, and
  // this pass writes only links, so no read meets a write).
  void resolveLinks() {
    const auto linkFrom = static_cast<std::uint32_t>(kNone - cornerCount_);  // links: [linkFrom, kNone)
    forRange(threads_, cornerCount_, 1 << 14, [&](std::size_t begin, std::size_t end) {
      for (std::size_t c = begin; c < end; ++c) {
        const std::uint32_t i = indices_[c];
        if (i >= linkFrom && i != kNone) indices_[c] = indices_[kNone - 1 - i];
      }
    });
  }

  CornerMesh& cornerMesh_;
  TriMesh& mesh_;
  TangentWorkspace::AdapterBuffers& buffers_;
  unsigned threads_;
  std::size_t cornerCount_, halfedgeCount_;
  std::uint32_t* indices_ = nullptr;
};

}  // namespace

Report computeTangents(CornerMesh& cornerMesh, const Options& options, TangentWorkspace& workspace,
                       std::span<FrameSource> cornerSources) {
  const std::size_t cornerCount = cornerMesh.cornerHalfedge.size();
  if (!cornerSources.empty() && cornerSources.size() != cornerCount)
    throw std::invalid_argument("cornerSources: expected one per corner");
  if (cornerCount >= (std::size_t(1) << 31)) throw std::invalid_argument("mesh: more than 2^31 corners");
  // The array call on the corners' values: the same bits.
  CornerGather corners(cornerMesh, workspace.adapterBuffers(), threadCount(options));
  const MeshArrays arrays = corners.gather();
  Report report = computeCornerTangents(arrays, CornerOutputs{corners.tangents(), cornerSources, {}}, options, workspace);
  report.nonManifoldFaces = std::max(report.nonManifoldFaces, cornerMesh.nonManifoldFaces);
  report.splitVertices = 0;  // corners of the half-edge mesh are its vertices here
  report.outputVertices = cornerCount;
  corners.writeBack();
  return report;
}

}  // namespace tangent
