// SPDX-License-Identifier: MIT
#include "stress_cases.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>
#include <set>

namespace tangent::bench {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

// n x n quads on a gently curved sheet over [0, size]^2 at `offset`, UVs over [0, uvSize]^2.
StressCase grid(const std::string& name, int n, double size, double offset, double uvSize) {
  StressCase c;
  c.name = name;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const double x = size * i / n, y = size * j / n;
      const double z = 0.05 * size * std::sin(3.0 * i / n) * std::cos(2.0 * j / n);
      c.positions.insert(c.positions.end(), {static_cast<float>(offset + x), static_cast<float>(offset + y), static_cast<float>(offset + z)});
      const double nx = -0.15 * std::cos(3.0 * i / n) * std::cos(2.0 * j / n), ny = 0.1 * std::sin(3.0 * i / n) * std::sin(2.0 * j / n);
      const double l = std::sqrt(nx * nx + ny * ny + 1);
      c.normals.insert(c.normals.end(), {static_cast<float>(nx / l), static_cast<float>(ny / l), static_cast<float>(1 / l)});
      c.uvs.insert(c.uvs.end(), {static_cast<float>(uvSize * i / n), static_cast<float>(uvSize * j / n)});
    }
  }
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const std::uint32_t a = j * (n + 1) + i, b = a + 1, cc = a + n + 1, d = cc + 1;
      c.indices.insert(c.indices.end(), {a, b, d, a, d, cc});
    }
  }
  return c;
}

// A fan of slivers: triangles (0, i, i+1) whose far edge is `aspect` times shorter than the others.
StressCase slivers(double aspect) {
  StressCase c;
  c.name = "slivers, aspect 1e" + std::to_string(static_cast<int>(std::lround(std::log10(aspect))));
  const int count = 16;
  c.positions = {0, 0, 0};
  c.normals = {0, 0, 1};
  c.uvs = {0, 0};
  for (int i = 0; i <= count; ++i) {
    const double y = i / aspect;
    c.positions.insert(c.positions.end(), {1.0f, static_cast<float>(y), 0.0f});
    c.normals.insert(c.normals.end(), {0, 0, 1});
    c.uvs.insert(c.uvs.end(), {1.0f, static_cast<float>(y)});
  }
  for (std::uint32_t i = 1; i <= static_cast<std::uint32_t>(count); ++i) c.indices.insert(c.indices.end(), {0, i, i + 1});
  return c;
}

void scalePositions(StressCase& c, double scale) {
  for (float& p : c.positions) p = static_cast<float>(p * scale);
}

// Degenerate triangles in space and in UV: slivers, UV areas down to 1e-30 and zero,
// collinear UVs, two vertices at one place.
void addDegenerateTriangles(std::vector<StressCase>& cases) {
  for (double aspect : {1e3, 1e6, 1e9}) cases.push_back(slivers(aspect));
  for (int exponent : {3, 6, 9, 12, 15}) {
    // UV triangles of area ~ (1e-e)^2 / (2 n^2): 1e-6 ... 1e-30 for the whole sheet
    cases.push_back(grid("UV area 1e-" + std::to_string(2 * exponent), 8, 1.0, 0.0, std::pow(10.0, -exponent)));
  }
  {
    StressCase c = grid("UV area exactly zero", 8, 1.0, 0.0, 1.0);
    for (float& uv : c.uvs) uv = 0.5f;
    cases.push_back(std::move(c));
  }
  {
    StressCase c = grid("collinear UVs", 8, 1.0, 0.0, 1.0);
    for (std::size_t v = 0; v < c.uvs.size() / 2; ++v) c.uvs[2 * v + 1] = c.uvs[2 * v];  // u = v on every vertex
    cases.push_back(std::move(c));
  }
  {
    StressCase c = grid("coincident vertices", 8, 1.0, 0.0, 1.0);
    for (int k = 0; k < 3; ++k) c.positions[3 * 10 + k] = c.positions[3 * 11 + k];  // vertex 10 onto 11
    cases.push_back(std::move(c));
  }
}

// Float precision: small edges far from the origin, scales of 1e-30 and 1e30, denormals.
void addPrecisionLimits(std::vector<StressCase>& cases) {
  for (int exponent : {4, 5, 6, 7}) {
    // Edges of 1e-2 at an offset: at 1e6 a few float ulps, at 1e7 below one ulp (collapsed).
    cases.push_back(grid("offset 1e" + std::to_string(exponent) + ", edges 1e-2", 8, 8e-2, std::pow(10.0, exponent), 1.0));
  }
  for (int exponent : {-30, 30}) {
    StressCase c = grid("scaled by 1e" + std::to_string(exponent), 8, 1.0, 0.0, 1.0);
    scalePositions(c, std::pow(10.0, exponent));
    cases.push_back(std::move(c));
  }
  {
    StressCase c = grid("denormal coordinates", 8, 1.0, 0.0, 1.0);
    scalePositions(c, 1e-40);
    cases.push_back(std::move(c));
  }
}

// Broken input on one vertex (NaN or Inf in its position, normal or UV); the rest must equal
// the clean run away from it.
void addBrokenVertex(std::vector<StressCase>& cases) {
  static const StressCase cleanGrid = grid("clean grid", 8, 1.0, 0.0, 1.0);
  const std::uint32_t broken = 40;  // an interior vertex of the 9 x 9 grid
  for (const char* what : {"NaN position", "Inf position", "NaN normal", "Inf normal", "NaN UV", "Inf UV"}) {
    StressCase c = cleanGrid;
    c.name = what;
    const std::string name = what;
    const float value = name.rfind("NaN", 0) == 0 ? kNaN : kInf;
    if (name.find("position") != std::string::npos) c.positions[3 * broken + 1] = value;
    else if (name.find("normal") != std::string::npos) c.normals[3 * broken + 2] = value;
    else c.uvs[2 * broken] = value;
    c.brokenVertices = {broken};
    c.clean = &cleanGrid;
    cases.push_back(std::move(c));
  }
}

// Normals that are not unit or face away: zero length, lengths 1e-20 and 1e20, opposed.
void addOddNormals(std::vector<StressCase>& cases) {
  {
    StressCase c = grid("zero-length normals", 8, 1.0, 0.0, 1.0);
    for (std::size_t v = 0; v < c.normals.size() / 3; v += 3)
      for (int k = 0; k < 3; ++k) c.normals[3 * v + k] = 0;
    cases.push_back(std::move(c));
  }
  for (int exponent : {-20, 20}) {
    StressCase c = grid("normals of length 1e" + std::to_string(exponent), 8, 1.0, 0.0, 1.0);
    for (float& n : c.normals) n = static_cast<float>(n * std::pow(10.0, exponent));
    cases.push_back(std::move(c));
  }
  {
    StressCase c = grid("face-opposed normals", 8, 1.0, 0.0, 1.0);
    for (float& n : c.normals) n = -n;
    cases.push_back(std::move(c));
  }
}

// A pole: 1000 triangles around one vertex, UVs polar around it.
StressCase pole() {
  StressCase c;
  c.name = "pole with 1000 triangles";
  const int count = 1000;
  c.positions = {0, 0, 1};
  c.normals = {0, 0, 1};
  c.uvs = {0.5f, 0.0f};
  for (int i = 0; i <= count; ++i) {
    const double a = 2 * std::numbers::pi * i / count;
    c.positions.insert(c.positions.end(), {static_cast<float>(0.2 * std::cos(a)), static_cast<float>(0.2 * std::sin(a)), 0.98f});
    const double l = std::sqrt(0.04 + 0.98 * 0.98);
    c.normals.insert(c.normals.end(), {static_cast<float>(0.2 * std::cos(a) / l), static_cast<float>(0.2 * std::sin(a) / l), static_cast<float>(0.98 / l)});
    c.uvs.insert(c.uvs.end(), {static_cast<float>(double(i) / count), 0.1f});
  }
  for (std::uint32_t i = 1; i <= static_cast<std::uint32_t>(count); ++i) c.indices.insert(c.indices.end(), {0, i, i + 1});
  return c;
}

// Two mirrored islands meeting at vertex 0 only: a bow tie in 3D and in UV.
StressCase islandsMeetingAtAVertex() {
  StressCase c;
  c.name = "mirrored islands meeting at a vertex";
  c.positions = {0, 0, 0, 1, -0.5f, 0, 1, 0.5f, 0, -1, -0.5f, 0, -1, 0.5f, 0};
  c.normals = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
  c.uvs = {0.5f, 0.5f, 1, 0, 1, 1, 1, 0, 1, 1};  // the left triangle maps mirrored onto the right's UVs
  c.indices = {0, 1, 2, 0, 4, 3};
  return c;
}

// Edges shared by three and by five faces.
StressCase nonManifoldEdges() {
  StressCase c;
  c.name = "edges shared by 3 and 5 faces";
  c.positions = {0, 0, 0, 1, 0, 0};
  c.normals = {0, 0, 1, 0, 0, 1};
  c.uvs = {0, 0, 1, 0};
  for (int i = 0; i < 5; ++i) {
    const double a = 2 * std::numbers::pi * i / 5 + 0.3;
    c.positions.insert(c.positions.end(), {0.5f, static_cast<float>(std::cos(a)), static_cast<float>(std::sin(a))});
    c.normals.insert(c.normals.end(), {0, static_cast<float>(std::cos(a)), static_cast<float>(std::sin(a))});
    c.uvs.insert(c.uvs.end(), {0.5f, static_cast<float>(0.2 * i + 0.1)});
    c.indices.insert(c.indices.end(), {0, 1, static_cast<std::uint32_t>(2 + i)});
  }
  c.positions.insert(c.positions.end(), {2, 0, 0});
  c.normals.insert(c.normals.end(), {0, 0, 1});
  c.uvs.insert(c.uvs.end(), {2, 0});
  for (std::uint32_t apex : {2u, 3u, 4u}) c.indices.insert(c.indices.end(), {1, 7, apex});  // edge (1, 7) thrice
  return c;
}

}  // namespace

std::vector<StressCase> stressCases() {
  std::vector<StressCase> cases;
  addDegenerateTriangles(cases);
  addPrecisionLimits(cases);
  addBrokenVertex(cases);
  addOddNormals(cases);
  cases.push_back(pole());
  cases.push_back(islandsMeetingAtAVertex());
  cases.push_back(nonManifoldEdges());
  return cases;
}

StressOutcome runStressCase(const StressCase& c, const Options& options) {
  StressOutcome outcome;
  const std::size_t corners = c.indices.size();
  outcome.corners = corners;
  std::vector<float> first(corners * 4, kNaN), second(corners * 4, kNaN);
  const auto start = std::chrono::steady_clock::now();
  outcome.report = computeCornerTangents(c.arrays(), first, options);
  outcome.milliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  computeCornerTangents(c.arrays(), second, options);
  outcome.undefinedCorners = outcome.report.fallbackFromNeighbours + outcome.report.fallbackFixed;
  for (std::size_t k = 0; k < corners; ++k) {
    const float* t = &first[4 * k];
    if (std::memcmp(t, &second[4 * k], 16) != 0) ++outcome.changedOnRerun;
    if (!std::isfinite(t[0]) || !std::isfinite(t[1]) || !std::isfinite(t[2]) || !std::isfinite(t[3])) {
      ++outcome.notFinite;
      continue;
    }
    const double length = std::sqrt(double(t[0]) * t[0] + double(t[1]) * t[1] + double(t[2]) * t[2]);
    if (std::abs(length - 1) > 1e-6) ++outcome.notUnit;
    if (t[3] != 1.0f && t[3] != -1.0f) ++outcome.badW;
    const float* n = &c.normals[3 * c.indices[k]];
    const double nl = std::sqrt(double(n[0]) * n[0] + double(n[1]) * n[1] + double(n[2]) * n[2]);
    if (nl > 0 && std::isfinite(nl)) {
      const double d = (double(t[0]) * n[0] + double(t[1]) * n[1] + double(t[2]) * n[2]) / nl;
      if (std::abs(d) > 1e-5) ++outcome.notOrthogonal;
    }
  }
  if (c.clean) {
    // The broken vertices and every vertex that shares a triangle with one.
    std::set<std::uint32_t> near(c.brokenVertices.begin(), c.brokenVertices.end());
    for (std::size_t t = 0; t < corners / 3; ++t) {
      for (int k = 0; k < 3; ++k) {
        if (std::count(c.brokenVertices.begin(), c.brokenVertices.end(), c.indices[3 * t + k]))
          for (int j = 0; j < 3; ++j) near.insert(c.indices[3 * t + j]);
      }
    }
    std::vector<float> clean(corners * 4);
    computeCornerTangents(c.clean->arrays(), clean, options);
    // A corner outside the broken vertices' 1-ring sums only its own triangles, none of which
    // holds a broken vertex.
    for (std::size_t k = 0; k < corners; ++k) {
      if (!near.count(c.indices[k]) && std::memcmp(&first[4 * k], &clean[4 * k], 16) != 0) ++outcome.changedAwayFromBrokenInput;
    }
  }
  return outcome;
}

}  // namespace tangent::bench
