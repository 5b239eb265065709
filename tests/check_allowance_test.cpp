// SPDX-License-Identifier: MIT
// check's rounding allowance is tight, not only loose enough (issue 68). Each bound that
// `reference` derives from a component type is held between an independent estimate of what
// the rounding can do and a stated factor of it:
//  - the input allowance's coarse and fine bounds (reference_allowance.cpp, referenceAllowance) on
//    positions and UVs stored as normalized BYTE / SHORT, on a grid, slivers, a sphere's poles
//    and mirrored islands: the estimate moves the stored values within half a step (random
//    and worst-corner moves), recomputes the fresh tangents and keeps each vertex's largest
//    angle change;
//  - a stored vector's direction error (storedVectorRounding's angle, added for TANGENT and
//    NORMAL): the vector itself, and the fresh tangents when stored normals are moved.
// The boundary controls through `tangent check` on written files are in check_quantized_test.cpp.
// Deterministic (fixed seeds), and small enough for the sanitizer build.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "read/primitive.hpp"
#include "support/test_assets.hpp"
#include "tangent/tangent.hpp"
#include "check/tangent_rules.hpp"

namespace {

namespace detail = tangent::gltf::detail;
using tangent::testing::GridMesh;

// The stated factors (docs/check.md, "How tight the allowance is"): at the vertex where the
// rounding comes closest to a bound, the estimate reaches at least 1/factor of it. Each is
// below twice the loosest measured ratio and above it, so that a bound doubled or halved fails.
//  - fine: asin(1.25 E / |S|), E the sum of the inputs' |dS_j|: 1.25 for the second order, and
//    each input's move counted at full length although only its part across S turns S:
//    stated 2 (measured 1.05 to 1.78).
//  - coarse: each triangle's tangent turned by its own worst case, 2 eu (|e1| + |e2|) for
//    |e1 dv2' - e2 dv1'| which a right-angled triangle reaches only to sqrt(2) of, and the
//    triangles' worst cases added although no one move of the inputs gives them all:
//    stated 2.5 (measured 1.42 to 2.20).
//  - a stored vector's direction, asin(sqrt(3) e): reached where the error box's corner lies
//    across the vector; a fresh tangent follows its normal's tilt along the tangent only,
//    sqrt(2) e of sqrt(3) e on an axis-aligned frame: stated 1.5 for NORMAL (measured 1.22 to
//    1.39), 1.1 for TANGENT itself.
constexpr double kFineFactor = 2.0;
constexpr double kCoarseFactor = 2.5;
constexpr double kNormalFactor = 1.5;
constexpr double kTangentFactor = 1.1;

struct InputType {
  const char* name;
  double position;  // half a step: normalized BYTE / SHORT positions
  double uv;        // normalized UNSIGNED_BYTE / UNSIGNED_SHORT UVs
};
constexpr InputType kInputTypes[] = {{"BYTE", 0.5 / 127, 0.5 / 255}, {"SHORT", 0.5 / 32767, 0.5 / 65535}};

struct Shape {
  std::string name;
  GridMesh mesh;
};

std::vector<Shape> shapes() {
  GridMesh slivers = tangent::testing::makeGrid(8, 4, false);
  for (std::size_t v = 0; v < slivers.positions.size() / 3; ++v) slivers.positions[3 * v + 1] *= 0.05f;  // 40:1 in 3D, square in UV
  return {{"grid", tangent::testing::makeGrid(8, 8, false)},
          {"slivers", slivers},
          {"poles", tangent::testing::makeSphere(12, 6)},
          {"mirrored", tangent::testing::makeGrid(8, 8, true)}};
}

float roundTo(float value, double halfStep) { return static_cast<float>(std::round(value / (2 * halfStep)) * 2 * halfStep); }

// The mesh as a quantizing tool stores it: positions and UVs on their grids.
detail::PrimitiveGeometry storedGeometry(const GridMesh& mesh, const InputType& type) {
  detail::PrimitiveGeometry g;
  g.vertexCount = mesh.positions.size() / 3;
  g.positions = mesh.positions;
  g.normals = mesh.normals;
  g.uvs = mesh.uvs;
  g.corners = mesh.indices;
  for (float& x : g.positions) x = roundTo(x, type.position);
  for (float& x : g.uvs) x = roundTo(x, type.uv);
  return g;
}

std::vector<float> freshTangents(const detail::PrimitiveGeometry& g) {
  std::vector<float> corners(4 * g.corners.size());
  tangent::Options options;
  options.uvOrigin = tangent::kGltfUvOrigin;
  options.threads = 1;
  tangent::computeCornerTangents({g.positions, g.normals, g.uvs, g.corners}, corners, options);
  return corners;
}

// The turn from a to b about n, signed.
double signedTurnDegrees(const float* a, const float* b, const float* n) {
  const double cross[3] = {double(a[1]) * b[2] - double(a[2]) * b[1], double(a[2]) * b[0] - double(a[0]) * b[2],
                           double(a[0]) * b[1] - double(a[1]) * b[0]};
  const double along = cross[0] * n[0] + cross[1] * n[1] + cross[2] * n[2];
  return along < 0 ? -detail::angleBetweenDegrees(a, b) : detail::angleBetweenDegrees(a, b);
}

// One input that rounding moves: a component of a group of equal values (a seam's copies
// move together, as rounding moves them). attribute 0: position (component 0-2), 1: UV (0-1),
// 2: normal (0-2).
struct Input {
  int attribute, component;
  std::vector<std::uint32_t> vertices;
};

std::vector<Input> inputsOf(const detail::PrimitiveGeometry& g, int attribute) {
  const std::vector<float>& values = attribute == 0 ? g.positions : attribute == 1 ? g.uvs : g.normals;
  const int width = attribute == 1 ? 2 : 3;
  std::map<std::vector<float>, std::vector<std::uint32_t>> groups;
  for (std::uint32_t v = 0; v < g.vertexCount; ++v)
    groups[std::vector<float>(values.begin() + width * v, values.begin() + width * (v + 1))].push_back(v);
  std::vector<Input> inputs;
  for (const auto& [value, vertices] : groups)
    for (int c = 0; c < width; ++c) inputs.push_back({attribute, c, vertices});
  return inputs;
}

void move(detail::PrimitiveGeometry& g, const Input& input, double by) {
  std::vector<float>& values = input.attribute == 0 ? g.positions : input.attribute == 1 ? g.uvs : g.normals;
  const int width = input.attribute == 1 ? 2 : 3;
  for (const std::uint32_t v : input.vertices) values[width * v + input.component] += static_cast<float>(by);
}

// Readers normalize a stored normal (unitNormals).
void normalize(detail::PrimitiveGeometry& g) {
  for (std::size_t v = 0; v < g.vertexCount; ++v) {
    float* n = &g.normals[3 * v];
    const double length = detail::length3(n);
    for (int k = 0; k < 3; ++k) n[k] = static_cast<float>(n[k] / length);
  }
}

// Per vertex, the largest angle between a corner's fresh tangent on `stored` and on `stored`
// with every input moved by up to its half step: 16 random moves, then for each vertex the
// corner of the box that turns its frame furthest to first order (each input at the end of
// its range that turns the vertex's frame one way), both ways round.
std::vector<double> estimateDegrees(const detail::PrimitiveGeometry& stored, const std::vector<Input>& inputs,
                                    const std::vector<double>& halfStep) {
  const std::vector<float> base = freshTangents(stored);
  const std::size_t cornerCount = stored.corners.size();
  std::vector<std::vector<std::uint32_t>> cornersOf(stored.vertexCount);
  for (std::size_t c = 0; c < cornerCount; ++c) cornersOf[stored.corners[c]].push_back(static_cast<std::uint32_t>(c));
  std::vector<double> estimate(stored.vertexCount, 0);
  auto measure = [&](const detail::PrimitiveGeometry& moved) {
    detail::PrimitiveGeometry unit = moved;
    if (inputs.front().attribute == 2) normalize(unit);
    const std::vector<float> fresh = freshTangents(unit);
    for (std::size_t c = 0; c < cornerCount; ++c) {
      const std::uint32_t v = stored.corners[c];
      estimate[v] = std::max(estimate[v], detail::angleBetweenDegrees(&base[4 * c], &fresh[4 * c]));
    }
  };
  std::mt19937 random(68);
  for (int trial = 0; trial < 16; ++trial) {
    detail::PrimitiveGeometry moved = stored;
    for (std::size_t j = 0; j < inputs.size(); ++j) move(moved, inputs[j], halfStep[j] * (2.0 * random() / 4294967295.0 - 1));
    measure(moved);
  }
  // The first-order turn of each vertex's frame per input (at the vertex's first corner).
  std::vector<std::vector<double>> turn(inputs.size(), std::vector<double>(stored.vertexCount, 0));
  for (std::size_t j = 0; j < inputs.size(); ++j) {
    detail::PrimitiveGeometry moved = stored;
    move(moved, inputs[j], halfStep[j]);
    if (inputs[j].attribute == 2) normalize(moved);
    const std::vector<float> fresh = freshTangents(moved);
    for (std::uint32_t v = 0; v < stored.vertexCount; ++v) {
      if (cornersOf[v].empty()) continue;
      const std::uint32_t c = cornersOf[v].front();
      turn[j][v] = signedTurnDegrees(&base[4 * c], &fresh[4 * c], &stored.normals[3 * v]);
    }
  }
  for (std::uint32_t v = 0; v < stored.vertexCount; ++v) {
    for (const double way : {1.0, -1.0}) {
      detail::PrimitiveGeometry moved = stored;
      for (std::size_t j = 0; j < inputs.size(); ++j)
        if (turn[j][v] != 0) move(moved, inputs[j], way * (turn[j][v] > 0 ? halfStep[j] : -halfStep[j]));
      measure(moved);
    }
  }
  return estimate;
}

struct Tightness {
  double tightest = 0;        // largest estimate / bound over the compared vertices
  double worstExcess = 0;     // largest estimate - bound (degrees): > 0 is a false alarm
  std::size_t compared = 0;
};

Tightness tightness(const std::vector<float>& bound, const std::vector<double>& estimate, const std::vector<char>& comparable) {
  Tightness t;
  for (std::size_t v = 0; v < bound.size(); ++v) {
    if (!comparable[v] || bound[v] >= detail::kUncomparableDegrees || !(estimate[v] > 1e-4)) continue;
    ++t.compared;
    t.tightest = std::max(t.tightest, estimate[v] / bound[v]);
    t.worstExcess = std::max(t.worstExcess, estimate[v] - bound[v]);
  }
  return t;
}

// The vertices all of whose triangles keep their UV orientation under the rounding.
std::vector<char> decidedVertices(const detail::PrimitiveGeometry& g, const detail::ReferenceAllowance& allowance) {
  std::vector<char> comparable(g.vertexCount, 1);
  for (std::size_t c = 0; c < g.corners.size(); ++c)
    if (!allowance.decided(c / 3)) comparable[g.corners[c]] = 0;
  return comparable;
}

TEST(AllowanceTightness, CoarseAndFineBoundsHoldTheRoundingWithinTheirStatedFactors) {
  for (const InputType& type : kInputTypes) {
    for (const Shape& shape : shapes()) {
      SCOPED_TRACE(std::string(type.name) + " positions and UVs, " + shape.name);
      const detail::PrimitiveGeometry stored = storedGeometry(shape.mesh, type);
      const detail::InputRounding rounding{type.position, type.uv};
      const detail::AllowanceBounds bounds = detail::allowanceBounds(stored, rounding);
      const std::vector<char> comparable = decidedVertices(stored, detail::referenceAllowance(stored, rounding));
      std::vector<Input> inputs = inputsOf(stored, 0), uvInputs = inputsOf(stored, 1);
      inputs.insert(inputs.end(), uvInputs.begin(), uvInputs.end());
      std::vector<double> halfStep;
      for (const Input& input : inputs) halfStep.push_back(input.attribute == 0 ? type.position : type.uv);
      const std::vector<double> estimate = estimateDegrees(stored, inputs, halfStep);
      const Tightness coarse = tightness(bounds.coarseDegrees, estimate, comparable);
      const Tightness fine = tightness(bounds.fineDegrees, estimate, comparable);
      std::printf("%-5s %-8s compared %zu: coarse bound / estimate %.2f (excess %.3g deg), fine %.2f (excess %.3g deg)\n", type.name,
                  shape.name.c_str(), coarse.compared, 1 / coarse.tightest, coarse.worstExcess, 1 / fine.tightest, fine.worstExcess);
      ASSERT_GT(coarse.compared, 0u);
      EXPECT_LE(coarse.worstExcess, 0) << "coarse bound below what rounding does";
      EXPECT_LE(fine.worstExcess, 0) << "fine bound below what rounding does";
      EXPECT_GE(coarse.tightest * kCoarseFactor, 1) << "coarse bound more than " << kCoarseFactor << "x what rounding does";
      EXPECT_GE(fine.tightest * kFineFactor, 1) << "fine bound more than " << kFineFactor << "x what rounding does";
    }
  }
}

// Float positions and UVs are what the tangents were baked from: no allowance, and no angle
// for a float TANGENT or NORMAL.
TEST(AllowanceTightness, FloatInputsHaveNoAllowance) {
  const detail::PrimitiveGeometry g = storedGeometry(tangent::testing::makeGrid(4, 4, false), {"float", 0, 0});
  const detail::AllowanceBounds bounds = detail::allowanceBounds(g, {});
  EXPECT_TRUE(bounds.coarseDegrees.empty() && bounds.fineDegrees.empty());
  EXPECT_TRUE(detail::referenceAllowance(g, {}).vertexDegrees.empty());
  EXPECT_EQ(detail::storedVectorRounding(detail::StoredComponent::float32).angleDegrees, 0);
}

// A stored TANGENT's own direction error: unit vectors over the sphere, each moved to every
// corner of its error box (half a step per component), turn by at most storedVectorRounding's
// angle, and come within kTangentFactor of it.
TEST(AllowanceTightness, StoredVectorAngleHoldsWithinItsStatedFactor) {
  for (const detail::StoredComponent component : {detail::StoredComponent::normalizedByte, detail::StoredComponent::normalizedShort}) {
    const detail::StoredVectorRounding rounding = detail::storedVectorRounding(component);
    const double e = rounding.componentError;
    double worst = 0;
    for (int i = 0; i <= 40; ++i) {
      for (int j = 0; j < 80; ++j) {
        const double theta = M_PI * i / 40, phi = 2 * M_PI * j / 80;
        const float exact[3] = {float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)), float(std::cos(theta))};
        for (int corner = 0; corner < 8; ++corner) {
          const float moved[3] = {float(exact[0] + (corner & 1 ? e : -e)), float(exact[1] + (corner & 2 ? e : -e)),
                                  float(exact[2] + (corner & 4 ? e : -e))};
          worst = std::max(worst, detail::angleBetweenDegrees(exact, moved));
        }
      }
    }
    std::printf("%-16s TANGENT: bound / estimate %.3f\n", detail::toString(component), rounding.angleDegrees / worst);
    EXPECT_GE(rounding.angleDegrees * (1 + 1e-6), worst);  // float rounding of the moved vector
    EXPECT_LE(rounding.angleDegrees, kTangentFactor * worst);
  }
}

// A NORMAL's direction error: the fresh tangents move with the stored normals, and
// storedVectorRounding's angle (what `orthogonal` and `reference` add for NORMAL) bounds that.
TEST(AllowanceTightness, NormalRoundingBoundHoldsWithinItsStatedFactor) {
  for (const detail::StoredComponent component : {detail::StoredComponent::normalizedByte, detail::StoredComponent::normalizedShort}) {
    const detail::StoredVectorRounding rounding = detail::storedVectorRounding(component);
    for (const Shape& shape : shapes()) {
      SCOPED_TRACE(std::string(detail::toString(component)) + " normals, " + shape.name);
      detail::PrimitiveGeometry stored = storedGeometry(shape.mesh, {"float", 0, 0});
      stored.positions = shape.mesh.positions;
      stored.uvs = shape.mesh.uvs;
      const double bits = double((1 << (rounding.significantBits - 1)) - 1);
      for (float& x : stored.normals) x = static_cast<float>(std::round(x * bits) / bits);
      const std::vector<Input> inputs = inputsOf(stored, 2);
      const std::vector<double> halfStep(inputs.size(), rounding.componentError);
      normalize(stored);
      const std::vector<double> estimate = estimateDegrees(stored, inputs, halfStep);
      const std::vector<float> bound(stored.vertexCount, static_cast<float>(rounding.angleDegrees));
      const Tightness t = tightness(bound, estimate, std::vector<char>(stored.vertexCount, 1));
      std::printf("%-16s normals %-8s compared %zu: bound / estimate %.2f (excess %.3g deg)\n", detail::toString(component),
                  shape.name.c_str(), t.compared, 1 / t.tightest, t.worstExcess);
      ASSERT_GT(t.compared, 0u);
      EXPECT_LE(t.worstExcess, 0) << "normal bound below what rounding does";
      EXPECT_GE(t.tightest * kNormalFactor, 1) << "normal bound more than " << kNormalFactor << "x what rounding does";
    }
  }
}

}  // namespace
