// SPDX-License-Identifier: MIT
// bake's names (tangent formats, normals modes, actions), output paths, and its results as the
// JSON of `tangent bake --report` (docs/report.md).
#include "read/primitive.hpp"
#include "tangent/gltf.hpp"

namespace tangent::gltf {

using Json = nlohmann::ordered_json;

std::optional<TangentFormat> parseTangentFormat(std::string_view name) {
  if (name == "float") return TangentFormat::float32;
  if (name == "short") return TangentFormat::normalizedShort;
  if (name == "byte") return TangentFormat::normalizedByte;
  return std::nullopt;
}

std::optional<NormalsMode> parseNormalsMode(std::string_view name) {
  if (name == "flat") return NormalsMode::flat;
  if (name == "smooth") return NormalsMode::smooth;
  if (name == "keep") return NormalsMode::keep;
  return std::nullopt;
}

const char* toString(NormalsMode mode) {
  switch (mode) {
    case NormalsMode::flat: return "flat";
    case NormalsMode::smooth: return "smooth";
    case NormalsMode::keep: return "keep";
  }
  return "?";
}

const char* toString(PrimitiveAction action) {
  switch (action) {
    case PrimitiveAction::baked: return "baked";
    case PrimitiveAction::kept: return "kept";
    case PrimitiveAction::skipped: return "skipped";
  }
  return "?";
}

const char* toString(TangentFormat format) {
  switch (format) {
    case TangentFormat::float32: return "float";
    case TangentFormat::normalizedShort: return "short";
    case TangentFormat::normalizedByte: return "byte";
  }
  return "?";
}

std::filesystem::path outputPathFor(const std::filesystem::path& input, const std::filesystem::path& outputDir) {
  std::filesystem::path name = input.filename();
  if (detail::isMeshFile(input)) name.replace_extension(".glb");
  return outputDir / name;
}

nlohmann::ordered_json toJson(const Report& report) {
  Json json = {{"method", toString(report.method)},
               {"weighting", report.weighting ? toString(*report.weighting) : std::string_view()}};
  for (const ReportCount& count : reportCounts(report)) json[std::string(count.name)] = count.value;  // the core's one list
  return json;
}

nlohmann::ordered_json toJson(const BakeResult& result) {
  Json primitives = Json::array();
  for (const PrimitiveResult& p : result.primitives) {
    Json entry = {{"mesh", p.mesh}, {"meshName", p.meshName}, {"primitive", p.primitive},
                  {"action", toString(p.action)}, {"reason", p.reason}};
    if (p.texCoord >= 0) entry["texCoord"] = p.texCoord;
    if (!p.failedChecks.empty()) entry["failedChecks"] = p.failedChecks;
    if (p.action == PrimitiveAction::baked) {
      entry["tangentFormat"] = toString(p.tangentFormat);
      entry["verticesIn"] = p.verticesIn;
      entry["verticesOut"] = p.verticesOut;
      if (p.normalsGenerated) entry["normalsGenerated"] = toString(*p.normalsGenerated);
      entry["tangents"] = toJson(p.tangents);
    }
    primitives.push_back(std::move(entry));
  }
  Json warnings = Json::array();
  for (const auto& w : result.warnings) warnings.push_back(w);
  Json out = Json::object();  // members moved in: an initializer list would copy every primitive's entry
  out["primitives"] = std::move(primitives);
  out["extensionsRemoved"] = result.extensionsRemoved;
  out["warnings"] = std::move(warnings);
  out["bytesWritten"] = result.bytesWritten;
  Json written = Json::array();
  for (const auto& file : result.filesWritten) written.push_back(file.generic_string());
  out["filesWritten"] = std::move(written);
  return out;
}

}  // namespace tangent::gltf
