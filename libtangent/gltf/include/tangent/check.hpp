// Validation of the tangents stored in a glTF file: what `tangent check` runs for CI.
#pragma once

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tangent/tangent.hpp"

namespace tangent::gltf {

struct CheckOptions {
  Method method = Method::mikktspace;  // what `reference` recomputes with
  double toleranceDegrees = 1.0;       // for `orthogonal` and `reference`
  bool all = false;                    // every triangle primitive, not only normal-mapped ones
  std::filesystem::path assetRoot;     // folder buffer and image URIs may not leave (empty: the file's)
};

// The checks, in the order they run. `present` and `format` gate the rest.
inline constexpr const char* kCheckNames[] = {"present", "format",      "finite",     "unit",     "w",
                                              "w-uniform", "orthogonal", "handedness", "reference"};

struct CheckSample {
  std::uint64_t element = 0;  // vertex, triangle or corner index, per the finding's unit
  double severity = 0;        // larger is worse (deviation, angle...)
  std::string detail;         // the values, for people
};

struct CheckFinding {
  std::string check;
  std::string unit;            // "vertices", "triangles", "corners" or "primitive"
  std::uint64_t failed = 0;
  std::uint64_t total = 0;
  std::string message;         // what is wrong, with the threshold
  std::vector<CheckSample> worst;  // up to 5, worst first
};

struct PrimitiveCheck {
  int mesh = 0;
  std::string meshName;
  int primitive = 0;
  int texCoord = -1;
  std::uint64_t vertices = 0;
  std::uint64_t triangles = 0;
  std::vector<std::string> passed;      // checks that ran clean
  std::vector<std::string> notRun;      // checks a failed gate (present, format) made moot
  std::vector<CheckFinding> findings;
  std::uint64_t referenceUndefined = 0; // corners the reference method leaves arbitrary: not compared
};

struct FileCheck {
  std::string file;
  std::string error;                     // unreadable input (then no primitives)
  std::vector<PrimitiveCheck> primitives;  // those that need tangents
  std::vector<std::string> skipped;        // primitives not checked, and why
  bool clean() const;
};

// Never throws for bad input: an unreadable file comes back with `error` set.
FileCheck checkFile(const std::filesystem::path& input, const CheckOptions& options);

nlohmann::ordered_json toJson(const FileCheck& check);

}  // namespace tangent::gltf
