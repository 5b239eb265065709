// SPDX-License-Identifier: MIT
// `tangent check`: are the stored tangents present, well formed, orthogonal, of the right
// handedness for the normal texture's UV set, and close to freshly computed ones?
// Handedness in glTF's convention, tangent::handedness: w = -sign(UV area) (README, "glTF's w convention").
#include "tangent/check.hpp"

#include <algorithm>
#include <cmath>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <unordered_map>

#include "read/accessors.hpp"
#include "read/asset.hpp"
#include "read/primitive.hpp"
#include "check/check_primitive.hpp"
#include "check/generators.hpp"
#include "entry_point.hpp"
#include "check/tangent_rules.hpp"
#include "read/validate.hpp"
#include "tangent/gltf.hpp"
#include "tangent/text.hpp"
#include "tangent/verdict.hpp"

namespace tangent::gltf {
namespace {

using namespace detail;

using Json = nlohmann::ordered_json;
constexpr std::size_t kWorstKept = 5;

std::string format(const char* pattern, auto... values) {
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

std::string tangentText(const float* t) { return format("(%.6g, %.6g, %.6g, w %.6g)", t[0], t[1], t[2], t[3]); }

using detail::finite4;

// Gates (present, format) that fail make the rest moot.
void skipFrom(CheckId first, const CheckOptions& options, PrimitiveCheck& result) {
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

// A check that compared fewer than options.minCoverage of its elements: a warning (not a
// finding: a file with 8-bit UVs cannot do better) with the counts and why the rest was left.
void coverageWarning(const CheckOptions& options, const char* check, const char* unit, std::uint64_t total, std::uint64_t undecided,
                     std::uint64_t undefined, const char* undecidedWhy, const char* undefinedWhy, PrimitiveCheck& result) {
  if (total == 0 || undecided + undefined > total) return;
  const std::uint64_t compared = total - undecided - undefined;
  if (!(double(compared) < options.minCoverage * double(total))) return;
  std::string why = format("%llu %s", static_cast<unsigned long long>(undecided), undecidedWhy);
  if (undefined) why += format(", %llu %s", static_cast<unsigned long long>(undefined), undefinedWhy);
  result.warnings.push_back(format("%s compared only %llu of %llu %s (%.1f%%, below --min-coverage %.3g): %s; its verdict says "
                                   "nothing about the rest",
                                   check, static_cast<unsigned long long>(compared), static_cast<unsigned long long>(total), unit,
                                   100.0 * double(compared) / double(total), options.minCoverage, why.c_str()));
}

// check's `reference` rule at one corner: every count, finding and per-corner verdict of
// `reference` comes from it. `allowanceDegrees` is the corner's vertex's allowance for rounded
// positions/UVs; `wDecided` whether rounding leaves its triangle's UV orientation decided.
struct ReferenceJudgement {
  ReferenceVerdict verdict = ReferenceVerdict::notChecked;
  double angle = 0;          // degrees, where compared
  double limit = 0;          // the corner's limit, where compared
  bool wUndecided = false;   // compared on the angle alone
  bool wDiffers = false;     // the w compared differs from the recomputed one
};

ReferenceJudgement judgeReference(FrameSource source, float allowanceDegrees, bool wDecided, const float* stored, const float* fresh,
                                  const StoredTangentLimits& limits, double toleranceDegrees) {
  ReferenceJudgement judgement;
  if (source == FrameSource::neighbour || source == FrameSource::fixed) {
    judgement.verdict = ReferenceVerdict::undefined;
    return judgement;
  }
  if (allowanceDegrees >= kUncomparableDegrees) {
    judgement.verdict = ReferenceVerdict::unresolved;
    return judgement;
  }
  if (!finite4(stored)) return judgement;  // `finite` reported it
  // w follows the triangle's UV orientation: where rounding leaves that open, only the angle is
  // compared (handedness skips the triangle alike), and only where w agrees: where it differs,
  // the rounding turned the triangle over, and its corner's frame now comes from the group of
  // the other orientation at the vertex, which no allowance bounds.
  if (!wDecided && (stored[3] < 0) != (fresh[3] < 0)) {
    judgement.verdict = ReferenceVerdict::unresolved;
    return judgement;
  }
  judgement.angle = angleBetweenDegrees(stored, fresh);
  judgement.limit = referenceLimitDegrees(limits, toleranceDegrees, allowanceDegrees);
  judgement.wUndecided = !wDecided;
  const float comparedW = wDecided ? stored[3] : fresh[3];
  judgement.wDiffers = (comparedW < 0) != (fresh[3] < 0);
  judgement.verdict = referenceFails(judgement.angle, comparedW, fresh[3], judgement.limit) ? ReferenceVerdict::disagrees
                                                                                             : ReferenceVerdict::agrees;
  return judgement;
}

// One primitive's drawn part as the phases of checkDrawnPart read it. `used` is the part of its
// vertex buffer it draws and `part` that part's geometry (gatherGeometry or keepUsedVertices);
// elements in messages are the buffer's vertices and the primitive's triangles and corners.
// `frames` is what the reference is computed from: `part`, or (a primitive without NORMAL)
// its split with the spec's flat normals, its corners in the part's order.
struct DrawnPart {
  const UsedVertices& used;
  const PrimitiveGeometry& part;
  const StoredTangents& stored;
  const PrimitiveGeometry& frames;
  const ReferenceAllowance& allowance;
  bool flatNormals = false;
  // Per corner, the verdict the phases fill in; null where the caller keeps none (the CLI).
  std::vector<CornerVerdict>* verdicts = nullptr;
  // Per vertex of `part`, the CornerProblem bits of the per-vertex checks (empty without verdicts).
  std::vector<std::uint8_t> vertexProblems;
};

// w-uniform and handedness, triangle by triangle.
void checkTriangles(DrawnPart& drawn, const CheckOptions& options, PrimitiveCheck& result) {
  const UsedVertices& used = drawn.used;
  const PrimitiveGeometry& part = drawn.part;
  const std::vector<float>& tangents = drawn.stored.values;
  const std::size_t triangleCount = part.corners.size() / 3;
  FindingBuilder uniform(CheckId::wUniform, "triangles", triangleCount, "none", 0, options);
  FindingBuilder handedness(CheckId::handedness, "triangles", triangleCount, "uv-area", 0, options);
  std::uint64_t handednessDegenerate = 0;  // no UV or 3D area: no orientation to judge
  for (std::size_t t = 0; t < triangleCount; ++t) {
    const std::uint32_t* local = &part.corners[3 * t];
    const std::uint32_t c[3] = {used.vertices[local[0]], used.vertices[local[1]], used.vertices[local[2]]};
    const float w0 = tangents[4 * c[0] + 3], w1 = tangents[4 * c[1] + 3], w2 = tangents[4 * c[2] + 3];
    const bool uniformW = w0 == w1 && w1 == w2;
    if (!uniformW) uniform.fail(t, 1, format("triangle %zu (vertices %u %u %u) w = %.6g %.6g %.6g", t, c[0], c[1], c[2], w0, w1, w2));
    // Orientation in the normal texture's UV set, on triangles with UV and 3D area.
    const float* uv[3] = {&part.uvs[2 * local[0]], &part.uvs[2 * local[1]], &part.uvs[2 * local[2]]};
    const double det = uvAreaTimesTwo(uv[0], uv[1], uv[2]);
    const float expected = expectedW(det);
    const double area =
        areaTimesTwo(&part.positions[3 * local[0]], &part.positions[3 * local[1]], &part.positions[3 * local[2]]);
    if (expected == 0 || !std::isfinite(det) || !(area > 0)) {
      ++handednessDegenerate;
      continue;
    }
    // Each corner's w against the triangle's orientation (the corners the verdicts mark): one
    // flipped corner fails the triangle here too, besides `w-uniform`. Invalid w: `w` reported it.
    const float w[3] = {w0, w1, w2};
    if (!validW(w0) && !validW(w1) && !validW(w2)) continue;
    if (!drawn.allowance.decided(t)) {
      ++result.handednessUndecided;
      continue;
    }
    const auto flipped = [&](float corner) { return validW(corner) && corner != expected; };
    if (!std::any_of(w, w + 3, flipped)) continue;
    handedness.fail(t, std::abs(det),
                    uniformW ? format("triangle %zu (vertices %u %u %u) has w = %.0f, its UV orientation needs %.0f", t, c[0], c[1],
                                      c[2], w0, expected)
                             : format("triangle %zu (vertices %u %u %u) has w = %.6g %.6g %.6g, its UV orientation needs %.0f", t,
                                      c[0], c[1], c[2], w0, w1, w2, expected));
    if (drawn.verdicts)
      for (int k = 0; k < 3; ++k)
        if (flipped(w[k])) (*drawn.verdicts)[3 * t + k].problems |= handedness.problemBit(kProblemHandedness);
  }
  uniform.finish(result, "w differs between the corners of a triangle (a vertex shared across a mirror seam?)");
  handedness.finish(result, "w disagrees with the triangle's orientation in the normal texture's UV set (w = -sign(UV area) in glTF)");
  if (options.runs(CheckId::handedness))
    coverageWarning(options, "handedness", "triangles", triangleCount, result.handednessUndecided, handednessDegenerate,
                    "whose UV orientation rounded positions/UVs leave undecided", "without UV or 3D area", result);
}

// orthogonal on the vertices the primitive draws.
void checkOrthogonal(DrawnPart& drawn, const CheckOptions& options, PrimitiveCheck& result) {
  const UsedVertices& used = drawn.used;
  const PrimitiveGeometry& part = drawn.part;
  const StoredTangents& stored = drawn.stored;
  const std::vector<float>& tangents = stored.values;
  FindingBuilder orthogonal(CheckId::orthogonal, "vertices", result.vertices, "degrees", stored.orthogonalLimit, options);
  // Per vertex, the normal its tangent is judged against: NORMAL, or (flat normals) the face
  // normal of its corner furthest from its tangent's plane.
  std::vector<const float*> normalOf(part.vertexCount, nullptr);
  if (drawn.flatNormals) {
    std::vector<double> worstOffPlane(part.vertexCount, -2);
    for (std::size_t c = 0; c < part.corners.size(); ++c) {
      const std::uint32_t local = part.corners[c];
      const float* n = &drawn.frames.normals[3 * drawn.frames.corners[c]];
      const double offPlane = offPlaneDegrees(&tangents[4 * used.vertices[local]], n);
      if (offPlane > worstOffPlane[local]) worstOffPlane[local] = offPlane, normalOf[local] = n;
    }
  } else {
    for (std::size_t local = 0; local < part.vertexCount; ++local) normalOf[local] = &part.normals[3 * local];
  }
  for (std::size_t local = 0; local < part.vertexCount; ++local) {
    const std::uint32_t v = used.vertices[local];
    const float* t = &tangents[4 * v];
    const float* normal = normalOf[local];
    if (!finite4(t) || !normal) continue;
    const double offPlane = offPlaneDegrees(t, normal);
    if (!(offPlane > stored.orthogonalLimit)) continue;
    orthogonal.fail(v, offPlane, format("vertex %u is %.4g deg out of the tangent plane, N = (%.4g, %.4g, %.4g)%s, T = ", v, offPlane,
                                        normal[0], normal[1], normal[2], drawn.flatNormals ? " (flat)" : "") + tangentText(t));
    if (drawn.verdicts) drawn.vertexProblems[local] |= orthogonal.problemBit(kProblemNotOrthogonal);
  }
  // The limits in words: the tolerance, plus rounding where there is any.
  const bool roundedFrame = stored.limits.tangentAngleDegrees > 0 || stored.limits.normalAngleDegrees > 0;
  const std::string frameRounding =
      roundedFrame ? format(" (%.3g + rounding of %s TANGENT and %s NORMAL)", options.orthogonalToleranceDegrees, stored.component,
                            result.normalComponent.c_str())
                   : "";
  orthogonal.finish(result, format("xyz leaves the plane normal to NORMAL by more than %.3g deg", stored.orthogonalLimit) + frameRounding);
}

// reference: against freshly computed tangents, on corners where the method defines a frame,
// computed on the vertices the primitive draws, as bake computes them (judgeReference per corner).
void checkReference(DrawnPart& drawn, const CheckOptions& options, TangentWorkspace& workspace, PrimitiveCheck& result) {
  const StoredTangents& stored = drawn.stored;
  const std::vector<std::uint32_t>& corners = drawn.part.corners;
  const std::string generator = toString(Generator{options.method, options.weighting});
  FindingBuilder reference(CheckId::reference, "corners", corners.size(), "degrees", stored.referenceLimit, options);
  if (options.runs(CheckId::reference)) {
    std::vector<float> computed;
    std::vector<FrameSource> sources;
    computeFrames(drawn.frames, options.method, options.weighting, workspace, computed, sources);
    for (std::size_t c = 0; c < corners.size(); ++c) {
      const std::uint32_t v = drawn.used.vertices[corners[c]];
      const float extra = drawn.allowance.vertex(drawn.frames.corners[c]);
      const float* storedTangent = &stored.values[4 * v];
      const float* fresh = &computed[4 * c];
      const ReferenceJudgement judged = judgeReference(sources[c], extra, drawn.allowance.decided(c / 3), storedTangent, fresh,
                                                       stored.limits, options.referenceToleranceDegrees);
      if (judged.verdict == ReferenceVerdict::undefined) ++result.referenceUndefined;
      if (judged.verdict == ReferenceVerdict::unresolved) ++result.referenceUnresolved;
      if (judged.verdict != ReferenceVerdict::undefined && extra < kUncomparableDegrees)
        result.referenceAllowanceMaxDegrees = std::max(result.referenceAllowanceMaxDegrees, double(extra));
      if (judged.wUndecided) ++result.referenceWUndecided;
      if (judged.verdict == ReferenceVerdict::disagrees)
        reference.fail(c, judged.angle,
                       format("corner %zu (vertex %u): %.4g deg from %s (limit %.3g)%s; stored ", c, v, judged.angle, generator.c_str(),
                              judged.limit, judged.wDiffers ? ", w differs" : "") +
                           tangentText(storedTangent) + ", computed " + tangentText(fresh),
                       judged.wDiffers);
      if (!drawn.verdicts) continue;
      CornerVerdict& verdict = (*drawn.verdicts)[c];
      verdict.reference = judged.verdict;
      verdict.wUndecided = judged.wUndecided;
      verdict.referenceDegrees = static_cast<float>(judged.angle);
      if (judged.verdict == ReferenceVerdict::disagrees) verdict.problems |= kProblemFarFromReference;
    }
    coverageWarning(options, "reference", "corners", corners.size(), result.referenceUnresolved, result.referenceUndefined,
                    "whose frame or UV orientation rounded positions/UVs leave undecided", ("where " + generator + " defines no frame").c_str(),
                    result);
  }
  std::string referenceRounding;
  if (stored.limits.tangentAngleDegrees > 0 || stored.limits.normalAngleDegrees > 0)
    referenceRounding = format(" (%.3g + rounding of %s TANGENT and %s NORMAL)", options.referenceToleranceDegrees, stored.component,
                               result.normalComponent.c_str());
  if (drawn.allowance.orientationDecided.size())
    referenceRounding += format(", plus up to %.3g deg per corner for rounded positions/UVs", result.referenceAllowanceMaxDegrees);
  reference.finish(result, format("differs from freshly computed %s tangents by more than %.3g deg", generator.c_str(), stored.referenceLimit) +
                               referenceRounding + ", or in w");
}

// The checks of one primitive that need its triangles (w-uniform, handedness, orthogonal on the
// vertices it draws, reference), after the per-vertex ones, as the phases above; `verdicts`
// (null: not kept) gets the verdict of each corner of part.corners.
void checkDrawnPart(const UsedVertices& used, const PrimitiveGeometry& part, const StoredTangents& stored,
                    const VertexFindings& undrawn, const InputRounding& rounding, const CheckOptions& options,
                    TangentWorkspace& workspace, PrimitiveCheck& result, std::vector<CornerVerdict>* verdicts) {
  if (verdicts) verdicts->assign(part.corners.size(), CornerVerdict{});
  std::vector<std::uint8_t> vertexProblems(verdicts ? part.vertexCount : 0, 0);
  VertexFindings vertexFindings(result.vertices, stored, options);
  for (std::size_t local = 0; local < used.vertices.size(); ++local) {
    const std::uint8_t problems = vertexFindings.check(used.vertices[local], stored);
    if (verdicts) vertexProblems[local] = problems;
  }
  vertexFindings.merge(undrawn);
  vertexFindings.finish(result, stored);

  // Rounded positions and UVs (KHR_mesh_quantization) move the recomputed frame: per vertex
  // allowance, and triangles whose UV orientation the rounding leaves open.
  // A primitive without NORMAL is judged against the spec's flat normals (glTF 2.0 3.7.2.1),
  // as bake generates them (withGeneratedNormals: a triangle without area gets +Z).
  const bool flatNormals = part.normals.empty();
  PrimitiveGeometry flat;
  if (flatNormals) {
    std::vector<std::uint32_t> source;
    flat = withGeneratedNormals(part, /*smooth=*/false, 0, source);
  }
  const PrimitiveGeometry& frames = flatNormals ? flat : part;
  const ReferenceAllowance allowance = referenceAllowance(frames, rounding);
  DrawnPart drawn{used, part, stored, frames, allowance, flatNormals, verdicts, std::move(vertexProblems)};

  checkTriangles(drawn, options, result);
  checkOrthogonal(drawn, options, result);
  checkReference(drawn, options, workspace, result);
  if (options.identify) identifyGenerator(frames, part, used, stored.values, workspace, result);
  // Ignored checks listed in check order (they finish in the order the passes run).
  std::sort(result.ignored.begin(), result.ignored.end(),
            [](const std::string& a, const std::string& b) { return *parseCheck(a) < *parseCheck(b); });
  if (verdicts)
    for (std::size_t c = 0; c < part.corners.size(); ++c) (*verdicts)[c].problems |= drawn.vertexProblems[part.corners[c]];
}

// The primitives `members` of `primitives`, which share their vertex attributes and TANGENT
// (sameVertexKey and the TANGENT accessor): the buffer and the stored tangents are read once;
// the vertices no member draws are checked once and count for every member. `verdicts` (null:
// not kept) is indexed as `results` and gets each checked member's corner verdicts.
void checkVertexGroup(const Asset& asset, const std::vector<PrimitiveToCheck>& primitives, const std::vector<std::size_t>& members,
                      const CheckOptions& options, TangentWorkspace& workspace, std::vector<PrimitiveCheck>& results,
                      std::vector<std::vector<CornerVerdict>>* verdicts) {
  auto verdictsOf = [&](std::size_t member) { return verdicts ? &(*verdicts)[member] : nullptr; };
  const PrimitiveToCheck& first = primitives[members.front()];
  PrimitiveGeometry buffer = readVertices(asset, *first.primitive, first.needs, first.where, /*normalOptional=*/true);

  // The vertices each member draws, and those none draws.
  std::vector<UsedVertices> parts;
  parts.reserve(members.size());
  {
    std::vector<std::uint32_t> slotOf(buffer.vertexCount, kNoSlot);
    std::vector<char> drawnByAny(buffer.vertexCount, 0);
    for (const std::size_t member : members) {
      PrimitiveGeometry drawn;
      drawn.vertexCount = buffer.vertexCount;
      readCorners(asset, *primitives[member].primitive, primitives[member].where, drawn);
      parts.push_back(usedVertices(drawn.corners, slotOf));
      for (const std::uint32_t v : parts.back().vertices) drawnByAny[v] = 1;
    }
    const std::size_t undrawnCount = static_cast<std::size_t>(std::count(drawnByAny.begin(), drawnByAny.end(), 0));
    for (std::size_t k = 0; k < members.size(); ++k) {
      results[members[k]].vertices = parts[k].vertices.size() + undrawnCount;
      results[members[k]].triangles = parts[k].corners.size() / 3;
    }
    // Kept in `parts` as an extra entry: the undrawn vertices, ascending.
    UsedVertices undrawn;
    for (std::uint32_t v = 0; v < buffer.vertexCount; ++v) {
      if (!drawnByAny[v]) undrawn.vertices.push_back(v);
    }
    parts.push_back(std::move(undrawn));
  }
  const std::vector<std::uint32_t>& undrawnVertices = parts.back().vertices;

  const Json& attributes = (*first.primitive)["attributes"];
  const int tangentAccessor = accessorOf(attributes, "TANGENT");
  if (tangentAccessor < 0) {
    for (std::size_t k = 0; k < members.size(); ++k) {
      const std::size_t member = members[k];
      if (parts[k].corners.empty()) {
        // No triangle is drawn (a strip of two indices): nothing is shaded with the normal
        // texture, and bake leaves such a primitive as it is.
        (options.runs(CheckId::present) ? results[member].passed : results[member].ignored).push_back("present");
        skipFrom(CheckId::format, options, results[member]);
        continue;
      }
      FindingBuilder present(CheckId::present, "primitive", 1, "none", 0, options);
      present.fail(0, 1, "no TANGENT attribute");
      present.finish(results[member], "TANGENT is missing: the material's normal texture needs it (run tangent bake, or pass "
                                      "--allow-missing when clients compute MikkTSpace)");
      skipFrom(CheckId::format, options, results[member]);
    }
    return;
  }
  for (const std::size_t member : members) (options.runs(CheckId::present) ? results[member].passed : results[member].ignored).push_back("present");
  const AccessorData data = readAccessor(asset.model, tangentAccessor, first.where + ": TANGENT");
  const std::optional<StoredComponent> tangentComponent = storedComponentOf(data.componentType, data.normalized);
  // Without NORMAL the spec's flat normals are used: exact floats.
  const int normalAccessor = accessorOf(attributes, "NORMAL");
  const std::optional<StoredComponent> normalComponent =
      normalAccessor < 0 ? std::optional<StoredComponent>(StoredComponent::float32)
                         : storedComponentOf(asset.json["accessors"][normalAccessor].value("componentType", 0),
                                             asset.json["accessors"][normalAccessor].value("normalized", false));
  if (data.type != TINYGLTF_TYPE_VEC4 || !tangentComponent || data.count != buffer.vertexCount) {
    for (const std::size_t member : members) {
      FindingBuilder formatCheck(CheckId::format, "primitive", 1, "none", 0, options);
      formatCheck.fail(0, 1, format("%s of %s%s, %zu elements", typeName(data.type), componentTypeName(data.componentType),
                                    data.normalized ? " normalized" : "", data.count));
      formatCheck.finish(results[member], format("TANGENT (accessor %d) must be VEC4 of FLOAT or normalized BYTE/SHORT with one "
                                                 "element per vertex (%zu)", tangentAccessor, buffer.vertexCount));
      skipFrom(CheckId::finite, options, results[member]);
    }
    return;
  }
  StoredTangents stored;
  stored.limits = storedTangentLimits(*tangentComponent, normalComponent.value_or(StoredComponent::float32));
  stored.orthogonalLimit = orthogonalLimitDegrees(stored.limits, options.orthogonalToleranceDegrees);
  stored.referenceLimit = referenceLimitDegrees(stored.limits, options.referenceToleranceDegrees, 0);
  stored.component = toString(*tangentComponent);
  stored.values = toFloats(data);
  const double normalLimit = normalLengthWarningLimit(normalComponent.value_or(StoredComponent::float32));
  for (const std::size_t member : members) {
    PrimitiveCheck& result = results[member];
    result.normalsNormalized = buffer.normalLengths.normalized;
    result.worstNormalLength = buffer.normalLengths.worstLength;
    result.normalLengthLimit = normalLimit;
    if (buffer.normalLengths.worstDeviation() > normalLimit)
      result.warnings.push_back(format("NORMAL is not unit length: worst %.6g, beyond the %.3g of %s rounding; %llu normals normalized "
                                       "first, as glTF readers do",
                                       buffer.normalLengths.worstLength, normalLimit,
                                       toString(normalComponent.value_or(StoredComponent::float32)),
                                       static_cast<unsigned long long>(buffer.normalLengths.normalized)));
    (options.runs(CheckId::format) ? result.passed : result.ignored).push_back("format");
    result.tangentComponent = stored.component;
    result.normalComponent = normalComponent ? toString(*normalComponent) : "";
    result.unitLimit = stored.limits.unitDeviation;
    result.orthogonalLimitDegrees = stored.orthogonalLimit;
    result.referenceLimitDegrees = stored.referenceLimit;
  }

  VertexFindings undrawn(0, stored, options);
  for (const std::uint32_t v : undrawnVertices) undrawn.check(v, stored);
  const InputRounding rounding = inputRounding(asset, *first.primitive, first.needs.texCoord, first.needs.hasNormalTexture);
  if (members.size() == 1) {
    // The usual single primitive: the buffer, kept to the vertices it draws in place, is its
    // part (no gathered copy of every attribute).
    keepUsedVertices(buffer, parts[0]);
    checkDrawnPart(parts[0], buffer, stored, undrawn, rounding, options, workspace, results[members[0]], verdictsOf(members[0]));
    return;
  }
  for (std::size_t k = 0; k < members.size(); ++k)
    checkDrawnPart(parts[k], gatherGeometry(buffer, parts[k]), stored, undrawn, rounding, options, workspace,
                   results[members[k]], verdictsOf(members[k]));
}

}  // namespace

namespace detail {

std::vector<PrimitiveCheck> checkPrimitives(const Asset& asset, const std::vector<PrimitiveToCheck>& primitives,
                                            const CheckOptions& options, std::vector<std::vector<CornerVerdict>>* verdicts) {
  std::vector<PrimitiveCheck> results(primitives.size());
  if (verdicts) verdicts->assign(primitives.size(), {});
  // One verdict per set of inputs and TANGENT; those sets grouped by vertex buffer and TANGENT.
  std::vector<std::size_t> sameAs(primitives.size());
  std::vector<std::vector<std::size_t>> groups;
  {
    std::unordered_map<std::string, std::size_t> firstOfInput, groupOfVertices;
    for (std::size_t i = 0; i < primitives.size(); ++i) {
      const PrimitiveToCheck& p = primitives[i];
      const std::string tangent = " TANGENT " + std::to_string(accessorOf((*p.primitive)["attributes"], "TANGENT"));
      const auto input = firstOfInput.emplace(sameInputKey(asset.json, *p.primitive, p.needs) + tangent, i);
      sameAs[i] = input.first->second;
      if (!input.second) continue;
      const auto group = groupOfVertices.emplace(sameVertexKey(asset.json, *p.primitive, p.needs) + tangent, groups.size());
      if (group.second) groups.emplace_back();
      groups[group.first->second].push_back(i);
    }
  }
  CachedWorkspace workspace;  // the thread's cached workspace (tangent.hpp)
  for (const std::vector<std::size_t>& members : groups)
    checkVertexGroup(asset, primitives, members, options, workspace.get(), results, verdicts);
  for (std::size_t i = 0; i < primitives.size(); ++i) {
    if (sameAs[i] == i) continue;
    results[i] = results[sameAs[i]];
    if (verdicts) (*verdicts)[i] = (*verdicts)[sameAs[i]];
  }
  return results;
}

}  // namespace detail

namespace {

// The images[] index of the primitive's material's normal texture, or -1.
long normalTextureImage(const Json& doc, const Json& primitive) {
  auto index = [&doc](const Json& object, const char* key, const char* array) -> long {
    if (!object.is_object() || !object.contains(key) || !object[key].is_number_unsigned()) return -1;
    const std::size_t i = object[key].get<std::size_t>();
    return doc.contains(array) && doc[array].is_array() && i < doc[array].size() ? long(i) : -1;
  };
  const long material = index(primitive, "material", "materials");
  if (material < 0 || !doc["materials"][material].contains("normalTexture")) return -1;
  const long texture = index(doc["materials"][material]["normalTexture"], "index", "textures");
  return texture < 0 ? -1 : index(doc["textures"][texture], "source", "images");
}

// The primitives of `asset` (loaded from `input`) that need tangents, checked into `result`;
// `corners` (null: not kept) gets the verdicts per corner of those that reached the per-corner
// checks, keyed by their indices.
void checkLoaded(const detail::Asset& asset, const std::filesystem::path& input, const CheckOptions& options, FileCheck& result,
                 std::vector<PrimitiveVerdicts>* corners) {
  const Json& doc = asset.json;
  std::vector<detail::PrimitiveToCheck> pending;  // primitives to check, and their slots in result.primitives
  std::vector<std::size_t> pendingSlot;
  const std::size_t meshCount = doc.contains("meshes") ? doc["meshes"].size() : 0;
  for (std::size_t m = 0; m < meshCount; ++m) {
    const Json& mesh = doc["meshes"][m];
    for (std::size_t p = 0; p < mesh["primitives"].size(); ++p) {
      const Json& primitive = mesh["primitives"][p];
      const std::string label = detail::primitiveLabel(doc, static_cast<int>(m), static_cast<int>(p));
      const detail::PrimitiveNeeds needs = detail::primitiveNeeds(doc, primitive, options.all || asset.fromMeshFile);
      const bool hasUv = detail::accessorOf(primitive["attributes"], "TEXCOORD_" + std::to_string(needs.texCoord)) >= 0;
      auto newCheck = [&] {
        PrimitiveCheck check;
        check.mesh = static_cast<int>(m);
        check.primitive = static_cast<int>(p);
        check.texCoord = needs.texCoord;
        if (mesh.contains("name") && mesh["name"].is_string()) check.meshName = mesh["name"].get<std::string>();
        return check;
      };
      if (const std::string problem = detail::missingUvSet(primitive, needs); !problem.empty()) {
        // A normal texture sampling a UV set the primitive lacks: a broken file, not a skip.
        PrimitiveCheck check = newCheck();
        FindingBuilder formatCheck(CheckId::format, "primitive", 1, "none", 0, options);
        formatCheck.fail(0, 1, problem);
        formatCheck.finish(check, problem);
        skipFrom(CheckId::finite, options, check);
        result.primitives.push_back(std::move(check));
        continue;
      }
      // A primitive without NORMAL is checked against the spec's flat normals (checkDrawnPart).
      if (!detail::bakesTangents(needs) || !hasUv) {
        std::string why = needs.why;
        if (detail::bakesTangents(needs)) why = "no TEXCOORD_" + std::to_string(needs.texCoord) + " attribute";
        result.skipped.push_back(label + ": " + why);
        continue;
      }
      if (options.allowMissing && detail::accessorOf(primitive["attributes"], "TANGENT") < 0) {
        result.skipped.push_back(label + ": no TANGENT, allowed (--allow-missing: clients compute MikkTSpace from TEXCOORD_" +
                                 std::to_string(needs.texCoord) + ")");
        continue;
      }
      // Checked below, all together: primitives that share inputs or a vertex buffer share work.
      pendingSlot.push_back(result.primitives.size());
      pending.push_back({&primitive, needs, input.string() + ": " + label});
      result.primitives.push_back(newCheck());
    }
  }
  std::vector<std::vector<CornerVerdict>> cornerVerdicts;
  std::vector<PrimitiveCheck> verdicts = detail::checkPrimitives(asset, pending, options, corners ? &cornerVerdicts : nullptr);
  for (std::size_t i = 0; i < pending.size(); ++i) {
    PrimitiveCheck& named = result.primitives[pendingSlot[i]];
    PrimitiveCheck& verdict = verdicts[i];
    verdict.mesh = named.mesh;
    verdict.primitive = named.primitive;
    verdict.meshName = std::move(named.meshName);
    verdict.texCoord = named.texCoord;
    named = std::move(verdict);
    // Consumers of the frame on other UV sets: the one TANGENT cannot serve them all.
    if (!pending[i].needs.otherFrames.empty()) named.warnings.push_back(pending[i].needs.otherFrames);
    // A normal texture whose image holds no data (neither uri nor bufferView; the loader
    // warned): the tangents are checked all the same.
    const long image = normalTextureImage(doc, *pending[i].primitive);
    if (image >= 0 && doc["images"][image].is_object() && !doc["images"][image].contains("uri") && !doc["images"][image].contains("bufferView"))
      named.warnings.push_back(format("its normal texture's image, images[%ld], has neither uri nor bufferView (no image data)", image));
    if (corners && !cornerVerdicts[i].empty())
      corners->push_back({PrimitiveIndex{named.mesh, named.primitive}, std::move(cornerVerdicts[i])});
  }
}

FileCheck checkAsset(const std::filesystem::path& input, const CheckOptions& options) {
  FileCheck result;
  result.file = input.string();
  const auto started = std::chrono::steady_clock::now();
  checkLoaded(detail::loadAsset(input, options.assetRoot), input, options, result, nullptr);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return result;
}

}  // namespace

FileCheck checkFile(const std::filesystem::path& input, const CheckOptions& options) {
  return detail::throwingInputError(input, [&] { return checkAsset(input, options); });
}

std::vector<PrimitiveVerdicts> detail::checkCorners(const Asset& asset, const std::filesystem::path& input, const CheckOptions& options) {
  FileCheck discarded;
  std::vector<PrimitiveVerdicts> corners;
  checkLoaded(asset, input, options, discarded, &corners);
  return corners;
}

std::vector<PrimitiveVerdicts> checkCorners(const std::filesystem::path& input, const CheckOptions& options) {
  return detail::throwingInputError(
      input, [&] { return detail::checkCorners(detail::loadAsset(input, options.assetRoot), input, options); });
}

}  // namespace tangent::gltf
