// SPDX-License-Identifier: MIT
#include "support/reference_rule.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

namespace tangent::testing {
namespace {

double degreesBetween(const double a[3], const double b[3]) {
  const double cross[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  const double sine = std::sqrt(cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]);
  const double cosine = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  return std::atan2(sine, cosine) * 180.0 / 3.14159265358979323846;
}

double degreesBetween(const float a[3], const float b[3]) {
  const double da[3] = {a[0], a[1], a[2]}, db[3] = {b[0], b[1], b[2]};
  return degreesBetween(da, db);
}

// Same sign, same length (a zero vector is at angle 0 from anything) and within
// kStableDegrees: a frame that moves by more than that between face orders sums terms that
// cancel, and its float rounding depends on the order of the sum. A few runs see only part of
// that spread (measured: 0.005 degrees over 13 runs, 0.034 over all 5040 orders of a
// 7-triangle fan), so such a corner is not compared at kAgreeDegrees.
bool sameFrame(const ReferenceFrame& a, const ReferenceFrame& b) {
  auto length = [](const float* t) { return std::sqrt(double{t[0]} * t[0] + double{t[1]} * t[1] + double{t[2]} * t[2]); };
  return a.written && b.written && a.sign == b.sign && std::abs(length(a.tangent) - length(b.tangent)) < kDefinedTolerance &&
         degreesBetween(a.tangent, b.tangent) <= kStableDegrees;
}

// The reference frame is a unit vector orthogonal to the corner's unit normal.
bool definedFrame(const ReferenceFrame& frame, const float* normal) {
  if (!frame.written || (frame.sign != 1.0f && frame.sign != -1.0f)) return false;
  const double t[3] = {frame.tangent[0], frame.tangent[1], frame.tangent[2]};
  double n[3] = {normal[0], normal[1], normal[2]};
  const double tangentLength = std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
  const double normalLength = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (!std::isfinite(tangentLength) || !std::isfinite(normalLength) || normalLength == 0) return false;
  for (double& c : n) c /= normalLength;
  return std::abs(tangentLength - 1) <= kDefinedTolerance &&
         std::abs(t[0] * n[0] + t[1] * n[1] + t[2] * n[2]) <= kDefinedTolerance;
}

bool validOurs(const float* tangent) {
  for (int i = 0; i < 4; ++i)
    if (!std::isfinite(tangent[i])) return false;
  const double length =
      std::sqrt(double{tangent[0]} * tangent[0] + double{tangent[1]} * tangent[1] + double{tangent[2]} * tangent[2]);
  return std::abs(length - 1) < kUnitTolerance && (tangent[3] == 1.0f || tangent[3] == -1.0f);
}

// Shuffle 0 reverses the triangle order, so every pair of triangles comes in the other order
// in one run (the reference pairs the triangles of a non-manifold edge in face order).
// Shuffles 0 and 1 rotate every triangle by one and by two corners, so every triangle is seen
// from each of its corners (the reference's float arithmetic starts at a triangle's first
// corner). The others are random orders with random rotations.
FaceOrder shuffledOrder(std::size_t triangles, std::mt19937_64& engine, int shuffle) {
  FaceOrder order;
  order.triangleOrder.resize(triangles);
  for (std::size_t i = 0; i < triangles; ++i) order.triangleOrder[i] = static_cast<std::uint32_t>(shuffle == 0 ? triangles - 1 - i : i);
  if (shuffle != 0) {
    for (std::size_t i = triangles; i > 1; --i) std::swap(order.triangleOrder[i - 1], order.triangleOrder[engine() % i]);
  }
  order.cornerRotation.resize(triangles);
  for (auto& rotation : order.cornerRotation) rotation = static_cast<std::uint8_t>(shuffle < 2 ? shuffle + 1 : engine() % 3);
  return order;
}

}  // namespace

std::string_view toString(CornerClass cornerClass) {
  switch (cornerClass) {
    case CornerClass::compared:
      return "compared";
    case CornerClass::undefined:
      return "undefined";
    case CornerClass::unstable:
      return "unstable";
    case CornerClass::referenceMixedW:
      return "reference-mixed-w";
  }
  return "?";
}

void RuleCounts::add(const RuleCounts& o) {
  meshes += o.meshes;
  triangles += o.triangles;
  corners += o.corners;
  compared += o.compared;
  undefined += o.undefined;
  unstable += o.unstable;
  referenceMixedW += o.referenceMixedW;
  unreached += o.unreached;
  angleFailures += o.angleFailures;
  wFailures += o.wFailures;
  invalidCorners += o.invalidCorners;
  mixedWTriangles += o.mixedWTriangles;
  referenceFailures += o.referenceFailures;
  maxDegrees = std::max(maxDegrees, o.maxDegrees);
}

std::string RuleCounts::describe() const {
  char line[512];
  std::snprintf(line, sizeof line,
                "%llu meshes, %llu triangles, %llu corners: compared %llu (%.1f%%), undefined %llu (%llu unreached), "
                "unstable %llu, "
                "reference-mixed-w %llu | failures: angle %llu, w %llu, invalid %llu, mixed-w triangles %llu, "
                "reference %llu | max %.4g deg on compared",
                static_cast<unsigned long long>(meshes), static_cast<unsigned long long>(triangles),
                static_cast<unsigned long long>(corners), static_cast<unsigned long long>(compared),
                corners ? 100.0 * static_cast<double>(compared) / static_cast<double>(corners) : 0.0,
                static_cast<unsigned long long>(undefined), static_cast<unsigned long long>(unreached),
                static_cast<unsigned long long>(unstable), static_cast<unsigned long long>(referenceMixedW),
                static_cast<unsigned long long>(angleFailures), static_cast<unsigned long long>(wFailures),
                static_cast<unsigned long long>(invalidCorners), static_cast<unsigned long long>(mixedWTriangles),
                static_cast<unsigned long long>(referenceFailures), maxDegrees);
  return line;
}

RuleResult applyReferenceRule(const MeshArrays& mesh, std::span<const float> ours, std::uint64_t shuffleSeed) {
  const std::size_t corners = mesh.indices.size();
  const std::size_t triangles = corners / 3;
  RuleResult result;
  RuleCounts& counts = result.counts;
  counts.meshes = 1;
  counts.triangles = triangles;
  counts.corners = corners;

  std::mt19937_64 engine(shuffleSeed);
  result.reference.push_back(referenceCornerFrames(mesh));
  for (int s = 0; s < kShuffles; ++s)
    result.reference.push_back(referenceCornerFrames(mesh, shuffledOrder(triangles, engine, s)));
  for (auto& run : result.reference) {
    if (run.empty()) {  // the reference failed: count it, and treat its corners as unwritten
      ++counts.referenceFailures;
      run.resize(corners);
    }
    counts.referenceFailures += static_cast<std::uint64_t>(
        std::count_if(run.begin(), run.end(), [](const ReferenceFrame& f) { return !f.written; }));
  }

  // The initial space can also be computed (a flat patch with tangent x, bitangent y and unit
  // magnitudes). With every UV doubled (exact; welding, orientation and directions unchanged)
  // computed magnitudes halve while the initial space stays: unreached is initial in both.
  std::vector<float> doubledUvs(mesh.uvs.begin(), mesh.uvs.end());
  for (float& uv : doubledUvs) uv *= 2;
  MeshArrays doubled = mesh;
  doubled.uvs = doubledUvs;
  const std::vector<ReferenceFrame> doubledRun = referenceCornerFrames(doubled);

  const std::vector<ReferenceFrame>& original = result.reference[0];
  result.classes.assign(corners, CornerClass::compared);
  result.degrees.assign(corners, 0.0);
  result.failed.assign(corners, false);
  for (std::size_t c = 0; c < corners; ++c) {
    const float* normal = &mesh.normals[3 * std::size_t{mesh.indices[c]}];
    CornerClass& cornerClass = result.classes[c];
    const std::size_t first = c - c % 3;
    // Mixed w in any run: a zero-UV triangle reached from both sides in some order leaves one
    // corner with the reference's initial space, whose (1,0,0) can equal a computed frame.
    const bool mixedW = std::any_of(result.reference.begin(), result.reference.end(), [&](const auto& run) {
      return run[first].sign != run[first + 1].sign || run[first].sign != run[first + 2].sign;
    });
    if (!definedFrame(original[c], normal)) {
      cornerClass = CornerClass::undefined;
    } else if (original[c].initialSpace && (doubledRun.empty() || doubledRun[c].initialSpace)) {
      // (1,0,0) left where no group reaches can happen to be orthogonal to the normal.
      cornerClass = CornerClass::undefined;
      ++counts.unreached;
    } else if (!std::all_of(result.reference.begin() + 1, result.reference.end(),
                            [&](const auto& run) { return sameFrame(original[c], run[c]); }))
      cornerClass = CornerClass::unstable;
    else if (mixedW)
      cornerClass = CornerClass::referenceMixedW;

    const float* tangent = &ours[4 * c];
    // Against the reference's direction in the tangent plane: ours is orthogonal to the normal
    // by contract, the reference's only up to its float rounding, which a sum of cancelling
    // terms magnifies (measured: 0.026 degrees out of the plane on a sliver fan).
    {
      const double len2 = double{normal[0]} * normal[0] + double{normal[1]} * normal[1] + double{normal[2]} * normal[2];
      const float* r = original[c].tangent;
      double inPlane[3] = {r[0], r[1], r[2]};
      if (len2 > 0 && std::isfinite(len2)) {
        const double d = (r[0] * double{normal[0]} + r[1] * double{normal[1]} + r[2] * double{normal[2]}) / len2;
        for (int i = 0; i < 3; ++i) inPlane[i] -= d * normal[i];
      }
      const double ourTangent[3] = {tangent[0], tangent[1], tangent[2]};
      result.degrees[c] = degreesBetween(ourTangent, inPlane);
    }
    bool failed = false;
    if (!validOurs(tangent)) {
      ++counts.invalidCorners;
      failed = true;
    }
    switch (cornerClass) {
      case CornerClass::compared:
        ++counts.compared;
        if (std::isnan(result.degrees[c]) || result.degrees[c] > kAgreeDegrees) {
          ++counts.angleFailures;
          failed = true;
        }
        if (tangent[3] != -original[c].sign) {
          ++counts.wFailures;
          failed = true;
        }
        if (!std::isnan(result.degrees[c])) counts.maxDegrees = std::max(counts.maxDegrees, result.degrees[c]);
        break;
      case CornerClass::undefined:
        ++counts.undefined;
        break;
      case CornerClass::unstable:
        ++counts.unstable;
        break;
      case CornerClass::referenceMixedW:
        ++counts.referenceMixedW;
        break;
    }
    result.failed[c] = failed;
  }
  for (std::size_t t = 0; t < triangles; ++t) {
    const float w0 = ours[12 * t + 3], w1 = ours[12 * t + 7], w2 = ours[12 * t + 11];
    if (w0 != w1 || w0 != w2) {
      ++counts.mixedWTriangles;
      for (int k = 0; k < 3; ++k) result.failed[3 * t + k] = true;
    }
  }
  return result;
}

std::string describeCorners(const MeshArrays& mesh, std::span<const float> ours, const RuleResult& result) {
  std::string out;
  char line[1024];
  for (std::size_t c = 0; c < mesh.indices.size(); ++c) {
    const std::uint32_t v = mesh.indices[c];
    int n = std::snprintf(
        line, sizeof line,
        "%s corner %zu (triangle %zu, vertex %u) p=(%g %g %g) n=(%g %g %g) uv=(%g %g) %-17s ours=(%.6f %.6f %.6f w %g) "
        "%.4g deg; reference fSign, tangent per run:",
        result.failed[c] ? "FAIL" : "ok  ", c, c / 3, v, mesh.positions[3 * v], mesh.positions[3 * v + 1],
        mesh.positions[3 * v + 2], mesh.normals[3 * v], mesh.normals[3 * v + 1], mesh.normals[3 * v + 2],
        mesh.uvs[2 * v], mesh.uvs[2 * v + 1], std::string(toString(result.classes[c])).c_str(), ours[4 * c],
        ours[4 * c + 1], ours[4 * c + 2], ours[4 * c + 3], result.degrees[c]);
    out.append(line, static_cast<std::size_t>(std::max(0, std::min(n, static_cast<int>(sizeof line) - 1))));
    for (const auto& run : result.reference) {
      const ReferenceFrame& f = run[c];
      n = std::snprintf(line, sizeof line, " [%+g (%.6f %.6f %.6f)]", f.sign, f.tangent[0], f.tangent[1], f.tangent[2]);
      out.append(line, static_cast<std::size_t>(std::max(0, std::min(n, static_cast<int>(sizeof line) - 1))));
    }
    out += '\n';
  }
  return out;
}

}  // namespace tangent::testing
