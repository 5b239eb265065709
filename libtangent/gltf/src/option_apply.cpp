// SPDX-License-Identifier: MIT
// The option table's values (tangent/option_table.hpp) applied to the glTF layer's options:
// what `tangent bake`, `tangent check` and Python's bake(), bake_tree() and check() share.
#include <cstdlib>
#include <string>

#include "tangent/batch.hpp"
#include "tangent/check.hpp"
#include "tangent/gltf.hpp"
#include "tangent/option_table.hpp"

namespace tangent::gltf {
namespace {

double number(std::string_view value) {
  return std::strtod(std::string(value).c_str(), nullptr);
}

// A checked list value ("unit,w") as the set of checks it names.
std::bitset<kCheckCount> checkSet(std::string_view list) {
  std::bitset<kCheckCount> set;
  while (true) {
    const std::size_t comma = list.find(',');
    if (const auto id = parseCheck(list.substr(0, comma))) set.set(static_cast<std::size_t>(*id));
    if (comma == std::string_view::npos) return set;
    list.remove_prefix(comma + 1);
  }
}

}  // namespace

bool applyBakeOption(BakeOptions& options, const options::Option& option, std::string_view value) {
  if (!(option.commands & options::kBake)) return false;
  if (options::applyOption(options.tangents, option, value)) return true;
  const std::string_view name = option.name;
  if (name == "all")
    options.all = options::isTrue(value);
  else if (name == "overwrite")
    options.overwrite = options::isTrue(value);
  else if (name == "asset-root")
    options.assetRoot = std::string(value);
  else if (name == "keep-external")
    options.keepExternalImages = options::isTrue(value);
  else if (name == "tangent-format")
    options.tangentFormat = parseTangentFormat(value).value_or(options.tangentFormat);
  else if (name == "normals")
    options.normals = parseNormalsMode(value).value_or(options.normals);
  else if (name == "crease-angle")
    options.creaseAngleDegrees = number(value);
  else
    return false;
  return true;
}

bool applyBatchOption(BatchOptions& options, const options::Option& option, std::string_view value) {
  if (!(option.commands & options::kBakeTree)) return false;
  if (option.name == "force")
    options.force = options::isTrue(value);
  else if (option.name == "verify")
    options.verify = options::isTrue(value);
  else
    return applyBakeOption(options.bake, option, value);
  return true;
}

bool applyCheckOption(CheckOptions& options, const options::Option& option, std::string_view value) {
  if (!(option.commands & options::kCheck)) return false;
  const std::string_view name = option.name;
  if (name == "only") {
    options.enabled = checkSet(value);
  } else if (name == "ignore") {
    options.enabled &= ~checkSet(value);
  } else if (name == "tolerance") {
    const std::size_t equals = value.find('=');
    const std::string_view which = equals == std::string_view::npos ? std::string_view() : value.substr(0, equals);
    const double degrees = number(equals == std::string_view::npos ? value : value.substr(equals + 1));
    if (which.empty() || which == "orthogonal") options.orthogonalToleranceDegrees = degrees;
    if (which.empty() || which == "reference") options.referenceToleranceDegrees = degrees;
  } else if (name == "orthogonal-tolerance") {
    options.orthogonalToleranceDegrees = number(value);
  } else if (name == "reference-tolerance") {
    options.referenceToleranceDegrees = number(value);
  } else if (name == "min-coverage") {
    options.minCoverage = number(value);
  } else if (name == "allow-missing") {
    options.allowMissing = options::isTrue(value);
  } else if (name == "reference") {
    if (const auto generator = parseGenerator(value)) {
      options.method = generator->method;
      options.weighting = generator->weighting;
    }
  } else if (name == "method") {
    options.method = parseMethod(value).value_or(options.method);
    options.weighting = Weighting::angle;
  } else if (name == "all") {
    options.all = options::isTrue(value);
  } else if (name == "identify") {
    options.identify = options::isTrue(value);
  } else if (name == "asset-root") {
    options.assetRoot = std::string(value);
  } else {
    return false;
  }
  return true;
}

}  // namespace tangent::gltf
