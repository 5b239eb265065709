// SPDX-License-Identifier: MIT
// Wavefront OBJ: `v`, `vt` and `vn` lines, and `f` lines whose corners name them as
// `v`, `v/vt`, `v//vn` or `v/vt/vn` (1-based; negative: counted back from the line). Every
// number is checked and every reference resolved against the lines before it; a malformed file
// throws InputError naming the line. Each corner keeps the UV and normal its face gives it (a
// vertex may have a hard edge: a normal per face); a corner without one takes the last its
// vertex was given on any face, as OpenMesh's reader did. Other lines (`o`, `g`, `s`, `usemtl`,
// `mtllib`, `l`, `p`, ...) are skipped: no material library is opened.
#include <algorithm>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "mesh_files/mesh_import.hpp"
#include "tangent/gltf.hpp"

namespace tangent::gltf::detail {

void readObj(const std::string& text, CheckedImporter& importer, const std::string& label) {
  std::vector<Vec2f> texcoords;
  std::vector<Vec3f> normals;
  std::size_t lineNumber = 0;
  const char* const kinds[3] = {"vertex", "texture coordinate", "normal"};
  // One corner of a face line: indices (0-based) of its vertex, UV (-1: none) and normal (-1: none).
  struct Corner {
    std::int64_t vertex, uv, normal;
  };
  std::vector<Corner> corners;
  Polygon vertices;
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t end = std::min(text.find('\n', at), text.size());
    const std::string line = text.substr(at, end - at);
    at = end + 1;
    ++lineNumber;
    const std::vector<std::string> w = words(line);
    if (w.empty()) continue;
    auto fail = [&](const std::string& what) {
      throw InputError(label + ": OBJ line " + std::to_string(lineNumber) + ": " + what);
    };
    const int kind = w[0] == "v" ? 0 : w[0] == "vt" ? 1 : w[0] == "vn" ? 2 : -1;
    if (kind >= 0) {
      // u alone is a texture coordinate (v = 0); a vertex and a normal need three numbers. A
      // number that does not parse (nan, 1e39) is refused: skipping the line would make every
      // later reference name another element.
      const std::size_t needed = kind == 1 ? 1 : 3, used = kind == 1 ? 2 : 3;
      float x[3] = {0.0f, 0.0f, 0.0f};
      for (std::size_t k = 1; k <= used; ++k) {
        const std::string value = k < w.size() ? w[k] : std::string();
        if (k > needed && value.empty()) break;
        const std::optional<float> number = finiteFloat(value);
        if (!number)
          fail(std::string(kinds[kind]) + " '" + line.substr(0, 60) + "' needs " + std::to_string(needed) +
               " finite numbers" + (value.empty() ? "" : "; '" + value.substr(0, 20) + "' is not one"));
        x[k - 1] = *number;
      }
      if (kind == 0) importer.addVertex({x[0], x[1], x[2]});
      if (kind == 1) texcoords.push_back({x[0], x[1]});
      if (kind == 2) normals.push_back({x[0], x[1], x[2]});
      continue;
    }
    if (w[0] != "f") continue;
    if (w.size() < 4) fail("a face needs at least three vertices");
    const std::int64_t counts[3] = {static_cast<std::int64_t>(importer.vertexCount()), static_cast<std::int64_t>(texcoords.size()),
                                    static_cast<std::int64_t>(normals.size())};
    corners.clear();
    vertices.clear();
    for (std::size_t k = 1; k < w.size(); ++k) {
      std::int64_t resolved[3] = {-1, -1, -1};
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
        const std::int64_t oneBased = negative ? counts[part] - index + 1 : index;
        if (index == 0 || oneBased < 1 || oneBased > counts[part])
          fail("face corner '" + w[k].substr(0, 40) + "' refers to " + kinds[part] + " " + number + ", but " +
               std::to_string(counts[part]) + " are defined before this line");
        resolved[part] = oneBased - 1;
        if (slash == w[k].size()) break;
      }
      corners.push_back({resolved[0], resolved[1], resolved[2]});
      vertices.push_back(static_cast<VertexIndex>(resolved[0]));
    }
    // The vertices' own UV and normal, for corners that give none: the last given, in file order.
    for (const Corner& c : corners) {
      const auto v = static_cast<VertexIndex>(c.vertex);
      if (c.uv >= 0) importer.setUv(v, texcoords[static_cast<std::size_t>(c.uv)]);
      if (c.normal >= 0) importer.setNormal(v, normals[static_cast<std::size_t>(c.normal)]);
    }
    addSimplePolygons(importer, vertices, [&](std::size_t face, std::size_t n, const auto& position) {
      for (std::size_t j = 0; j < n; ++j) {
        const Corner& c = corners[position(j)];
        if (c.uv >= 0) importer.setCornerUv(face, j, texcoords[static_cast<std::size_t>(c.uv)]);
        if (c.normal >= 0) importer.setCornerNormal(face, j, normals[static_cast<std::size_t>(c.normal)]);
      }
    });
  }
}

}  // namespace tangent::gltf::detail
