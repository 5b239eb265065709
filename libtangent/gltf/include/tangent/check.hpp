// SPDX-License-Identifier: MIT
// Validation of the tangents stored in a glTF file: what `tangent check` runs for CI.
#pragma once

#include <bitset>
#include <cstdint>
#include <filesystem>
#include <iterator>
#include <optional>
#include <string_view>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tangent/option_table.hpp"
#include "tangent/tangent.hpp"

namespace tangent::gltf {

// The checks, in the order they run. `present` and `format` gate the rest.
enum class CheckId { present, format, finite, unit, w, wUniform, orthogonal, handedness, reference };
inline constexpr const char* kCheckNames[] = {"present", "format",      "finite",     "unit",     "w",
                                              "w-uniform", "orthogonal", "handedness", "reference"};
inline constexpr std::size_t kCheckCount = std::size(kCheckNames);
inline const char* toString(CheckId id) { return kCheckNames[static_cast<std::size_t>(id)]; }
std::optional<CheckId> parseCheck(std::string_view name);

// A tangent generator the library has, named as `check --reference` takes it and `--identify`
// reports it: "mikktspace", "lengyel/angle", "lengyel/area", "lengyel/uniform", "flat",
// "meshopt" (the weighting only matters to lengyel; "lengyel" alone is lengyel/angle).
struct Generator {
  Method method = Method::mikktspace;
  Weighting weighting = Weighting::angle;
  bool operator==(const Generator&) const = default;
};
inline constexpr Generator kGenerators[] = {{Method::mikktspace, Weighting::angle}, {Method::lengyel, Weighting::angle},
                                            {Method::lengyel, Weighting::area},      {Method::lengyel, Weighting::uniform},
                                            {Method::flat, Weighting::angle},        {Method::meshopt, Weighting::angle}};
std::string toString(const Generator& generator);
std::optional<Generator> parseGenerator(std::string_view name);
// Every generator's name, for messages: "mikktspace, lengyel/angle, ... or meshopt".
std::string generatorNames();

inline constexpr double kDefaultMinCoverage = 0.5;

struct CheckOptions {
  Method method = Method::mikktspace;     // what `reference` recomputes with (--reference, --method)
  Weighting weighting = Weighting::angle;  // with it: lengyel's weighting
  double orthogonalToleranceDegrees = 1.0;  // `orthogonal`, on top of the rounding limits
  double referenceToleranceDegrees = 1.0;   // `reference`, on top of the rounding limits
  // --min-coverage: the share of a primitive's corners (`reference`) or triangles (`handedness`)
  // below which having compared so few is a warning (rounded positions/UVs leave the rest
  // undecided); 0 turns the warning off. Half: below it, "ok" rests on fewer elements than it
  // leaves out (NormalTangentTest through gltfpack -vt 8: 2.9% of corners compared; defaults: 100%).
  double minCoverage = kDefaultMinCoverage;
  std::bitset<kCheckCount> enabled = std::bitset<kCheckCount>().set();  // --only / --ignore
  bool allowMissing = false;               // no TANGENT: skipped (the client computes MikkTSpace)
  bool all = false;                        // every triangle primitive, not only normal-mapped ones
  bool identify = false;                   // --identify: name the generator closest to the stored tangents
  std::filesystem::path assetRoot;         // folder buffer and image URIs may not leave (empty: the file's)
  std::string configFile;                  // where the settings came from, for the report ("" for none)
  bool runs(CheckId id) const { return enabled.test(static_cast<std::size_t>(id)); }
};

// A checked value of the option table (tangent/option_table.hpp) into `options`, as the command
// line and Python's check() give them; false when the option is not one of check's.
bool applyCheckOption(CheckOptions& options, const options::Option& option, std::string_view value);

// Reads a check configuration (JSON: only, ignore, tolerance {orthogonal, reference}, method,
// reference (a generator name), minCoverage, allowMissing, all; README "tangent check") into `options`. Throws std::runtime_error naming
// the file and the member that is wrong.
void applyCheckConfig(const std::filesystem::path& file, CheckOptions& options);

// The settings as the JSON report records them.
nlohmann::ordered_json toJson(const CheckOptions& options);

struct CheckSample {
  std::uint64_t element = 0;  // vertex, triangle or corner index, per the finding's unit
  double severity = 0;        // larger is worse, in the finding's severityUnit
  bool wDiffers = false;      // `reference` only: w disagrees too (ranked before any angle)
  std::string detail;         // the values, for people
};

struct CheckFinding {
  std::string check;
  std::string unit;            // "vertices", "triangles", "corners" or "primitive"
  std::uint64_t failed = 0;
  std::uint64_t total = 0;
  std::string message;         // what is wrong, with the threshold
  std::string severityUnit;    // of the samples' severity: "degrees", "length", "uv-area" or "none"
  double limit = 0;            // the threshold applied, in severityUnit (0 where exact)
  std::vector<CheckSample> worst;  // up to 5, worst first
};

// How close the stored tangents are to one generator's (check --identify), over the corners
// that generator defines a frame for.
struct GeneratorMatch {
  std::string name;            // a generator's name (toString(Generator))
  double medianDegrees = 0;
  double maxDegrees = 0;
  double wAgreement = 0;       // share of corners whose w agrees
};
// The largest median angle and smallest w agreement at which --identify still names a generator.
inline constexpr double kIdentifyMedianDegrees = 0.5;
inline constexpr double kIdentifyWAgreement = 0.99;

struct PrimitiveCheck {
  int mesh = 0;
  std::string meshName;
  int primitive = 0;
  int texCoord = -1;
  std::uint64_t vertices = 0;
  std::uint64_t triangles = 0;
  std::vector<std::string> passed;      // checks that ran clean
  std::vector<std::string> notRun;      // checks a failed gate (present, format) made moot
  std::vector<std::string> ignored;     // checks --only / --ignore left out
  std::string tangentComponent;         // "float", "normalized SHORT", "normalized BYTE" ("" when unknown)
  std::string normalComponent;
  double unitLimit = 0;                 // the limits applied (tangent_rules): | |xyz| - 1 |
  double orthogonalLimitDegrees = 0;
  double referenceLimitDegrees = 0;     // before the per-corner allowance for rounded positions/UVs
  std::vector<CheckFinding> findings;
  std::uint64_t referenceUndefined = 0; // corners the reference method leaves arbitrary: not compared
  std::uint64_t referenceUnresolved = 0; // corners whose frame rounded positions/UVs leave open (the allowance reaches 180 deg, or
                                         // their triangle's UV orientation is undecided and w differs): not compared
  double referenceAllowanceMaxDegrees = 0;  // largest per-corner allowance for rounded positions/UVs
  std::uint64_t handednessUndecided = 0;  // triangles whose UV orientation rounded positions/UVs leave open: not judged
  std::uint64_t referenceWUndecided = 0;  // corners of such triangles whose angle was compared (w agrees) but not their w
  // NORMAL as glTF readers treat it: lengths further than kNormalLengthKept (normals.hpp) from 1
  // are normalized before the reference is computed; a length beyond what the component type's
  // rounding explains is a warning, not a finding.
  std::uint64_t normalsNormalized = 0;  // vertices whose NORMAL was normalized
  double worstNormalLength = 1;         // the stored length furthest from 1 (zero normals aside)
  double normalLengthLimit = 0;         // largest | |N| - 1 | not warned about
  std::vector<std::string> warnings;    // for people: what was accepted but is not as the spec says
  // --identify: every generator, closest first, and the verdict: the closest one's name, or
  // "none of these (nearest: NAME)" when it is further than kIdentifyMedianDegrees or agrees on
  // w at fewer than kIdentifyWAgreement of the corners.
  std::vector<GeneratorMatch> generators;
  std::string generator;
};

struct FileCheck {
  std::string file;
  std::string error;                     // unreadable input (then no primitives): set by callers
                                         // that report such a file (the CLI), never by checkFile
  std::vector<PrimitiveCheck> primitives;  // those that need tangents
  std::vector<std::string> skipped;        // primitives not checked, and why
  double seconds = 0;                      // time spent checking the file
  bool clean() const;
};

// Throws InputError on unreadable input (the same message `tangent check` reports).
FileCheck checkFile(const std::filesystem::path& input, const CheckOptions& options);

nlohmann::ordered_json toJson(const FileCheck& check);

}  // namespace tangent::gltf
