// SPDX-License-Identifier: MIT
// glTF adapter: reads .gltf/.glb (and OBJ/PLY/OFF through its own readers), bakes TANGENT
// into the primitives that need it, writes glTF atomically. Layer above the core.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "tangent/option_table.hpp"
#include "tangent/tangent.hpp"

namespace tangent::gltf {

// The one exception the entry points of this layer (bakeFile, describeFile, checkFile,
// loadScene, and through them OBJ/PLY/OFF files) throw for an input they cannot use: what()
// is "<file>: <element>: <reason>", naming the file, the element (mesh, primitive, accessor,
// URI, line; absent when the whole file is at fault) and what is wrong. Each entry point
// translates whatever its work throws into it once (see src/entry_point.hpp).
class InputError : public std::runtime_error {
 public:
  // A message that names file and element itself, as the readers below the entry points build it.
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
  // The message from its three parts; `element` may be empty.
  InputError(const std::string& file, const std::string& element, const std::string& reason)
      : std::runtime_error(file + (element.empty() ? "" : ": " + element) + ": " + reason) {}
};

// How bake stores the TANGENT it writes: glTF's float, or normalized SHORT/BYTE under
// KHR_mesh_quantization (declared in extensionsUsed and extensionsRequired).
enum class TangentFormat { float32, normalizedShort, normalizedByte };
std::optional<TangentFormat> parseTangentFormat(std::string_view name);  // "float", "short", "byte"
const char* toString(TangentFormat format);

// What bake does for a primitive without NORMAL (glTF 2.0 3.7.2.1: clients MUST then use flat
// normals): generate flat ones (the default), smooth ones (welded by position, triangles within
// the crease angle averaged), or keep the primitive as it is (no tangents either).
enum class NormalsMode { flat, smooth, keep };
std::optional<NormalsMode> parseNormalsMode(std::string_view name);  // "flat", "smooth", "keep"
const char* toString(NormalsMode mode);

// Files a run of several bakes must leave as they are: its inputs, the files they use (buffers
// and images with relative URIs) and what the run has written so far. Known by device and
// inode, so that another spelling of a path, a symbolic link to it or a hard link of it is the
// same file. A bake given one (BakeOptions::protectedFiles) refuses, before writing anything,
// an output or image copy that would change one of them, and gives a .gltf's buffer a name
// that is not one of them; an image copy with the bytes already there is not written at all.
class ProtectedFiles {
 public:
  // `path` (left out where it does not exist).
  void add(const std::filesystem::path& path);
  // `input` and the files its buffers and images name; only `input` where its JSON cannot be
  // read (its bake then says why).
  void addInput(const std::filesystem::path& input);
  // Whether `path` exists and is one of the files added.
  bool contains(const std::filesystem::path& path) const;

 private:
  std::set<std::pair<std::uint64_t, std::uint64_t>> files_;  // (device, inode)
};

struct BakeOptions {
  Options tangents;         // method, weighting (uvOrigin is always kGltfUvOrigin)
  bool all = false;         // every triangle primitive, not only those with a normalTexture
  bool overwrite = false;   // recompute valid existing TANGENT too
  TangentFormat tangentFormat = TangentFormat::float32;  // of the TANGENT bake writes
  // Folder that buffer and image URIs may not leave after resolving `..` and symbolic links
  // (empty: the input's own folder). See the README's "Security and limits".
  std::filesystem::path assetRoot;
  NormalsMode normals = NormalsMode::flat;  // for primitives without NORMAL
  double creaseAngleDegrees = 60;           // NormalsMode::smooth: larger angles between triangles stay sharp
  // A .glb output embeds the images the input refers to by URI (files and data: URIs) in its
  // BIN chunk, as its buffers, so that it is one self-contained file; true keeps external
  // images as files copied beside it instead, as a .gltf output always does.
  bool keepExternalImages = false;
  // The other files of a run (not owned; null: only this bake's own input and its files).
  const ProtectedFiles* protectedFiles = nullptr;
};

// A checked value of the option table (tangent/option_table.hpp) into `options`; false when the
// option is not one of bake's options (nothing changed).
bool applyBakeOption(BakeOptions& options, const options::Option& option, std::string_view value);

// What bake did with a primitive; toString gives the report's "action" names.
enum class PrimitiveAction { baked, kept, skipped };
const char* toString(PrimitiveAction action);  // "baked", "kept", "skipped"

// What happened to one primitive.
struct PrimitiveResult {
  int mesh = 0;
  int primitive = 0;
  std::string meshName;
  PrimitiveAction action = PrimitiveAction::skipped;
  std::string reason;       // why (always set)
  std::vector<std::string> failedChecks;  // the checks an existing TANGENT failed (then replaced)
  int texCoord = -1;        // UV set used, -1 when none
  std::uint64_t verticesIn = 0;
  std::uint64_t verticesOut = 0;
  Report tangents;          // core report, when baked
  TangentFormat tangentFormat = TangentFormat::float32;  // of the TANGENT written, when baked
  std::optional<NormalsMode> normalsGenerated;  // the NORMAL bake wrote (the primitive had none), when baked
};

struct BakeResult {
  std::vector<PrimitiveResult> primitives;
  std::vector<std::string> warnings;
  // Compression extensions (KHR_draco_mesh_compression, EXT_meshopt_compression) taken out of
  // extensionsUsed/extensionsRequired because no baked-over data uses them any more.
  std::vector<std::string> extensionsRemoved;
  std::uint64_t bytesWritten = 0;
  // The output, its .bin and the image copies beside it, placed now or already there with the
  // same bytes (a run protects them from its later bakes; the report's "filesWritten").
  std::vector<std::filesystem::path> filesWritten;
};

// Reads `input`, bakes, writes `output` (.glb or .gltf + .bin beside it). The input is never
// written to; outputs appear complete or not at all. Throws InputError on bad input (an
// unusable output path included) and std::runtime_error when writing the output fails.
BakeResult bakeFile(const std::filesystem::path& input, const std::filesystem::path& output,
                    const BakeOptions& options);

// The output path bake uses for `input` in `outputDir` (OBJ/PLY/OFF become .glb).
std::filesystem::path outputPathFor(const std::filesystem::path& input, const std::filesystem::path& outputDir);

// Meshes, primitives, attributes, and which need tangents and why, as JSON.
// `assetRoot` as in BakeOptions. Throws InputError on unreadable input.
nlohmann::ordered_json describeFile(const std::filesystem::path& input, const std::filesystem::path& assetRoot = {});

// Result of a bake as the JSON written by `tangent bake --report`.
nlohmann::ordered_json toJson(const BakeResult& result);
nlohmann::ordered_json toJson(const Report& report);

}  // namespace tangent::gltf
