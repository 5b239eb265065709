// SPDX-License-Identifier: MIT
// check --config FILE.json: the same settings as the command line's, from a file.
#include <fstream>

#include "read/validate.hpp"
#include "tangent/check.hpp"
#include "tangent/text.hpp"

namespace tangent::gltf {

using Json = nlohmann::ordered_json;
using detail::checkJsonDepth;
using detail::kMaxJsonBytes;

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
  // A regular file only: /dev/zero was read without end, a FIFO waited forever.
  const auto status = std::filesystem::status(file, ec);
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
    throw std::runtime_error(file.string() + ": the check configuration is not a regular file");
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
      options.weighting = Weighting::angle;
    } else if (key == "reference") {
      const std::optional<Generator> generator = value.is_string() ? parseGenerator(value.get<std::string>()) : std::nullopt;
      if (!generator)
        throw std::runtime_error(where + ": reference must be " + generatorNames());
      options.method = generator->method;
      options.weighting = generator->weighting;
    } else if (key == "minCoverage") {
      if (!value.is_number() || !(value.get<double>() >= 0) || value.get<double>() > 1)
        throw std::runtime_error(where + ": minCoverage must be a fraction in [0, 1] (0: no warning)");
      options.minCoverage = value.get<double>();
    } else if (key == "allowMissing" || key == "all") {
      if (!value.is_boolean()) throw std::runtime_error(where + ": " + key + " must be true or false");
      (key == "all" ? options.all : options.allowMissing) = value.get<bool>();
    } else {
      throw std::runtime_error(where + ": unknown setting \"" + key + "\" (only, ignore, tolerance, method, reference, minCoverage, allowMissing, all)");
    }
  }
  options.configFile = file.string();
}

}  // namespace tangent::gltf
