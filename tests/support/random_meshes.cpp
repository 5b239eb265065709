// SPDX-License-Identifier: MIT
#include "support/random_meshes.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>
#include <random>

namespace tangent::testing {

std::string_view toString(MeshFeature feature) {
  switch (feature) {
    case MeshFeature::smoothGrid:
      return "smooth-grid";
    case MeshFeature::flatGrid:
      return "flat-grid";
    case MeshFeature::jitter:
      return "jitter";
    case MeshFeature::uvSeam:
      return "uv-seam";
    case MeshFeature::normalSeam:
      return "normal-seam";
    case MeshFeature::mirroredIsland:
      return "mirrored-island";
    case MeshFeature::weldedCopies:
      return "welded-copies";
    case MeshFeature::nonManifoldEdge:
      return "non-manifold-edge";
    case MeshFeature::nonManifoldVertex:
      return "non-manifold-vertex";
    case MeshFeature::flippedWinding:
      return "flipped-winding";
    case MeshFeature::duplicatedFace:
      return "duplicated-face";
    case MeshFeature::rotatedDuplicate:
      return "rotated-duplicate";
    case MeshFeature::identicalUvs:
      return "identical-uvs";
    case MeshFeature::collinearUvs:
      return "collinear-uvs";
    case MeshFeature::degenerate:
      return "degenerate";
    case MeshFeature::sliver:
      return "sliver";
    case MeshFeature::subgroupSplit:
      return "subgroup-split";
    case MeshFeature::count:
      break;
  }
  return "?";
}

namespace {

using Vec3 = std::array<float, 3>;
using Vec2 = std::array<float, 2>;

struct Vertex {
  Vec3 position{}, normal{0, 0, 1};
  Vec2 uv{};
};

// Own draws on top of mt19937_64: the standard distributions differ between libraries.
class Random {
 public:
  explicit Random(std::uint64_t seed) : engine_(seed) {}
  int between(int lo, int hi) {  // inclusive
    return lo + static_cast<int>(engine_() % static_cast<std::uint64_t>(hi - lo + 1));
  }
  double unit() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  double real(double lo, double hi) { return lo + (hi - lo) * unit(); }
  bool chance(double p) { return unit() < p; }
  float eighths(int lo, int hi) { return static_cast<float>(between(lo, hi)) / 8.0f; }  // exact
  float sign() { return chance(0.5) ? 1.0f : -1.0f; }
  std::uint64_t bits() { return engine_(); }

 private:
  std::mt19937_64 engine_;
};

Vec3 normalized(double x, double y, double z) {
  const double length = std::sqrt(x * x + y * y + z * z);
  return {static_cast<float>(x / length), static_cast<float>(y / length), static_cast<float>(z / length)};
}

// A signed permutation of the axes and an offset of whole eighths: moves a construction
// without rounding anything.
struct ExactPlacement {
  std::array<int, 3> axis{0, 1, 2};
  Vec3 sign{1, 1, 1};
  Vec3 offset{0, 0, 0};
  float scale = 1;  // a power of two

  static ExactPlacement random(Random& random) {
    ExactPlacement placement;
    for (int i = 2; i > 0; --i) std::swap(placement.axis[i], placement.axis[random.between(0, i)]);
    for (float& s : placement.sign) s = random.sign();
    for (float& o : placement.offset) o = random.eighths(-16, 16);
    placement.scale = std::ldexp(1.0f, random.between(-2, 2));
    return placement;
  }
  Vec3 point(const Vec3& p) const {
    Vec3 out{};
    for (int i = 0; i < 3; ++i) out[axis[i]] = sign[i] * p[i] * scale + offset[axis[i]];
    return out;
  }
  Vec3 direction(const Vec3& d) const {
    Vec3 out{};
    for (int i = 0; i < 3; ++i) out[axis[i]] = sign[i] * d[i];
    return out;
  }
};

class Builder {
 public:
  explicit Builder(std::uint64_t seed) : random(seed) {}

  Random random;
  std::array<bool, kMeshFeatureCount> enabled{};  // the cases this mesh may use
  std::vector<Vertex> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::array<bool, kMeshFeatureCount> features{};

  void mark(MeshFeature feature) { features[static_cast<std::size_t>(feature)] = true; }
  bool allows(MeshFeature feature) const { return enabled[static_cast<std::size_t>(feature)]; }
  double chanceIf(MeshFeature feature, double p) const { return allows(feature) ? p : 0.0; }
  std::uint32_t add(const Vertex& vertex) {
    vertices.push_back(vertex);
    return static_cast<std::uint32_t>(vertices.size() - 1);
  }
  void triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c) { triangles.push_back({a, b, c}); }

  RandomMesh finish() const {
    RandomMesh mesh;
    for (const Vertex& v : vertices) {
      mesh.positions.insert(mesh.positions.end(), v.position.begin(), v.position.end());
      mesh.normals.insert(mesh.normals.end(), v.normal.begin(), v.normal.end());
      mesh.uvs.insert(mesh.uvs.end(), v.uv.begin(), v.uv.end());
    }
    for (const auto& t : triangles) mesh.indices.insert(mesh.indices.end(), t.begin(), t.end());
    mesh.features = features;
    return mesh;
  }
};

// ---- grid patches ---------------------------------------------------------------------

enum class SeamKind { none, uvShift, uvRotate, normal, mirror, weldedCopy };

// Coordinates along one axis of a grid: whole eighths, sometimes a zero-width column (two
// equal coordinates) or a sliver column (1/1024 wide).
std::vector<float> gridCoordinates(Builder& b, int cells, double zeroChance, double sliverChance, bool& zero,
                                   bool& sliver) {
  std::vector<float> out{0};
  for (int i = 0; i < cells; ++i) {
    float step = b.random.eighths(1, 4);
    if (b.random.chance(zeroChance)) {
      step = 0;
      zero = true;
    } else if (b.random.chance(sliverChance)) {
      step = 1.0f / 1024;
      sliver = true;
    }
    out.push_back(out.back() + step);
  }
  return out;
}

// Deterministic height noise from a position's bits: equal positions stay equal.
float jitterAt(float x, float y) {
  std::uint32_t bx = 0, by = 0;
  std::memcpy(&bx, &x, 4);
  std::memcpy(&by, &y, 4);
  std::uint64_t h = (std::uint64_t{bx} << 32 | by) * 0x9E3779B97F4A7C15ull;
  h ^= h >> 29;
  h *= 0xBF58476D1CE4E5B9ull;
  h ^= h >> 32;
  return static_cast<float>(static_cast<double>(h & 0xFFFF) / 65535.0 - 0.5) * 0.02f;
}

void addGrid(Builder& b, int maxTriangles) {
  Random& r = b.random;
  const int nx = std::clamp(r.between(1, 8), 1, std::max(1, maxTriangles / 2));
  const int ny = std::clamp(r.between(1, 8), 1, std::max(1, maxTriangles / (2 * nx)));
  bool zeroX = false, sliverX = false, zeroY = false, sliverY = false;
  const double zeroChance = b.chanceIf(MeshFeature::degenerate, 0.1),
               sliverChance = b.chanceIf(MeshFeature::sliver, 0.1);
  const std::vector<float> xs = gridCoordinates(b, nx, zeroChance, sliverChance, zeroX, sliverX);
  const std::vector<float> ys = gridCoordinates(b, ny, zeroChance, sliverChance, zeroY, sliverY);
  // UVs: a power-of-two scale with a sign per axis (a negative product mirrors the patch),
  // sometimes a zero-width UV column or row (collinear UVs; both: identical UVs).
  const float su = r.sign() * std::ldexp(1.0f, r.between(-2, 1));
  float sv = r.sign() * std::ldexp(1.0f, r.between(-2, 1));
  if (!b.allows(MeshFeature::mirroredIsland) && su * sv < 0) sv = -sv;
  const bool swapUv = r.chance(0.3);
  const Vec2 uvOffset{r.eighths(-8, 8), r.eighths(-8, 8)};
  const bool identicalUvs = r.chance(b.chanceIf(MeshFeature::identicalUvs, 0.3));
  const int flatU = identicalUvs || r.chance(b.chanceIf(MeshFeature::collinearUvs, 0.3))
                        ? r.between(0, nx - 1)
                        : -1;  // cell column with zero u width
  const int flatV = identicalUvs ? r.between(0, ny - 1) : -1;
  if (su * sv < 0) b.mark(MeshFeature::mirroredIsland);
  if (flatU >= 0 || flatV >= 0) b.mark(MeshFeature::collinearUvs);
  if (flatU >= 0 && flatV >= 0) b.mark(MeshFeature::identicalUvs);
  if (zeroX || zeroY) b.mark(MeshFeature::degenerate);
  if (sliverX || sliverY) b.mark(MeshFeature::sliver);
  auto gridUv = [&](int i, int j) {
    // Cumulative u of column i with column flatU collapsed.
    float u = static_cast<float>(i), v = static_cast<float>(j);
    if (flatU >= 0 && i > flatU) u -= 1;
    if (flatV >= 0 && j > flatV) v -= 1;
    u = u * su / 4 + uvOffset[0];
    v = v * sv / 4 + uvOffset[1];
    return swapUv ? Vec2{v, u} : Vec2{u, v};
  };

  const bool smooth = !b.allows(MeshFeature::flatGrid) || (b.allows(MeshFeature::smoothGrid) && r.chance(0.5));
  const bool jitter = smooth && r.chance(b.chanceIf(MeshFeature::jitter, 0.6));
  b.mark(smooth ? MeshFeature::smoothGrid : MeshFeature::flatGrid);
  if (jitter) b.mark(MeshFeature::jitter);
  const double amplitude = r.real(0.1, 0.6), fx = r.real(0.5, 3), fy = r.real(0.5, 3), phase = r.real(0, 6.3);

  // A seam along vertex column s: cells right of it use a second chart.
  std::vector<SeamKind> kinds;
  if (b.allows(MeshFeature::uvSeam)) kinds.insert(kinds.end(), {SeamKind::uvShift, SeamKind::uvRotate});
  if (b.allows(MeshFeature::normalSeam)) kinds.push_back(SeamKind::normal);
  if (b.allows(MeshFeature::mirroredIsland)) kinds.push_back(SeamKind::mirror);
  if (b.allows(MeshFeature::weldedCopies)) kinds.push_back(SeamKind::weldedCopy);
  const int s = nx >= 2 && !kinds.empty() && r.chance(0.7) ? r.between(1, nx - 1) : -1;
  SeamKind seam = SeamKind::none;
  if (s >= 0) {
    seam = kinds[static_cast<std::size_t>(r.between(0, static_cast<int>(kinds.size()) - 1))];
    switch (seam) {
      case SeamKind::uvShift:
      case SeamKind::uvRotate:
        b.mark(MeshFeature::uvSeam);
        break;
      case SeamKind::normal:
        b.mark(MeshFeature::normalSeam);
        break;
      case SeamKind::mirror:
        b.mark(MeshFeature::mirroredIsland);
        break;
      case SeamKind::weldedCopy:
        b.mark(MeshFeature::weldedCopies);
        break;
      case SeamKind::none:
        break;
    }
  }
  const Vec2 chartShift{r.eighths(-8, 8), r.eighths(1, 8)};
  const Vec3 seamNormalTilt{static_cast<float>(r.real(-0.8, 0.8)), static_cast<float>(r.real(-0.8, 0.8)), 0};
  const ExactPlacement placement = ExactPlacement::random(r);

  auto makeVertex = [&](int i, int j, int chart) {
    Vertex v;
    const float x = xs[i], y = ys[j];
    double z = 0, dzdx = 0, dzdy = 0;
    if (smooth) {
      z = amplitude * std::sin(fx * x + phase) * std::cos(fy * y);
      dzdx = amplitude * fx * std::cos(fx * x + phase) * std::cos(fy * y);
      dzdy = -amplitude * fy * std::sin(fx * x + phase) * std::sin(fy * y);
    }
    float zf = static_cast<float>(z);
    if (jitter) zf += jitterAt(x, y);
    Vec3 normal = smooth ? normalized(-dzdx, -dzdy, 1) : Vec3{0, 0, 1};
    Vec2 uv = gridUv(i, j);
    if (chart == 1) {
      switch (seam) {
        case SeamKind::uvShift:
          uv = {uv[0] + chartShift[0], uv[1] + chartShift[1]};
          break;
        case SeamKind::uvRotate:
          uv = {-uv[1] + chartShift[0], uv[0] + chartShift[1]};
          break;
        case SeamKind::normal:
          normal = normalized(normal[0] + seamNormalTilt[0], normal[1] + seamNormalTilt[1], normal[2]);
          break;
        case SeamKind::mirror: {
          const Vec2 axisUv = gridUv(s, j);
          const int k = swapUv ? 1 : 0;  // the grid's x runs along uv[k]
          uv[k] = 2 * axisUv[k] - uv[k];
          break;
        }
        case SeamKind::weldedCopy:
        case SeamKind::none:
          break;
      }
    }
    v.position = placement.point({x, y, zf});
    v.normal = placement.direction(normal);
    v.uv = uv;
    return v;
  };

  // Vertex ids per (column, row, chart); a mirror seam keeps one vertex on the seam.
  std::vector<std::uint32_t> ids(static_cast<std::size_t>((nx + 1) * (ny + 1) * 2), UINT32_MAX);
  auto vertex = [&](int i, int j, int chart) {
    if (i != s || seam == SeamKind::mirror) chart = (s >= 0 && i > s) ? 1 : 0;
    std::uint32_t& id = ids[static_cast<std::size_t>(((j * (nx + 1)) + i) * 2 + chart)];
    if (id == UINT32_MAX) id = b.add(makeVertex(i, j, chart));
    return id;
  };
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const int chart = (s >= 0 && i >= s) ? 1 : 0;
      const std::uint32_t a = vertex(i, j, chart), c1 = vertex(i + 1, j, chart), c2 = vertex(i + 1, j + 1, chart),
                          d = vertex(i, j + 1, chart);
      if (r.chance(0.5)) {
        b.triangle(a, c1, c2);
        b.triangle(a, c2, d);
      } else {
        b.triangle(a, c1, d);
        b.triangle(c1, c2, d);
      }
    }
  }
}

// ---- MikkTSpace subgroup split ----------------------------------------------------------

// Three triangles around c, all with positive UV area and connected through shared edges
// (same position, normal, UV), so one group; the third is folded over the first so its
// tangent, projected on the common normal, is exactly opposite: (c,p0,p1) and (c,p1,p2)
// give +x, (c,p2,p3) gives -x.
void addSubgroupSplit(Builder& b) {
  Random& r = b.random;
  const ExactPlacement placement = ExactPlacement::random(r);
  const float uvScale = std::ldexp(1.0f, r.between(-3, 0));
  const Vec2 uvOffset{r.eighths(-8, 8), r.eighths(-8, 8)};
  auto vertex = [&](Vec3 p, Vec2 uv) {
    Vertex v;
    v.position = placement.point(p);
    v.normal = placement.direction({0, 0, 1});
    v.uv = {uv[0] * uvScale + uvOffset[0], uv[1] * uvScale + uvOffset[1]};
    return b.add(v);
  };
  const std::uint32_t c = vertex({0, 0, 0}, {0, 0}), p0 = vertex({0, -1, 0}, {0, -1}), p1 = vertex({1, 0, 0}, {1, 0}),
                      p2 = vertex({0, 1, 0}, {0, 1}), p3 = vertex({0.5f, 0, 0}, {-1, 0});
  b.triangle(c, p0, p1);
  b.triangle(c, p1, p2);
  b.triangle(c, p2, p3);
  b.mark(MeshFeature::subgroupSplit);
}

// ---- changes to what is there -----------------------------------------------------------

std::uint32_t anyTriangle(Builder& b) {
  return static_cast<std::uint32_t>(b.random.between(0, static_cast<int>(b.triangles.size()) - 1));
}

void addFins(Builder& b) {
  const auto t = b.triangles[anyTriangle(b)];
  const int k = b.random.between(0, 2);
  const std::uint32_t a = t[k], c = t[(k + 1) % 3];
  const int fins = b.random.between(1, 2);
  for (int f = 0; f < fins; ++f) {
    const Vertex& va = b.vertices[a];
    const Vertex& vc = b.vertices[c];
    Vertex tip;
    for (int i = 0; i < 3; ++i)
      tip.position[i] = (va.position[i] + vc.position[i]) / 2 + va.normal[i] * b.random.eighths(1, 4) * b.random.sign();
    tip.normal = normalized(va.normal[0] + b.random.real(-1, 1), va.normal[1] + b.random.real(-1, 1),
                            va.normal[2] + b.random.real(-1, 1));
    tip.uv = {(va.uv[0] + vc.uv[0]) / 2 + b.random.eighths(-2, 2), (va.uv[1] + vc.uv[1]) / 2 + b.random.eighths(1, 3)};
    const std::uint32_t tipId = b.add(tip);
    if (b.random.chance(0.5))
      b.triangle(a, c, tipId);
    else
      b.triangle(c, a, tipId);
  }
  b.mark(MeshFeature::nonManifoldEdge);
}

void addTouchingFan(Builder& b) {
  const auto t = b.triangles[anyTriangle(b)];
  std::uint32_t center = t[b.random.between(0, 2)];
  if (b.random.chance(b.chanceIf(MeshFeature::weldedCopies, 0.5))) {  // touch through a copy with identical attributes
    center = b.add(Vertex(b.vertices[center]));
    b.mark(MeshFeature::weldedCopies);
  }
  const Vertex hub = b.vertices[center];
  const int spokes = b.random.between(3, 5);
  const bool closed = b.random.chance(0.5);
  const ExactPlacement turn = ExactPlacement::random(b.random);
  std::vector<std::uint32_t> rim;
  for (int k = 0; k < spokes; ++k) {
    const double angle = 2 * std::numbers::pi * k / spokes;
    const Vec3 local{static_cast<float>(std::cos(angle) * 0.5), static_cast<float>(std::sin(angle) * 0.5), 0.25f};
    const Vec3 offset = turn.direction(local);
    Vertex v = hub;
    for (int i = 0; i < 3; ++i) v.position[i] = hub.position[i] + offset[i];
    v.uv = {hub.uv[0] + local[0] / 2, hub.uv[1] + local[1] / 2};
    rim.push_back(b.add(v));
  }
  for (int k = 0; k + 1 < spokes + (closed ? 1 : 0); ++k) b.triangle(center, rim[k], rim[(k + 1) % spokes]);
  b.mark(MeshFeature::nonManifoldVertex);
}

void flipWindings(Builder& b) {
  const int n = b.random.between(1, 3);
  for (int k = 0; k < n; ++k) {
    auto& t = b.triangles[anyTriangle(b)];
    std::swap(t[1], t[2]);
  }
  b.mark(MeshFeature::flippedWinding);
}

void duplicateFaces(Builder& b) {
  const int n = b.random.between(1, 3);
  for (int k = 0; k < n; ++k) {
    auto t = b.triangles[anyTriangle(b)];
    const bool rotated =
        !b.allows(MeshFeature::duplicatedFace) || (b.allows(MeshFeature::rotatedDuplicate) && b.random.chance(0.5));
    if (rotated) {
      std::rotate(t.begin(), t.begin() + b.random.between(1, 2), t.end());
      b.mark(MeshFeature::rotatedDuplicate);
    } else {
      b.mark(MeshFeature::duplicatedFace);
    }
    b.triangles.push_back(t);
  }
}

// A triangle's corners replaced by copies whose UVs are all equal, or on a line.
void flattenUvs(Builder& b) {
  auto& t = b.triangles[anyTriangle(b)];
  const bool identical =
      !b.allows(MeshFeature::collinearUvs) || (b.allows(MeshFeature::identicalUvs) && b.random.chance(0.5));
  const Vertex first = b.vertices[t[0]];
  for (int k = 1; k < 3; ++k) {
    Vertex v = b.vertices[t[k]];
    if (identical) {
      v.uv = first.uv;
    } else {
      const float along = static_cast<float>(k) / 4;
      v.uv = {first.uv[0] + along, first.uv[1] + 2 * along};
    }
    t[k] = b.add(v);
  }
  b.mark(identical ? MeshFeature::identicalUvs : MeshFeature::collinearUvs);
}

// Triangles with two corners at one position: by index, or by a copy with another UV.
void addDegenerates(Builder& b) {
  const auto t = b.triangles[anyTriangle(b)];
  switch (b.random.between(0, 2)) {
    case 0:
      b.triangle(t[0], t[0], t[1]);
      break;
    case 1: {
      Vertex v = b.vertices[t[0]];
      v.uv[0] += 0.125f;
      b.triangle(t[0], b.add(v), t[1]);
      break;
    }
    default: {  // a copy of another corner moved onto the first: same position, other UV and normal
      Vertex v = b.vertices[t[1]];
      v.position = b.vertices[t[0]].position;
      b.triangle(t[0], b.add(v), t[2]);
      break;
    }
  }
  b.mark(MeshFeature::degenerate);
}

void addSliver(Builder& b) {
  const auto t = b.triangles[anyTriangle(b)];
  const Vertex& a = b.vertices[t[0]];
  const Vertex& c = b.vertices[t[1]];
  Vertex tip;
  const float along = static_cast<float>(b.random.real(0.2, 0.8));
  for (int i = 0; i < 3; ++i)
    tip.position[i] = a.position[i] + along * (c.position[i] - a.position[i]) + 1e-4f * a.normal[(i + 1) % 3];
  for (int i = 0; i < 2; ++i) tip.uv[i] = a.uv[i] + along * (c.uv[i] - a.uv[i]) + (b.random.chance(0.5) ? 0.0f : 0.25f);
  tip.normal = a.normal;
  b.triangle(t[1], t[0], b.add(tip));
  b.mark(MeshFeature::sliver);
}

// Some triangles get private copies of their vertices (identical attributes).
void deindexSome(Builder& b) {
  const int n = b.random.between(1, std::max(1, static_cast<int>(b.triangles.size()) / 4));
  for (int k = 0; k < n; ++k) {
    auto& t = b.triangles[anyTriangle(b)];
    for (auto& index : t) index = b.add(Vertex(b.vertices[index]));
  }
  b.mark(MeshFeature::weldedCopies);
}

}  // namespace

// Each mesh allows a random subset of the cases (so a failing case shows in which meshes
// fail), then combines what it allows at random.
std::optional<MeshFeature> parseMeshFeature(std::string_view name) {
  for (std::size_t f = 0; f < kMeshFeatureCount; ++f)
    if (toString(static_cast<MeshFeature>(f)) == name) return static_cast<MeshFeature>(f);
  return std::nullopt;
}

RandomMesh randomMesh(std::uint64_t seed, std::optional<MeshFeature> only) {
  using enum MeshFeature;
  Builder b(seed);
  for (bool& allowed : b.enabled) allowed = b.random.chance(0.3);
  if (only) {
    b.enabled = {};
    b.enabled[static_cast<std::size_t>(*only)] = true;
  }
  if (!b.allows(smoothGrid) && !b.allows(flatGrid))
    b.enabled[static_cast<std::size_t>(b.random.chance(0.5) ? smoothGrid : flatGrid)] = true;
  const int target = b.random.between(20, 400);
  while (static_cast<int>(b.triangles.size()) < target) {
    if (b.random.chance(b.chanceIf(subgroupSplit, 0.25)))
      addSubgroupSplit(b);
    else
      addGrid(b, target - static_cast<int>(b.triangles.size()));
  }
  if (b.allows(nonManifoldEdge)) addFins(b);
  if (b.allows(nonManifoldVertex)) addTouchingFan(b);
  if (b.allows(flippedWinding)) flipWindings(b);
  if (b.allows(duplicatedFace) || b.allows(rotatedDuplicate)) duplicateFaces(b);
  if (b.allows(identicalUvs) || b.allows(collinearUvs)) flattenUvs(b);
  if (b.allows(degenerate)) addDegenerates(b);
  if (b.allows(sliver)) addSliver(b);
  if (b.allows(weldedCopies) && b.random.chance(0.7)) deindexSome(b);
  return b.finish();
}

CornerRun runCorners(const MeshArrays& mesh, unsigned threads, TangentWorkspace& workspace, Method method) {
  CornerRun out;
  out.tangents.assign(mesh.indices.size() * 4, std::numeric_limits<float>::quiet_NaN());
  out.cornerVertex.assign(mesh.indices.size(), ~0u);
  Options options;
  options.threads = threads;
  options.method = method;
  out.report = computeCornerTangents(mesh, CornerOutputs{out.tangents, {}, out.cornerVertex}, options, workspace);
  return out;
}

GridMesh hardMesh(std::size_t triangles) {
  GridMesh m;
  for (std::uint64_t seed = 1; m.indices.size() < 3 * triangles; ++seed) {
    const RandomMesh part = randomMesh(seed);
    const auto base = static_cast<std::uint32_t>(m.positions.size() / 3);
    m.positions.insert(m.positions.end(), part.positions.begin(), part.positions.end());
    m.normals.insert(m.normals.end(), part.normals.begin(), part.normals.end());
    m.uvs.insert(m.uvs.end(), part.uvs.begin(), part.uvs.end());
    for (std::uint32_t i : part.indices) m.indices.push_back(base + i);
  }
  return m;
}

}  // namespace tangent::testing

