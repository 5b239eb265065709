// SPDX-License-Identifier: MIT
// glTF adapter: reads .gltf/.glb (and OBJ/PLY/OFF through OpenMesh's readers), bakes TANGENT
// into the primitives that need it, writes glTF atomically. Layer above the core.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "tangent/tangent.hpp"

namespace tangent::gltf {

// Any problem with an input file: the message names file, mesh, primitive and accessor.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// How bake stores the TANGENT it writes: glTF's float, or normalized SHORT/BYTE under
// KHR_mesh_quantization (declared in extensionsUsed and extensionsRequired).
enum class TangentFormat { float32, normalizedShort, normalizedByte };
std::optional<TangentFormat> parseTangentFormat(std::string_view name);  // "float", "short", "byte"
const char* toString(TangentFormat format);

struct BakeOptions {
  Options tangents;         // method, weighting (uvOrigin is always topLeft for glTF)
  bool all = false;         // every triangle primitive, not only those with a normalTexture
  bool overwrite = false;   // recompute valid existing TANGENT too
  TangentFormat tangentFormat = TangentFormat::float32;  // of the TANGENT bake writes
  // Folder that buffer and image URIs may not leave after resolving `..` and symbolic links
  // (empty: the input's own folder). See the README's "Security and limits".
  std::filesystem::path assetRoot;
};

// What happened to one primitive.
struct PrimitiveResult {
  int mesh = 0;
  int primitive = 0;
  std::string meshName;
  std::string action;       // "baked", "kept", "skipped"
  std::string reason;       // why (always set)
  std::vector<std::string> failedChecks;  // the checks an existing TANGENT failed (then replaced)
  int texCoord = -1;        // UV set used, -1 when none
  std::uint64_t verticesIn = 0;
  std::uint64_t verticesOut = 0;
  Report tangents;          // core report, when baked
  TangentFormat tangentFormat = TangentFormat::float32;  // of the TANGENT written, when baked
};

struct BakeResult {
  std::vector<PrimitiveResult> primitives;
  std::vector<std::string> warnings;
  // Compression extensions (KHR_draco_mesh_compression, EXT_meshopt_compression) taken out of
  // extensionsUsed/extensionsRequired because no baked-over data uses them any more.
  std::vector<std::string> extensionsRemoved;
  std::uint64_t bytesWritten = 0;
};

// Reads `input`, bakes, writes `output` (.glb or .gltf + .bin beside it). The input is never
// written to; outputs appear complete or not at all. Throws InputError on bad input and
// std::runtime_error on I/O failure.
BakeResult bakeFile(const std::filesystem::path& input, const std::filesystem::path& output,
                    const BakeOptions& options);

// The output path bake uses for `input` in `outputDir` (OBJ/PLY/OFF become .glb).
std::filesystem::path outputPathFor(const std::filesystem::path& input, const std::filesystem::path& outputDir);

// Meshes, primitives, attributes, and which need tangents and why, as JSON.
// `assetRoot` as in BakeOptions.
nlohmann::ordered_json describeFile(const std::filesystem::path& input, const std::filesystem::path& assetRoot = {});

// Result of a bake as the JSON written by `tangent bake --report`.
nlohmann::ordered_json toJson(const BakeResult& result);
nlohmann::ordered_json toJson(const Report& report);

}  // namespace tangent::gltf
