// SPDX-License-Identifier: MIT
// Builds the welded half-edge mesh of the OpenMesh call (tangent/openmesh.hpp).
#include <OpenMesh/Core/System/omstream.hh>

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "tangent/openmesh.hpp"

namespace tangent {

CornerMesh::CornerMesh() { mesh.add_property(tangent, "tangent"); }
CornerMesh::CornerMesh(CornerMesh&&) noexcept = default;
CornerMesh& CornerMesh::operator=(CornerMesh&&) noexcept = default;
CornerMesh::~CornerMesh() = default;

namespace {

// Exact position identity; +0 and -0 weld, NaNs weld only with identical bits.
struct PositionKey {
  std::uint32_t bits[3];
  bool operator==(const PositionKey&) const = default;
};

struct PositionKeyHash {
  std::size_t operator()(const PositionKey& key) const noexcept {
    std::uint64_t h = 0x9E3779B97F4A7C15ull;
    for (std::uint32_t b : key.bits) {
      h ^= b + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
    }
    return static_cast<std::size_t>(h);
  }
};

PositionKey positionKey(const float* p) {
  PositionKey key{};
  for (int i = 0; i < 3; ++i) {
    float value = p[i] == 0.0f ? 0.0f : p[i];
    key.bits[i] = std::bit_cast<std::uint32_t>(value);
  }
  return key;
}

// OpenMesh reports refused faces on its error stream; we count them instead.
class QuietOpenMeshErrors {
 public:
  QuietOpenMeshErrors() : wasEnabled_(omerr().is_enabled()) { omerr().disable(); }
  ~QuietOpenMeshErrors() {
    if (wasEnabled_) omerr().enable();
  }
  QuietOpenMeshErrors(const QuietOpenMeshErrors&) = delete;
  QuietOpenMeshErrors& operator=(const QuietOpenMeshErrors&) = delete;

 private:
  bool wasEnabled_;
};

}  // namespace

namespace {

// Bit pattern of a corner (position, normal, UV) for ordering; +0 and -0 alike.
std::array<std::uint32_t, 8> cornerBits(const MeshArrays& arrays, std::uint32_t vertex) {
  std::array<std::uint32_t, 8> bits{};
  const float* values[3] = {&arrays.positions[3 * vertex], &arrays.normals[3 * vertex], &arrays.uvs[2 * vertex]};
  const int sizes[3] = {3, 3, 2};
  int at = 0;
  for (int part = 0; part < 3; ++part) {
    for (int i = 0; i < sizes[part]; ++i) {
      const float value = values[part][i] == 0.0f ? 0.0f : values[part][i];
      bits[at++] = std::bit_cast<std::uint32_t>(value);
    }
  }
  return bits;
}

// Triangles in an order that depends only on their contents: each by its corners' bits,
// starting at its smallest corner (rotation kept), ties by input position.
std::vector<std::uint32_t> canonicalTriangleOrder(const MeshArrays& arrays) {
  const std::size_t triangleCount = arrays.indices.size() / 3;
  using Key = std::array<std::array<std::uint32_t, 8>, 3>;
  std::vector<Key> keys(triangleCount);
  for (std::size_t t = 0; t < triangleCount; ++t) {
    std::array<std::array<std::uint32_t, 8>, 3> corners;
    for (int k = 0; k < 3; ++k) corners[k] = cornerBits(arrays, arrays.indices[3 * t + k]);
    int start = 0;
    for (int k = 1; k < 3; ++k) {
      if (corners[k] < corners[start]) start = k;
    }
    for (int k = 0; k < 3; ++k) keys[t][k] = corners[(start + k) % 3];
  }
  std::vector<std::uint32_t> order(triangleCount);
  for (std::uint32_t t = 0; t < triangleCount; ++t) order[t] = t;
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return keys[a] < keys[b]; });
  return order;
}

// Adds the faces in `order`; faces OpenMesh refuses (or with a repeated vertex) go on
// duplicated vertices.
void addFaces(CornerMesh& result, const MeshArrays& arrays, const std::vector<std::uint32_t>& inputToWeld,
              const std::vector<std::uint32_t>* order) {
  TriMesh& mesh = result.mesh;
  const std::size_t triangleCount = arrays.indices.size() / 3;
  result.cornerHalfedge.assign(triangleCount * 3, OpenMesh::HalfedgeHandle());
  for (std::size_t step = 0; step < triangleCount; ++step) {
    const std::size_t t = order ? (*order)[step] : step;
    OpenMesh::VertexHandle corners[3];
    for (int k = 0; k < 3; ++k) corners[k] = OpenMesh::VertexHandle(static_cast<int>(inputToWeld[arrays.indices[3 * t + k]]));
    OpenMesh::FaceHandle face;
    const bool repeatedVertex = corners[0] == corners[1] || corners[1] == corners[2] || corners[0] == corners[2];
    if (!repeatedVertex) face = mesh.add_face(corners[0], corners[1], corners[2]);
    if (!face.is_valid()) {
      // Refused (complex vertex/edge) or collapsed: keep the face on its own vertices.
      if (!repeatedVertex) ++result.nonManifoldFaces;
      for (auto& corner : corners) {
        const auto weld = static_cast<std::uint32_t>(corner.idx());
        const TriMesh::Point position = mesh.point(corner);  // add_vertex may reallocate the points
        corner = mesh.add_vertex(position);
        result.weldedVertex.push_back(weld);
      }
      face = mesh.add_face(corners[0], corners[1], corners[2]);
    }
    for (auto halfedge : mesh.fh_range(face)) {
      for (int k = 0; k < 3; ++k) {
        if (mesh.to_vertex_handle(halfedge) == corners[k]) {
          const std::uint32_t input = arrays.indices[3 * t + k];
          const float* n = &arrays.normals[3 * input];
          const float* uv = &arrays.uvs[2 * input];
          mesh.set_normal(halfedge, TriMesh::Normal(n[0], n[1], n[2]));
          mesh.set_texcoord2D(halfedge, TriMesh::TexCoord2D(uv[0], uv[1]));
          result.cornerHalfedge[3 * t + k] = halfedge;
        }
      }
    }
  }
  result.halfedgeCorner.assign(mesh.n_halfedges(), CornerMesh::kNoCorner);
  for (std::size_t corner = 0; corner < result.cornerHalfedge.size(); ++corner)
    result.halfedgeCorner[result.cornerHalfedge[corner].idx()] = static_cast<std::uint32_t>(corner);
}

}  // namespace

CornerMesh buildCornerMesh(const MeshArrays& arrays) {
  checkMeshArrays(arrays);  // the array call's checks and messages
  const std::size_t vertexCount = arrays.positions.size() / 3;

  // Weld by exact position; the welded vertices are added in input vertex order.
  std::unordered_map<PositionKey, std::uint32_t, PositionKeyHash> weldIndex;
  weldIndex.reserve(vertexCount);
  std::vector<std::uint32_t> inputToWeld(vertexCount);
  std::vector<std::uint32_t> weldSource;
  for (std::size_t v = 0; v < vertexCount; ++v) {
    auto [it, inserted] = weldIndex.try_emplace(positionKey(&arrays.positions[3 * v]), static_cast<std::uint32_t>(weldIndex.size()));
    if (inserted) weldSource.push_back(static_cast<std::uint32_t>(v));
    inputToWeld[v] = it->second;
  }
  auto makeMesh = [&](const std::vector<std::uint32_t>* order) {
    CornerMesh result;
    const std::size_t triangleCount = arrays.indices.size() / 3;
    result.mesh.reserve(weldSource.size(), triangleCount * 3 / 2 + 3, triangleCount);
    for (std::uint32_t v : weldSource) {
      const float* p = &arrays.positions[3 * v];
      result.mesh.add_vertex(TriMesh::Point(p[0], p[1], p[2]));
      result.weldedVertex.push_back(static_cast<std::uint32_t>(result.weldedVertex.size()));
    }
    addFaces(result, arrays, inputToWeld, order);
    return result;
  };

  QuietOpenMeshErrors quiet;
  CornerMesh result = makeMesh(nullptr);
  if (result.nonManifoldFaces > 0) {
    // Which of the faces around a non-manifold edge OpenMesh refuses depends on the order
    // they come in: build again in an order given by the faces' contents.
    const std::vector<std::uint32_t> order = canonicalTriangleOrder(arrays);
    result = makeMesh(&order);
  }
  return result;
}

}  // namespace tangent
