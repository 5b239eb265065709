// SPDX-License-Identifier: MIT
// The OpenMesh mesh that OBJ, PLY and OFF files are read into, and the importer every reader
// hands it through, which checks each handle and count the file gives (mesh_file.cpp turns the
// mesh into a GLB). PLY and OFF have their own readers here (ply_reader.cpp, off_reader.cpp):
// OpenMesh's trusted every count in the file.
#pragma once

#include <OpenMesh/Core/IO/importer/ImporterT.hh>
#include <OpenMesh/Core/IO/Options.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <cstdint>
#include <string>
#include <type_traits>
#include <unordered_map>
#include <utility>
#include <vector>

#include "tangent/gltf.hpp"

namespace tangent::gltf::detail {

struct ImportTraits : OpenMesh::DefaultTraits {
  VertexAttributes(OpenMesh::Attributes::Normal | OpenMesh::Attributes::TexCoord2D);
  HalfedgeAttributes(OpenMesh::Attributes::PrevHalfedge | OpenMesh::Attributes::TexCoord2D);
  FaceAttributes(OpenMesh::Attributes::Normal);
};
// A polygon mesh: OpenMesh's readers leave the UVs of the diagonals unset when they
// triangulate into a TriMesh, so polygons are fanned here from their own corners.
using ImportMesh = OpenMesh::PolyMesh_ArrayKernelT<ImportTraits>;

// OpenMesh's readers trust the file: a face naming a vertex that does not exist reaches
// add_face and then per-halfedge writes through an invalid handle, and a header count is
// looped over (and reserved) whatever the file holds. Every call that takes a handle or a
// count from the file is checked here first; a refusal throws InputError naming the file
// and the element. Counts are bounded by the file's size (a vertex or face takes at least
// 3 bytes in every format).
class CheckedImporter : public OpenMesh::IO::ImporterT<ImportMesh> {
  using Base = OpenMesh::IO::ImporterT<ImportMesh>;

 public:
  // uvSet: which vertices' and halfedges' UVs the file gave (by index). OpenMesh reports
  // texture coordinates when the file has any "vt" line, also where no face refers to them,
  // and leaves the UVs it never set uninitialized.
  // normalSet: likewise the vertices the file gave a normal (an OBJ with "vn" lines whose faces
  // are "f v/vt" sets none, and OpenMesh still reports normals).
  CheckedImporter(ImportMesh& mesh, std::string label, std::uintmax_t fileBytes, std::vector<char>& vertexUvSet,
                  std::vector<char>& halfedgeUvSet, std::vector<char>& normalSet)
      : Base(mesh),
        mesh_(mesh),
        label_(std::move(label)),
        limit_(fileBytes / 3 + 16),
        vertexUvSet_(vertexUvSet),
        halfedgeUvSet_(halfedgeUvSet),
        normalSet_(normalSet) {}

  OpenMesh::VertexHandle add_vertex(const OpenMesh::Vec3f& point) override {
    countVertex();
    return Base::add_vertex(point);
  }
  OpenMesh::VertexHandle add_vertex() override {
    countVertex();
    return Base::add_vertex();
  }
  OpenMesh::FaceHandle add_face(const OpenMesh::IO::BaseImporter::VHandles& vertices) override {
    if (++faces_ > limit_) throw InputError(label_ + ": more faces than the file's size allows; the file is malformed");
    for (std::size_t k = 0; k < vertices.size(); ++k) {
      if (!validVertex(vertices[k]))
        throw InputError(label_ + ": face " + std::to_string(faces_) + " corner " + std::to_string(k + 1) + " refers to vertex " +
                         std::to_string(vertices[k].idx() + 1) + " (1-based), but the file has " +
                         std::to_string(mesh_.n_vertices()) + " vertices there");
    }
    const std::size_t before = mesh_.n_vertices();
    const OpenMesh::FaceHandle face = Base::add_face(vertices);
    // A face that would make the mesh non-manifold OpenMesh adds on copies of its vertices, made
    // in corner order, with the position only: the copies get the normal and UV the file gave
    // the originals, and the face's corner UVs (add_face_texcoords) find the copy.
    copiedFace_ = OpenMesh::FaceHandle();
    if (face.is_valid() && mesh_.n_vertices() == before + vertices.size()) {
      copiedFace_ = face;
      copiedFrom_ = vertices;
      copiedBase_ = before;
      for (std::size_t k = 0; k < vertices.size(); ++k) {
        const OpenMesh::VertexHandle copy(static_cast<int>(before + k));
        const auto original = static_cast<std::size_t>(vertices[k].idx());
        if (original < normalSet_.size() && normalSet_[original]) {
          Base::set_normal(copy, mesh_.normal(vertices[k]));
          mark(normalSet_, before + k);
        }
        if (original < vertexUvSet_.size() && vertexUvSet_[original]) {
          Base::set_texcoord(copy, mesh_.texcoord2D(vertices[k]));
          mark(vertexUvSet_, before + k);
        }
      }
    }
    return face;
  }
  void add_face_texcoords(OpenMesh::FaceHandle face, OpenMesh::VertexHandle vertex,
                          const std::vector<OpenMesh::Vec2f>& uvs) override {
    if (!validFace(face) || !validVertex(vertex)) return;  // a face add_face refused (repeated vertex)
    Base::add_face_texcoords(face, cornerVertex(face, vertex), uvs);
  }
  void add_face_texcoords(OpenMesh::FaceHandle face, OpenMesh::VertexHandle vertex,
                          const std::vector<OpenMesh::Vec3f>& uvs) override {
    if (!validFace(face) || !validVertex(vertex)) return;
    Base::add_face_texcoords(face, cornerVertex(face, vertex), uvs);
  }
  void set_point(OpenMesh::VertexHandle v, const OpenMesh::Vec3f& p) override { vertex(v, "position"), Base::set_point(v, p); }
  void set_normal(OpenMesh::VertexHandle v, const OpenMesh::Vec3f& n) override {
    vertex(v, "normal"), Base::set_normal(v, n);
    mark(normalSet_, static_cast<std::size_t>(v.idx()));
  }
  void set_normal(OpenMesh::VertexHandle v, const OpenMesh::Vec3d& n) override {
    vertex(v, "normal"), Base::set_normal(v, n);
    mark(normalSet_, static_cast<std::size_t>(v.idx()));
  }
  void set_texcoord(OpenMesh::VertexHandle v, const OpenMesh::Vec2f& t) override {
    vertex(v, "UV"), Base::set_texcoord(v, t);
    mark(vertexUvSet_, static_cast<std::size_t>(v.idx()));
  }
  void set_texcoord(OpenMesh::VertexHandle v, const OpenMesh::Vec3f& t) override { vertex(v, "UV"), Base::set_texcoord(v, t); }
  void set_texcoord(OpenMesh::HalfedgeHandle h, const OpenMesh::Vec2f& t) override {
    if (!h.is_valid() || static_cast<std::size_t>(h.idx()) >= mesh_.n_halfedges()) return;
    Base::set_texcoord(h, t);
    mark(halfedgeUvSet_, static_cast<std::size_t>(h.idx()));
  }
  void set_texcoord(OpenMesh::HalfedgeHandle h, const OpenMesh::Vec3f& t) override {
    if (h.is_valid() && static_cast<std::size_t>(h.idx()) < mesh_.n_halfedges()) Base::set_texcoord(h, t);
  }
  void set_color(OpenMesh::VertexHandle v, const OpenMesh::Vec3uc& c) override { vertex(v, "colour"), Base::set_color(v, c); }
  void set_color(OpenMesh::VertexHandle v, const OpenMesh::Vec4uc& c) override { vertex(v, "colour"), Base::set_color(v, c); }
  void set_color(OpenMesh::VertexHandle v, const OpenMesh::Vec3f& c) override { vertex(v, "colour"), Base::set_color(v, c); }
  void set_color(OpenMesh::VertexHandle v, const OpenMesh::Vec4f& c) override { vertex(v, "colour"), Base::set_color(v, c); }
  void set_normal(OpenMesh::FaceHandle f, const OpenMesh::Vec3f& n) override { if (validFace(f)) Base::set_normal(f, n); }
  void set_normal(OpenMesh::FaceHandle f, const OpenMesh::Vec3d& n) override { if (validFace(f)) Base::set_normal(f, n); }
  void set_color(OpenMesh::FaceHandle f, const OpenMesh::Vec3uc& c) override { if (validFace(f)) Base::set_color(f, c); }
  void set_color(OpenMesh::FaceHandle f, const OpenMesh::Vec4uc& c) override { if (validFace(f)) Base::set_color(f, c); }
  void set_color(OpenMesh::FaceHandle f, const OpenMesh::Vec3f& c) override { if (validFace(f)) Base::set_color(f, c); }
  void set_color(OpenMesh::FaceHandle f, const OpenMesh::Vec4f& c) override { if (validFace(f)) Base::set_color(f, c); }
  void set_face_texindex(OpenMesh::FaceHandle f, int id) override { if (validFace(f)) Base::set_face_texindex(f, id); }
  void reserve(unsigned int vertices, unsigned int edges, unsigned int faces) override {
    if (vertices > limit_ || faces > limit_)
      throw InputError(label_ + ": header declares " + std::to_string(vertices) + " vertices and " + std::to_string(faces) +
                       " faces, more than a file of this size can hold");
    Base::reserve(vertices, std::min<unsigned>(edges, static_cast<unsigned>(limit_ * 2)), faces);
  }

 private:
  bool validVertex(OpenMesh::VertexHandle v) const { return v.is_valid() && static_cast<std::size_t>(v.idx()) < mesh_.n_vertices(); }
  bool validFace(OpenMesh::FaceHandle f) const { return f.is_valid() && static_cast<std::size_t>(f.idx()) < mesh_.n_faces(); }
  void vertex(OpenMesh::VertexHandle v, const char* what) const {
    if (!validVertex(v))
      throw InputError(label_ + ": " + what + " given for vertex " + std::to_string(v.idx() + 1) + " (1-based), but the file has " +
                       std::to_string(mesh_.n_vertices()) + " vertices there");
  }
  static void mark(std::vector<char>& set, std::size_t i) {
    if (set.size() <= i) set.resize(i + 1, 0);
    set[i] = 1;
  }
  // The vertex of `face` that stands for the file's `vertex`: its copy where add_face copied.
  OpenMesh::VertexHandle cornerVertex(OpenMesh::FaceHandle face, OpenMesh::VertexHandle vertex) const {
    if (face != copiedFace_) return vertex;
    const auto at = std::find(copiedFrom_.begin(), copiedFrom_.end(), vertex);
    if (at == copiedFrom_.end()) return vertex;
    return OpenMesh::VertexHandle(static_cast<int>(copiedBase_ + static_cast<std::size_t>(at - copiedFrom_.begin())));
  }
  void countVertex() {
    if (++vertices_ > limit_) throw InputError(label_ + ": more vertices than the file's size allows; the file is malformed");
  }

  ImportMesh& mesh_;
  std::string label_;
  std::uintmax_t limit_;
  std::uintmax_t vertices_ = 0, faces_ = 0;
  std::vector<char>& vertexUvSet_;
  std::vector<char>& halfedgeUvSet_;
  std::vector<char>& normalSet_;
  OpenMesh::FaceHandle copiedFace_;  // the last face added on copies of its vertices
  OpenMesh::IO::BaseImporter::VHandles copiedFrom_;
  std::size_t copiedBase_ = 0;  // the copy of copiedFrom_[k] is vertex copiedBase_ + k
};

// The whitespace-separated words of a line.
inline std::vector<std::string> words(const std::string& line) {
  std::vector<std::string> out;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    const std::size_t start = i;
    while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
  return out;
}

// A non-negative integer of at most 10 digits.
inline bool isCount(const std::string& word) {
  return !word.empty() && word.size() <= 10 && std::all_of(word.begin(), word.end(), [](unsigned char c) { return std::isdigit(c); });
}


// A word that is one finite number as a whole ("1e39", "nan", "1x" are not), as float.
inline std::optional<float> finiteFloat(const std::string& word) {
  char* end = nullptr;
  const float x = std::strtof(word.c_str(), &end);
  if (word.empty() || end != word.c_str() + word.size() || !std::isfinite(x)) return std::nullopt;
  return x;
}

// Hash of a polygon's vertex: an index, or an OpenMesh handle (by its index).
struct VertexKeyHash {
  template <class Vertex>
  std::size_t operator()(const Vertex& v) const {
    if constexpr (std::is_integral_v<Vertex>) return std::hash<Vertex>()(v);
    else return std::hash<int>()(v.idx());
  }
};

// Whether a polygon visits a vertex more than once (no allocation for the usual small one).
template <class Vertex>
bool visitsAVertexTwice(const std::vector<Vertex>& vertices) {
  const std::size_t n = vertices.size();
  if (n <= 32) {
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t j = i + 1; j < n; ++j) {
        if (vertices[i] == vertices[j]) return true;
      }
    }
    return false;
  }
  std::vector<Vertex> sorted(vertices);
  std::sort(sorted.begin(), sorted.end());
  return std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end();
}

// A polygon that visits a vertex more than once, as the simple polygons a half-edge mesh can
// hold (OpenMesh refuses a face with a repeated vertex, and its OBJ reader then put the face's
// UVs on the wrong corners). Walking the corners, a vertex met again closes a loop: the corners
// from its first visit up to the second are one piece, and the second visit stands for the
// vertex from then on, so each visit's corner (its UV) is in exactly one piece:
// "f 1 2 3 1 4 5" is (1 2 3) with the first visit's corner and (1 4 5) with the second's. A
// corner repeating the one before it ("f 1 2 3 3") closes a loop of one corner. Pieces of fewer
// than three corners have no area and are dropped. Pieces come as their loops close, the rest
// last, each in the polygon's winding, as positions in `vertices`. Linear in the corners.
template <class Vertex>
std::vector<std::vector<std::size_t>> simplePolygons(const std::vector<Vertex>& vertices) {
  std::vector<std::vector<std::size_t>> pieces;
  std::vector<std::size_t> path;                // positions in `vertices`, no vertex twice
  std::unordered_map<Vertex, std::size_t, VertexKeyHash> onPath;  // vertex -> its index in path
  for (std::size_t k = 0; k < vertices.size(); ++k) {
    const auto [at, added] = onPath.try_emplace(vertices[k], path.size());
    if (!added) {
      const std::size_t from = at->second;
      if (path.size() - from >= 3) pieces.emplace_back(path.begin() + static_cast<std::ptrdiff_t>(from), path.end());
      for (std::size_t i = from + 1; i < path.size(); ++i) onPath.erase(vertices[path[i]]);
      path.resize(from);
    }
    path.push_back(k);
  }
  if (path.size() >= 3) pieces.push_back(std::move(path));
  return pieces;
}

// Adds a polygon of the file as its simplePolygons.
inline void addSimplePolygons(CheckedImporter& importer, const OpenMesh::IO::BaseImporter::VHandles& corners) {
  if (!visitsAVertexTwice(corners)) {
    importer.add_face(corners);
    return;
  }
  OpenMesh::IO::BaseImporter::VHandles piece;
  for (const std::vector<std::size_t>& positions : simplePolygons(corners)) {
    piece.clear();
    for (std::size_t k : positions) piece.push_back(corners[k]);
    importer.add_face(piece);
  }
}

// Each reads a whole file's bytes into `importer` and sets
// `options` to what the file gave (VertexNormal, VertexTexCoord, FaceTexCoord); a malformed
// file throws InputError naming `label` and the element.
void readPly(const std::string& text, CheckedImporter& importer, OpenMesh::IO::Options& options, const std::string& label);
void readOff(const std::string& text, CheckedImporter& importer, OpenMesh::IO::Options& options, const std::string& label);

}  // namespace tangent::gltf::detail
