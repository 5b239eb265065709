// SPDX-License-Identifier: MIT
// check's phases on the triangles a primitive draws: w-uniform and handedness per triangle,
// orthogonal per drawn vertex, reference per corner against freshly computed frames (as bake
// computes them), and --identify. Handedness in glTF's convention, tangent::handedness:
// w = -sign(UV area) (README, "glTF's w convention").
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "check/check_phases.hpp"
#include "check/generators.hpp"
#include "check/tangent_rules.hpp"
#include "read/primitive.hpp"

namespace tangent::gltf::detail {
namespace {

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

}  // namespace

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

}  // namespace tangent::gltf::detail
