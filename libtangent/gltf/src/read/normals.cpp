// SPDX-License-Identifier: MIT
// NORMAL as glTF readers treat it (normals.hpp).
#include "read/normals.hpp"

#include "read/primitive.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <numbers>
#include <unordered_map>

namespace tangent::gltf::detail {

bool normalNeedsNormalizing(double length) { return std::abs(length - 1.0) > kNormalLengthKept; }

double NormalLengths::worstDeviation() const { return std::abs(worstLength - 1.0); }

NormalLengths unitNormals(std::span<float> normals) {
  NormalLengths found;
  for (std::size_t i = 0; i + 2 < normals.size(); i += 3) {
    float* n = &normals[i];
    const double length = std::sqrt(double(n[0]) * n[0] + double(n[1]) * n[1] + double(n[2]) * n[2]);
    if (!(length > 0) || !std::isfinite(length)) {
      ++found.zero;
      continue;
    }
    if (std::abs(length - 1.0) > found.worstDeviation()) found.worstLength = length;
    if (!normalNeedsNormalizing(length)) continue;
    ++found.normalized;
    for (int k = 0; k < 3; ++k) n[k] = static_cast<float>(n[k] / length);
  }
  return found;
}

namespace {

using Vec3 = std::array<double, 3>;

Vec3 at(std::span<const float> positions, std::uint32_t v) { return {positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]}; }
Vec3 minus(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec3 cross(const Vec3& a, const Vec3& b) { return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}; }
double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec3 unit(const Vec3& v) {
  const double length = std::sqrt(dot(v, v));
  if (!(length > 0) || !std::isfinite(length)) return {0, 0, 0};
  return {v[0] / length, v[1] / length, v[2] / length};
}

// The unit normal of each triangle (zero without area).
std::vector<Vec3> faceNormals(std::span<const float> positions, std::span<const std::uint32_t> corners) {
  std::vector<Vec3> normals(corners.size() / 3);
  for (std::size_t t = 0; t < normals.size(); ++t) {
    const Vec3 p0 = at(positions, corners[3 * t]);
    normals[t] = unit(cross(minus(at(positions, corners[3 * t + 1]), p0), minus(at(positions, corners[3 * t + 2]), p0)));
  }
  return normals;
}

// The angle of triangle t at its corner k.
double cornerAngle(std::span<const float> positions, std::span<const std::uint32_t> corners, std::size_t t, int k) {
  const Vec3 here = at(positions, corners[3 * t + k]);
  const Vec3 a = minus(at(positions, corners[3 * t + (k + 1) % 3]), here), b = minus(at(positions, corners[3 * t + (k + 2) % 3]), here);
  const Vec3 c = cross(a, b);
  return std::atan2(std::sqrt(dot(c, c)), dot(a, b));
}

// Per corner, the smooth normal (see the header).
std::vector<Vec3> smoothCornerNormals(std::span<const float> positions, std::span<const std::uint32_t> corners,
                                      const std::vector<Vec3>& faces, double creaseAngleDegrees) {
  // Corners grouped by position (welding): vertices within kWeldTolerance of the bounding box's
  // diagonal are one position (a UV seam's two copies of a vertex differ in the last bits where
  // sin(2 pi) is not 0), found through a grid of cells that size; then the corners of each
  // group (counting sort).
  const std::size_t vertexCount = positions.size() / 3;
  Vec3 low{0, 0, 0}, high{0, 0, 0};
  for (std::size_t v = 0; v < vertexCount; ++v) {
    for (int k = 0; k < 3; ++k) {
      const double x = positions[3 * v + k];
      if (!std::isfinite(x)) continue;
      low[k] = v == 0 ? x : std::min(low[k], x);
      high[k] = v == 0 ? x : std::max(high[k], x);
    }
  }
  constexpr double kWeldTolerance = 1e-6;
  const double diagonal = std::sqrt(dot(minus(high, low), minus(high, low)));
  const double cell = diagonal > 0 ? kWeldTolerance * diagonal : 1.0;
  std::map<std::array<std::int64_t, 3>, std::vector<std::uint32_t>> verticesInCell;  // representative vertices
  std::vector<std::uint32_t> groupOf(vertexCount);
  std::vector<std::uint32_t> groupOfRepresentative(vertexCount, 0);
  std::size_t groupCount = 0;
  for (std::size_t v = 0; v < vertexCount; ++v) {
    const Vec3 p = at(positions, static_cast<std::uint32_t>(v));
    std::array<std::int64_t, 3> key;
    for (int k = 0; k < 3; ++k) key[k] = std::isfinite(p[k]) ? static_cast<std::int64_t>(std::floor((p[k] - low[k]) / cell)) : 0;
    std::int64_t found = -1;
    for (int dx = -1; dx <= 1 && found < 0; ++dx)
      for (int dy = -1; dy <= 1 && found < 0; ++dy)
        for (int dz = -1; dz <= 1 && found < 0; ++dz) {
          const auto near = verticesInCell.find({key[0] + dx, key[1] + dy, key[2] + dz});
          if (near == verticesInCell.end()) continue;
          for (const std::uint32_t r : near->second) {
            const Vec3 d = minus(at(positions, r), p);
            if (dot(d, d) <= cell * cell) {
              found = r;
              break;
            }
          }
        }
    if (found < 0) {
      verticesInCell[key].push_back(static_cast<std::uint32_t>(v));
      groupOfRepresentative[v] = static_cast<std::uint32_t>(groupCount++);
      groupOf[v] = groupOfRepresentative[v];
    } else {
      groupOf[v] = groupOfRepresentative[static_cast<std::size_t>(found)];
    }
  }
  std::vector<std::uint32_t> start(groupCount + 1, 0);
  for (const std::uint32_t v : corners) ++start[groupOf[v] + 1];
  for (std::size_t g = 0; g + 1 < start.size(); ++g) start[g + 1] += start[g];
  std::vector<std::uint32_t> members(corners.size()), fill(start.begin(), start.end() - 1);
  for (std::size_t c = 0; c < corners.size(); ++c) members[fill[groupOf[corners[c]]]++] = static_cast<std::uint32_t>(c);

  const double cosCrease = std::cos(creaseAngleDegrees * std::numbers::pi / 180);
  std::vector<Vec3> normals(corners.size());
  for (std::size_t c = 0; c < corners.size(); ++c) {
    const Vec3& own = faces[c / 3];
    const std::uint32_t g = groupOf[corners[c]];
    Vec3 sum{0, 0, 0};
    for (std::uint32_t i = start[g]; i < start[g + 1]; ++i) {
      const std::uint32_t other = members[i];
      const Vec3& face = faces[other / 3];
      // A triangle without area has no direction of its own: its corners take every face there.
      if (other / 3 != c / 3 && own != Vec3{0, 0, 0} && dot(face, own) < cosCrease) continue;
      const double weight = cornerAngle(positions, corners, other / 3, static_cast<int>(other % 3));
      for (int k = 0; k < 3; ++k) sum[k] += weight * face[k];
    }
    normals[c] = unit(sum);
    if (normals[c] == Vec3{0, 0, 0}) normals[c] = {0, 0, 1};
  }
  return normals;
}

}  // namespace

GeneratedNormals generateNormals(std::span<const float> positions, std::span<const std::uint32_t> corners, bool smooth,
                                 double creaseAngleDegrees) {
  const std::vector<Vec3> faces = faceNormals(positions, corners);
  std::vector<Vec3> cornerNormals;
  if (smooth) {
    cornerNormals = smoothCornerNormals(positions, corners, faces, creaseAngleDegrees);
  } else {
    cornerNormals.resize(corners.size());
    for (std::size_t c = 0; c < corners.size(); ++c) cornerNormals[c] = faces[c / 3] == Vec3{0, 0, 0} ? Vec3{0, 0, 1} : faces[c / 3];
  }
  // A new vertex per (input vertex, normal bits), numbered in corner order.
  GeneratedNormals out;
  out.corners.resize(corners.size());
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> newOfVertex;  // input vertex -> its new vertices
  for (std::size_t c = 0; c < corners.size(); ++c) {
    const float n[3] = {static_cast<float>(cornerNormals[c][0]), static_cast<float>(cornerNormals[c][1]),
                        static_cast<float>(cornerNormals[c][2])};
    std::vector<std::uint32_t>& candidates = newOfVertex[corners[c]];
    std::uint32_t found = 0xffffffffu;
    for (const std::uint32_t candidate : candidates) {
      if (std::memcmp(&out.normals[3 * candidate], n, sizeof n) == 0) found = candidate;
    }
    if (found == 0xffffffffu) {
      found = static_cast<std::uint32_t>(out.source.size());
      out.source.push_back(corners[c]);
      out.normals.insert(out.normals.end(), n, n + 3);
      candidates.push_back(found);
    }
    out.corners[c] = found;
  }
  return out;
}

PrimitiveGeometry withGeneratedNormals(const PrimitiveGeometry& geometry, bool smooth, double creaseAngleDegrees,
                                       std::vector<std::uint32_t>& sourceVertex) {
  GeneratedNormals generated = generateNormals(geometry.positions, geometry.corners, smooth, creaseAngleDegrees);
  PrimitiveGeometry expanded;
  expanded.vertexCount = generated.source.size();
  expanded.mode = 4;
  expanded.indexComponentType = geometry.indexComponentType;
  expanded.positions.resize(3 * expanded.vertexCount);
  expanded.uvs.resize(2 * expanded.vertexCount);
  for (std::size_t v = 0; v < expanded.vertexCount; ++v) {
    std::copy_n(&geometry.positions[3 * generated.source[v]], 3, &expanded.positions[3 * v]);
    if (!geometry.uvs.empty()) std::copy_n(&geometry.uvs[2 * generated.source[v]], 2, &expanded.uvs[2 * v]);
  }
  expanded.normals = std::move(generated.normals);
  expanded.corners = std::move(generated.corners);
  sourceVertex = std::move(generated.source);
  return expanded;
}

}  // namespace tangent::gltf::detail
