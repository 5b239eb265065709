// SPDX-License-Identifier: MIT
// tangent/framing.hpp: which triangles a check flags and the camera target around them, on
// hand-made draw items whose boxes and sides are worked out by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "tangent/framing.hpp"

namespace {

using tangent::gltf::CheckId;
using tangent::gltf::DrawItem;

constexpr std::array<float, 16> kIdentity{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

// Eight triangles in a row along x on z = 0, each 1 wide: triangle t spans x in [t, t + 1],
// y in [0, 1]; normals +z; tangents +x with w = 1.
DrawItem row() {
  DrawItem item;
  for (int t = 0; t < 8; ++t) {
    const float corners[3][2] = {{float(t), 0}, {float(t + 1), 0}, {float(t + 1), 1}};
    for (const auto& c : corners) {
      item.positions.insert(item.positions.end(), {c[0], c[1], 0});
      item.normals.insert(item.normals.end(), {0, 0, 1});
      item.tangents.insert(item.tangents.end(), {1, 0, 0, 1});
    }
  }
  item.cornerProblems.assign(24, 0);
  return item;
}

TEST(Framing, EachCheckFlagsTheTrianglesOfItsCornerBit) {
  DrawItem item = row();
  item.cornerProblems[4] = tangent::gltf::kProblemFarFromReference;                           // triangle 1
  item.cornerProblems[9] = tangent::gltf::kProblemNotUnit | tangent::gltf::kProblemBadW;  // triangle 3
  EXPECT_EQ(tangent::gltf::flaggedTriangles(item, CheckId::reference), (std::vector<std::uint8_t>{0, 1, 0, 0, 0, 0, 0, 0}));
  EXPECT_EQ(tangent::gltf::flaggedTriangles(item, CheckId::unit), (std::vector<std::uint8_t>{0, 0, 0, 1, 0, 0, 0, 0}));
  EXPECT_EQ(tangent::gltf::flaggedTriangles(item, CheckId::w), (std::vector<std::uint8_t>{0, 0, 0, 1, 0, 0, 0, 0}));
  EXPECT_EQ(tangent::gltf::flaggedTriangles(item, CheckId::orthogonal), (std::vector<std::uint8_t>(8, 0)));
  EXPECT_EQ(tangent::gltf::flaggedTriangles(item, std::nullopt), (std::vector<std::uint8_t>{0, 1, 0, 1, 0, 0, 0, 0}));
  EXPECT_EQ(tangent::gltf::flaggedTriangles(item, CheckId::present), (std::vector<std::uint8_t>(8, 0)));
}

TEST(Framing, WUniformFlagsTrianglesWhoseCornersDisagreeInW) {
  DrawItem item = row();
  item.tangents[4 * 7 + 3] = -1;  // triangle 2's second corner
  EXPECT_EQ(tangent::gltf::flaggedTriangles(item, CheckId::wUniform), (std::vector<std::uint8_t>{0, 0, 1, 0, 0, 0, 0, 0}));
}

TEST(Framing, TheBoxIsTheFlaggedTrianglesGrownToTheMinimumShareSeenFromTheirSide) {
  const DrawItem item = row();
  // The row's box is 8 x 1 x 0: half-diagonal sqrt(65)/2, so every half-extent is at least
  // kMinFrameShare * sqrt(65) / 2 / sqrt(3) (0.93, more than the triangle's 0.5).
  const float minHalf = tangent::gltf::kMinFrameShare * std::sqrt(65.0f) / 2 / std::sqrt(3.0f);
  const std::vector<std::uint8_t> flagged{0, 0, 1, 0, 0, 0, 0, 0};  // x in [2, 3], y in [0, 1]
  const auto framing = tangent::gltf::frameTriangles(item, kIdentity, flagged);
  ASSERT_TRUE(framing);
  EXPECT_EQ(framing->flaggedTriangles, 1u);
  EXPECT_EQ(framing->camera, "front");  // the normals face +z
  EXPECT_FLOAT_EQ(framing->lo[0], 2.5f - minHalf);
  EXPECT_FLOAT_EQ(framing->hi[0], 2.5f + minHalf);
  EXPECT_FLOAT_EQ(framing->lo[2], -minHalf);
  EXPECT_FLOAT_EQ(framing->hi[2], minHalf);

  // In world space: a node turned 90 deg about y (x -> -z, z -> x) and moved by +10 in y.
  const std::array<float, 16> turned{0, 0, -1, 0, 0, 1, 0, 0, 1, 0, 0, 0, 0, 10, 0, 1};
  const auto moved = tangent::gltf::frameTriangles(item, turned, flagged);
  ASSERT_TRUE(moved);
  EXPECT_EQ(moved->camera, "right");  // the normals now face +x
  EXPECT_FLOAT_EQ(moved->lo[2], -2.5f - minHalf);
  EXPECT_FLOAT_EQ(moved->lo[1], 10.5f - minHalf);
}

TEST(Framing, NothingFlaggedFramesThePrimitiveAndNoFinitePositionNothing) {
  DrawItem item = row();
  const auto whole = tangent::gltf::frameTriangles(item, kIdentity, std::vector<std::uint8_t>(8, 0));
  ASSERT_TRUE(whole);
  EXPECT_EQ(whole->flaggedTriangles, 0u);
  EXPECT_FLOAT_EQ(whole->lo[0], 0.0f);
  EXPECT_FLOAT_EQ(whole->hi[0], 8.0f);
  EXPECT_EQ(whole->camera, "iso");  // nothing flagged: no normals to face
  for (float& p : item.positions) p = NAN;
  EXPECT_FALSE(tangent::gltf::frameTriangles(item, kIdentity, std::vector<std::uint8_t>(8, 1)));
  EXPECT_FALSE(tangent::gltf::frameTriangles(DrawItem{}, kIdentity, {}));
}

}  // namespace
