// SPDX-License-Identifier: MIT
// check's results and options as JSON (docs/check-json.md), and the names of its checks and
// generators.
#include <algorithm>

#include "check/check_primitive.hpp"
#include "tangent/check.hpp"

namespace tangent::gltf {

using Json = nlohmann::ordered_json;

bool FileCheck::clean() const {
  if (!error.empty()) return false;
  return std::all_of(primitives.begin(), primitives.end(), [](const PrimitiveCheck& p) { return p.findings.empty(); });
}

namespace detail {

std::string findingsSummary(const PrimitiveCheck& check) {
  std::string text;
  for (const CheckFinding& f : check.findings) {
    if (!text.empty()) text += "; ";
    text += f.check + ": " + std::to_string(f.failed) + " of " + std::to_string(f.total) + " " + f.unit;
  }
  return text;
}

}  // namespace detail

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
    entry["referenceWUndecidedCorners"] = p.referenceWUndecided;
    entry["handednessUndecidedTriangles"] = p.handednessUndecided;
    entry["normals"] = {{"normalized", p.normalsNormalized}, {"worstLength", p.worstNormalLength}, {"warningLimit", p.normalLengthLimit}};
    entry["warnings"] = p.warnings;
    if (!p.generator.empty()) {
      Json generators = Json::array();
      for (const GeneratorMatch& g : p.generators)
        generators.push_back({{"name", g.name}, {"medianDegrees", g.medianDegrees}, {"maxDegrees", g.maxDegrees}, {"wAgreement", g.wAgreement}});
      entry["generator"] = p.generator;
      entry["generators"] = generators;
    }
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

std::string toString(const Generator& generator) {
  std::string name(toString(generator.method));
  if (generator.method == Method::lengyel) name += "/" + std::string(toString(generator.weighting));
  return name;
}

std::optional<Generator> parseGenerator(std::string_view name) {
  if (name == "lengyel") return Generator{Method::lengyel, Weighting::angle};
  for (const Generator& generator : kGenerators)
    if (toString(generator) == name) return generator;
  return std::nullopt;
}

std::string generatorNames() {
  std::string names;
  for (std::size_t i = 0; i < std::size(kGenerators); ++i)
    names += (i == 0 ? "" : i + 1 == std::size(kGenerators) ? " or " : ", ") + toString(kGenerators[i]);
  return names;
}

nlohmann::ordered_json toJson(const CheckOptions& options) {
  Json checks = Json::array(), ignored = Json::array();
  for (std::size_t i = 0; i < kCheckCount; ++i) (options.enabled.test(i) ? checks : ignored).push_back(kCheckNames[i]);
  Json settings = {{"method", std::string(toString(options.method))},
                   {"reference", toString(Generator{options.method, options.weighting})},
                   {"tolerance", {{"orthogonal", options.orthogonalToleranceDegrees}, {"reference", options.referenceToleranceDegrees}}},
                   {"minCoverage", options.minCoverage},
                   {"checks", checks},
                   {"ignored", ignored},
                   {"allowMissing", options.allowMissing},
                   {"all", options.all}};
  settings["config"] = options.configFile.empty() ? Json(nullptr) : Json(options.configFile);
  return settings;
}

}  // namespace tangent::gltf
