// SPDX-License-Identifier: MIT
// OBJ, PLY and OFF through our readers (obj_reader.cpp, ply_reader.cpp, off_reader.cpp), into
// plain arrays (ImportedPolygons), converted to an in-memory GLB so that the rest of bake treats them
// like any glTF input. These formats carry no materials: every mesh
// gets tangents. Their UV origin is bottom-left, so v becomes 1 - v for glTF. A file without
// normals gives a primitive without NORMAL, which bake then generates (--normals).

#include <algorithm>
#include <array>
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
#include <optional>
#include <map>
#include <tuple>
#include <unordered_map>

#include "read/asset.hpp"
#include "mesh_files/mesh_import.hpp"
#include "tangent/gltf.hpp"
#include "tangent/text.hpp"

namespace tangent::gltf::detail {
namespace {

void appendFloats(std::vector<std::uint8_t>& bin, const std::vector<float>& values) {
  if (values.empty()) return;  // a file without normals: no bytes, and memcpy wants real pointers
  const std::size_t at = bin.size();
  bin.resize(at + values.size() * 4);
  std::memcpy(bin.data() + at, values.data(), values.size() * 4);
}

// Polygons to triangles, appended to `indices` in the polygon's winding. A convex polygon
// (every quad a file is likely to hold) is fanned from its first corner, as before; a concave
// one is cut into ears (Meisters, "Polygons have ears", 1975) in the plane of its Newell
// normal, so that no triangle covers ground outside it (a fan there folds triangles over,
// with flipped normals and tangents). Polygons of more than kMaxEarClippedCorners corners, and
// those it cannot finish (self-intersecting), are fanned.
constexpr std::size_t kMaxEarClippedCorners = 256;

// `ring`'s triangles fanned from its first corner.
void fanTriangles(const std::vector<std::uint32_t>& ring, std::vector<std::uint32_t>& indices) {
  for (std::size_t i = 1; i + 1 < ring.size(); ++i) indices.insert(indices.end(), {ring[0], ring[i], ring[i + 1]});
}

// A polygon in the plane of its Newell normal, which drops its largest axis and keeps the
// other two (ua, va) in cyclic order, so that the polygon's signed area there has the sign of
// that component; `orientation` makes turns that follow the polygon positive.
struct PolygonPlane {
  const std::vector<float>& positions;
  const std::vector<std::uint32_t>& polygon;
  int ua = 0, va = 0;
  double orientation = 1;

  double at(std::size_t corner, int axis) const { return static_cast<double>(positions[3 * polygon[corner] + axis]); }
  // Twice the signed area of (p, q, r) in the plane, positive where the turn follows the polygon.
  double turn(std::size_t p, std::size_t q, std::size_t r) const {
    return orientation * ((at(q, ua) - at(p, ua)) * (at(r, va) - at(p, va)) - (at(q, va) - at(p, va)) * (at(r, ua) - at(p, ua)));
  }
  // Whether q turns back on the edge p-q (a zero-width spike turns by zero too).
  bool reverses(std::size_t p, std::size_t q, std::size_t r) const {
    return (at(q, ua) - at(p, ua)) * (at(r, ua) - at(q, ua)) + (at(q, va) - at(p, va)) * (at(r, va) - at(q, va)) < 0;
  }
};

// The polygon's plane; none where its Newell normal is zero or not finite.
std::optional<PolygonPlane> planeOf(const std::vector<float>& positions, const std::vector<std::uint32_t>& polygon) {
  const std::size_t n = polygon.size();
  auto at = [&](std::size_t corner, int axis) { return static_cast<double>(positions[3 * polygon[corner] + axis]); };
  double normal[3] = {0, 0, 0};
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = (i + 1) % n;
    for (int a = 0; a < 3; ++a) {
      const int b = (a + 1) % 3, c = (a + 2) % 3;
      normal[a] += (at(i, b) - at(j, b)) * (at(i, c) + at(j, c));
    }
  }
  int drop = 0;
  for (int a = 1; a < 3; ++a) {
    if (std::fabs(normal[a]) > std::fabs(normal[drop])) drop = a;
  }
  if (normal[drop] == 0.0 || !std::isfinite(normal[drop])) return std::nullopt;
  return PolygonPlane{positions, polygon, (drop + 1) % 3, (drop + 2) % 3, normal[drop] > 0 ? 1.0 : -1.0};
}

// Convex: no corner turns the other way, and none turns back on its edge.
bool isConvex(const PolygonPlane& plane) {
  const std::size_t n = plane.polygon.size();
  bool convex = true;
  for (std::size_t i = 0; i < n && convex; ++i) {
    const std::size_t p = (i + n - 1) % n, q = (i + 1) % n;
    const double t = plane.turn(p, i, q);
    convex = t > 0 || (t == 0 && !plane.reverses(p, i, q));
  }
  return convex;
}

// Ear clipping of a concave polygon; what it cannot finish (self-intersecting) is fanned.
void clipEars(const PolygonPlane& plane, std::vector<std::uint32_t>& indices) {
  const std::vector<std::uint32_t>& polygon = plane.polygon;
  const std::size_t n = polygon.size();
  std::vector<std::size_t> previous(n), next(n);
  for (std::size_t i = 0; i < n; ++i) previous[i] = (i + n - 1) % n, next[i] = (i + 1) % n;
  auto isEar = [&](std::size_t i) {
    const std::size_t p = previous[i], q = next[i];
    if (plane.turn(p, i, q) <= 0) return false;
    for (std::size_t r = next[q]; r != p; r = next[r]) {
      // A corner on or inside the triangle (other than a copy of one of its corners) blocks it.
      const auto same = [&](std::size_t a) { return plane.at(r, plane.ua) == plane.at(a, plane.ua) && plane.at(r, plane.va) == plane.at(a, plane.va); };
      if (same(p) || same(i) || same(q)) continue;
      if (plane.turn(p, i, r) >= 0 && plane.turn(i, q, r) >= 0 && plane.turn(q, p, r) >= 0) return false;
    }
    return true;
  };
  // Each corner's ear status is kept and recomputed only for the two neighbours of a clipped
  // ear (quadratic in all); a corner that only the clipped one blocked is found when a search
  // comes up empty and every status is recomputed once.
  std::vector<char> ear(n);
  for (std::size_t k = 0; k < n; ++k) ear[k] = isEar(k);
  std::size_t remaining = n, i = 0;
  bool fresh = true;
  while (remaining > 3) {
    std::size_t searched = 0;
    while (!ear[i] && searched < remaining) i = next[i], ++searched;
    if (!ear[i]) {
      if (!fresh) {
        for (std::size_t k = 0, r = i; k < remaining; ++k, r = next[r]) ear[r] = isEar(r);
        fresh = true;
        continue;
      }
      std::vector<std::uint32_t> ring;
      for (std::size_t k = 0, r = i; k < remaining; ++k, r = next[r]) ring.push_back(polygon[r]);
      return fanTriangles(ring, indices);
    }
    const std::size_t p = previous[i], q = next[i];
    indices.insert(indices.end(), {polygon[p], polygon[i], polygon[q]});
    next[p] = q;
    previous[q] = p;
    --remaining;
    ear[p] = isEar(p);
    ear[q] = isEar(q);
    fresh = false;
    i = q;
  }
  indices.insert(indices.end(), {polygon[previous[i]], polygon[i], polygon[next[i]]});
}

void triangulatePolygon(const std::vector<float>& positions, const std::vector<std::uint32_t>& polygon,
                        std::vector<std::uint32_t>& indices) {
  if (polygon.size() <= 3 || polygon.size() > kMaxEarClippedCorners) return fanTriangles(polygon, indices);
  const std::optional<PolygonPlane> plane = planeOf(positions, polygon);
  if (!plane || isConvex(*plane)) return fanTriangles(polygon, indices);
  clipEars(*plane, indices);
}

}  // namespace

namespace {

// The file read once into memory and parsed by the reader its extension names.
ImportedPolygons readPolygons(const std::filesystem::path& path) {
  ImportedPolygons mesh;
  std::error_code ec;
  const std::uintmax_t fileBytes = std::filesystem::file_size(path, ec);
  if (ec) throw InputError(path.string() + ": cannot be read: " + ec.message());
  const std::string extension = lowerExtension(path);
  // An OBJ, PLY or OFF is read once, into memory, and parsed from there by our readers.
  std::string text;
  {
    // In one read of the size the file has (a character at a time through istreambuf_iterator
    // took 5% of a 56 MB OBJ's bake); a file that shrank since is taken as it now is.
    std::ifstream file(path, std::ios::binary);
    if (!file) throw InputError(path.string() + ": cannot be opened");
    text.resize(static_cast<std::size_t>(fileBytes));
    file.read(text.data(), static_cast<std::streamsize>(text.size()));
    text.resize(static_cast<std::size_t>(file.gcount()));
  }
  {
    CheckedImporter importer(mesh, path.string(), fileBytes);
    try {
      if (extension == ".obj")
        readObj(text, importer, path.string());
      else if (extension == ".off")
        readOff(text, importer, path.string());
      else if (extension == ".ply")
        readPly(text, importer, path.string());
      else
        throw InputError(path.string() + ": not an OBJ, PLY or OFF file");
    } catch (const std::bad_alloc&) {
      throw InputError(path.string() + ": a count in the file is larger than memory allows; the file is malformed");
    } catch (const std::length_error&) {
      throw InputError(path.string() + ": a count in the file is out of range; the file is malformed");
    }
  }
  return mesh;  // `text` freed on return: its memory is not held while the GLB is built
}

// The arrays of the GLB's one primitive: one glTF vertex per distinct (vertex, UV, normal),
// UVs in glTF's top-left origin, polygons triangulated.
struct MeshFileArrays {
  std::vector<float> positions, normals, uvs;  // normals empty: the file gave not every corner one
  std::vector<std::uint32_t> indices;
};

MeshFileArrays gltfVertices(const ImportedPolygons& mesh, const std::filesystem::path& path) {
  // NORMAL where the file gave every corner one (its own, or its vertex's); else none (bake
  // generates them as for a glTF without NORMAL), never the values left unset.
  auto hasNormal = [&](std::size_t corner) { return mesh.hasCornerNormal(corner) || mesh.normalSet[mesh.corners[corner]]; };
  bool haveNormals = true;
  for (std::size_t corner = 0; haveNormals && corner < mesh.corners.size(); ++corner) haveNormals = hasNormal(corner);
  const bool cornerUvs = mesh.anyCornerUv(), vertexUvs = mesh.anyUv;
  if (!cornerUvs && !vertexUvs) throw InputError(path.string() + ": has no texture coordinates; tangents need UVs");

  // One glTF vertex per distinct (vertex, UV, normal).
  std::map<std::array<std::uint32_t, 6>, std::uint32_t> vertexOf;
  MeshFileArrays out;
  std::vector<float>& positions = out.positions;
  std::vector<float>& normals = out.normals;
  std::vector<float>& uvs = out.uvs;
  std::vector<std::uint32_t>& indices = out.indices;
  std::vector<std::uint32_t> polygon;
  for (std::size_t face = 0; face < mesh.faceCount(); ++face) {
    polygon.clear();
    for (std::size_t corner = mesh.faceStart[face]; corner < mesh.faceStart[face + 1]; ++corner) {
      const std::uint32_t vertex = mesh.corners[corner];
      // A corner's own UV where the file gave one, else its vertex's.
      const bool own = cornerUvs && mesh.hasCornerUv(corner);
      if (!own && !(vertexUvs && mesh.uvSet[vertex]))
        throw InputError(path.string() + ": face " + std::to_string(face + 1) + " (1-based) has no texture coordinate at its vertex " +
                         std::to_string(std::uint64_t{vertex} + 1) + "; tangents need UVs on every face");
      const Vec2f uv = own ? mesh.cornerUvs[corner] : mesh.uvs[vertex];
      const float u = uv.x, v = 1.0f - uv.y;
      const Vec3f n = !haveNormals                    ? Vec3f{0.0f, 0.0f, 1.0f}
                      : mesh.hasCornerNormal(corner) ? mesh.cornerNormals[corner]
                                                     : mesh.normals[vertex];
      const std::array<std::uint32_t, 6> key = {vertex, std::bit_cast<std::uint32_t>(u), std::bit_cast<std::uint32_t>(v),
                                                std::bit_cast<std::uint32_t>(n.x), std::bit_cast<std::uint32_t>(n.y),
                                                std::bit_cast<std::uint32_t>(n.z)};
      auto [it, inserted] = vertexOf.try_emplace(key, static_cast<std::uint32_t>(positions.size() / 3));
      if (inserted) {
        const Vec3f p = mesh.points[vertex];
        // A NaN or infinity would make the GLB invalid (its min/max null, the data refused by
        // the validator): named here instead.
        for (const float x : {p.x, p.y, p.z, n.x, n.y, n.z, u, v}) {
          if (!std::isfinite(x))
            throw InputError(path.string() + ": vertex " + std::to_string(std::uint64_t{vertex} + 1) +
                             " (1-based) has a coordinate, normal or UV that is not a finite number");
        }
        positions.insert(positions.end(), {p.x, p.y, p.z});
        if (haveNormals) normals.insert(normals.end(), {n.x, n.y, n.z});
        uvs.insert(uvs.end(), {u, v});
      }
      polygon.push_back(it->second);
    }
    triangulatePolygon(positions, polygon, indices);
  }
  return out;
}

// The GLB: POSITION, NORMAL where there are normals, TEXCOORD_0 and the indices in one buffer.
std::vector<std::uint8_t> meshGlb(const MeshFileArrays& arrays, const std::filesystem::path& path) {
  const std::vector<float>& positions = arrays.positions;
  const std::vector<std::uint32_t>& indices = arrays.indices;
  const bool haveNormals = !arrays.normals.empty();
  const std::size_t vertexCount = positions.size() / 3;
  float lo[3] = {positions[0], positions[1], positions[2]}, hi[3] = {lo[0], lo[1], lo[2]};
  for (std::size_t i = 0; i < positions.size(); ++i) {
    lo[i % 3] = std::min(lo[i % 3], positions[i]);
    hi[i % 3] = std::max(hi[i % 3], positions[i]);
  }

  std::vector<std::uint8_t> bin;
  appendFloats(bin, positions);
  appendFloats(bin, arrays.normals);
  appendFloats(bin, arrays.uvs);
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

}  // namespace

std::vector<std::uint8_t> meshFileToGlb(const std::filesystem::path& path) {
  const ImportedPolygons mesh = readPolygons(path);
  if (mesh.faceCount() == 0) throw InputError(path.string() + ": has no faces");
  return meshGlb(gltfVertices(mesh, path), path);
}

}  // namespace tangent::gltf::detail
