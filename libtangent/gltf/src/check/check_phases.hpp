// SPDX-License-Identifier: MIT
// What check's phases share: how one check collects its failures (FindingBuilder), the stored
// TANGENT of a vertex group with its limits, the per-vertex checks, and the phases that need a
// primitive's triangles (checkDrawnPart, drawn_part.cpp), which check.cpp runs per primitive.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "check/tangent_rules.hpp"
#include "read/primitive.hpp"
#include "tangent/check.hpp"
#include "tangent/verdict.hpp"

namespace tangent::gltf::detail {

constexpr std::size_t kWorstKept = 5;

inline std::string format(const char* pattern, auto... values) {
  char text[256];
  std::snprintf(text, sizeof text, pattern, values...);
  return text;
}

// Collects failures of one check; keeps the worst few. A check --only/--ignore leaves out
// is listed as ignored and collects nothing.
class FindingBuilder {
 public:
  FindingBuilder(CheckId check, std::string unit, std::uint64_t total, std::string severityUnit, double limit,
                 const CheckOptions& options)
      : enabled_(options.runs(check)) {
    finding_.check = toString(check);
    finding_.unit = std::move(unit);
    finding_.total = total;
    finding_.severityUnit = std::move(severityUnit);
    finding_.limit = limit;
  }
  void fail(std::uint64_t element, double severity, std::string detail, bool wDiffers = false) {
    if (!enabled_) return;
    ++finding_.failed;
    finding_.worst.push_back({element, severity, wDiffers, std::move(detail)});
    if (finding_.worst.size() > 4 * kWorstKept) trim();
  }
  // Adds the failures `other` collected (the same check, on other elements of the primitive).
  void merge(const FindingBuilder& other) {
    if (!enabled_) return;
    finding_.failed += other.finding_.failed;
    finding_.worst.insert(finding_.worst.end(), other.finding_.worst.begin(), other.finding_.worst.end());
    if (finding_.worst.size() > 4 * kWorstKept) trim();
  }
  // `bit` where the check runs, else 0: a check --only/--ignore leaves out marks no corner.
  std::uint8_t problemBit(std::uint8_t bit) const { return enabled_ ? bit : 0; }
  // Adds the finding to `primitive` (or records a pass, or that the check was ignored).
  void finish(PrimitiveCheck& primitive, std::string message) {
    if (!enabled_) {
      primitive.ignored.push_back(finding_.check);
      return;
    }
    if (finding_.failed == 0) {
      primitive.passed.push_back(finding_.check);
      return;
    }
    trim();
    finding_.message = std::move(message);
    primitive.findings.push_back(std::move(finding_));
  }

 private:
  // The worst first (w differs, then severity), the lower element first among equals: the same
  // samples whatever order the elements were failed or merged in.
  void trim() {
    std::stable_sort(finding_.worst.begin(), finding_.worst.end(), [](const CheckSample& a, const CheckSample& b) {
      if (a.wDiffers != b.wDiffers) return a.wDiffers;
      if (a.severity != b.severity) return a.severity > b.severity;
      return a.element < b.element;
    });
    if (finding_.worst.size() > kWorstKept) finding_.worst.resize(kWorstKept);
  }
  bool enabled_;
  CheckFinding finding_;
};

inline std::string tangentText(const float* t) { return format("(%.6g, %.6g, %.6g, w %.6g)", t[0], t[1], t[2], t[3]); }

// Gates (present, format) that fail make the rest moot.
inline void skipFrom(CheckId first, const CheckOptions& options, PrimitiveCheck& result) {
  for (std::size_t i = static_cast<std::size_t>(first); i < kCheckCount; ++i)
    (options.enabled.test(i) ? result.notRun : result.ignored).push_back(kCheckNames[i]);
}

// The stored TANGENT of a vertex group, read once, and the limits its component types give.
struct StoredTangents {
  std::vector<float> values;  // 4 per vertex of the buffer
  StoredTangentLimits limits;
  const char* component = "";
  double orthogonalLimit = 0;
  double referenceLimit = 0;
};

// The checks of one stored tangent on its own (finite, unit, w): one rule for the vertices a
// primitive draws and those no primitive of its buffer draws.
struct VertexFindings {
  VertexFindings(std::uint64_t total, const StoredTangents& stored, const CheckOptions& options)
      : finite(CheckId::finite, "vertices", total, "none", 0, options),
        unit(CheckId::unit, "vertices", total, "length", stored.limits.unitDeviation, options),
        w(CheckId::w, "vertices", total, "none", 0, options) {}
  // The CornerProblem bits of vertex v's failures.
  std::uint8_t check(std::size_t v, const StoredTangents& stored) {
    const float* t = &stored.values[4 * v];
    if (!finite4(t)) {
      finite.fail(v, 1, "vertex " + std::to_string(v) + " " + tangentText(t));
      return finite.problemBit(kProblemNotFinite);
    }
    std::uint8_t problems = 0;
    if (!unitOk(t, stored.limits)) {
      unit.fail(v, unitDeviation(t), format("vertex %zu |xyz| = %.6g ", v, length3(t)) + tangentText(t));
      problems |= unit.problemBit(kProblemNotUnit);
    }
    if (!validW(t[3])) {
      w.fail(v, std::abs(std::abs(t[3]) - 1.0), format("vertex %zu w = %.6g", v, t[3]));
      problems |= w.problemBit(kProblemBadW);
    }
    return problems;
  }
  void merge(const VertexFindings& other) {
    finite.merge(other.finite);
    unit.merge(other.unit);
    w.merge(other.w);
  }
  void finish(PrimitiveCheck& result, const StoredTangents& stored) {
    finite.finish(result, "TANGENT has NaN or infinite components");
    unit.finish(result, format("|xyz| differs from 1 by more than %.3g (%s)", stored.limits.unitDeviation, stored.component));
    w.finish(result, "w must be exactly +1 or -1");
  }
  FindingBuilder finite, unit, w;
};

// The checks of one primitive that need its triangles (w-uniform, handedness, orthogonal on the
// vertices it draws, reference), after the per-vertex ones; `used` is the part of the vertex
// buffer it draws, `part` that part's geometry, `undrawn` the per-vertex findings of the
// vertices no primitive of the buffer draws. `verdicts` (null: not kept) gets the verdict of
// each corner of part.corners.
void checkDrawnPart(const UsedVertices& used, const PrimitiveGeometry& part, const StoredTangents& stored,
                    const VertexFindings& undrawn, const InputRounding& rounding, const CheckOptions& options,
                    TangentWorkspace& workspace, PrimitiveCheck& result, std::vector<CornerVerdict>* verdicts);

}  // namespace tangent::gltf::detail
