// SPDX-License-Identifier: MIT
// What OBJ, PLY and OFF files are read into (plain arrays: each face's corners as the file
// lists them), and the importer every reader hands it through, which checks each handle and
// count the file gives (mesh_file.cpp turns the polygons into a GLB). Each format has its own
// reader (obj_reader.cpp, ply_reader.cpp, off_reader.cpp): OpenMesh's looped, crashed or
// allocated gigabytes on malformed files, and its half-edge mesh changed what the file said.
#pragma once

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "tangent/gltf.hpp"

namespace tangent::gltf::detail {

// A vertex of the file by its 0-based index, and the values the readers give it or its corners.
using VertexIndex = std::uint32_t;
struct Vec2f {
  float x = 0.0f, y = 0.0f;
};
struct Vec3f {
  float x = 0.0f, y = 0.0f, z = 0.0f;
};
// A polygon's corners, as vertex indices.
using Polygon = std::vector<VertexIndex>;

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

// A polygon mesh as a file gives it: every face is its corners, in the file's order, each with
// the UV and normal the file gave that corner or else its vertex. Not a half-edge mesh, which a
// GLB does not need: OpenMesh's add_face looked for each new edge among the outgoing half-edges
// of its vertex, so faces meeting at one vertex without sharing edges (petals, a triangle soup
// around a point) took time quadratic in their number, a face that would make the mesh
// non-manifold went onto copies of its vertices, and a vertex had one normal for all its faces.
struct ImportedPolygons {
  std::vector<Vec3f> points, normals;
  std::vector<Vec2f> uvs;          // per vertex
  std::vector<char> normalSet, uvSet;        // which vertices the file gave a normal, a UV
  std::vector<std::size_t> faceStart{0};     // face f's corners: [faceStart[f], faceStart[f + 1])
  std::vector<std::uint32_t> corners;        // each corner's vertex
  // Each corner's own UV and normal, where the Set arrays say so; both left empty until a file
  // gives a corner one (PLY and OFF never give a corner a normal).
  std::vector<Vec2f> cornerUvs;
  std::vector<char> cornerUvSet;
  std::vector<Vec3f> cornerNormals;
  std::vector<char> cornerNormalSet;
  bool anyUv = false;  // whether any vertex has one
  std::size_t faceCount() const { return faceStart.size() - 1; }
  bool anyCornerUv() const { return !cornerUvSet.empty(); }
  bool hasCornerUv(std::size_t corner) const { return corner < cornerUvSet.size() && cornerUvSet[corner]; }
  bool hasCornerNormal(std::size_t corner) const { return corner < cornerNormalSet.size() && cornerNormalSet[corner]; }
};

// What the readers (obj_reader.cpp, ply_reader.cpp, off_reader.cpp) hand the polygons through.
// They check the file's syntax; this checks each handle and count the file gives: a refusal
// throws InputError naming the file and the element. Counts are bounded by the file's size (a
// vertex or face takes at least 3 bytes in every format).
class CheckedImporter {
 public:
  CheckedImporter(ImportedPolygons& mesh, std::string label, std::uintmax_t fileBytes)
      : mesh_(mesh), label_(std::move(label)), limit_(fileBytes / 3 + 16) {}

  VertexIndex addVertex(const Vec3f& point) {
    if (mesh_.points.size() >= limit_) throw InputError(label_ + ": more vertices than the file's size allows; the file is malformed");
    if (mesh_.points.size() >= kMaxVertices) throw InputError(label_ + ": more than 2^32 - 1 vertices, which glTF indices cannot address");
    mesh_.points.push_back(point);
    mesh_.normals.emplace_back();
    mesh_.uvs.emplace_back();
    mesh_.normalSet.push_back(0);
    mesh_.uvSet.push_back(0);
    return static_cast<VertexIndex>(mesh_.points.size() - 1);
  }
  // A face of at least three corners, none repeated (the readers cut a polygon that visits a
  // vertex twice into simplePolygons first): its index, or none.
  std::optional<std::size_t> addFace(const Polygon& vertices) {
    if (mesh_.faceCount() >= limit_) throw InputError(label_ + ": more faces than the file's size allows; the file is malformed");
    for (std::size_t k = 0; k < vertices.size(); ++k) {
      if (!validVertex(vertices[k]))
        throw InputError(label_ + ": face " + std::to_string(mesh_.faceCount() + 1) + " corner " + std::to_string(k + 1) +
                         " refers to vertex " + std::to_string(std::uint64_t{vertices[k]} + 1) + " (1-based), but the file has " +
                         std::to_string(mesh_.points.size()) + " vertices there");
    }
    if (vertices.size() < 3 || visitsAVertexTwice(vertices)) return std::nullopt;
    mesh_.corners.insert(mesh_.corners.end(), vertices.begin(), vertices.end());
    mesh_.faceStart.push_back(mesh_.corners.size());
    return mesh_.faceCount() - 1;
  }
  // Corner `k` of `face` (in the order addFace took them) gets its own UV or normal.
  void setCornerUv(std::size_t face, std::size_t k, const Vec2f& uv) { setCorner(mesh_.cornerUvs, mesh_.cornerUvSet, corner(face, k), uv); }
  void setCornerNormal(std::size_t face, std::size_t k, const Vec3f& normal) {
    setCorner(mesh_.cornerNormals, mesh_.cornerNormalSet, corner(face, k), normal);
  }
  // A vertex's normal and UV: where a corner has none of its own.
  void setNormal(VertexIndex v, const Vec3f& n) {
    vertex(v, "normal");
    mesh_.normals[v] = n;
    mesh_.normalSet[v] = 1;
  }
  void setUv(VertexIndex v, const Vec2f& uv) {
    vertex(v, "UV");
    mesh_.uvs[v] = uv;
    mesh_.uvSet[v] = 1;
    mesh_.anyUv = true;
  }
  void reserve(unsigned int vertices, unsigned int faces) {
    if (vertices > limit_ || faces > limit_)
      throw InputError(label_ + ": header declares " + std::to_string(vertices) + " vertices and " + std::to_string(faces) +
                       " faces, more than a file of this size can hold");
    mesh_.points.reserve(vertices);
    mesh_.faceStart.reserve(std::size_t{faces} + 1);
  }
  std::size_t vertexCount() const { return mesh_.points.size(); }
  std::size_t faceCount() const { return mesh_.faceCount(); }

 private:
  static constexpr std::size_t kMaxVertices = 0xffffffffu;
  bool validVertex(VertexIndex v) const { return v < mesh_.points.size(); }
  std::size_t corner(std::size_t face, std::size_t k) const { return mesh_.faceStart[face] + k; }
  // Grown up to the corner on its first value (vector growth: amortized constant time).
  template <class Value>
  static void setCorner(std::vector<Value>& values, std::vector<char>& set, std::size_t c, const Value& value) {
    if (set.size() <= c) set.resize(c + 1, 0), values.resize(c + 1);
    values[c] = value;
    set[c] = 1;
  }
  void vertex(VertexIndex v, const char* what) const {
    if (!validVertex(v))
      throw InputError(label_ + ": " + what + " given for vertex " + std::to_string(std::uint64_t{v} + 1) + " (1-based), but the file has " +
                       std::to_string(mesh_.points.size()) + " vertices there");
  }

  ImportedPolygons& mesh_;
  std::string label_;
  std::uintmax_t limit_;
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
  std::unordered_map<Vertex, std::size_t> onPath;  // vertex -> its index in path
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

// Adds a polygon of the file (`corners`) as its simplePolygons, and calls onFace(face, n, position)
// for each face added: n corners, position(j) the position in `corners` of the face's corner j (what
// a reader needs to give the face's corners their own UVs and normals).
template <class OnFace>
void addSimplePolygons(CheckedImporter& importer, const Polygon& corners, OnFace&& onFace) {
  if (!visitsAVertexTwice(corners)) {
    if (const std::optional<std::size_t> face = importer.addFace(corners)) onFace(*face, corners.size(), [](std::size_t j) { return j; });
    return;
  }
  Polygon piece;
  for (const std::vector<std::size_t>& positions : simplePolygons(corners)) {
    piece.clear();
    for (std::size_t k : positions) piece.push_back(corners[k]);
    if (const std::optional<std::size_t> face = importer.addFace(piece))
      onFace(*face, positions.size(), [&positions](std::size_t j) { return positions[j]; });
  }
}
inline void addSimplePolygons(CheckedImporter& importer, const Polygon& corners) {
  addSimplePolygons(importer, corners, [](std::size_t, std::size_t, const auto&) {});
}

// Each reads a whole file's bytes into `importer`; a malformed file throws InputError naming
// `label` and the element.
void readObj(const std::string& text, CheckedImporter& importer, const std::string& label);
void readPly(const std::string& text, CheckedImporter& importer, const std::string& label);
void readOff(const std::string& text, CheckedImporter& importer, const std::string& label);

}  // namespace tangent::gltf::detail
