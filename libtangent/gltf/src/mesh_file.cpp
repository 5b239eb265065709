// OBJ, PLY and OFF through OpenMesh's readers, converted to an in-memory GLB so that the rest
// of bake treats them like any glTF input. These formats carry no materials: every mesh
// gets tangents. Their UV origin is bottom-left, so v becomes 1 - v for glTF.
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>

#include <bit>
#include <cstring>
#include <map>
#include <tuple>
#include <unordered_map>

#include "asset.hpp"
#include "tangent/gltf.hpp"

namespace tangent::gltf::detail {
namespace {

struct ImportTraits : OpenMesh::DefaultTraits {
  VertexAttributes(OpenMesh::Attributes::Normal | OpenMesh::Attributes::TexCoord2D);
  HalfedgeAttributes(OpenMesh::Attributes::PrevHalfedge | OpenMesh::Attributes::TexCoord2D);
  FaceAttributes(OpenMesh::Attributes::Normal);
};
// A polygon mesh: OpenMesh's readers leave the UVs of the diagonals unset when they
// triangulate into a TriMesh, so polygons are fanned here from their own corners.
using ImportMesh = OpenMesh::PolyMesh_ArrayKernelT<ImportTraits>;

void appendFloats(std::vector<std::uint8_t>& bin, const std::vector<float>& values) {
  const std::size_t at = bin.size();
  bin.resize(at + values.size() * 4);
  std::memcpy(&bin[at], values.data(), values.size() * 4);
}

}  // namespace

std::vector<std::uint8_t> meshFileToGlb(const std::filesystem::path& path) {
  ImportMesh mesh;
  OpenMesh::IO::Options options = OpenMesh::IO::Options::VertexNormal | OpenMesh::IO::Options::VertexTexCoord |
                                  OpenMesh::IO::Options::FaceTexCoord;
  if (!OpenMesh::IO::read_mesh(mesh, path.string(), options))
    throw InputError(path.string() + ": OpenMesh cannot read this file");
  if (mesh.n_faces() == 0) throw InputError(path.string() + ": has no faces");
  const bool haveNormals = options.check(OpenMesh::IO::Options::VertexNormal);
  const bool cornerUvs = options.check(OpenMesh::IO::Options::FaceTexCoord);
  const bool vertexUvs = options.check(OpenMesh::IO::Options::VertexTexCoord);
  if (!cornerUvs && !vertexUvs) throw InputError(path.string() + ": has no texture coordinates; tangents need UVs");
  if (!haveNormals) {
    mesh.update_face_normals();
    mesh.update_vertex_normals();
  }

  // One glTF vertex per distinct (vertex, UV).
  std::map<std::tuple<int, std::uint32_t, std::uint32_t>, std::uint32_t> vertexOf;
  std::vector<float> positions, normals, uvs;
  std::vector<std::uint32_t> indices;
  std::vector<std::uint32_t> polygon;
  for (auto face : mesh.faces()) {
    polygon.clear();
    for (auto halfedge : mesh.fh_range(face)) {
      const auto vertex = mesh.to_vertex_handle(halfedge);
      const auto uv = cornerUvs ? mesh.texcoord2D(halfedge) : mesh.texcoord2D(vertex);
      const float u = uv[0], v = 1.0f - uv[1];
      auto key = std::make_tuple(vertex.idx(), std::bit_cast<std::uint32_t>(u), std::bit_cast<std::uint32_t>(v));
      auto [it, inserted] = vertexOf.try_emplace(key, static_cast<std::uint32_t>(positions.size() / 3));
      if (inserted) {
        const auto p = mesh.point(vertex);
        const auto n = mesh.normal(vertex);
        positions.insert(positions.end(), {p[0], p[1], p[2]});
        normals.insert(normals.end(), {n[0], n[1], n[2]});
        uvs.insert(uvs.end(), {u, v});
      }
      polygon.push_back(it->second);
    }
    for (std::size_t i = 1; i + 1 < polygon.size(); ++i) indices.insert(indices.end(), {polygon[0], polygon[i], polygon[i + 1]});
  }
  const std::size_t vertexCount = positions.size() / 3;
  float lo[3] = {positions[0], positions[1], positions[2]}, hi[3] = {lo[0], lo[1], lo[2]};
  for (std::size_t i = 0; i < positions.size(); ++i) {
    lo[i % 3] = std::min(lo[i % 3], positions[i]);
    hi[i % 3] = std::max(hi[i % 3], positions[i]);
  }

  std::vector<std::uint8_t> bin;
  appendFloats(bin, positions);
  appendFloats(bin, normals);
  appendFloats(bin, uvs);
  const std::size_t indexOffset = bin.size();
  bin.resize(indexOffset + indices.size() * 4);
  std::memcpy(&bin[indexOffset], indices.data(), indices.size() * 4);

  using Json = nlohmann::ordered_json;
  const std::size_t n = vertexCount;
  Json doc = {
      {"asset", {{"version", "2.0"}, {"generator", "libtangent (from " + path.filename().string() + ")"}}},
      {"scene", 0},
      {"scenes", Json::array({{{"nodes", Json::array({0})}}})},
      {"nodes", Json::array({{{"mesh", 0}, {"name", path.stem().string()}}})},
      {"meshes", Json::array({{{"name", path.stem().string()},
                               {"primitives", Json::array({{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}}},
                                                            {"indices", 3}}})}}})},
      {"accessors", Json::array({{{"bufferView", 0}, {"componentType", 5126}, {"count", n}, {"type", "VEC3"},
                                  {"min", Json::array({lo[0], lo[1], lo[2]})}, {"max", Json::array({hi[0], hi[1], hi[2]})}},
                                 {{"bufferView", 1}, {"componentType", 5126}, {"count", n}, {"type", "VEC3"}},
                                 {{"bufferView", 2}, {"componentType", 5126}, {"count", n}, {"type", "VEC2"}},
                                 {{"bufferView", 3}, {"componentType", 5125}, {"count", indices.size()}, {"type", "SCALAR"}}})},
      {"bufferViews", Json::array({{{"buffer", 0}, {"byteLength", n * 12}, {"target", 34962}},
                                   {{"buffer", 0}, {"byteOffset", n * 12}, {"byteLength", n * 12}, {"target", 34962}},
                                   {{"buffer", 0}, {"byteOffset", n * 24}, {"byteLength", n * 8}, {"target", 34962}},
                                   {{"buffer", 0}, {"byteOffset", indexOffset}, {"byteLength", indices.size() * 4}, {"target", 34963}}})},
      {"buffers", Json::array({{{"byteLength", bin.size()}}})}};
  return makeGlb(doc.dump(), bin);
}

}  // namespace tangent::gltf::detail
