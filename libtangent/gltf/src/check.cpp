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

#include "accessors.hpp"
#include "asset.hpp"
#include "primitive.hpp"
#include "check_primitive.hpp"
#include "entry_point.hpp"
#include "tangent_rules.hpp"
#include "validate.hpp"
#include "tangent/gltf.hpp"
#include "tangent/text.hpp"

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
  void trim() {
    std::stable_sort(finding_.worst.begin(), finding_.worst.end(), [](const CheckSample& a, const CheckSample& b) {
      return a.wDiffers != b.wDiffers ? a.wDiffers : a.severity > b.severity;
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

}  // namespace

namespace detail {

void checkPrimitiveTangents(const Asset& asset, const Json& primitive, const PrimitiveNeeds& needs, const std::string& where,
                            const CheckOptions& options, PrimitiveCheck& result) {
  const Json& attributes = primitive["attributes"];
  const PrimitiveGeometry geometry = readGeometry(asset, primitive, needs, where);
  result.vertices = geometry.vertexCount;
  result.triangles = geometry.corners.size() / 3;

  const int tangentAccessor = accessorOf(attributes, "TANGENT");
  if (tangentAccessor < 0) {
    FindingBuilder present(CheckId::present, "primitive", 1, "none", 0, options);
    present.fail(0, 1, "no TANGENT attribute");
    present.finish(result, "TANGENT is missing: the material's normal texture needs it (run tangent bake, or pass "
                           "--allow-missing when clients compute MikkTSpace)");
    skipFrom(CheckId::format, options, result);
    return;
  }
  (options.runs(CheckId::present) ? result.passed : result.ignored).push_back("present");
  const AccessorData data = readAccessor(asset.model, tangentAccessor, where + ": TANGENT");
  const std::optional<StoredComponent> tangentComponent = storedComponentOf(data.componentType, data.normalized);
  const int normalAccessor = accessorOf(attributes, "NORMAL");
  const Json& normalJson = asset.json["accessors"][normalAccessor];
  const std::optional<StoredComponent> normalComponent =
      storedComponentOf(normalJson.value("componentType", 0), normalJson.value("normalized", false));
  if (data.type != TINYGLTF_TYPE_VEC4 || !tangentComponent || data.count != geometry.vertexCount) {
    FindingBuilder formatCheck(CheckId::format, "primitive", 1, "none", 0, options);
    formatCheck.fail(0, 1, format("%s of %s%s, %zu elements", typeName(data.type), componentTypeName(data.componentType),
                                  data.normalized ? " normalized" : "", data.count));
    formatCheck.finish(result, format("TANGENT (accessor %d) must be VEC4 of FLOAT or normalized BYTE/SHORT with one element "
                                      "per vertex (%zu)", tangentAccessor, geometry.vertexCount));
    skipFrom(CheckId::finite, options, result);
    return;
  }
  (options.runs(CheckId::format) ? result.passed : result.ignored).push_back("format");
  const StoredTangentLimits limits =
      storedTangentLimits(*tangentComponent, normalComponent.value_or(StoredComponent::float32));
  const double orthogonalLimit = orthogonalLimitDegrees(limits, options.orthogonalToleranceDegrees);
  const double referenceLimit = referenceLimitDegrees(limits, options.referenceToleranceDegrees, 0);
  result.tangentComponent = toString(*tangentComponent);
  result.normalComponent = normalComponent ? toString(*normalComponent) : "";
  result.unitLimit = limits.unitDeviation;
  result.orthogonalLimitDegrees = orthogonalLimit;
  result.referenceLimitDegrees = referenceLimit;

  const std::vector<float> tangents = toFloats(data);
  const std::size_t n = geometry.vertexCount;
  const char* component = toString(*tangentComponent);

  FindingBuilder finite(CheckId::finite, "vertices", n, "none", 0, options);
  FindingBuilder unit(CheckId::unit, "vertices", n, "length", limits.unitDeviation, options);
  FindingBuilder w(CheckId::w, "vertices", n, "none", 0, options);
  for (std::size_t v = 0; v < n; ++v) {
    const float* t = &tangents[4 * v];
    if (!finite4(t)) {
      finite.fail(v, 1, "vertex " + std::to_string(v) + " " + tangentText(t));
      continue;
    }
    if (!unitOk(t, limits))
      unit.fail(v, unitDeviation(t), format("vertex %zu |xyz| = %.6g ", v, length3(t)) + tangentText(t));
    if (!validW(t[3])) w.fail(v, std::abs(std::abs(t[3]) - 1.0), format("vertex %zu w = %.6g", v, t[3]));
  }
  finite.finish(result, "TANGENT has NaN or infinite components");
  unit.finish(result, format("|xyz| differs from 1 by more than %.3g (%s)", limits.unitDeviation, component));
  w.finish(result, "w must be exactly +1 or -1");

  // Rounded positions and UVs (KHR_mesh_quantization) move the recomputed frame: per vertex
  // allowance, and triangles whose UV orientation the rounding leaves open.
  const ReferenceAllowance allowance =
      referenceAllowance(geometry, inputRounding(asset, primitive, needs.texCoord, needs.hasNormalTexture));

  const std::size_t triangleCount = geometry.corners.size() / 3;
  FindingBuilder uniform(CheckId::wUniform, "triangles", triangleCount, "none", 0, options);
  FindingBuilder handedness(CheckId::handedness, "triangles", triangleCount, "uv-area", 0, options);
  FindingBuilder orthogonal(CheckId::orthogonal, "vertices", n, "degrees", orthogonalLimit, options);
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
    const double det = uvAreaTimesTwo(uv[0], uv[1], uv[2]);
    const float expected = expectedW(det);
    const double area = areaTimesTwo(&geometry.positions[3 * c[0]], &geometry.positions[3 * c[1]], &geometry.positions[3 * c[2]]);
    if (expected == 0 || !std::isfinite(det) || !(area > 0) || !validW(w0) || !allowance.decided(t)) continue;
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
    const double offPlane = offPlaneDegrees(t, normal);
    if (offPlane > orthogonalLimit)
      orthogonal.fail(v, offPlane, format("vertex %zu is %.4g deg out of the tangent plane, N = (%.4g, %.4g, %.4g), T = ", v, offPlane,
                                          normal[0], normal[1], normal[2]) + tangentText(t));
  }
  // The limits in words: the tolerance, plus rounding where there is any.
  const bool roundedFrame = limits.tangentAngleDegrees > 0 || limits.normalAngleDegrees > 0;
  const std::string frameRounding =
      roundedFrame ? format(" (%.3g + rounding of %s TANGENT and %s NORMAL)", options.orthogonalToleranceDegrees, component,
                            result.normalComponent.c_str())
                   : "";
  orthogonal.finish(result, format("xyz leaves the plane normal to NORMAL by more than %.3g deg", orthogonalLimit) + frameRounding);

  // Against freshly computed tangents, on corners where the method defines a frame.
  FindingBuilder reference(CheckId::reference, "corners", geometry.corners.size(), "degrees", referenceLimit, options);
  if (options.runs(CheckId::reference)) {
    Options core;
    core.method = options.method;
    core.uvOrigin = kGltfUvOrigin;
    core.threads = threadsFor(geometry.corners.size(), core.threads);
    std::vector<float> computed(geometry.corners.size() * 4);
    std::vector<FrameSource> sources(geometry.corners.size());
    computeCornerTangents({geometry.positions, geometry.normals, geometry.uvs, geometry.corners}, computed, core, sources);
    for (std::size_t c = 0; c < geometry.corners.size(); ++c) {
      if (sources[c] == FrameSource::neighbour || sources[c] == FrameSource::fixed) {
        ++result.referenceUndefined;
        continue;
      }
      const std::uint32_t v = geometry.corners[c];
      const float extra = allowance.vertex(v);
      if (extra >= kUncomparableDegrees) {
        ++result.referenceUnresolved;
        continue;
      }
      result.referenceAllowanceMaxDegrees = std::max(result.referenceAllowanceMaxDegrees, double(extra));
      const float* stored = &tangents[4 * v];
      const float* fresh = &computed[4 * c];
      if (!finite4(stored)) continue;  // `finite` reported it
      const double angle = angleBetweenDegrees(stored, fresh);
      const double limit = referenceLimitDegrees(limits, options.referenceToleranceDegrees, extra);
      if (referenceFails(angle, stored[3], fresh[3], limit)) {
        const bool wDiffers = (stored[3] < 0) != (fresh[3] < 0);
        reference.fail(c, angle,
                       format("corner %zu (vertex %u): %.4g deg from %s (limit %.3g)%s; stored ", c, v, angle,
                              std::string(toString(options.method)).c_str(), limit, wDiffers ? ", w differs" : "") +
                           tangentText(stored) + ", computed " + tangentText(fresh),
                       wDiffers);
      }
    }
  }
  // Ignored checks listed in check order (they finish in the order the passes run).
  std::sort(result.ignored.begin(), result.ignored.end(),
            [](const std::string& a, const std::string& b) { return *parseCheck(a) < *parseCheck(b); });
  std::string referenceRounding;
  if (roundedFrame)
    referenceRounding = format(" (%.3g + rounding of %s TANGENT and %s NORMAL)", options.referenceToleranceDegrees, component,
                               result.normalComponent.c_str());
  if (allowance.orientationDecided.size())
    referenceRounding += format(", plus up to %.3g deg per corner for rounded positions/UVs", result.referenceAllowanceMaxDegrees);
  reference.finish(result, format("differs from freshly computed %s tangents by more than %.3g deg",
                                  std::string(toString(options.method)).c_str(), referenceLimit) +
                               referenceRounding + ", or in w");
}

std::string findingsSummary(const PrimitiveCheck& check) {
  std::string text;
  for (const CheckFinding& f : check.findings) {
    if (!text.empty()) text += "; ";
    text += f.check + ": " + std::to_string(f.failed) + " of " + std::to_string(f.total) + " " + f.unit;
  }
  return text;
}

}  // namespace detail

bool FileCheck::clean() const {
  if (!error.empty()) return false;
  return std::all_of(primitives.begin(), primitives.end(), [](const PrimitiveCheck& p) { return p.findings.empty(); });
}

namespace {

FileCheck checkAsset(const std::filesystem::path& input, const CheckOptions& options) {
  FileCheck result;
  result.file = input.string();
  const auto started = std::chrono::steady_clock::now();
  {
    const detail::Asset asset = detail::loadAsset(input, options.assetRoot);
    const Json& doc = asset.json;
    std::unordered_map<std::string, PrimitiveCheck> verdicts;  // by detail::sameInputKey and TANGENT
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
          FindingBuilder formatCheck(CheckId::format, "primitive", 1, "none", 0, options);
          formatCheck.fail(0, 1, problem);
          formatCheck.finish(check, problem);
          skipFrom(CheckId::finite, options, check);
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
        if (options.allowMissing && detail::accessorOf(primitive["attributes"], "TANGENT") < 0) {
          result.skipped.push_back(label + ": no TANGENT, allowed (--allow-missing: clients compute MikkTSpace from TEXCOORD_" +
                                   std::to_string(needs.texCoord) + ")");
          continue;
        }
        // Primitives with the same inputs and TANGENT get the same verdict: checked once.
        const std::string key = detail::sameInputKey(doc, primitive, needs) +
                                std::to_string(detail::accessorOf(primitive["attributes"], "TANGENT"));
        auto known = verdicts.find(key);
        if (known == verdicts.end()) {
          PrimitiveCheck verdict;
          checkPrimitiveTangents(asset, primitive, needs, input.string() + ": " + label, options, verdict);
          known = verdicts.emplace(key, std::move(verdict)).first;
        }
        PrimitiveCheck check = known->second;
        const PrimitiveCheck named = newCheck();
        check.mesh = named.mesh;
        check.primitive = named.primitive;
        check.meshName = named.meshName;
        check.texCoord = named.texCoord;
        result.primitives.push_back(std::move(check));
      }
    }
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return result;
}

}  // namespace

FileCheck checkFile(const std::filesystem::path& input, const CheckOptions& options) {
  return detail::throwingInputError(input, [&] { return checkAsset(input, options); });
}

nlohmann::ordered_json toJson(const FileCheck& check) {
  Json primitives = Json::array();
  for (const PrimitiveCheck& p : check.primitives) {
    Json findings = Json::array();
    for (const CheckFinding& f : p.findings) {
      Json worst = Json::array();
      for (const CheckSample& s : f.worst) {
        Json sample = {{"element", s.element}, {"severity", s.severity}};
        if (f.check == "reference") sample["wDiffers"] = s.wDiffers;
        sample["detail"] = s.detail;
        worst.push_back(std::move(sample));
      }
      findings.push_back({{"check", f.check}, {"unit", f.unit}, {"failed", f.failed}, {"total", f.total},
                          {"message", f.message}, {"severityUnit", f.severityUnit}, {"limit", f.limit}, {"worst", worst}});
    }
    Json entry = {{"mesh", p.mesh}, {"meshName", p.meshName}, {"primitive", p.primitive}, {"texCoord", p.texCoord},
                  {"vertices", p.vertices}, {"triangles", p.triangles}};
    if (!p.tangentComponent.empty())
      entry["limits"] = {{"tangentComponent", p.tangentComponent},
                         {"normalComponent", p.normalComponent},
                         {"unitDeviation", p.unitLimit},
                         {"orthogonalDegrees", p.orthogonalLimitDegrees},
                         {"referenceDegrees", p.referenceLimitDegrees},
                         {"referenceAllowanceMaxDegrees", p.referenceAllowanceMaxDegrees}};
    entry["passed"] = p.passed;
    entry["notRun"] = p.notRun;
    entry["ignored"] = p.ignored;
    entry["findings"] = findings;
    entry["referenceUndefinedCorners"] = p.referenceUndefined;
    entry["referenceUnresolvedCorners"] = p.referenceUnresolved;
    primitives.push_back(std::move(entry));
  }
  Json out = {{"file", check.file}, {"status", !check.error.empty() ? "error" : check.clean() ? "clean" : "findings"}};
  if (!check.error.empty()) out["error"] = check.error;
  out["primitives"] = primitives;
  out["skipped"] = check.skipped;
  return out;
}

std::optional<CheckId> parseCheck(std::string_view name) {
  for (std::size_t i = 0; i < kCheckCount; ++i) {
    if (name == kCheckNames[i]) return static_cast<CheckId>(i);
  }
  return std::nullopt;
}

namespace {

std::bitset<kCheckCount> checkSet(const Json& list, const std::string& where) {
  if (!list.is_array()) throw std::runtime_error(where + ": must be an array of check names");
  std::bitset<kCheckCount> set;
  for (const Json& name : list) {
    const std::optional<CheckId> id = name.is_string() ? parseCheck(name.get<std::string>()) : std::nullopt;
    if (!id) throw std::runtime_error(where + ": unknown check " + name.dump());
    set.set(static_cast<std::size_t>(*id));
  }
  return set;
}

double toleranceValue(const Json& value, const std::string& where) {
  if (!value.is_number() || !(value.get<double>() > 0) || value.get<double>() > 180)
    throw std::runtime_error(where + ": must be a number of degrees in (0, 180]");
  return value.get<double>();
}

}  // namespace

void applyCheckConfig(const std::filesystem::path& file, CheckOptions& options) {
  // The limits of a glTF's JSON (size, then nesting before the parser recurses): a config
  // nested a million deep overflowed the stack.
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(file, ec);
  if (!ec && size > kMaxJsonBytes)
    throw std::runtime_error(file.string() + ": the check configuration is " + std::to_string(size) + " bytes; the limit is " +
                             std::to_string(kMaxJsonBytes));
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error(file.string() + ": cannot read the check configuration");
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  checkJsonDepth(text, file.string(), "the check configuration");
  Json config;
  try {
    config = Json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(file.string() + ": not JSON: " + text::quoted(e.what()));
  }
  const std::string where = file.string();
  if (!config.is_object()) throw std::runtime_error(where + ": must be a JSON object");
  for (const auto& [key, value] : config.items()) {
    if (key == "only") {
      options.enabled = checkSet(value, where + ": only");
    } else if (key == "ignore") {
      options.enabled &= ~checkSet(value, where + ": ignore");
    } else if (key == "tolerance") {
      if (value.is_number()) {
        options.orthogonalToleranceDegrees = options.referenceToleranceDegrees = toleranceValue(value, where + ": tolerance");
      } else if (value.is_object()) {
        for (const auto& [check, degrees] : value.items()) {
          if (check == "orthogonal") options.orthogonalToleranceDegrees = toleranceValue(degrees, where + ": tolerance.orthogonal");
          else if (check == "reference") options.referenceToleranceDegrees = toleranceValue(degrees, where + ": tolerance.reference");
          else throw std::runtime_error(where + ": tolerance." + check + ": only orthogonal and reference have a tolerance");
        }
      } else {
        throw std::runtime_error(where + ": tolerance must be degrees or {\"orthogonal\": DEG, \"reference\": DEG}");
      }
    } else if (key == "method") {
      const std::optional<Method> method = value.is_string() ? parseMethod(value.get<std::string>()) : std::nullopt;
      if (!method || *method == Method::flat) throw std::runtime_error(where + ": method must be \"mikktspace\" or \"lengyel\"");
      options.method = *method;
    } else if (key == "allowMissing" || key == "all") {
      if (!value.is_boolean()) throw std::runtime_error(where + ": " + key + " must be true or false");
      (key == "all" ? options.all : options.allowMissing) = value.get<bool>();
    } else {
      throw std::runtime_error(where + ": unknown setting \"" + key + "\" (only, ignore, tolerance, method, allowMissing, all)");
    }
  }
  options.configFile = file.string();
}

nlohmann::ordered_json toJson(const CheckOptions& options) {
  Json checks = Json::array(), ignored = Json::array();
  for (std::size_t i = 0; i < kCheckCount; ++i) (options.enabled.test(i) ? checks : ignored).push_back(kCheckNames[i]);
  Json settings = {{"method", std::string(toString(options.method))},
                   {"tolerance", {{"orthogonal", options.orthogonalToleranceDegrees}, {"reference", options.referenceToleranceDegrees}}},
                   {"checks", checks},
                   {"ignored", ignored},
                   {"allowMissing", options.allowMissing},
                   {"all", options.all}};
  settings["config"] = options.configFile.empty() ? Json(nullptr) : Json(options.configFile);
  return settings;
}

}  // namespace tangent::gltf
