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

namespace {

// The text read line by line: the next line with something on it, comments removed, into
// `w`; messages name the line.
struct OffLines {
  const std::string& text;
  const std::string& label;
  std::size_t at = 0, lineNumber = 0;
  std::string line;
  std::vector<std::string> w;  // the words of the current line

  bool next() {
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
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(label + ": OFF line " + std::to_string(lineNumber) + ": " + what);
  }
};

// What the keyword line says: [ST][C][N]OFF (4OFF and nOFF refused).
struct OffKeyword {
  std::string keyword;
  bool texcoords = false, colours = false, hasNormals = false;
  std::size_t perVertex = 3;  // coordinates and normals
};

OffKeyword readOffKeyword(OffLines& lines) {
  std::vector<std::string>& w = lines.w;
  if (!lines.next()) throw InputError(lines.label + ": has no OFF keyword line (the file is empty or only comments)");
  // The keyword is optional (Geomview): a first line of counts is plain OFF. ModelNet's files
  // glue the vertex count to it ("OFF490 518 0"): the digits after "OFF" are the first count.
  if (isCount(w[0])) {
    w.insert(w.begin(), "OFF");
  } else if (const std::size_t off = w[0].find("OFF"); off != std::string::npos && off + 3 < w[0].size() && isCount(w[0].substr(off + 3))) {
    w.insert(w.begin() + 1, w[0].substr(off + 3));
    w[0].erase(off + 3);
  }
  OffKeyword out;
  out.keyword = w[0];
  const std::string& keyword = out.keyword;
  // [ST][C][N][4][n]OFF
  std::size_t k = 0;
  auto prefix = [&](const char* p) {
    const bool has = keyword.compare(k, std::strlen(p), p) == 0;
    if (has) k += std::strlen(p);
    return has;
  };
  out.texcoords = prefix("ST"), out.colours = prefix("C"), out.hasNormals = prefix("N");
  const bool homogeneous = prefix("4"), dimension = prefix("n");
  if (keyword.substr(k) != "OFF") lines.fail("expected an OFF keyword ([ST][C][N][4][n]OFF), found '" + keyword.substr(0, 40) + "'");
  if (homogeneous) lines.fail("4OFF (homogeneous coordinates) is not read");
  if (dimension) lines.fail("nOFF (a dimension other than 3) is not read");
  out.perVertex = out.hasNormals ? 6 : 3;
  return out;
}

// Refuses counts a file of its size cannot hold, before anything is allocated for them.
void boundOffCounts(const std::string& label, std::uintmax_t fileBytes, std::uint64_t vertices, std::uint64_t faces,
                    std::uint64_t vertexBytes, std::uint64_t faceBytes) {
  if (vertices * vertexBytes + faces * faceBytes > fileBytes + 8)
    throw InputError(label + ": OFF header declares " + std::to_string(vertices) + " vertices and " + std::to_string(faces) +
                     " faces, more than a file of " + std::to_string(fileBytes) + " bytes can hold");
}

// Binary OFF: after the keyword line, little-endian 32-bit counts, vertices and faces.
void readBinaryOff(OffLines& lines, const OffKeyword& kw, CheckedImporter& importer) {
  const std::string& text = lines.text;
  const std::string& label = lines.label;
  std::size_t& at = lines.at;
  if (kw.colours) lines.fail("binary OFF with colours (" + kw.keyword.substr(0, 40) + ") is not read");
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
  const std::size_t perVertex = kw.perVertex;
  boundOffCounts(label, text.size(), vertices, faces, 4 * (perVertex + (kw.texcoords ? 2 : 0)), 16);
  for (std::uint32_t v = 0; v < vertices; ++v) {
    float x[8];
    for (std::size_t c = 0; c < perVertex + (kw.texcoords ? 2 : 0); ++c) x[c] = f32("a vertex");
    const VertexIndex vertex = importer.addVertex({x[0], x[1], x[2]});
    if (kw.hasNormals) importer.setNormal(vertex, {x[3], x[4], x[5]});
    if (kw.texcoords) importer.setUv(vertex, {x[perVertex], x[perVertex + 1]});
  }
  Polygon corners;
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
}

// One ASCII vertex line: x y z [nx ny nz] [colour] [s t]. The texture coordinates follow the
// coordinates, or with colours (of 1 to 4 values) are the line's last two; without colours
// nothing may follow.
void readAsciiOffVertex(OffLines& lines, const OffKeyword& kw, std::uint64_t v, CheckedImporter& importer) {
  const std::vector<std::string>& w = lines.w;
  auto number = [&](const std::string& word, const std::string& what) {
    const std::optional<float> x = finiteFloat(word);
    if (!x) lines.fail(what + " '" + word.substr(0, 20) + "' is not a finite number");
    return *x;
  };
  const std::size_t perVertex = kw.perVertex;
  const std::size_t needed = perVertex + (kw.texcoords ? 2 : 0);
  if (w.size() < needed)
    lines.fail("vertex " + std::to_string(v + 1) + " lists " + std::to_string(w.size()) + " value(s); " + kw.keyword.substr(0, 40) +
               " needs " + std::to_string(needed) + " (x y z" + (kw.hasNormals ? " nx ny nz" : "") + (kw.texcoords ? " s t" : "") + ")");
  float x[8];
  for (std::size_t c = 0; c < perVertex; ++c) x[c] = number(w[c], "vertex " + std::to_string(v + 1) + " value");
  const VertexIndex vertex = importer.addVertex({x[0], x[1], x[2]});
  if (kw.hasNormals) importer.setNormal(vertex, {x[3], x[4], x[5]});
  if (kw.texcoords) {
    if (!kw.colours && w.size() != needed)
      lines.fail("vertex " + std::to_string(v + 1) + " lists " + std::to_string(w.size()) + " values; " + kw.keyword.substr(0, 40) +
                 " has no colours, so exactly " + std::to_string(needed) + " (x y z" + (kw.hasNormals ? " nx ny nz" : "") + " s t)");
    const std::string what = "vertex " + std::to_string(v + 1) + " texture coordinate";
    const std::size_t s = kw.colours ? w.size() - 2 : perVertex;
    importer.setUv(vertex, {number(w[s], what), number(w[s + 1], what)});
  }
}

// ASCII OFF: the counts (on the keyword line or the next), one vertex per line, then one face
// per line (n i1 .. in [colour]).
void readAsciiOff(OffLines& lines, const OffKeyword& kw, CheckedImporter& importer) {
  std::vector<std::string>& w = lines.w;
  // The counts: on the keyword line after the keyword, or on the next line.
  w.erase(w.begin());
  if (w.empty()) {
    if (!lines.next()) lines.fail("missing the vertex, face and edge counts");
  }
  if (w.size() < 2 || !isCount(w[0]) || !isCount(w[1]) || (w.size() > 2 && !isCount(w[2])))
    lines.fail("expected 'VERTICES FACES [EDGES]' as non-negative integers");
  const std::uint64_t vertices = std::stoull(w[0]), faces = std::stoull(w[1]);
  // An ASCII vertex takes at least 6 bytes ("0 0 0\n"), a face at least 8 ("3 0 1 2\n").
  boundOffCounts(lines.label, lines.text.size(), vertices, faces, 6, 8);
  for (std::uint64_t v = 0; v < vertices; ++v) {
    if (!lines.next()) lines.fail("the file ends after " + std::to_string(v) + " of " + std::to_string(vertices) + " vertices");
    readAsciiOffVertex(lines, kw, v, importer);
  }
  Polygon corners;
  for (std::uint64_t f = 0; f < faces; ++f) {
    if (!lines.next()) lines.fail("the file ends after " + std::to_string(f) + " of " + std::to_string(faces) + " faces");
    // n i1 .. in [colour]
    if (!isCount(w[0]) || std::stoull(w[0]) < 3 || std::stoull(w[0]) > w.size() - 1)
      lines.fail("face " + std::to_string(f + 1) + " declares '" + w[0].substr(0, 20) + "' corners but lists " +
                 std::to_string(w.size() - 1) + " numbers");
    const std::size_t n = std::stoull(w[0]);
    corners.clear();
    for (std::size_t c = 1; c <= n; ++c) {
      if (!isCount(w[c]) || std::stoull(w[c]) >= vertices)
        lines.fail("face " + std::to_string(f + 1) + " corner " + std::to_string(c) + " '" + w[c].substr(0, 20) +
                   "' is not a vertex index below " + std::to_string(vertices));
      corners.push_back(static_cast<VertexIndex>(std::stoull(w[c])));
    }
    addSimplePolygons(importer, corners);
  }
}

}  // namespace

void readOff(const std::string& text, CheckedImporter& importer, const std::string& label) {
  OffLines lines{text, label};
  const OffKeyword keyword = readOffKeyword(lines);
  if (lines.w.size() > 1 && lines.w[1] == "BINARY") readBinaryOff(lines, keyword, importer);
  else readAsciiOff(lines, keyword, importer);
}

}  // namespace tangent::gltf::detail
