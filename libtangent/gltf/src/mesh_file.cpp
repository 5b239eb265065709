// SPDX-License-Identifier: MIT
// OBJ, PLY and OFF through OpenMesh's readers, converted to an in-memory GLB so that the rest
// of bake treats them like any glTF input. These formats carry no materials: every mesh
// gets tangents. Their UV origin is bottom-left, so v becomes 1 - v for glTF. A file without
// normals gives a primitive without NORMAL, which bake then generates (--normals).
#include <OpenMesh/Core/IO/IOManager.hh>
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/IO/importer/ImporterT.hh>
#include <OpenMesh/Core/System/omstream.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>

#include <algorithm>
#include <cstdlib>
#include <cmath>
#include <iterator>
#include <new>
#include <sstream>
#include <stdexcept>
#include <bit>
#include <cctype>
#include <fstream>
#include <cstring>
#include <map>
#include <tuple>
#include <unordered_map>

#include "asset.hpp"
#include "tangent/gltf.hpp"
#include "tangent/text.hpp"

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
    return Base::add_face(vertices);
  }
  void add_face_texcoords(OpenMesh::FaceHandle face, OpenMesh::VertexHandle vertex,
                          const std::vector<OpenMesh::Vec2f>& uvs) override {
    if (!validFace(face) || !validVertex(vertex)) return;  // a face add_face refused (repeated vertex)
    Base::add_face_texcoords(face, vertex, uvs);
  }
  void add_face_texcoords(OpenMesh::FaceHandle face, OpenMesh::VertexHandle vertex,
                          const std::vector<OpenMesh::Vec3f>& uvs) override {
    if (!validFace(face) || !validVertex(vertex)) return;
    Base::add_face_texcoords(face, vertex, uvs);
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
};

std::vector<std::string> words(const std::string& line) {
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

bool isCount(const std::string& word) {
  return !word.empty() && word.size() <= 10 && std::all_of(word.begin(), word.end(), [](unsigned char c) { return std::isdigit(c); });
}

// Bytes of one PLY scalar type; 0 when the name is not one.
int plyTypeBytes(const std::string& type) {
  static const std::pair<const char*, int> types[] = {
      {"char", 1},  {"uchar", 1},  {"int8", 1},  {"uint8", 1},  {"short", 2},   {"ushort", 2},  {"int16", 2},
      {"uint16", 2}, {"int", 4},   {"uint", 4},  {"int32", 4},  {"uint32", 4},  {"float", 4},   {"float32", 4},
      {"double", 8}, {"float64", 8}};
  for (const auto& [name, bytes] : types) {
    if (type == name) return bytes;
  }
  return 0;
}

// OpenMesh's PLY and OFF header parsers loop forever on some malformed headers (found by
// fuzz_mesh_file): the header is checked here first, line by line, and every element count
// against the bytes that follow it.
void checkPlyHeader(std::istream& in, std::uintmax_t fileBytes, const std::string& label) {
  std::string line;
  std::size_t lineNumber = 0, headerBytes = 0;
  auto next = [&]() -> bool {
    if (!std::getline(in, line)) return false;
    ++lineNumber;
    headerBytes += line.size() + 1;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    return true;
  };
  auto fail = [&](const std::string& what) -> void {
    throw InputError(label + ": PLY header line " + std::to_string(lineNumber) + ": " + what);
  };
  if (!next() || line != "ply") fail("the file must start with a line 'ply'");
  if (!next()) fail("missing format line");
  const std::vector<std::string> format = words(line);
  if (format.size() != 3 || format[0] != "format" || format[2] != "1.0" ||
      (format[1] != "ascii" && format[1] != "binary_little_endian" && format[1] != "binary_big_endian"))
    fail("expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
  const bool ascii = format[1] == "ascii";
  struct Element {
    std::string name;
    std::uint64_t count = 0, minBytes = 0;
  };
  std::vector<Element> elements;
  for (;;) {
    if (!next()) fail("the header has no end_header line");
    if (headerBytes > (1u << 20)) fail("the header is longer than 1 MiB");
    const std::vector<std::string> w = words(line);
    if (w.empty() || w[0] == "comment" || w[0] == "obj_info") continue;
    if (w[0] == "end_header") break;
    if (w[0] == "element") {
      if (w.size() != 3 || !isCount(w[2])) fail("expected 'element NAME COUNT'");
      elements.push_back({w[1], std::stoull(w[2]), 0});
    } else if (w[0] == "property") {
      if (elements.empty()) fail("a property before any element");
      if (w.size() == 3 && plyTypeBytes(w[1])) {
        elements.back().minBytes += ascii ? 2 : plyTypeBytes(w[1]);
      } else if (w.size() == 5 && w[1] == "list" && plyTypeBytes(w[2]) && plyTypeBytes(w[3])) {
        elements.back().minBytes += ascii ? 2 : plyTypeBytes(w[2]);
      } else {
        fail("expected 'property TYPE NAME' or 'property list TYPE TYPE NAME'");
      }
    } else {
      // Free text in a header (an old Blender wrote one line of it) is not PLY; OpenMesh's
      // parser misreads it into crashes (fuzz_mesh_file), so it is refused.
      fail("unknown keyword '" + w[0].substr(0, 40) + "' (a PLY header line is comment, obj_info, element, property or end_header)");
    }
  }
  const std::uintmax_t body = fileBytes > headerBytes ? fileBytes - headerBytes : 0;
  for (const Element& e : elements) {
    if (e.count > 0 && e.count * std::max<std::uint64_t>(e.minBytes, 1) > body + 1)
      throw InputError(label + ": PLY header declares " + std::to_string(e.count) + " " + e.name +
                       " elements, more than the " + std::to_string(body) + " bytes after the header can hold");
  }
}

// OFF is read here, not by OpenMesh: its reader takes the counts after the keyword line
// whatever that line holds, reads numbers as one token stream across lines (a bad number
// leaves the stream failed and every later count at its maximum: a face of 4 billion corners,
// found by fuzz_mesh_file), and ignores comments. Here the file is read one vertex or face per
// line, every number is checked, and the mesh reaches the same checked importer. ASCII and
// binary (OpenMesh's layout: little-endian 32-bit counts, indices and floats); colours, which
// no glTF attribute here takes, are skipped in ASCII and refused in binary.
void readOff(const std::string& text, CheckedImporter& importer, OpenMesh::IO::Options& options, const std::string& label) {
  std::size_t at = 0, lineNumber = 0;
  std::string line;
  auto next = [&]() -> bool {  // the next line with something on it, comments removed
    while (at < text.size()) {
      const std::size_t end = std::min(text.find('\n', at), text.size());
      line.assign(text, at, end - at);
      at = end + 1;
      ++lineNumber;
      const std::size_t hash = line.find('#');
      if (hash != std::string::npos) line.erase(hash);
      if (!words(line).empty()) return true;
    }
    return false;
  };
  auto fail = [&](const std::string& what) -> void {
    throw InputError(label + ": OFF line " + std::to_string(lineNumber) + ": " + what);
  };
  if (!next()) throw InputError(label + ": has no OFF keyword line (the file is empty or only comments)");
  std::vector<std::string> w = words(line);
  const std::string keyword = w[0];
  // [ST][C][N][4][n]OFF
  std::size_t k = 0;
  auto prefix = [&](const char* p) {
    const bool has = keyword.compare(k, std::strlen(p), p) == 0;
    if (has) k += std::strlen(p);
    return has;
  };
  const bool texcoords = prefix("ST"), colours = prefix("C"), hasNormals = prefix("N");
  const bool homogeneous = prefix("4"), dimension = prefix("n");
  if (keyword.substr(k) != "OFF") fail("expected an OFF keyword ([ST][C][N][4][n]OFF), found '" + keyword.substr(0, 40) + "'");
  if (homogeneous) fail("4OFF (homogeneous coordinates) is not read");
  if (dimension) fail("nOFF (a dimension other than 3) is not read");
  const std::size_t perVertex = hasNormals ? 6 : 3;
  const std::uintmax_t fileBytes = text.size();
  auto bound = [&](std::uint64_t vertices, std::uint64_t faces, std::uint64_t vertexBytes, std::uint64_t faceBytes) {
    if (vertices * vertexBytes + faces * faceBytes > fileBytes + 8)
      throw InputError(label + ": OFF header declares " + std::to_string(vertices) + " vertices and " + std::to_string(faces) +
                       " faces, more than a file of " + std::to_string(fileBytes) + " bytes can hold");
  };
  std::vector<OpenMesh::VertexHandle> handles;
  OpenMesh::IO::BaseImporter::VHandles corners;

  if (w.size() > 1 && w[1] == "BINARY") {
    if (colours) fail("binary OFF with colours (" + keyword.substr(0, 40) + ") is not read");
    // The binary part starts after the keyword line's newline.
    auto u32 = [&](const char* what) -> std::uint32_t {
      if (at + 4 > text.size()) throw InputError(label + ": binary OFF ends inside " + std::string(what));
      const auto* b = reinterpret_cast<const unsigned char*>(text.data() + at);
      at += 4;
      return std::uint32_t{b[0]} | std::uint32_t{b[1]} << 8 | std::uint32_t{b[2]} << 16 | std::uint32_t{b[3]} << 24;
    };
    auto f32 = [&](const char* what) { return std::bit_cast<float>(u32(what)); };
    const std::uint32_t vertices = u32("the counts"), faces = u32("the counts");
    u32("the counts");  // edges, unused
    bound(vertices, faces, 4 * (perVertex + (texcoords ? 2 : 0)), 16);
    for (std::uint32_t v = 0; v < vertices; ++v) {
      float x[8];
      for (std::size_t c = 0; c < perVertex + (texcoords ? 2 : 0); ++c) x[c] = f32("a vertex");
      const auto vh = importer.add_vertex(OpenMesh::Vec3f(x[0], x[1], x[2]));
      if (hasNormals) importer.set_normal(vh, OpenMesh::Vec3f(x[3], x[4], x[5]));
      if (texcoords) importer.set_texcoord(vh, OpenMesh::Vec2f(x[perVertex], x[perVertex + 1]));
      handles.push_back(vh);
    }
    for (std::uint32_t f = 0; f < faces; ++f) {
      const std::uint32_t n = u32("a face");
      if (n < 3 || n > (text.size() - at) / 4)
        throw InputError(label + ": binary OFF face " + std::to_string(f + 1) + " declares " + std::to_string(n) +
                         " corners (at least 3, and no more than the rest of the file holds)");
      corners.clear();
      for (std::uint32_t c = 0; c < n; ++c) {
        const std::uint32_t index = u32("a face");
        if (index >= vertices)
          throw InputError(label + ": binary OFF face " + std::to_string(f + 1) + " corner " + std::to_string(c + 1) +
                           " is vertex " + std::to_string(index) + ", not one below " + std::to_string(vertices));
        corners.push_back(handles[index]);
      }
      importer.add_face(corners);
    }
  } else {
    // The counts: on the keyword line after the keyword, or on the next line.
    w.erase(w.begin());
    if (w.empty()) {
      if (!next()) fail("missing the vertex, face and edge counts");
      w = words(line);
    }
    if (w.size() < 2 || !isCount(w[0]) || !isCount(w[1]) || (w.size() > 2 && !isCount(w[2])))
      fail("expected 'VERTICES FACES [EDGES]' as non-negative integers");
    const std::uint64_t vertices = std::stoull(w[0]), faces = std::stoull(w[1]);
    // An ASCII vertex takes at least 6 bytes ("0 0 0\n"), a face at least 8 ("3 0 1 2\n").
    bound(vertices, faces, 6, 8);
    auto number = [&](const std::string& word, const std::string& what) {
      char* end = nullptr;
      const float x = std::strtof(word.c_str(), &end);
      if (end != word.c_str() + word.size() || !std::isfinite(x))
        fail(what + " '" + word.substr(0, 20) + "' is not a finite number");
      return x;
    };
    for (std::uint64_t v = 0; v < vertices; ++v) {
      if (!next()) fail("the file ends after " + std::to_string(v) + " of " + std::to_string(vertices) + " vertices");
      w = words(line);
      // x y z [nx ny nz] [colour] [s t]: the texture coordinates are the line's last two.
      const std::size_t needed = perVertex + (texcoords ? 2 : 0);
      if (w.size() < needed)
        fail("vertex " + std::to_string(v + 1) + " lists " + std::to_string(w.size()) + " value(s); " + keyword.substr(0, 40) +
             " needs " + std::to_string(needed) + " (x y z" + (hasNormals ? " nx ny nz" : "") + (texcoords ? " s t" : "") + ")");
      float x[8];
      for (std::size_t c = 0; c < perVertex; ++c) x[c] = number(w[c], "vertex " + std::to_string(v + 1) + " value");
      const auto vh = importer.add_vertex(OpenMesh::Vec3f(x[0], x[1], x[2]));
      if (hasNormals) importer.set_normal(vh, OpenMesh::Vec3f(x[3], x[4], x[5]));
      if (texcoords) {
        const std::string what = "vertex " + std::to_string(v + 1) + " texture coordinate";
        importer.set_texcoord(vh, OpenMesh::Vec2f(number(w[w.size() - 2], what), number(w.back(), what)));
      }
      handles.push_back(vh);
    }
    for (std::uint64_t f = 0; f < faces; ++f) {
      if (!next()) fail("the file ends after " + std::to_string(f) + " of " + std::to_string(faces) + " faces");
      w = words(line);
      // n i1 .. in [colour]
      if (!isCount(w[0]) || std::stoull(w[0]) < 3 || std::stoull(w[0]) > w.size() - 1)
        fail("face " + std::to_string(f + 1) + " declares '" + w[0].substr(0, 20) + "' corners but lists " +
             std::to_string(w.size() - 1) + " numbers");
      const std::size_t n = std::stoull(w[0]);
      corners.clear();
      for (std::size_t c = 1; c <= n; ++c) {
        if (!isCount(w[c]) || std::stoull(w[c]) >= vertices)
          fail("face " + std::to_string(f + 1) + " corner " + std::to_string(c) + " '" + w[c].substr(0, 20) +
               "' is not a vertex index below " + std::to_string(vertices));
        corners.push_back(handles[std::stoull(w[c])]);
      }
      importer.add_face(corners);
    }
  }
  options.clear();
  if (hasNormals) options += OpenMesh::IO::Options::VertexNormal;
  if (texcoords) options += OpenMesh::IO::Options::VertexTexCoord;
}

// OpenMesh's OBJ reader asserts (aborts) on a face line without a vertex and trusts every
// reference: each `f` line is checked here against the v, vt and vn lines before it.
void checkObj(std::istream& in, const std::string& label) {
  std::string line;
  std::size_t lineNumber = 0;
  std::int64_t counts[3] = {0, 0, 0};  // v, vt, vn
  const char* const kinds[3] = {"vertex", "texture coordinate", "normal"};
  while (std::getline(in, line)) {
    ++lineNumber;
    const std::vector<std::string> w = words(line);
    if (w.empty()) continue;
    auto fail = [&](const std::string& what) {
      throw InputError(label + ": OBJ line " + std::to_string(lineNumber) + ": " + what);
    };
    const int kind = w[0] == "v" ? 0 : w[0] == "vt" ? 1 : w[0] == "vn" ? 2 : -1;
    if (kind >= 0) {
      // OpenMesh skips a line whose numbers do not parse (nan, 1e39) and numbers the rest
      // on, so every later reference would name another element: refused here instead.
      const std::size_t needed = kind == 1 ? 1 : 3;
      for (std::size_t k = 1; k <= needed; ++k) {
        const std::string value = k < w.size() ? w[k] : std::string();
        char* end = nullptr;
        const float x = value.empty() ? 0.0f : std::strtof(value.c_str(), &end);
        if (value.empty() || end != value.c_str() + value.size() || !std::isfinite(x))
          fail(std::string(kinds[kind]) + " '" + line.substr(0, 60) + "' needs " + std::to_string(needed) +
               " finite numbers" + (value.empty() ? "" : "; '" + value.substr(0, 20) + "' is not one"));
      }
      ++counts[kind];
      continue;
    }
    if (w[0] != "f") continue;
    if (w.size() < 4) fail("a face needs at least three vertices");
    for (std::size_t k = 1; k < w.size(); ++k) {
      std::size_t start = 0;
      for (int part = 0; part < 3 && start <= w[k].size(); ++part) {
        const std::size_t slash = std::min(w[k].find('/', start), w[k].size());
        const std::string number = w[k].substr(start, slash - start);
        start = slash + 1;
        if (number.empty()) {
          if (part == 0) fail("face corner '" + w[k].substr(0, 40) + "' has no vertex index");
          continue;
        }
        const bool negative = number[0] == '-';
        const std::string digits = negative || number[0] == '+' ? number.substr(1) : number;
        if (!isCount(digits)) fail("face corner '" + w[k].substr(0, 40) + "' is not an index");
        const std::int64_t index = std::stoll(digits);
        const std::int64_t resolved = negative ? counts[part] - index + 1 : index;
        if (index == 0 || resolved < 1 || resolved > counts[part])
          fail("face corner '" + w[k].substr(0, 40) + "' refers to " + kinds[part] + " " + number + ", but " +
               std::to_string(counts[part]) + " are defined before this line");
        if (slash == w[k].size()) break;
      }
    }
  }
}

// OpenMesh reports every non-manifold face on its error stream: muted while reading.
class MutedOpenMeshErrors {
 public:
  MutedOpenMeshErrors() { omerr().disable(); }
  ~MutedOpenMeshErrors() { omerr().enable(); }
  MutedOpenMeshErrors(const MutedOpenMeshErrors&) = delete;
  MutedOpenMeshErrors& operator=(const MutedOpenMeshErrors&) = delete;
};

void appendFloats(std::vector<std::uint8_t>& bin, const std::vector<float>& values) {
  if (values.empty()) return;  // a file without normals: no bytes, and memcpy wants real pointers
  const std::size_t at = bin.size();
  bin.resize(at + values.size() * 4);
  std::memcpy(bin.data() + at, values.data(), values.size() * 4);
}

}  // namespace

std::vector<std::uint8_t> meshFileToGlb(const std::filesystem::path& path) {
  ImportMesh mesh;
  OpenMesh::IO::Options options = OpenMesh::IO::Options::VertexNormal | OpenMesh::IO::Options::VertexTexCoord |
                                  OpenMesh::IO::Options::FaceTexCoord;
  std::error_code ec;
  const std::uintmax_t fileBytes = std::filesystem::file_size(path, ec);
  if (ec) throw InputError(path.string() + ": cannot be read: " + ec.message());
  const std::string extension = lowerExtension(path);
  // An OBJ or OFF is read once, into memory: an OBJ is checked, then given to OpenMesh from
  // there (below); an OFF is read here.
  std::string text;
  {
    std::ifstream header(path, std::ios::binary);
    if (extension == ".ply") checkPlyHeader(header, fileBytes, path.string());
    if (extension == ".obj" || extension == ".off") {
      text.assign(std::istreambuf_iterator<char>(header), std::istreambuf_iterator<char>());
    }
    if (extension == ".obj") {
      std::istringstream lines(text);
      checkObj(lines, path.string());
    }
  }
  std::vector<char> vertexUvSet, halfedgeUvSet, normalSet;
  {
    MutedOpenMeshErrors muted;
    CheckedImporter importer(mesh, path.string(), fileBytes, vertexUvSet, halfedgeUvSet, normalSet);
    bool read = false;
    try {
      if (extension == ".off") {
        readOff(text, importer, options, path.string());
        read = true;
      } else if (extension == ".obj") {
        // From memory, its mtllib lines blanked: OpenMesh opened the material library wherever
        // it named (outside the asset's folder, or a FIFO that never ends) and materials are
        // not used. Line numbers stay as in the file.
        for (std::size_t at = 0; at < text.size();) {
          const std::size_t end = std::min(text.find('\n', at), text.size());
          std::size_t first = at;
          while (first < end && (text[first] == ' ' || text[first] == '\t')) ++first;
          if (text.compare(first, 6, "mtllib") == 0 && (first + 6 == end || std::isspace(static_cast<unsigned char>(text[first + 6]))))
            std::fill(text.begin() + static_cast<std::ptrdiff_t>(at), text.begin() + static_cast<std::ptrdiff_t>(end), ' ');
          at = end + 1;
        }
        std::istringstream stream(std::move(text));
        read = OpenMesh::IO::IOManager().read(stream, ".obj", importer, options);
      } else {
        read = OpenMesh::IO::IOManager().read(path.string(), importer, options);
      }
    } catch (const std::bad_alloc&) {
      // A face's corner count is read and allocated before any corner reaches the importer.
      throw InputError(path.string() + ": a count in the file (a face's corners) is larger than memory allows; the file is malformed");
    } catch (const std::length_error&) {
      throw InputError(path.string() + ": a count in the file (a face's corners) is out of range; the file is malformed");
    }
    if (!read)
      throw InputError(path.string() + ": OpenMesh cannot read this file (malformed, or not " +
                       path.extension().string() + " at all)");
  }
  if (mesh.n_faces() == 0) throw InputError(path.string() + ": has no faces");
  auto isSet = [](const std::vector<char>& set, int i) { return static_cast<std::size_t>(i) < set.size() && set[i]; };
  // NORMAL where the file gave every vertex a face uses one; else none (bake generates them as
  // for a glTF without NORMAL), never the values OpenMesh left unset.
  bool haveNormals = options.check(OpenMesh::IO::Options::VertexNormal);
  for (auto face : mesh.faces()) {
    for (auto vertex : mesh.fv_range(face)) haveNormals = haveNormals && isSet(normalSet, vertex.idx());
    if (!haveNormals) break;
  }
  const bool cornerUvs = options.check(OpenMesh::IO::Options::FaceTexCoord) && !halfedgeUvSet.empty();
  const bool vertexUvs = options.check(OpenMesh::IO::Options::VertexTexCoord) && !vertexUvSet.empty();
  if (!cornerUvs && !vertexUvs) throw InputError(path.string() + ": has no texture coordinates; tangents need UVs");

  // One glTF vertex per distinct (vertex, UV).
  std::map<std::tuple<int, std::uint32_t, std::uint32_t>, std::uint32_t> vertexOf;
  std::vector<float> positions, normals, uvs;
  std::vector<std::uint32_t> indices;
  std::vector<std::uint32_t> polygon;
  for (auto face : mesh.faces()) {
    polygon.clear();
    for (auto halfedge : mesh.fh_range(face)) {
      const auto vertex = mesh.to_vertex_handle(halfedge);
      // A corner's own UV where the file gave one, else its vertex's.
      const bool own = cornerUvs && isSet(halfedgeUvSet, halfedge.idx());
      if (!own && !(vertexUvs && isSet(vertexUvSet, vertex.idx())))
        throw InputError(path.string() + ": face " + std::to_string(face.idx() + 1) +
                         " (1-based) has no texture coordinate at its vertex " + std::to_string(vertex.idx() + 1) +
                         "; tangents need UVs on every face");
      const auto uv = own ? mesh.texcoord2D(halfedge) : mesh.texcoord2D(vertex);
      const float u = uv[0], v = 1.0f - uv[1];
      auto key = std::make_tuple(vertex.idx(), std::bit_cast<std::uint32_t>(u), std::bit_cast<std::uint32_t>(v));
      auto [it, inserted] = vertexOf.try_emplace(key, static_cast<std::uint32_t>(positions.size() / 3));
      if (inserted) {
        const auto p = mesh.point(vertex);
        const auto n = haveNormals ? mesh.normal(vertex) : OpenMesh::Vec3f(0.0f, 0.0f, 1.0f);
        // A NaN or infinity would make the GLB invalid (its min/max null, the data refused by
        // the validator): named here instead.
        for (const float x : {p[0], p[1], p[2], n[0], n[1], n[2], u, v}) {
          if (!std::isfinite(x))
            throw InputError(path.string() + ": vertex " + std::to_string(vertex.idx() + 1) +
                             " (1-based) has a coordinate, normal or UV that is not a finite number");
        }
        positions.insert(positions.end(), {p[0], p[1], p[2]});
        if (haveNormals) normals.insert(normals.end(), {n[0], n[1], n[2]});
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
  // Without normals in the file the primitive has no NORMAL, and bake generates it as for glTF
  // (--normals: flat by default, as glTF 3.7.2.1 asks of readers and as Blender's OBJ importer
  // shades a mesh without normals or smoothing groups).
  Json attributes = {{"POSITION", 0}};
  Json accessors = Json::array({{{"bufferView", 0}, {"componentType", 5126}, {"count", n}, {"type", "VEC3"},
                                 {"min", Json::array({lo[0], lo[1], lo[2]})}, {"max", Json::array({hi[0], hi[1], hi[2]})}}});
  Json bufferViews = Json::array({{{"buffer", 0}, {"byteLength", n * 12}, {"target", 34962}}});
  std::size_t offset = n * 12;
  auto addVertexAttribute = [&](const char* name, const char* type, std::size_t bytes) {
    attributes[name] = accessors.size();
    accessors.push_back({{"bufferView", bufferViews.size()}, {"componentType", 5126}, {"count", n}, {"type", type}});
    bufferViews.push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", n * bytes}, {"target", 34962}});
    offset += n * bytes;
  };
  if (haveNormals) addVertexAttribute("NORMAL", "VEC3", 12);
  addVertexAttribute("TEXCOORD_0", "VEC2", 8);
  const std::size_t indicesAccessor = accessors.size();
  accessors.push_back({{"bufferView", bufferViews.size()}, {"componentType", 5125}, {"count", indices.size()}, {"type", "SCALAR"}});
  bufferViews.push_back({{"buffer", 0}, {"byteOffset", indexOffset}, {"byteLength", indices.size() * 4}, {"target", 34963}});
  Json doc = {
      {"asset", {{"version", "2.0"}, {"generator", "libtangent (from " + path.filename().string() + ")"}}},
      {"scene", 0},
      {"scenes", Json::array({{{"nodes", Json::array({0})}}})},
      {"nodes", Json::array({{{"mesh", 0}, {"name", path.stem().string()}}})},
      {"meshes", Json::array({{{"name", path.stem().string()},
                               {"primitives", Json::array({{{"attributes", attributes}, {"indices", indicesAccessor}}})}}})},
      {"accessors", accessors},
      {"bufferViews", bufferViews},
      {"buffers", Json::array({{{"byteLength", bin.size()}}})}};
  return makeGlb(text::dumpJson(doc), bin);
}

}  // namespace tangent::gltf::detail
