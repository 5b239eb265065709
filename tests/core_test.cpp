// SPDX-License-Identifier: MIT
// Core: exact values on tiny hand-made meshes, invariants on generated ones, determinism,
// degenerate input, and one test per error case.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <numbers>
#include <random>

#include "support/test_assets.hpp"
#include "tangent/frame_rules.hpp"
#include "tangent/openmesh.hpp"
#include "tangent/tangent.hpp"

namespace {

using tangent::MeshArrays;
using tangent::Options;
using tangent::Report;
using tangent::testing::GridMesh;

constexpr float kGarbage = std::numeric_limits<float>::quiet_NaN();

struct Result {
  std::vector<float> tangents;
  Report report;
};

// Output pre-filled with NaN so any corner left untouched fails the invariants.
Result run(const GridMesh& mesh, Options options = {}) {
  Result result;
  result.tangents.assign(mesh.indices.size() * 4, kGarbage);
  result.report = tangent::computeCornerTangents({mesh.positions, mesh.normals, mesh.uvs, mesh.indices}, result.tangents, options);
  return result;
}

void expectTangent(const Result& r, std::size_t corner, float x, float y, float z, float w) {
  SCOPED_TRACE("corner " + std::to_string(corner));
  EXPECT_NEAR(r.tangents[4 * corner + 0], x, 1e-6);
  EXPECT_NEAR(r.tangents[4 * corner + 1], y, 1e-6);
  EXPECT_NEAR(r.tangents[4 * corner + 2], z, 1e-6);
  EXPECT_EQ(r.tangents[4 * corner + 3], w);
}

// Unit, orthogonal to the corner's normal, |w| = 1, finite: on every corner.
void expectValidFrames(const GridMesh& mesh, const Result& r) {
  for (std::size_t c = 0; c < mesh.indices.size(); ++c) {
    const float* t = &r.tangents[4 * c];
    const float* n = &mesh.normals[3 * mesh.indices[c]];
    ASSERT_TRUE(std::isfinite(t[0]) && std::isfinite(t[1]) && std::isfinite(t[2]) && std::isfinite(t[3])) << "corner " << c;
    const double length = std::sqrt(double(t[0]) * t[0] + double(t[1]) * t[1] + double(t[2]) * t[2]);
    ASSERT_NEAR(length, 1.0, 1e-6) << "corner " << c;
    const double nLength = std::sqrt(double(n[0]) * n[0] + double(n[1]) * n[1] + double(n[2]) * n[2]);
    if (nLength > 0 && std::isfinite(nLength)) {
      ASSERT_NEAR((t[0] * n[0] + t[1] * n[1] + t[2] * n[2]) / nLength, 0.0, 1e-5) << "corner " << c;
    }
    ASSERT_TRUE(t[3] == 1.0f || t[3] == -1.0f) << "corner " << c << " w " << t[3];
  }
}

GridMesh quad() {
  // Unit quad in the xy plane facing +z; u along +x, v along +y (bottom-left origin).
  GridMesh m;
  m.positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  m.normals = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
  m.uvs = {0, 0, 1, 0, 1, 1, 0, 1};
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

TEST(Core, QuadExactFrame) {
  Options options;
  options.method = tangent::Method::lengyel;
  options.uvOrigin = tangent::UvOrigin::bottomLeft;
  const Result r = run(quad(), options);
  for (std::size_t c = 0; c < 6; ++c) expectTangent(r, c, 1, 0, 0, 1);
  EXPECT_EQ(r.report.mirroredCorners, 0u);
  EXPECT_EQ(r.report.splitVertices, 0u);
  EXPECT_EQ(r.report.method, tangent::Method::lengyel);
  EXPECT_EQ(r.report.weighting, tangent::Weighting::angle);
  EXPECT_EQ(run(quad()).report.method, tangent::Method::mikktspace);  // the default
}

TEST(Core, TopLeftUvOriginNegatesWOnly) {
  const Result r = run(quad());  // default: glTF convention
  for (std::size_t c = 0; c < 6; ++c) expectTangent(r, c, 1, 0, 0, -1);
  EXPECT_EQ(r.report.mirroredCorners, 6u);
}

// The one handedness rule, and every method following it: the quad's UVs turn counter-clockwise.
TEST(Core, HandednessRuleDecidesWForEveryMethodAndOrigin) {
  static_assert(tangent::handedness(1.0f, tangent::UvOrigin::topLeft) == -1.0f);
  static_assert(tangent::handedness(-1.0, tangent::UvOrigin::topLeft) == 1.0);
  static_assert(tangent::handedness(1.0f, tangent::UvOrigin::bottomLeft) == 1.0f);
  static_assert(tangent::kGltfUvOrigin == tangent::UvOrigin::topLeft);
  for (tangent::Method method : {tangent::Method::mikktspace, tangent::Method::lengyel, tangent::Method::flat}) {
    for (tangent::UvOrigin origin : {tangent::UvOrigin::topLeft, tangent::UvOrigin::bottomLeft}) {
      Options options;
      options.method = method;
      options.uvOrigin = origin;
      const Result r = run(quad(), options);
      for (std::size_t c = 0; c < 6; ++c) EXPECT_EQ(r.tangents[4 * c + 3], tangent::handedness(1.0f, origin)) << c;
    }
  }
}

TEST(Core, MirroredQuadsSplitSharedVertices) {
  // Two quads sharing the edge x = 1; the right quad's u runs back from 1 to 0, so the shared
  // vertices (same position, normal and UV) need two frames with opposite w.
  GridMesh m;
  m.positions = {0, 0, 0, 1, 0, 0, 2, 0, 0, 0, 1, 0, 1, 1, 0, 2, 1, 0};
  m.normals.assign(18, 0.0f);
  for (int v = 0; v < 6; ++v) m.normals[3 * v + 2] = 1;
  m.uvs = {0, 0, 1, 0, 0, 0, 0, 1, 1, 1, 0, 1};
  m.indices = {0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 4};
  Options options;
  options.uvOrigin = tangent::UvOrigin::bottomLeft;
  const Result r = run(m, options);
  for (std::size_t c = 0; c < 6; ++c) expectTangent(r, c, 1, 0, 0, 1);
  for (std::size_t c = 6; c < 12; ++c) expectTangent(r, c, -1, 0, 0, -1);
  EXPECT_EQ(r.report.splitVertices, 2u);  // vertices 1 and 4
  EXPECT_EQ(r.report.mirroredCorners, 6u);
}

GridMesh cube24() {
  // 24-vertex cube: 4 own vertices per face, u along the face's first edge.
  GridMesh m;
  const int axes[6][3] = {{0, 1, 2}, {0, 1, 2}, {1, 2, 0}, {1, 2, 0}, {2, 0, 1}, {2, 0, 1}};
  for (int f = 0; f < 6; ++f) {
    const float side = (f % 2 == 0) ? 1.0f : -1.0f;
    const int ua = axes[f][0], va = axes[f][1], na = axes[f][2];
    const std::uint32_t base = static_cast<std::uint32_t>(m.positions.size() / 3);
    const float corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (auto& c : corners) {
      float p[3] = {0, 0, 0}, n[3] = {0, 0, 0};
      p[ua] = c[0] * side;  // mirror u on the back faces so the winding stays outward
      p[va] = c[1];
      p[na] = side;
      n[na] = side;
      m.positions.insert(m.positions.end(), p, p + 3);
      m.normals.insert(m.normals.end(), n, n + 3);
      m.uvs.insert(m.uvs.end(), {(c[0] + 1) / 2, (c[1] + 1) / 2});
    }
    m.indices.insert(m.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
  }
  return m;
}

// Two closed fans around one vertex (the apexes of two cones, one above and one below) are
// two groups, with a frame each, though the vertex's corners all pair up one to one: a
// shortcut that took every such bucket for one fan would give both the frame of their sum
// (the two frames are 30 degrees apart, close enough for the fan shortcut's other tests).
TEST(Core, TwoClosedFansAtOneVertexAreTwoGroups) {
  const float turn = std::numbers::pi_v<float> / 6;  // the lower cone's u runs at 30 degrees
  GridMesh m;
  m.positions = {0, 0, 0};
  m.normals = {0, 0, 1};
  m.uvs = {0.5f, 0.5f};
  for (int cone = 0; cone < 2; ++cone) {
    const float a = cone == 0 ? 0 : turn;
    for (int i = 0; i < 3; ++i) {
      const float c = std::cos(2 * std::numbers::pi_v<float> * i / 3), s = std::sin(2 * std::numbers::pi_v<float> * i / 3);
      m.positions.insert(m.positions.end(), {c, s, cone == 0 ? 1.0f : -1.0f});
      m.normals.insert(m.normals.end(), {0, 0, 1});
      // UVs: the ring turned by -a (same UV orientation), so that u grows along (cos a, sin a).
      m.uvs.insert(m.uvs.end(), {0.5f + 0.4f * (c * std::cos(a) + s * std::sin(a)),
                                 0.5f + 0.4f * (s * std::cos(a) - c * std::sin(a))});
    }
  }
  m.indices = {0, 1, 2, 0, 2, 3, 0, 3, 1, 0, 4, 5, 0, 5, 6, 0, 6, 4};
  Options options;
  options.uvOrigin = tangent::UvOrigin::bottomLeft;
  for (unsigned threads : {1u, 2u}) {
    options.threads = threads;
    const Result r = run(m, options);
    for (std::size_t corner : {0, 3, 6}) expectTangent(r, corner, 1, 0, 0, 1);
    for (std::size_t corner : {9, 12, 15}) expectTangent(r, corner, std::cos(turn), std::sin(turn), 0, 1);
    EXPECT_EQ(r.report.splitVertices, 1u);
  }
}

TEST(Core, Cube24ExactFrames) {
  Options options;
  options.uvOrigin = tangent::UvOrigin::bottomLeft;
  const GridMesh m = cube24();
  const Result r = run(m, options);
  const int uAxis[6] = {0, 0, 1, 1, 2, 2};
  for (int f = 0; f < 6; ++f) {
    float expected[3] = {0, 0, 0};
    expected[uAxis[f]] = (f % 2 == 0) ? 1.0f : -1.0f;
    for (int c = 0; c < 6; ++c) expectTangent(r, 6 * f + c, expected[0], expected[1], expected[2], 1);
  }
  EXPECT_EQ(r.report.splitVertices, 0u);
  expectValidFrames(m, r);
}

TEST(Core, FlatGivesOneFramePerFace) {
  const GridMesh m = tangent::testing::makeSphere(12, 8);
  Options options;
  options.method = tangent::Method::flat;
  const Result r = run(m, options);
  expectValidFrames(m, r);
  EXPECT_EQ(r.report.method, tangent::Method::flat);
  EXPECT_EQ(r.report.weighting, std::nullopt);
  // Neighbouring faces on a sphere disagree, so shared vertices split.
  EXPECT_GT(r.report.splitVertices, 0u);
  const Result smooth = run(m);
  EXPECT_EQ(smooth.report.splitVertices, 0u);
}

// Two triangles sharing the edge 0-2, flat in z = 0 (normal +z, so projecting onto the
// tangent plane changes nothing), with one UV per vertex (piecewise linear, positive
// orientation in both):
//   A = (0, 1, 2): (0,0) (1,0) (0,1), uv = position: dP/du = (1, 0)
//   B = (0, 2, 3): (0,0) (0,1) (-2,-2), uv (0,0) (0,1) (-2,0): P = u (1,1) + v (0,1),
//       dP/du = (1, 1) / sqrt(2)
// Angles: at vertex 0, A pi/2 and B 3pi/4 (between (0,1) and (-1,-1)); at vertex 2, A pi/4
// (between (0,-1) and (1,-1)) and B atan2(2, 3) (between (0,-1) and (-2,-3): |cross| 2,
// dot 3). Areas: A 1/2, B 1/2 |(0,1) x (-2,-2)| = 1.
// Vertices 0 and 2 have one position, normal and UV each, and both methods group their two
// corners (lengyel by vertex, mikktspace across the shared edge): one frame, the normalized
// weighted sum of the two dP/du; mikktspace weights by the angles of the edges projected
// onto the tangent plane, here the angles themselves. Vertices 1 and 3 see one triangle: its
// own dP/du. In the bottom-left convention both triangles are right-handed (w = +1). At
// vertex 0 the three weightings differ: 27.2 (angle), 30.4 (area) and 22.5 (uniform) degrees
// from +x.
GridMesh twoTriangleFan() {
  GridMesh m;
  m.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, -2, -2, 0};
  for (int v = 0; v < 4; ++v) m.normals.insert(m.normals.end(), {0, 0, 1});
  m.uvs = {0, 0, 1, 0, 0, 1, -2, 0};
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

TEST(Core, EachWeightingGivesItsHandComputedFrame) {
  const double pi = std::numbers::pi, root2 = std::sqrt(2.0);
  struct Weights {
    double a, b;  // of triangle A's and B's dP/du
  };
  struct Expected {
    const char* name;
    tangent::Method method;
    tangent::Weighting weighting;
    Weights atVertex0, atVertex2;
  };
  const Weights angle0{pi / 2, 3 * pi / 4}, angle2{pi / 4, std::atan2(2.0, 3.0)}, area{0.5, 1.0}, uniform{1.0, 1.0};
  const GridMesh m = twoTriangleFan();
  for (const Expected& e : {Expected{"lengyel/angle", tangent::Method::lengyel, tangent::Weighting::angle, angle0, angle2},
                            Expected{"lengyel/area", tangent::Method::lengyel, tangent::Weighting::area, area, area},
                            Expected{"lengyel/uniform", tangent::Method::lengyel, tangent::Weighting::uniform, uniform, uniform},
                            Expected{"mikktspace", tangent::Method::mikktspace, tangent::Weighting::angle, angle0, angle2}}) {
    SCOPED_TRACE(e.name);
    Options options;
    options.method = e.method;
    options.weighting = e.weighting;
    options.uvOrigin = tangent::UvOrigin::bottomLeft;
    const Result r = run(m, options);
    auto sum = [&](Weights w) {  // w.a (1, 0) + w.b (1, 1) / sqrt(2), normalized
      const double x = w.a + w.b / root2, y = w.b / root2, length = std::hypot(x, y);
      return std::array<float, 2>{static_cast<float>(x / length), static_cast<float>(y / length)};
    };
    const auto at0 = sum(e.atVertex0), at2 = sum(e.atVertex2);
    const float diagonal = static_cast<float>(1 / root2);
    expectTangent(r, 0, at0[0], at0[1], 0, 1);  // A: vertices 0, 1, 2
    expectTangent(r, 1, 1, 0, 0, 1);
    expectTangent(r, 2, at2[0], at2[1], 0, 1);
    expectTangent(r, 3, at0[0], at0[1], 0, 1);  // B: vertices 0, 2, 3
    expectTangent(r, 4, at2[0], at2[1], 0, 1);
    expectTangent(r, 5, diagonal, diagonal, 0, 1);
    EXPECT_EQ(r.report.splitVertices, 0u);
  }
  // flat: every corner its own triangle's dP/du, so vertices 0 and 2 (in both triangles) need
  // two frames each: 2 more vertices.
  Options options;
  options.method = tangent::Method::flat;
  options.uvOrigin = tangent::UvOrigin::bottomLeft;
  const Result flat = run(m, options);
  const float diagonal = static_cast<float>(1 / root2);
  for (std::size_t c = 0; c < 3; ++c) expectTangent(flat, c, 1, 0, 0, 1);
  for (std::size_t c = 3; c < 6; ++c) expectTangent(flat, c, diagonal, diagonal, 0, 1);
  EXPECT_EQ(flat.report.splitVertices, 2u);
  EXPECT_EQ(flat.report.outputVertices, 6u);
}

TEST(Core, InvariantsOnGeneratedMeshes) {
  // The sphere also with every third triangle wound against its normals (inconsistent winding).
  for (const GridMesh& m : {tangent::testing::makeSphere(24, 12), tangent::testing::reverseWinding(tangent::testing::makeSphere(24, 12), 3),
                            tangent::testing::makeTorus(24, 12), tangent::testing::makeGrid(10, 7, true)}) {
    for (auto method : {tangent::Method::mikktspace, tangent::Method::lengyel, tangent::Method::flat}) {
      Options options;
      options.method = method;
      const Result r = run(m, options);
      expectValidFrames(m, r);
    }
  }
}

TEST(Core, TorusTangentFollowsU) {
  // On the torus u runs around the main ring: the exact tangent is (-sin a, cos a, 0).
  // Vertices on the u seam see triangles on one side only, so their frame is the chord's,
  // half a ring step (2.8 degrees here) off for any method: they are left out.
  const int rings = 64, sides = 32;
  const GridMesh m = tangent::testing::makeTorus(rings, sides);
  const Result r = run(m);
  double worst = 0;
  for (std::size_t c = 0; c < m.indices.size(); ++c) {
    const std::uint32_t ring = m.indices[c] / (sides + 1);
    if (ring == 0 || ring == static_cast<std::uint32_t>(rings)) continue;
    const float* p = &m.positions[3 * m.indices[c]];
    const double a = std::atan2(p[1], p[0]);
    const double dot = r.tangents[4 * c] * -std::sin(a) + r.tangents[4 * c + 1] * std::cos(a);
    worst = std::max(worst, std::acos(std::min(1.0, dot)) * 180 / M_PI);
  }
  EXPECT_LT(worst, 0.05);  // degrees: symmetric neighbourhoods cancel the chord error
}

// Same output bits when the faces come in another order or each triangle's corners rotate.
TEST(Core, FaceOrderAndCornerRotationDoNotChangeBits) {
  for (const GridMesh& m : {tangent::testing::makeSphere(20, 10), tangent::testing::makeGrid(9, 9, true)}) {
    for (auto method : {tangent::Method::mikktspace, tangent::Method::lengyel, tangent::Method::flat}) {
      Options options;
      options.method = method;
      const Result reference = run(m, options);
      const auto shuffled = tangent::testing::shuffleFacesAndRotateCorners(m, 7);
      const Result r = run(shuffled.mesh, options);
      for (std::size_t c = 0; c < shuffled.originalCorner.size(); ++c) {
        for (int j = 0; j < 4; ++j) {
          ASSERT_EQ(std::bit_cast<std::uint32_t>(r.tangents[4 * c + j]),
                    std::bit_cast<std::uint32_t>(reference.tangents[4 * shuffled.originalCorner[c] + j]));
        }
      }
    }
  }
}

TEST(Core, DegenerateAndZeroUvTrianglesAreCountedAndGetFrames) {
  GridMesh m = quad();
  // A zero-area triangle (repeated position) and a zero-UV-area triangle sharing vertex 2.
  m.positions.insert(m.positions.end(), {1, 1, 0, 2, 1, 0, 2, 2, 0});
  m.normals.insert(m.normals.end(), {0, 0, 1, 0, 0, 1, 0, 0, 1});
  m.uvs.insert(m.uvs.end(), {1, 1, 1, 1, 1, 1});
  m.indices.insert(m.indices.end(), {2, 4, 1});   // collapses: vertex 4 sits on vertex 2
  m.indices.insert(m.indices.end(), {2, 5, 6});   // real triangle, all UVs equal
  const Result r = run(m);
  expectValidFrames(m, r);
  EXPECT_EQ(r.report.degenerateTriangles, 1u);
  EXPECT_EQ(r.report.zeroUvAreaTriangles, 1u);
  EXPECT_GT(r.report.fallbackFromNeighbours, 0u);
  // The corner at vertex 2 of the zero-UV triangle inherits the quad's frame there.
  expectTangent(r, 9, 1, 0, 0, -1);
}

TEST(Core, NonFiniteInputIsReportedAndContained) {
  GridMesh m = tangent::testing::makeGrid(4, 4, false);
  m.positions[3 * 12] = std::numeric_limits<float>::quiet_NaN();
  m.uvs[2 * 3] = std::numeric_limits<float>::infinity();
  m.normals[3 * 20] = std::numeric_limits<float>::quiet_NaN();
  const Result r = run(m);
  EXPECT_GT(r.report.nonFiniteTriangles, 0u);
  EXPECT_GT(r.report.invalidNormals, 0u);
  for (std::size_t c = 0; c < m.indices.size(); ++c) {
    const float* t = &r.tangents[4 * c];
    ASSERT_TRUE(std::isfinite(t[0]) && std::isfinite(t[1]) && std::isfinite(t[2]));
    ASSERT_NEAR(std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]), 1.0f, 1e-6);
    ASSERT_TRUE(t[3] == 1.0f || t[3] == -1.0f);
  }
  // Corners far from the bad vertices are exactly what a clean mesh gives.
  const Result clean = run(tangent::testing::makeGrid(4, 4, false));
  EXPECT_EQ(std::vector<float>(r.tangents.end() - 8, r.tangents.end()), std::vector<float>(clean.tangents.end() - 8, clean.tangents.end()));
}

TEST(Core, NonManifoldFacesAreKeptAndCounted) {
  // Three triangles on the edge (0,1): OpenMesh refuses the third; it keeps its own vertices.
  GridMesh m;
  m.positions = {0, 0, 0, 1, 0, 0, 0.5f, 1, 0, 0.5f, -1, 0, 0.5f, 0, 1};
  m.normals = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
  m.uvs = {0, 0, 1, 0, 0.5f, 1, 0.5f, -1, 0.5f, 0.5f};
  m.indices = {0, 1, 2, 1, 0, 3, 0, 1, 4};
  tangent::CornerMesh cornerMesh = tangent::buildCornerMesh({m.positions, m.normals, m.uvs, m.indices});
  EXPECT_EQ(cornerMesh.mesh.n_faces(), 3u);
  EXPECT_EQ(cornerMesh.nonManifoldFaces, 1u);
  const Result r = run(m);
  EXPECT_EQ(r.report.nonManifoldFaces, 3u);  // every face on an edge that three faces share
  EXPECT_EQ(r.report.triangles, 3u);
  for (std::size_t c = 0; c < m.indices.size(); ++c) ASSERT_TRUE(std::isfinite(r.tangents[4 * c]));
}

// Report::nonManifoldFaces as each method sees an edge (tangent.hpp). A fin of three triangles
// on one edge (one running it one way, two the other) counts for every method. Triangles
// (0,2,1), (0,2,4), (2,1,0), (2,4,1): the third is the first again (a copy for mikktspace),
// and what is left runs edge (0,2) and edge (2,4) twice the same way and never back, which the
// reference's pairing never meets, while by positions (0,2) and (1,2) have three triangles each.
TEST(Core, NonManifoldFacesAreCountedAsEachMethodSeesAnEdge) {
  GridMesh fin;
  fin.positions = {0, 0, 0, 1, 0, 0, 0.5f, 1, 0, 0.5f, -1, 0, 0.5f, 0, 1};
  fin.normals = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
  fin.uvs = {0, 0, 1, 0, 0.5f, 1, 0.5f, -1, 0.5f, 0.5f};
  fin.indices = {0, 1, 2, 1, 0, 3, 1, 0, 4};
  GridMesh soup = fin;
  soup.indices = {0, 2, 1, 0, 2, 4, 2, 1, 0, 2, 4, 1};
  for (const tangent::Method method : {tangent::Method::mikktspace, tangent::Method::lengyel, tangent::Method::flat, tangent::Method::meshopt}) {
    Options options;
    options.method = method;
    SCOPED_TRACE(static_cast<int>(method));
    EXPECT_EQ(run(fin, options).report.nonManifoldFaces, 3u);
    EXPECT_EQ(run(soup, options).report.nonManifoldFaces, method == tangent::Method::mikktspace ? 0u : 4u);
  }
}

// Faces on an edge that more than two faces share, by positions (+0 and -0 alike), counted
// the plain way: every edge of a triangle at three distinct positions in a map.
std::uint64_t nonManifoldFacesByPositions(const GridMesh& m) {
  std::map<std::array<float, 3>, std::uint32_t> positionId;
  auto idOf = [&](std::uint32_t v) {
    std::array<float, 3> p;
    for (int i = 0; i < 3; ++i) p[i] = m.positions[3 * v + i] == 0 ? 0.0f : m.positions[3 * v + i];
    return positionId.emplace(p, static_cast<std::uint32_t>(positionId.size())).first->second;
  };
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::size_t>> facesOfEdge;
  for (std::size_t t = 0; t < m.indices.size() / 3; ++t) {
    const std::uint32_t p[3] = {idOf(m.indices[3 * t]), idOf(m.indices[3 * t + 1]), idOf(m.indices[3 * t + 2])};
    if (p[0] == p[1] || p[1] == p[2] || p[0] == p[2]) continue;
    for (int k = 0; k < 3; ++k) facesOfEdge[{std::min(p[k], p[(k + 1) % 3]), std::max(p[k], p[(k + 1) % 3])}].push_back(t);
  }
  std::vector<bool> onShared(m.indices.size() / 3, false);
  for (const auto& [edge, faces] : facesOfEdge) {
    if (faces.size() > 2)
      for (std::size_t t : faces) onShared[t] = true;
  }
  return static_cast<std::uint64_t>(std::count(onShared.begin(), onShared.end(), true));
}

// A torus with a fin on an edge of every third triangle: the fin's edge vertices are copies
// (other UVs), so only the position weld joins them, and a fin on every fifth one's next edge
// too; thousands of non-manifold edges, spread over every thread's share. lengyel, meshopt
// and flat count them as the plain count does, for any thread count and face order.
TEST(Core, ManyNonManifoldEdgesCountTheSameForEveryThreadCountAndOrder) {
  GridMesh m = tangent::testing::makeTorus(128, 64);  // over 2^14 triangles: the threaded way
  const std::size_t triangles = m.indices.size() / 3;
  auto copyVertex = [&](std::uint32_t v, float du) {
    for (int i = 0; i < 3; ++i) m.positions.push_back(m.positions[3 * v + i]);
    for (int i = 0; i < 3; ++i) m.normals.push_back(m.normals[3 * v + i]);
    m.uvs.insert(m.uvs.end(), {m.uvs[2 * v] + du, m.uvs[2 * v + 1]});
    return static_cast<std::uint32_t>(m.positions.size() / 3 - 1);
  };
  for (std::size_t t = 0; t < triangles; t += 3) {
    for (int k : {0, 1}) {
      if (k == 1 && t % 5 != 0) continue;
      const std::uint32_t a = m.indices[3 * t + k], b = m.indices[3 * t + (k + 1) % 3], c = m.indices[3 * t + (k + 2) % 3];
      const std::uint32_t apex = copyVertex(c, 0.25f);
      for (int i = 0; i < 3; ++i) m.positions[3 * apex + i] += 0.05f * m.normals[3 * c + i];  // off the surface
      m.indices.insert(m.indices.end(), {copyVertex(b, 0.5f), copyVertex(a, 0.5f), apex});
    }
  }
  const std::uint64_t expected = nonManifoldFacesByPositions(m);
  ASSERT_GT(expected, 5000u);
  const auto shuffled = tangent::testing::shuffleFacesAndRotateCorners(m, 7);
  for (const tangent::Method method : {tangent::Method::lengyel, tangent::Method::meshopt, tangent::Method::flat}) {
    SCOPED_TRACE(static_cast<int>(method));
    Options options;
    options.method = method;
    for (unsigned threads : {1u, 2u, 3u, 8u}) {
      options.threads = threads;
      EXPECT_EQ(run(m, options).report.nonManifoldFaces, expected) << threads;
      EXPECT_EQ(run(shuffled.mesh, options).report.nonManifoldFaces, expected) << threads;
    }
  }
}

// A fin on a closed fan: triangle (0, 1, 4) shares the edge from vertex 0 to vertex 1 with
// the fan's (0, 1, 2), and both run it the same way. At vertex 0 every corner's next vertex
// is the previous vertex of exactly one corner, but two corners lead to the same one, so the
// links from the fin's corner run into the fan's cycle without coming back: not one fan, and
// the three faces on the edge are non-manifold.
TEST(Core, FinOnAClosedFanIsNonManifold) {
  GridMesh m;
  m.positions = {0, 0, 0, 1, 0, 0, -0.5f, 0.87f, 0, -0.5f, -0.87f, 0, 0.5f, 0.3f, 0.8f};
  for (int v = 0; v < 5; ++v) m.normals.insert(m.normals.end(), {0, 0, 1});
  for (int v = 0; v < 5; ++v) m.uvs.insert(m.uvs.end(), {0.5f + 0.4f * m.positions[3 * v], 0.5f + 0.4f * m.positions[3 * v + 1]});
  // The fin first: its corner at vertex 0 starts the walk over the links.
  m.indices = {0, 1, 4, 0, 1, 2, 0, 2, 3, 0, 3, 1};
  for (unsigned threads : {1u, 2u}) {
    Options options;
    options.threads = threads;
    const Result r = run(m, options);
    EXPECT_EQ(r.report.nonManifoldFaces, 3u);  // the fin and the two fan faces on its edge
    expectValidFrames(m, r);
  }
}

TEST(Core, ZeroNormalGetsAFrameAndIsCounted) {
  GridMesh m = quad();
  m.normals[0] = m.normals[1] = m.normals[2] = 0;
  const Result r = run(m);
  EXPECT_EQ(r.report.invalidNormals, 2u);  // vertex 0 is used by two corners
  expectTangent(r, 0, 1, 0, 0, -1);
}

TEST(Core, HalfedgeMeshHoldsCornerAttributes) {
  const GridMesh m = tangent::testing::makeGrid(3, 3, true);
  tangent::CornerMesh cornerMesh = tangent::buildCornerMesh({m.positions, m.normals, m.uvs, m.indices});
  EXPECT_EQ(cornerMesh.mesh.n_vertices(), m.positions.size() / 3);  // welded: positions are distinct
  tangent::computeTangents(cornerMesh);
  for (std::size_t c = 0; c < m.indices.size(); ++c) {
    const auto h = cornerMesh.cornerHalfedge[c];
    EXPECT_EQ(cornerMesh.mesh.to_vertex_handle(h).idx(), static_cast<int>(m.indices[c]));
    EXPECT_FLOAT_EQ(cornerMesh.mesh.texcoord2D(h)[0], m.uvs[2 * m.indices[c]]);
    EXPECT_NEAR(cornerMesh.mesh.property(cornerMesh.tangent, h).norm(), std::sqrt(2.0), 1e-6);  // |xyz|=1, |w|=1
  }
  // The same bits as the plain-array call.
  const Result arrays = run(m);
  for (std::size_t c = 0; c < m.indices.size(); ++c) {
    const auto& t = cornerMesh.mesh.property(cornerMesh.tangent, cornerMesh.cornerHalfedge[c]);
    for (int i = 0; i < 4; ++i) ASSERT_EQ(static_cast<float>(t[i]), arrays.tangents[4 * c + i]) << c;
  }
}

TEST(CoreErrors, MismatchedNormals) {
  GridMesh m = quad();
  m.normals.pop_back();
  std::vector<float> out(m.indices.size() * 4);
  EXPECT_THROW(tangent::computeCornerTangents({m.positions, m.normals, m.uvs, m.indices}, out), std::invalid_argument);
}

TEST(CoreErrors, MismatchedUvs) {
  GridMesh m = quad();
  m.uvs.push_back(0);
  std::vector<float> out(m.indices.size() * 4);
  EXPECT_THROW(tangent::computeCornerTangents({m.positions, m.normals, m.uvs, m.indices}, out), std::invalid_argument);
}

TEST(CoreErrors, IndexOutOfRange) {
  GridMesh m = quad();
  m.indices[4] = 4;
  std::vector<float> out(m.indices.size() * 4);
  EXPECT_THROW(tangent::computeCornerTangents({m.positions, m.normals, m.uvs, m.indices}, out), std::invalid_argument);
}

// The check reads the indices sixteen at a time, then one at a time: a bad index in any
// lane, in the tail, or with its top bit set (which a signed compare would miss) is found,
// and the message names the first one; the largest valid index passes.
TEST(CoreErrors, IndexOutOfRangeAnywhere) {
  const GridMesh grid = tangent::testing::makeGrid(7, 5, false);  // 210 corners: 13 blocks and a tail
  const auto vertexCount = static_cast<std::uint32_t>(grid.positions.size() / 3);
  std::vector<float> out(grid.indices.size() * 4);
  {
    GridMesh m = grid;
    m.indices[17] = vertexCount - 1;
    EXPECT_NO_THROW(tangent::computeCornerTangents({m.positions, m.normals, m.uvs, m.indices}, out));
  }
  const std::size_t last = grid.indices.size() - 1;
  for (std::size_t at : {std::size_t(0), std::size_t(5), std::size_t(16), std::size_t(31), std::size_t(100), last}) {
    for (std::uint32_t bad : {vertexCount, vertexCount + 1, 0x7FFFFFFFu, 0x80000000u, 0xFFFFFFFFu}) {
      GridMesh m = grid;
      m.indices[at] = bad;
      if (at + 7 <= last) m.indices[at + 7] = bad;  // a later one too: the first is named
      try {
        tangent::computeCornerTangents({m.positions, m.normals, m.uvs, m.indices}, out);
        ADD_FAILURE() << "index " << bad << " at " << at << " was accepted";
      } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("indices[" + std::to_string(at) + "] = " + std::to_string(bad)), std::string::npos)
            << e.what();
      }
    }
  }
}

TEST(CoreErrors, IndicesNotTriangles) {
  GridMesh m = quad();
  m.indices.pop_back();
  std::vector<float> out(m.indices.size() * 4);
  EXPECT_THROW(tangent::computeCornerTangents({m.positions, m.normals, m.uvs, m.indices}, out), std::invalid_argument);
}

TEST(CoreErrors, OutputTooSmall) {
  const GridMesh m = quad();
  std::vector<float> out(m.indices.size() * 4 - 1);
  EXPECT_THROW(tangent::computeCornerTangents({m.positions, m.normals, m.uvs, m.indices}, out), std::invalid_argument);
}

TEST(CoreNames, ParseAndPrint) {
  EXPECT_EQ(tangent::parseMethod("flat"), tangent::Method::flat);
  EXPECT_EQ(tangent::parseMethod("mikktspace"), tangent::Method::mikktspace);
  EXPECT_EQ(tangent::parseMethod("lengyel"), tangent::Method::lengyel);
  EXPECT_EQ(tangent::parseMethod("mikk"), std::nullopt);
  for (tangent::Method method : {tangent::Method::mikktspace, tangent::Method::lengyel, tangent::Method::flat})
    EXPECT_EQ(tangent::parseMethod(tangent::toString(method)), method);
  const std::optional<tangent::Weighting> weighting = tangent::parseWeighting("area");
  ASSERT_TRUE(weighting);
  EXPECT_EQ(tangent::toString(*weighting), "area");
  EXPECT_EQ(tangent::parseWeighting(""), std::nullopt);
}

}  // namespace

namespace {

// The tangent of a vertex no triangle uses is the core's own fixed frame (FrameSource::fixed):
// bake, the WebAssembly package and the kernel's fallback give the same bits.
TEST(Core, UnusedVertexTangentIsTheKernelsFixedFrame) {
  for (const std::array<float, 3> normal : {std::array<float, 3>{1, 2, 3}, {0, 0, 1}, {-0.6f, 0.0f, 0.8f}, {-0.0f, 0.6f, -0.8f}, {5, -1, 0.5f}}) {
    GridMesh m;  // one triangle with its three corners at one point: nothing to borrow
    m.positions = {1, 1, 1, 1, 1, 1, 1, 1, 1};
    m.normals = {normal[0], normal[1], normal[2], normal[0], normal[1], normal[2], normal[0], normal[1], normal[2]};
    m.uvs = {0, 0, 1, 0, 0, 1};
    m.indices = {0, 1, 2};
    std::vector<tangent::FrameSource> sources(3);
    std::vector<float> tangents(12, kGarbage);
    tangent::computeCornerTangents({m.positions, m.normals, m.uvs, m.indices}, tangents, {}, sources);
    float unused[4];
    tangent::unusedVertexTangent(normal, unused);
    EXPECT_EQ(unused[3], 1.0f);
    for (int c = 0; c < 3; ++c) {
      ASSERT_EQ(sources[c], tangent::FrameSource::fixed);
      for (int i = 0; i < 3; ++i) EXPECT_EQ(std::bit_cast<std::uint32_t>(tangents[4 * c + i]), std::bit_cast<std::uint32_t>(unused[i]));
    }
  }
  // A zero or non-finite normal counts as +z.
  float fromZero[4], fromUp[4];
  tangent::unusedVertexTangent(std::array<float, 3>{0, 0, 0}, fromZero);
  tangent::unusedVertexTangent(std::array<float, 3>{0, 0, 1}, fromUp);
  EXPECT_EQ(0, std::memcmp(fromZero, fromUp, sizeof fromZero));
}

// The valence of the discs below: large enough that quadratic work at their centre runs past
// the tests' time limit; in the sanitizer build (Debug, several times slower) a tenth of it,
// which checks the same paths for memory errors while the release build checks their time.
#ifdef __SANITIZE_ADDRESS__
constexpr std::uint32_t kDiscTriangles = 40'000;
#else
constexpr std::uint32_t kDiscTriangles = 400'000;
#endif

// A disc of `triangles` triangles around one vertex, facing +z. The first `zeroUv` of every
// `period` triangles have zero UV area: their corners are copies of their vertices with the
// centre's UV, so the centre's corners share one vertex and the rim's do not.
GridMesh discAroundOneVertex(std::uint32_t triangles, std::uint32_t period, std::uint32_t zeroUv) {
  GridMesh m;
  auto add = [&](float x, float y, float u, float v) {
    m.positions.insert(m.positions.end(), {x, y, 0});
    m.normals.insert(m.normals.end(), {0, 0, 1});
    m.uvs.insert(m.uvs.end(), {u, v});
  };
  add(0, 0, 0.5f, 0.5f);
  for (std::uint32_t copy = 0; copy < 2; ++copy) {
    for (std::uint32_t i = 0; i < triangles; ++i) {
      const double angle = 2 * std::numbers::pi * i / triangles;
      const float x = static_cast<float>(std::cos(angle)), y = static_cast<float>(std::sin(angle));
      if (copy == 0) add(x, y, 0.5f + 0.5f * x, 0.5f + 0.5f * y);
      else add(x, y, 0.5f, 0.5f);
    }
  }
  for (std::uint32_t i = 0; i < triangles; ++i) {
    const std::uint32_t rim = i % period < zeroUv ? 1 + triangles : 1;
    m.indices.insert(m.indices.end(), {0, rim + i, rim + (i + 1) % triangles});
  }
  return m;
}

// Work at a vertex is linear in its valence: the corners without a frame of their own and
// the orientation of zero-UV triangles each read the vertex once, not once per corner, and
// the rim's corners without a frame read the centre once. With 400,000 triangles, quadratic
// work took minutes per call (far past the test's time limit); linear work takes a second.
TEST(Core, AVertexOfHighValenceWithoutUvAreaGetsFrames) {
  constexpr std::uint32_t kTriangles = kDiscTriangles;
  // All without UV area; every other one; two of every four (rim vertices with none).
  for (const auto& [period, zeroUv] : {std::pair{1u, 1u}, {2u, 1u}, {4u, 2u}}) {
    const GridMesh m = discAroundOneVertex(kTriangles, period, zeroUv);
    for (tangent::Method method : {tangent::Method::mikktspace, tangent::Method::flat, tangent::Method::lengyel}) {
      SCOPED_TRACE(std::string(tangent::toString(method)) + ", " + std::to_string(zeroUv) + " of " + std::to_string(period) + " without UV area");
      Options options;
      options.method = method;
      const Result r = run(m, options);
      expectValidFrames(m, r);
      EXPECT_EQ(r.report.zeroUvAreaTriangles, kTriangles / period * zeroUv);
      EXPECT_EQ(r.report.degenerateTriangles, 0u);
    }
  }
}

// The same disc with every other triangle collapsed onto an edge (its last corner a copy of
// its second, with the centre's UV): half the centre's corners are coincident (the
// reference's degenerate triangles) and copy a frame of their vertex, found once.
TEST(Core, AVertexOfHighValenceWithHalfItsTrianglesCollapsedGetsFrames) {
  constexpr std::uint32_t kTriangles = kDiscTriangles;
  GridMesh m = discAroundOneVertex(kTriangles, 1, 0);
  for (std::uint32_t i = 0; i < kTriangles; i += 2) m.indices[3 * i + 2] = 1 + kTriangles + i;
  for (tangent::Method method : {tangent::Method::mikktspace, tangent::Method::flat, tangent::Method::lengyel}) {
    SCOPED_TRACE(tangent::toString(method));
    Options options;
    options.method = method;
    const Result r = run(m, options);
    expectValidFrames(m, r);
    EXPECT_EQ(r.report.degenerateTriangles, kTriangles / 2);
  }
}

}  // namespace
