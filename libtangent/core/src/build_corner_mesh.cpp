// Builds the welded half-edge mesh the algorithms run on.
#include <OpenMesh/Core/System/omstream.hh>

#include <bit>
#include <cstring>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "tangent/halfedge_mesh.hpp"

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

CornerMesh buildCornerMesh(const MeshArrays& arrays) {
  if (arrays.positions.size() % 3 != 0) throw std::invalid_argument("positions: size is not a multiple of 3");
  const std::size_t vertexCount = arrays.positions.size() / 3;
  if (arrays.normals.size() != vertexCount * 3)
    throw std::invalid_argument("normals: expected " + std::to_string(vertexCount * 3) + " floats, got " +
                                std::to_string(arrays.normals.size()));
  if (arrays.uvs.size() != vertexCount * 2)
    throw std::invalid_argument("uvs: expected " + std::to_string(vertexCount * 2) + " floats, got " +
                                std::to_string(arrays.uvs.size()));
  if (arrays.indices.size() % 3 != 0) throw std::invalid_argument("indices: size is not a multiple of 3");
  for (std::size_t i = 0; i < arrays.indices.size(); ++i) {
    if (arrays.indices[i] >= vertexCount)
      throw std::invalid_argument("indices[" + std::to_string(i) + "] = " + std::to_string(arrays.indices[i]) +
                                  " is out of range (vertex count " + std::to_string(vertexCount) + ")");
  }

  CornerMesh result;
  TriMesh& mesh = result.mesh;
  const std::size_t triangleCount = arrays.indices.size() / 3;

  std::unordered_map<PositionKey, std::uint32_t, PositionKeyHash> weldIndex;
  weldIndex.reserve(vertexCount);
  std::vector<std::uint32_t> inputToWeld(vertexCount);
  for (std::size_t v = 0; v < vertexCount; ++v) {
    const float* p = &arrays.positions[3 * v];
    auto [it, inserted] = weldIndex.try_emplace(positionKey(p), static_cast<std::uint32_t>(weldIndex.size()));
    if (inserted) {
      mesh.add_vertex(TriMesh::Point(p[0], p[1], p[2]));
      result.weldedVertex.push_back(it->second);
    }
    inputToWeld[v] = it->second;
  }

  QuietOpenMeshErrors quiet;
  mesh.reserve(mesh.n_vertices(), triangleCount * 3 / 2 + 3, triangleCount);
  result.cornerHalfedge.resize(triangleCount * 3);
  for (std::size_t t = 0; t < triangleCount; ++t) {
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
  return result;
}

}  // namespace tangent
