// SPDX-License-Identifier: MIT
// weldPackedCorners (viewer/vertex_weld.hpp): corners equal bit for bit share one vertex, in order of
// first use, and the indices give back every corner exactly.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "vertex_weld.hpp"

namespace {

// Corners already packed (stride floats each), welded as the viewer welds them while packing.
tangent::viewer::WeldedVertices weldVertices(const std::vector<float>& corners, int stride) {
  return tangent::viewer::weldPackedCorners(corners.size() / stride, stride, [&](std::size_t c, float* out) {
    std::memcpy(out, &corners[c * stride], stride * sizeof(float));
  });
}

// Two triangles of a quad, as corners of 3 floats: the diagonal's two corners appear twice.
TEST(VertexWeld, SharedCornersBecomeOneVertexInOrderOfFirstUse) {
  const std::vector<float> corners = {0, 0, 0, 1, 0, 0, 1, 1, 0,   // a b c
                                      0, 0, 0, 1, 1, 0, 0, 1, 0};  // a c d
  const auto welded = weldVertices(corners, 3);
  EXPECT_EQ(welded.indices, (std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3}));
  EXPECT_EQ(welded.vertices, (std::vector<float>{0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}));
}

// Equal as numbers is not enough: -0 and 0 stay apart, a NaN is welded to the same NaN bits.
TEST(VertexWeld, EqualityIsBitwise) {
  const float nan = std::nanf("");
  const std::vector<float> corners = {0.0f, 1, -0.0f, 1, nan, 2, nan, 2, 0.0f, 1};
  const auto welded = weldVertices(corners, 2);
  EXPECT_EQ(welded.indices, (std::vector<std::uint32_t>{0, 1, 2, 2, 0}));
  ASSERT_EQ(welded.vertices.size(), 6u);
  EXPECT_TRUE(std::signbit(welded.vertices[2]));
}

// Many corners, each vertex used by several: every corner comes back from its index exactly.
TEST(VertexWeld, IndicesGiveBackEveryCorner) {
  constexpr int kStride = 5;
  std::vector<float> corners;
  for (int c = 0; c < 30000; ++c) {
    const int vertex = (c * 7919) % 4999;  // 4999 distinct vertices, each used 6 times
    for (int k = 0; k < kStride; ++k) corners.push_back(static_cast<float>(vertex) * 0.5f + static_cast<float>(k));
  }
  const auto welded = weldVertices(corners, kStride);
  EXPECT_EQ(welded.vertices.size(), 4999u * kStride);
  ASSERT_EQ(welded.indices.size(), 30000u);
  for (std::size_t c = 0; c < welded.indices.size(); ++c)
    ASSERT_EQ(std::memcmp(&welded.vertices[welded.indices[c] * kStride], &corners[c * kStride], kStride * sizeof(float)), 0) << c;
}

// Welding while packing, a block of 16 at a time: repeats inside one block, across blocks and in
// a last short block weld to their first use; pack is called once per corner, in order.
TEST(VertexWeld, WeldingWhilePackingIsWeldingThePackedCorners) {
  constexpr int kStride = 3;
  std::vector<float> corners;
  const int pattern[] = {0, 1, 0, 2, 2, 3, 1, 4, 5, 0, 6, 7, 7, 8, 9, 3, /* block 2 */ 3, 10, 0, 11, 11, 11, 12, 4, 13, 14, 15, 15, 16, 1, 17, 2, 18};
  for (const int vertex : pattern)
    for (int k = 0; k < kStride; ++k) corners.push_back(static_cast<float>(vertex) + 0.25f * static_cast<float>(k));
  const std::size_t count = corners.size() / kStride;
  std::vector<std::size_t> calls;
  const auto packed = tangent::viewer::weldPackedCorners(count, kStride, [&](std::size_t c, float* out) {
    calls.push_back(c);
    std::memcpy(out, &corners[c * kStride], kStride * sizeof(float));
  });
  // The expected indices: each pattern value's rank in order of first use, counted here.
  std::vector<int> firstUse;
  std::vector<std::uint32_t> expected;
  for (const int vertex : pattern) {
    auto at = std::find(firstUse.begin(), firstUse.end(), vertex);
    if (at == firstUse.end()) at = firstUse.insert(firstUse.end(), vertex);
    expected.push_back(static_cast<std::uint32_t>(at - firstUse.begin()));
  }
  EXPECT_EQ(packed.indices, expected);
  std::vector<float> expectedVertices;  // each distinct vertex's floats, in order of first use
  for (const int vertex : firstUse)
    for (int k = 0; k < kStride; ++k) expectedVertices.push_back(static_cast<float>(vertex) + 0.25f * static_cast<float>(k));
  EXPECT_EQ(packed.vertices, expectedVertices);
  EXPECT_EQ(packed.vertices.size(), 19u * kStride);  // vertices 0..18, in order of first use
  ASSERT_EQ(calls.size(), count);
  for (std::size_t c = 0; c < count; ++c) EXPECT_EQ(calls[c], c);
}

}  // namespace
