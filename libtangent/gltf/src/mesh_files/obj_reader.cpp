// SPDX-License-Identifier: MIT
// Wavefront OBJ: `v`, `vt` and `vn` lines, and `f` lines whose corners name them as
// `v`, `v/vt`, `v//vn` or `v/vt/vn` (1-based; negative: counted back from the line). Every
// number is checked and every reference resolved against the lines before it; a malformed file
// throws InputError naming the line. Each corner keeps the UV and normal its face gives it (a
// vertex may have a hard edge: a normal per face); a corner without one takes the last its
// vertex was given on any face, as OpenMesh's reader did. Other lines (`o`, `g`, `s`, `usemtl`,
// `mtllib`, `l`, `p`, ...) are skipped: no material library is opened.
#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "mesh_files/mesh_import.hpp"
#include "tangent/gltf.hpp"

namespace tangent::gltf::detail {

namespace {

const char* const kObjKinds[3] = {"vertex", "texture coordinate", "normal"};

// One corner of a face line: indices (0-based) of its vertex, UV (-1: none) and normal (-1: none).
struct ObjCorner {
  std::int64_t vertex, uv, normal;
};

// The line being read, for messages.
struct ObjLine {
  const std::string& label;
  std::size_t number;
  const std::string& text;
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(label + ": OBJ line " + std::to_string(number) + ": " + what);
  }
};

// The numbers of a v (kind 0), vt (1) or vn (2) line. u alone is a texture coordinate (v = 0); a
// vertex and a normal need three numbers. A number that does not parse (nan, 1e39) is refused:
// skipping the line would make every later reference name another element.
std::array<float, 3> readObjNumbers(const ObjLine& line, const std::vector<std::string>& w, int kind) {
  const std::size_t needed = kind == 1 ? 1 : 3, used = kind == 1 ? 2 : 3;
  std::array<float, 3> x = {0.0f, 0.0f, 0.0f};
  for (std::size_t k = 1; k <= used; ++k) {
    const std::string value = k < w.size() ? w[k] : std::string();
    if (k > needed && value.empty()) break;
    const std::optional<float> number = finiteFloat(value);
    if (!number)
      line.fail(std::string(kObjKinds[kind]) + " '" + line.text.substr(0, 60) + "' needs " + std::to_string(needed) +
                " finite numbers" + (value.empty() ? "" : "; '" + value.substr(0, 20) + "' is not one"));
    x[k - 1] = *number;
  }
  return x;
}

// A face corner "v", "v/vt", "v//vn" or "v/vt/vn" (1-based; negative: from the end of what is
// defined so far, `counts` per kind), resolved to 0-based indices.
ObjCorner resolveObjCorner(const ObjLine& line, const std::string& word, const std::int64_t (&counts)[3]) {
  std::int64_t resolved[3] = {-1, -1, -1};
  std::size_t start = 0;
  for (int part = 0; part < 3 && start <= word.size(); ++part) {
    const std::size_t slash = std::min(word.find('/', start), word.size());
    const std::string number = word.substr(start, slash - start);
    start = slash + 1;
    if (number.empty()) {
      if (part == 0) line.fail("face corner '" + word.substr(0, 40) + "' has no vertex index");
      continue;
    }
    const bool negative = number[0] == '-';
    const std::string digits = negative || number[0] == '+' ? number.substr(1) : number;
    if (!isCount(digits)) line.fail("face corner '" + word.substr(0, 40) + "' is not an index");
    const std::int64_t index = std::stoll(digits);
    const std::int64_t oneBased = negative ? counts[part] - index + 1 : index;
    if (index == 0 || oneBased < 1 || oneBased > counts[part])
      line.fail("face corner '" + word.substr(0, 40) + "' refers to " + kObjKinds[part] + " " + number + ", but " +
                std::to_string(counts[part]) + " are defined before this line");
    resolved[part] = oneBased - 1;
    if (slash == word.size()) break;
  }
  return {resolved[0], resolved[1], resolved[2]};
}

}  // namespace

void readObj(const std::string& text, CheckedImporter& importer, const std::string& label) {
  std::vector<Vec2f> texcoords;
  std::vector<Vec3f> normals;
  std::size_t lineNumber = 0;
  std::vector<ObjCorner> corners;
  Polygon vertices;
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t end = std::min(text.find('\n', at), text.size());
    const std::string line = text.substr(at, end - at);
    at = end + 1;
    ++lineNumber;
    const std::vector<std::string> w = words(line);
    if (w.empty()) continue;
    const ObjLine here{label, lineNumber, line};
    const int kind = w[0] == "v" ? 0 : w[0] == "vt" ? 1 : w[0] == "vn" ? 2 : -1;
    if (kind >= 0) {
      const std::array<float, 3> x = readObjNumbers(here, w, kind);
      if (kind == 0) importer.addVertex({x[0], x[1], x[2]});
      if (kind == 1) texcoords.push_back({x[0], x[1]});
      if (kind == 2) normals.push_back({x[0], x[1], x[2]});
      continue;
    }
    if (w[0] != "f") continue;
    if (w.size() < 4) here.fail("a face needs at least three vertices");
    const std::int64_t counts[3] = {static_cast<std::int64_t>(importer.vertexCount()), static_cast<std::int64_t>(texcoords.size()),
                                    static_cast<std::int64_t>(normals.size())};
    corners.clear();
    vertices.clear();
    for (std::size_t k = 1; k < w.size(); ++k) {
      corners.push_back(resolveObjCorner(here, w[k], counts));
      vertices.push_back(static_cast<VertexIndex>(corners.back().vertex));
    }
    // The vertices' own UV and normal, for corners that give none: the last given, in file order.
    for (const ObjCorner& c : corners) {
      const auto v = static_cast<VertexIndex>(c.vertex);
      if (c.uv >= 0) importer.setUv(v, texcoords[static_cast<std::size_t>(c.uv)]);
      if (c.normal >= 0) importer.setNormal(v, normals[static_cast<std::size_t>(c.normal)]);
    }
    addSimplePolygons(importer, vertices, [&](std::size_t face, std::size_t n, const auto& position) {
      for (std::size_t j = 0; j < n; ++j) {
        const ObjCorner& c = corners[position(j)];
        if (c.uv >= 0) importer.setCornerUv(face, j, texcoords[static_cast<std::size_t>(c.uv)]);
        if (c.normal >= 0) importer.setCornerNormal(face, j, normals[static_cast<std::size_t>(c.normal)]);
      }
    });
  }
}

}  // namespace tangent::gltf::detail
