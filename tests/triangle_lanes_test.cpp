// SPDX-License-Identifier: MIT
// White-box tests of the double triangle pass of lengyel, meshopt and flat in vector lanes
// (triangle_tangent_lanes.cpp): every field, corner angle and flat frame of every lane has the
// bits of the scalar functions (triangleTangent, cornerAngle, flatTriangleFrames,
// projectedEdgeWeight) on random and
// extreme triangles; and angleOf, the deterministic atan2 the weights use, against libm's.
// The whole-call tests (Workspace.SameBitsForEveryVectorWidth) compare only the float outputs,
// which a one-ulp change of a weight almost never moves: these compare the doubles.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "lengyel.hpp"
#include "triangle_tangent.hpp"

namespace {

using tangent::detail::FlatLanes;
using tangent::detail::TriangleKind;
using tangent::detail::TriangleLanes;
using tangent::detail::TriangleSource;
using tangent::detail::TriangleTangent;
using tangent::detail::Vec2;
using tangent::detail::Vec3;

std::uint64_t bits(double x) { return std::bit_cast<std::uint64_t>(x); }

// The widths this build and processor run.
std::vector<int> laneWidths() {
  std::vector<int> widths{1, 2};  // 1: triangleTangentsAt's scalar way
#if defined(TANGENT_DOUBLE_LANES4)
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx2")) widths.push_back(4);
#endif
  return widths;
}

// Random triangles with the cases the pass tells apart: ordinary, slivers, coincident and
// collinear corners, zero and mirrored UV area, +0/-0, huge and tiny scales, NaN and infinity.
struct Soup {
  std::vector<float> positions, uvs;
  std::vector<std::uint32_t> indices, weld;
};

Soup randomSoup(std::size_t triangles, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::uniform_int_distribution<int> pick(0, 15);
  Soup soup;
  for (std::size_t t = 0; t < triangles; ++t) {
    const int kind = pick(random);
    const float scale = kind == 1 ? 1e30f : kind == 2 ? 1e-30f : kind == 3 ? 1e5f : 1.0f;
    float p[3][3], uv[3][2];
    for (int k = 0; k < 3; ++k) {
      for (int a = 0; a < 3; ++a) p[k][a] = unit(random) * scale;
      for (int a = 0; a < 2; ++a) uv[k][a] = unit(random);
    }
    if (kind == 4) std::copy(p[0], p[0] + 3, p[2]);  // coincident corners
    if (kind == 5) {                                // collinear
      for (int a = 0; a < 3; ++a) p[2][a] = p[0][a] + 2.0f * (p[1][a] - p[0][a]);
    }
    if (kind == 6) std::copy(uv[0], uv[0] + 2, uv[1]);  // zero UV area
    if (kind == 7) p[1][2] = -0.0f, p[0][2] = 0.0f;     // signed zeros
    if (kind == 8) p[2][1] = std::numeric_limits<float>::quiet_NaN();
    if (kind == 9) uv[1][0] = std::numeric_limits<float>::infinity();
    if (kind == 10) {  // a sliver: the third corner just off the first edge
      for (int a = 0; a < 3; ++a) p[2][a] = 0.5f * (p[0][a] + p[1][a]);
      p[2][0] += 1e-6f;
    }
    if (kind == 11) std::swap(uv[1], uv[2]);  // the other orientation
    for (int k = 0; k < 3; ++k) {
      const auto vertex = static_cast<std::uint32_t>(soup.weld.size());
      soup.positions.insert(soup.positions.end(), p[k], p[k] + 3);
      soup.uvs.insert(soup.uvs.end(), uv[k], uv[k] + 2);
      soup.indices.push_back(vertex);
      soup.weld.push_back(vertex);
    }
  }
  // Corners in shuffled vertex order, and one vertex in five read at another's position (its
  // weld representative), so that a read of the position at the vertex or of the UV at the
  // representative gives other values.
  std::vector<std::uint32_t> order(soup.weld.size());
  for (std::size_t v = 0; v < order.size(); ++v) order[v] = static_cast<std::uint32_t>(v);
  std::shuffle(order.begin(), order.end(), random);
  for (std::uint32_t& index : soup.indices) index = order[index];
  std::uniform_int_distribution<std::uint32_t> anyVertex(0, static_cast<std::uint32_t>(soup.weld.size() - 1));
  for (std::size_t v = 0; v < soup.weld.size(); v += 5) soup.weld[v] = anyVertex(random);
  return soup;
}

// Triangle t's positions (at its vertices' representatives) and UVs (at its vertices), as the
// lanes must read them.
void trianglesCorners(const Soup& soup, std::size_t t, std::array<Vec3, 3>& positions, std::array<Vec2, 3>& uvs) {
  for (int k = 0; k < 3; ++k) {
    const std::uint32_t vertex = soup.indices[3 * t + k];
    const float* p = &soup.positions[3 * std::size_t(soup.weld[vertex])];
    positions[k] = {p[0], p[1], p[2]};
    uvs[k] = {soup.uvs[2 * std::size_t(vertex)], soup.uvs[2 * std::size_t(vertex) + 1]};
  }
}

// Every triangle of `soup` through triangleTangentsAt on `width` lanes, four at a time (no face
// normals): each(first, count, triangles) per block, with `values` as the lanes left them.
template <class Each>
void forEachBlock(const Soup& soup, int width, TriangleLanes& values, const Each& each) {
  const TriangleSource source{soup.positions.data(), soup.uvs.data(), soup.indices.data(), soup.weld.data()};
  const std::size_t triangleCount = soup.indices.size() / 3;
  TriangleTangent triangles[4];
  const bool wantFaceNormal[4] = {false, false, false, false};
  for (std::size_t first = 0; first < triangleCount; first += 4) {
    const int count = static_cast<int>(std::min<std::size_t>(4, triangleCount - first));
    tangent::detail::triangleTangentsAt(source, first, count, wantFaceNormal, width, values, triangles);
    each(first, count, triangles);
  }
}

void expectSameBits(const Vec3& a, const Vec3& b, const char* what, std::size_t t) {
  for (int i = 0; i < 3; ++i) EXPECT_EQ(bits(a[i]), bits(b[i])) << what << " of triangle " << t << ", axis " << i;
}

TEST(TriangleLanes, EveryLaneHasTheScalarBits) {
  const Soup soup = randomSoup(20003, 7);  // not a multiple of 4: a short last block
  const TriangleSource source{soup.positions.data(), soup.uvs.data(), soup.indices.data(), soup.weld.data()};
  const std::size_t triangleCount = soup.indices.size() / 3;
  std::size_t usable = 0, compared = 0;
  for (const int width : laneWidths()) {
    SCOPED_TRACE("lanes " + std::to_string(width));
    TriangleLanes values{};
    values.wantAngles = true;
    TriangleTangent lanes[4];
    for (std::size_t first = 0; first < triangleCount; first += 4) {
      const int count = static_cast<int>(std::min<std::size_t>(4, triangleCount - first));
      const bool wantFaceNormal[4] = {first % 3 == 0, true, false, true};
      tangent::detail::triangleTangentsAt(source, first, count, wantFaceNormal, width, values, lanes);
      for (int i = 0; i < count; ++i) {
        const std::size_t t = first + i;
        std::array<Vec3, 3> positions;
        std::array<Vec2, 3> uvs;
        trianglesCorners(soup, t, positions, uvs);
        const TriangleTangent scalar = tangent::detail::triangleTangent(positions, uvs, wantFaceNormal[i]);
        ASSERT_EQ(lanes[i].kind, scalar.kind) << "triangle " << t;
        EXPECT_EQ(lanes[i].orientation, scalar.orientation) << "triangle " << t;
        EXPECT_EQ(lanes[i].coincident, scalar.coincident) << "triangle " << t;
        EXPECT_EQ(bits(lanes[i].area), bits(scalar.area)) << "triangle " << t;
        expectSameBits(lanes[i].tangent, scalar.tangent, "tangent", t);
        expectSameBits(lanes[i].bitangent, scalar.bitangent, "bitangent", t);
        expectSameBits(lanes[i].faceNormal, scalar.faceNormal, "face normal", t);
        ++compared;
        if (scalar.kind != TriangleKind::usable) continue;
        ++usable;
        for (int k = 0; k < 3; ++k) {
          if (width > 1) {  // the scalar way leaves the angles to cornerAngle
            EXPECT_EQ(bits(values.cornerAngle(i, k)), bits(tangent::detail::cornerAngle(positions, k)))
                << "angle at corner " << k << " of triangle " << t;
          }
          expectSameBits(values.position(i, k), positions[k], "position", t);
        }
      }
    }
  }
  EXPECT_EQ(compared, triangleCount * laneWidths().size());
  EXPECT_GT(usable, compared / 3) << "the soup should be mostly usable triangles";
}

TEST(TriangleLanes, FlatFramesHaveTheScalarBits) {
  const Soup soup = randomSoup(8001, 11);
  const std::size_t triangleCount = soup.indices.size() / 3;
  std::mt19937 random(3);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (const int width : laneWidths()) {
    SCOPED_TRACE("lanes " + std::to_string(width));
    TriangleLanes values{};
    FlatLanes flat{};
    std::size_t framed = 0;
    forEachBlock(soup, width, values, [&](std::size_t first, int count, const TriangleTangent* triangles) {
      Vec3 normals[4][3];
      for (int i = 0; i < 4; ++i) {
        flat.usable[i] = i < count && triangles[i].kind == TriangleKind::usable;
        if (i >= count) continue;
        for (int k = 0; k < 3; ++k) {  // unit normals, one in eight nearly along the tangent
          Vec3 n(unit(random), unit(random), unit(random));
          if ((first + i + k) % 8 == 0) n = triangles[i].tangent + Vec3(1e-9, 0, 0);
          normals[i][k] = n / n.norm();
          for (int a = 0; a < 3; ++a) flat.normal[k][a][i] = normals[i][k][a];
        }
        for (int a = 0; a < 3; ++a) {
          flat.tangent[a][i] = triangles[i].tangent[a];
          flat.bitangent[a][i] = triangles[i].bitangent[a];
        }
        flat.uvSide[i] = triangles[i].orientation < 0 ? -1.0 : 1.0;
      }
      tangent::detail::flatFrameLanes(flat, width);
      for (int i = 0; i < count; ++i) {
        const tangent::detail::TriangleTerms terms{triangles[i].tangent, triangles[i].bitangent, triangles[i].orientation,
                                                   triangles[i].kind};
        const bool invalid[3] = {false, false, false};
        float scalar[12] = {};
        std::uint8_t state[3] = {};
        tangent::detail::flatTriangleFrames(terms, normals[i], invalid, scalar, state, 0);
        for (int k = 0; k < 3; ++k) {
          const bool scalarFramed = (state[k] & tangent::detail::kUndefined) == 0;
          ASSERT_EQ(flat.framed[k][i], scalarFramed) << "corner " << k << " of triangle " << first + i;
          if (!scalarFramed) continue;
          ++framed;
          for (int a = 0; a < 3; ++a) {
            EXPECT_EQ(std::bit_cast<std::uint32_t>(static_cast<float>(flat.frame[k][a][i])),
                      std::bit_cast<std::uint32_t>(scalar[4 * k + a]))
                << "corner " << k << " of triangle " << first + i;
          }
          EXPECT_EQ(static_cast<float>(flat.w[k][i]), scalar[4 * k + 3]) << "w, corner " << k << " of triangle " << first + i;
        }
      }
    });
    EXPECT_GT(framed, triangleCount);
  }
}

TEST(TriangleLanes, MeshoptWeightsHaveTheScalarBits) {
  const Soup soup = randomSoup(8002, 13);
  const std::size_t triangleCount = soup.indices.size() / 3;
  std::mt19937 random(4);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (const int width : laneWidths()) {
    SCOPED_TRACE("lanes " + std::to_string(width));
    TriangleLanes values{};
    tangent::detail::MeshoptLanes lanes{};
    std::size_t weighted = 0;
    forEachBlock(soup, width, values, [&](std::size_t first, int count, const TriangleTangent* triangles) {
      Vec3 normals[4][3];
      for (int i = 0; i < count; ++i) {
        for (int k = 0; k < 3; ++k) {  // unit normals, one in eight along an edge (a zero projection)
          Vec3 n(unit(random), unit(random), unit(random));
          if ((first + i + k) % 8 == 0) n = values.position(i, (k + 1) % 3) - values.position(i, k);
          normals[i][k] = n / n.norm();
          for (int a = 0; a < 3; ++a) lanes.normal[(k - values.start[i] + 3) % 3][a][i] = normals[i][k][a];
        }
        for (int a = 0; a < 3; ++a) lanes.tangent[a][i] = triangles[i].tangent[a];
      }
      tangent::detail::meshoptWeightLanes(values, lanes, width);
      for (int i = 0; i < count; ++i) {
        if (triangles[i].kind != TriangleKind::usable) continue;  // weighted 0 without the lanes
        std::array<Vec3, 3> positions;
        for (int k = 0; k < 3; ++k) positions[k] = values.position(i, k);
        for (int k = 0; k < 3; ++k) {
          const double scalar = tangent::detail::projectedEdgeWeight(positions, k, normals[i][k], triangles[i].tangent);
          EXPECT_EQ(bits(lanes.weight[(k - values.start[i] + 3) % 3][i]), bits(scalar))
              << "corner " << k << " of triangle " << first + i;
          weighted += scalar > 0;
        }
      }
    });
    EXPECT_GT(weighted, triangleCount);
  }
}

TEST(TriangleLanes, AngleOfIsWithinTwoUlpsOfLibm) {
  using tangent::detail::angleOf;
  const double pi = std::numbers::pi;
  EXPECT_EQ(angleOf(1, 0), pi / 2);
  EXPECT_EQ(angleOf(0, -1), pi);
  EXPECT_EQ(bits(angleOf(0, 1)), bits(0.0));
  EXPECT_EQ(angleOf(1, 1), pi / 4);
  EXPECT_TRUE(std::isnan(angleOf(0, 0)));
  std::mt19937_64 random(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0), exponent(-8.0, 8.0);
  std::size_t same = 0;
  const std::size_t samples = 200000;
  for (std::size_t i = 0; i < samples; ++i) {
    const double y = unit(random) * std::pow(10.0, exponent(random));
    const double x = (unit(random) - 0.5) * std::pow(10.0, exponent(random));
    const double ours = angleOf(y, x), libm = std::atan2(y, x);
    const auto distance = std::bit_cast<std::int64_t>(ours) - std::bit_cast<std::int64_t>(libm);
    ASSERT_LE(std::abs(distance), 2) << "angleOf(" << y << ", " << x << ") = " << ours << ", atan2 " << libm;
    same += distance == 0;
  }
  EXPECT_GT(same, samples / 2) << "most should be libm's bits";
}

}  // namespace
