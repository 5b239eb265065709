// `tangent check`: are the stored tangents present, well formed, orthogonal, of the right
// handedness for the normal texture's UV set, and close to freshly computed ones?
// Handedness in glTF's convention: w = -sign(UV area) (see README, "glTF's w convention").
#include "tangent/check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "accessors.hpp"
#include "asset.hpp"
#include "primitive.hpp"
#include "tangent_rules.hpp"
#include "tangent/gltf.hpp"

namespace tangent::gltf {
namespace {

using Json = nlohmann::ordered_json;
constexpr std::size_t kWorstKept = 5;

std::string format(const char* pattern, auto... values) {
  char text[256];
  std::snprintf(text, sizeof text, pattern, values...);
  return text;
}

// Collects failures of one check; keeps the worst few.
class FindingBuilder {
 public:
  FindingBuilder(std::string check, std::string unit, std::uint64_t total) {
    finding_.check = std::move(check);
    finding_.unit = std::move(unit);
    finding_.total = total;
  }
  void fail(std::uint64_t element, double severity, std::string detail) {
    ++finding_.failed;
    finding_.worst.push_back({element, severity, std::move(detail)});
    if (finding_.worst.size() > 4 * kWorstKept) trim();
  }
  // Adds the finding to `primitive` (or records a pass).
  void finish(PrimitiveCheck& primitive, std::string message) {
    if (finding_.failed == 0) {
      primitive.passed.push_back(finding_.check);
      return;
    }
    trim();
    finding_.message = std::move(message);
    primitive.findings.push_back(std::move(finding_));
  }

 private:
  void trim() {
    std::stable_sort(finding_.worst.begin(), finding_.worst.end(),
                     [](const CheckSample& a, const CheckSample& b) { return a.severity > b.severity; });
    if (finding_.worst.size() > kWorstKept) finding_.worst.resize(kWorstKept);
  }
  CheckFinding finding_;
};

std::string tangentText(const float* t) { return format("(%.6g, %.6g, %.6g, w %.6g)", t[0], t[1], t[2], t[3]); }

using detail::finite4;
using detail::length3;

void checkPrimitive(const detail::Asset& asset, const Json& primitive, const detail::PrimitiveNeeds& needs,
                    const std::string& where, const CheckOptions& options, PrimitiveCheck& result) {
  const Json& attributes = primitive["attributes"];
  const detail::PrimitiveGeometry geometry = detail::readGeometry(asset, primitive, needs, where);
  result.vertices = geometry.vertexCount;
  result.triangles = geometry.corners.size() / 3;
  auto skipRest = [&](std::size_t from) {
    for (std::size_t i = from; i < std::size(kCheckNames); ++i) result.notRun.push_back(kCheckNames[i]);
  };

  const int tangentAccessor = detail::accessorOf(attributes, "TANGENT");
  if (tangentAccessor < 0) {
    FindingBuilder present("present", "primitive", 1);
    present.fail(0, 1, "no TANGENT attribute");
    present.finish(result, "TANGENT is missing: the material's normal texture needs it (run tangent bake)");
    skipRest(1);
    return;
  }
  result.passed.push_back("present");
  const detail::AccessorData data = detail::readAccessor(asset.model, tangentAccessor, where + ": TANGENT");
  const bool floatType = data.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT;
  const bool quantized = data.normalized && (data.componentType == TINYGLTF_COMPONENT_TYPE_BYTE ||
                                              data.componentType == TINYGLTF_COMPONENT_TYPE_SHORT);
  if (data.type != TINYGLTF_TYPE_VEC4 || !(floatType || quantized) || data.count != geometry.vertexCount) {
    FindingBuilder formatCheck("format", "primitive", 1);
    formatCheck.fail(0, 1, format("%s of %s%s, %zu elements", detail::typeName(data.type), detail::componentTypeName(data.componentType),
                                  data.normalized ? " normalized" : "", data.count));
    formatCheck.finish(result, format("TANGENT (accessor %d) must be VEC4 of FLOAT or normalized BYTE/SHORT with one element "
                                      "per vertex (%zu)", tangentAccessor, geometry.vertexCount));
    skipRest(2);
    return;
  }
  result.passed.push_back("format");
  const std::vector<float> tangents = detail::toFloats(data);
  const std::size_t n = geometry.vertexCount;

  FindingBuilder finite("finite", "vertices", n);
  FindingBuilder unit("unit", "vertices", n);
  FindingBuilder w("w", "vertices", n);
  // Quantized tangents cannot be unit to 1e-3: allow their rounding (half a step per component).
  const double unitTolerance = data.componentType == TINYGLTF_COMPONENT_TYPE_BYTE && data.normalized ? 0.5 / 127 * std::sqrt(3.0) + 1e-3 : 1e-3;
  for (std::size_t v = 0; v < n; ++v) {
    const float* t = &tangents[4 * v];
    if (!finite4(t)) {
      finite.fail(v, 1, "vertex " + std::to_string(v) + " " + tangentText(t));
      continue;
    }
    const double length = length3(t);
    if (std::abs(length - 1.0) > unitTolerance)
      unit.fail(v, std::abs(length - 1.0), format("vertex %zu |xyz| = %.6g ", v, length) + tangentText(t));
    if (!detail::validW(t[3])) w.fail(v, std::abs(std::abs(t[3]) - 1.0), format("vertex %zu w = %.6g", v, t[3]));
  }
  finite.finish(result, "TANGENT has NaN or infinite components");
  unit.finish(result, format("|xyz| differs from 1 by more than %.3g", unitTolerance));
  w.finish(result, "w must be exactly +1 or -1");

  const std::size_t triangleCount = geometry.corners.size() / 3;
  FindingBuilder uniform("w-uniform", "triangles", triangleCount);
  FindingBuilder handedness("handedness", "triangles", triangleCount);
  FindingBuilder orthogonal("orthogonal", "vertices", n);
  std::vector<char> usedVertex(n, 0);
  for (std::size_t t = 0; t < triangleCount; ++t) {
    const std::uint32_t* c = &geometry.corners[3 * t];
    for (int k = 0; k < 3; ++k) usedVertex[c[k]] = 1;
    const float w0 = tangents[4 * c[0] + 3], w1 = tangents[4 * c[1] + 3], w2 = tangents[4 * c[2] + 3];
    if (!(w0 == w1 && w1 == w2)) {
      uniform.fail(t, 1, format("triangle %zu (vertices %u %u %u) w = %.6g %.6g %.6g", t, c[0], c[1], c[2], w0, w1, w2));
      continue;
    }
    // Orientation in the normal texture's UV set, on triangles with UV and 3D area.
    const float* uv[3] = {&geometry.uvs[2 * c[0]], &geometry.uvs[2 * c[1]], &geometry.uvs[2 * c[2]]};
    const double det = detail::uvAreaTimesTwo(uv[0], uv[1], uv[2]);
    const float expected = detail::expectedW(det);
    const double area = detail::areaTimesTwo(&geometry.positions[3 * c[0]], &geometry.positions[3 * c[1]], &geometry.positions[3 * c[2]]);
    if (expected == 0 || !std::isfinite(det) || !(area > 0) || !detail::validW(w0)) continue;
    if (w0 != expected)
      handedness.fail(t, std::abs(det), format("triangle %zu (vertices %u %u %u) has w = %.0f, its UV orientation needs %.0f", t, c[0],
                                                c[1], c[2], w0, expected));
  }
  uniform.finish(result, "w differs between the corners of a triangle (a vertex shared across a mirror seam?)");
  handedness.finish(result, "w disagrees with the triangle's orientation in the normal texture's UV set (w = -sign(UV area) in glTF)");

  for (std::size_t v = 0; v < n; ++v) {
    const float* t = &tangents[4 * v];
    const float* normal = &geometry.normals[3 * v];
    if (!usedVertex[v] || !finite4(t)) continue;
    const double offPlane = detail::offPlaneDegrees(t, normal);
    if (offPlane > options.toleranceDegrees)
      orthogonal.fail(v, offPlane, format("vertex %zu is %.4g deg out of the tangent plane, N = (%.4g, %.4g, %.4g), T = ", v, offPlane,
                                          normal[0], normal[1], normal[2]) + tangentText(t));
  }
  orthogonal.finish(result, format("xyz leaves the plane normal to NORMAL by more than %.3g deg", options.toleranceDegrees));

  // Against freshly computed tangents, on corners where the method defines a frame.
  Options core;
  core.method = options.method;
  core.uvOrigin = UvOrigin::topLeft;
  std::vector<float> computed(geometry.corners.size() * 4);
  std::vector<FrameSource> sources(geometry.corners.size());
  computeCornerTangents({geometry.positions, geometry.normals, geometry.uvs, geometry.corners}, computed, core, sources);
  FindingBuilder reference("reference", "corners", geometry.corners.size());
  for (std::size_t c = 0; c < geometry.corners.size(); ++c) {
    if (sources[c] == FrameSource::neighbour || sources[c] == FrameSource::fixed) {
      ++result.referenceUndefined;
      continue;
    }
    const std::uint32_t v = geometry.corners[c];
    const float* stored = &tangents[4 * v];
    const float* fresh = &computed[4 * c];
    if (!finite4(stored)) continue;  // `finite` reported it
    const double angle = detail::angleBetweenDegrees(stored, fresh);
    const bool wDiffers = (stored[3] < 0) != (fresh[3] < 0);
    if (angle > options.toleranceDegrees || wDiffers)
      reference.fail(c, angle + (wDiffers ? 360 : 0),
                     format("corner %zu (vertex %u): %.4g deg from %s; stored ", c, v, angle, std::string(toString(options.method)).c_str()) +
                         tangentText(stored) + ", computed " + tangentText(fresh));
  }
  reference.finish(result, format("differs from freshly computed %s tangents by more than %.3g deg, or in w",
                                  std::string(toString(options.method)).c_str(), options.toleranceDegrees));
}

}  // namespace

bool FileCheck::clean() const {
  if (!error.empty()) return false;
  return std::all_of(primitives.begin(), primitives.end(), [](const PrimitiveCheck& p) { return p.findings.empty(); });
}

FileCheck checkFile(const std::filesystem::path& input, const CheckOptions& options) {
  FileCheck result;
  result.file = input.string();
  try {
    const detail::Asset asset = detail::loadAsset(input, options.assetRoot);
    const Json& doc = asset.json;
    const std::size_t meshCount = doc.contains("meshes") ? doc["meshes"].size() : 0;
    for (std::size_t m = 0; m < meshCount; ++m) {
      const Json& mesh = doc["meshes"][m];
      for (std::size_t p = 0; p < mesh["primitives"].size(); ++p) {
        const Json& primitive = mesh["primitives"][p];
        const std::string label = detail::primitiveLabel(doc, static_cast<int>(m), static_cast<int>(p));
        const detail::PrimitiveNeeds needs = detail::primitiveNeeds(doc, primitive, options.all || asset.fromMeshFile);
        const bool hasNormal = detail::accessorOf(primitive["attributes"], "NORMAL") >= 0;
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
          CheckFinding finding;
          finding.check = "format";
          finding.unit = "primitive";
          finding.failed = finding.total = 1;
          finding.message = problem;
          check.findings.push_back(std::move(finding));
          for (const char* name : kCheckNames) {
            if (std::string(name) != "present" && std::string(name) != "format") check.notRun.push_back(name);
          }
          result.primitives.push_back(std::move(check));
          continue;
        }
        if (!needs.triangles || needs.texCoord < 0 || !hasNormal || !hasUv) {
          std::string why = needs.why;
          if (needs.triangles && needs.texCoord >= 0)
            why = !hasNormal ? "no NORMAL attribute" : "no TEXCOORD_" + std::to_string(needs.texCoord) + " attribute";
          result.skipped.push_back(label + ": " + why);
          continue;
        }
        PrimitiveCheck check = newCheck();
        checkPrimitive(asset, primitive, needs, input.string() + ": " + label, options, check);
        result.primitives.push_back(std::move(check));
      }
    }
  } catch (const std::exception& e) {
    result.primitives.clear();
    result.error = e.what();
  }
  return result;
}

nlohmann::ordered_json toJson(const FileCheck& check) {
  Json primitives = Json::array();
  for (const PrimitiveCheck& p : check.primitives) {
    Json findings = Json::array();
    for (const CheckFinding& f : p.findings) {
      Json worst = Json::array();
      for (const CheckSample& s : f.worst) worst.push_back({{"element", s.element}, {"severity", s.severity}, {"detail", s.detail}});
      findings.push_back({{"check", f.check}, {"unit", f.unit}, {"failed", f.failed}, {"total", f.total},
                          {"message", f.message}, {"worst", worst}});
    }
    primitives.push_back({{"mesh", p.mesh}, {"meshName", p.meshName}, {"primitive", p.primitive}, {"texCoord", p.texCoord},
                          {"vertices", p.vertices}, {"triangles", p.triangles}, {"passed", p.passed}, {"notRun", p.notRun},
                          {"findings", findings}, {"referenceUndefinedCorners", p.referenceUndefined}});
  }
  Json out = {{"file", check.file}, {"status", !check.error.empty() ? "error" : check.clean() ? "clean" : "findings"}};
  if (!check.error.empty()) out["error"] = check.error;
  out["primitives"] = primitives;
  out["skipped"] = check.skipped;
  return out;
}

}  // namespace tangent::gltf
