// SPDX-License-Identifier: MIT
// OFF is read here, not by OpenMesh: its reader takes the counts after the keyword line
// whatever that line holds, reads numbers as one token stream across lines (a bad number
// leaves the stream failed and every later count at its maximum: a face of 4 billion corners,
// found by fuzz_mesh_file), and does not skip comments. Here the file is read one vertex or face per
// line, every number is checked, and the mesh reaches the same checked importer. ASCII and
// binary (OpenMesh's layout: little-endian 32-bit counts, indices and floats); colours, which
// no glTF attribute here takes, are skipped in ASCII and refused in binary.
// Format: Geomview's OFF (geomview.org/docs/html/OFF.html), with OpenMesh's binary layout; the
// keyword may be left out, or (as in ModelNet) have the vertex count glued to it.
#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "mesh_files/mesh_import.hpp"
#include "tangent/gltf.hpp"

namespace tangent::gltf::detail {

void readOff(const std::string& text, CheckedImporter& importer, const std::string& label) {
  std::size_t at = 0, lineNumber = 0;
  std::string line;
  std::vector<std::string> w;  // the words of the current line
  auto next = [&]() -> bool {  // the next line with something on it, comments removed, into w
    while (at < text.size()) {
      const std::size_t end = std::min(text.find('\n', at), text.size());
      line.assign(text, at, end - at);
      at = end + 1;
      ++lineNumber;
      const std::size_t hash = line.find('#');
      if (hash != std::string::npos) line.erase(hash);
      w = words(line);
      if (!w.empty()) return true;
    }
    return false;
  };
  auto fail = [&](const std::string& what) -> void {
    throw InputError(label + ": OFF line " + std::to_string(lineNumber) + ": " + what);
  };
  if (!next()) throw InputError(label + ": has no OFF keyword line (the file is empty or only comments)");
  // The keyword is optional (Geomview): a first line of counts is plain OFF. ModelNet's files
  // glue the vertex count to it ("OFF490 518 0"): the digits after "OFF" are the first count.
  if (isCount(w[0])) {
    w.insert(w.begin(), "OFF");
  } else if (const std::size_t off = w[0].find("OFF"); off != std::string::npos && off + 3 < w[0].size() && isCount(w[0].substr(off + 3))) {
    w.insert(w.begin() + 1, w[0].substr(off + 3));
    w[0].erase(off + 3);
  }
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
  Polygon corners;

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
      const VertexIndex vertex = importer.addVertex({x[0], x[1], x[2]});
      if (hasNormals) importer.setNormal(vertex, {x[3], x[4], x[5]});
      if (texcoords) importer.setUv(vertex, {x[perVertex], x[perVertex + 1]});
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
        corners.push_back(index);
      }
      addSimplePolygons(importer, corners);
    }
  } else {
    // The counts: on the keyword line after the keyword, or on the next line.
    w.erase(w.begin());
    if (w.empty()) {
      if (!next()) fail("missing the vertex, face and edge counts");
    }
    if (w.size() < 2 || !isCount(w[0]) || !isCount(w[1]) || (w.size() > 2 && !isCount(w[2])))
      fail("expected 'VERTICES FACES [EDGES]' as non-negative integers");
    const std::uint64_t vertices = std::stoull(w[0]), faces = std::stoull(w[1]);
    // An ASCII vertex takes at least 6 bytes ("0 0 0\n"), a face at least 8 ("3 0 1 2\n").
    bound(vertices, faces, 6, 8);
    auto number = [&](const std::string& word, const std::string& what) {
      const std::optional<float> x = finiteFloat(word);
      if (!x) fail(what + " '" + word.substr(0, 20) + "' is not a finite number");
      return *x;
    };
    for (std::uint64_t v = 0; v < vertices; ++v) {
      if (!next()) fail("the file ends after " + std::to_string(v) + " of " + std::to_string(vertices) + " vertices");
      // x y z [nx ny nz] [colour] [s t]: the texture coordinates follow the coordinates, or with
      // colours (of 1 to 4 values) are the line's last two; without colours nothing may follow.
      const std::size_t needed = perVertex + (texcoords ? 2 : 0);
      if (w.size() < needed)
        fail("vertex " + std::to_string(v + 1) + " lists " + std::to_string(w.size()) + " value(s); " + keyword.substr(0, 40) +
             " needs " + std::to_string(needed) + " (x y z" + (hasNormals ? " nx ny nz" : "") + (texcoords ? " s t" : "") + ")");
      float x[8];
      for (std::size_t c = 0; c < perVertex; ++c) x[c] = number(w[c], "vertex " + std::to_string(v + 1) + " value");
      const VertexIndex vertex = importer.addVertex({x[0], x[1], x[2]});
      if (hasNormals) importer.setNormal(vertex, {x[3], x[4], x[5]});
      if (texcoords) {
        if (!colours && w.size() != needed)
          fail("vertex " + std::to_string(v + 1) + " lists " + std::to_string(w.size()) + " values; " + keyword.substr(0, 40) +
               " has no colours, so exactly " + std::to_string(needed) + " (x y z" + (hasNormals ? " nx ny nz" : "") + " s t)");
        const std::string what = "vertex " + std::to_string(v + 1) + " texture coordinate";
        const std::size_t s = colours ? w.size() - 2 : perVertex;
        importer.setUv(vertex, {number(w[s], what), number(w[s + 1], what)});
      }

    }
    for (std::uint64_t f = 0; f < faces; ++f) {
      if (!next()) fail("the file ends after " + std::to_string(f) + " of " + std::to_string(faces) + " faces");
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
        corners.push_back(static_cast<VertexIndex>(std::stoull(w[c])));
      }
      addSimplePolygons(importer, corners);
    }
  }
}

}  // namespace tangent::gltf::detail
