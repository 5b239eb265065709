// SPDX-License-Identifier: MIT
// The stress suite: every stiff or extreme case, every method: finite, unit (1e-6), orthogonal
// to the normal (1e-5), w exactly +-1, the same bits on every run, broken input contained.
#include <gtest/gtest.h>

#include "stress_cases.hpp"

namespace {

class Stress : public ::testing::TestWithParam<tangent::Method> {};

TEST_P(Stress, EveryCaseKeepsTheInvariants) {
  tangent::Options options;
  options.method = GetParam();
  for (const auto& stressCase : tangent::bench::stressCases()) {
    SCOPED_TRACE(stressCase.name);
    const auto outcome = tangent::bench::runStressCase(stressCase, options);
    EXPECT_EQ(outcome.notFinite, 0u);
    EXPECT_EQ(outcome.notUnit, 0u);
    EXPECT_EQ(outcome.notOrthogonal, 0u);
    EXPECT_EQ(outcome.badW, 0u);
    EXPECT_EQ(outcome.changedOnRerun, 0u);
    EXPECT_EQ(outcome.changedAwayFromBrokenInput, 0u);
    EXPECT_EQ(outcome.report.corners, stressCase.indices.size());
  }
}

INSTANTIATE_TEST_SUITE_P(Methods, Stress,
                         ::testing::Values(tangent::Method::mikktspace, tangent::Method::lengyel, tangent::Method::flat,
                                           tangent::Method::meshopt),
                         [](const auto& param) { return std::string(tangent::toString(param.param)); });

// Where a frame cannot be defined, the report says so instead of hiding it.
TEST(StressReport, UndefinedFramesAreCounted) {
  for (const auto& stressCase : tangent::bench::stressCases()) {
    const auto outcome = tangent::bench::runStressCase(stressCase, {});
    if (stressCase.name == "UV area exactly zero" || stressCase.name == "collinear UVs") {
      EXPECT_EQ(outcome.report.zeroUvAreaTriangles, stressCase.indices.size() / 3) << stressCase.name;
      EXPECT_EQ(outcome.undefinedCorners, stressCase.indices.size()) << stressCase.name;
    }
    if (stressCase.name == "offset 1e7, edges 1e-2") {
      EXPECT_GT(outcome.report.degenerateTriangles, 0u) << "float32 collapses 1e-2 edges at 1e7";
    }
    if (stressCase.name == "NaN position") {
      EXPECT_GT(outcome.report.nonFiniteTriangles, 0u);
    }
    if (stressCase.name == "NaN normal") {
      EXPECT_GT(outcome.report.invalidNormals, 0u);
    }
    if (stressCase.name.rfind("UV area 1e-", 0) == 0 || stressCase.name.rfind("scaled by", 0) == 0 ||
        stressCase.name == "denormal coordinates" || stressCase.name.rfind("slivers", 0) == 0) {
      EXPECT_EQ(outcome.undefinedCorners, 0u) << stressCase.name << ": tiny but valid triangles keep their frames";
    }
  }
}

}  // namespace
