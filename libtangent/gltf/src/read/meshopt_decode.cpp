// SPDX-License-Identifier: MIT
// EXT_meshopt_compression (KhronosGroup/glTF, extensions/2.0/Vendor/EXT_meshopt_compression):
// a bufferView's bytes decoded from its compressed source with meshoptimizer's codecs
// (mode ATTRIBUTES, TRIANGLES or INDICES), then the filter (NONE, OCTAHEDRAL, QUATERNION,
// EXPONENTIAL) applied. The spec's validity rules are checked before any decoder runs.
#include <meshoptimizer.h>

#include <cstring>
#include <optional>

#include "read/compression.hpp"
#include "tangent/gltf.hpp"

namespace tangent::gltf::detail {
namespace {

using Json = nlohmann::ordered_json;

// No meshopt stream decodes to more than this many times its size: the attribute codec
// stores at least a 2-bit header per 16 bytes of a byte channel (64x), the index codecs at
// least one byte per triangle or index. Checked before the output is allocated.
constexpr std::uint64_t kMaxExpansion = 128;
constexpr std::uint64_t kMaxDecodedBytes = std::uint64_t(1) << 31;

enum class Mode { attributes, triangles, indices };
enum class Filter { none, octahedral, quaternion, exponential };

std::optional<Mode> parseMode(const std::string& text) {
  if (text == "ATTRIBUTES") return Mode::attributes;
  if (text == "TRIANGLES") return Mode::triangles;
  if (text == "INDICES") return Mode::indices;
  return std::nullopt;
}

std::optional<Filter> parseFilter(const std::string& text) {
  if (text == "NONE") return Filter::none;
  if (text == "OCTAHEDRAL") return Filter::octahedral;
  if (text == "QUATERNION") return Filter::quaternion;
  if (text == "EXPONENTIAL") return Filter::exponential;
  return std::nullopt;
}

struct MeshoptView {
  int buffer = -1;
  std::uint64_t byteOffset = 0, byteLength = 0, byteStride = 0, count = 0;
  Mode mode = Mode::attributes;
  Filter filter = Filter::none;
};

class ViewDecoder {
 public:
  ViewDecoder(Asset& asset, std::size_t viewIndex)
      : asset_(asset), view_(viewIndex),
        where_(asset.path.string() + ": bufferViews[" + std::to_string(viewIndex) + "] " + kMeshoptExtension + ": ") {}

  void decode();

 private:
  [[noreturn]] void fail(const std::string& what) const { throw InputError(where_ + what); }
  std::uint64_t unsignedMember(const Json& object, const char* key, bool required) const;
  MeshoptView parse() const;

  Asset& asset_;
  std::size_t view_;
  std::string where_;
};

std::uint64_t ViewDecoder::unsignedMember(const Json& object, const char* key, bool required) const {
  auto it = object.find(key);
  if (it == object.end()) {
    if (required) fail(std::string(key) + " is required");
    return 0;
  }
  if (!it->is_number_integer() || it->get<std::int64_t>() < 0) fail(std::string(key) + " must be a non-negative integer");
  return it->get<std::uint64_t>();
}

MeshoptView ViewDecoder::parse() const {
  const Json& viewJson = asset_.json["bufferViews"][view_];
  const Json& ext = viewJson["extensions"][kMeshoptExtension];
  if (!ext.is_object()) fail("must be an object");
  MeshoptView view;
  const std::uint64_t buffer = unsignedMember(ext, "buffer", true);
  view.byteOffset = unsignedMember(ext, "byteOffset", false);
  view.byteLength = unsignedMember(ext, "byteLength", true);
  view.byteStride = unsignedMember(ext, "byteStride", true);
  view.count = unsignedMember(ext, "count", true);
  if (!ext.contains("mode") || !ext["mode"].is_string()) fail("mode is required and must be a string");
  const auto mode = parseMode(ext["mode"].get<std::string>());
  if (!mode) fail("mode '" + ext["mode"].get<std::string>() + "' is not ATTRIBUTES, TRIANGLES or INDICES");
  view.mode = *mode;
  if (ext.contains("filter")) {
    const auto filter = ext["filter"].is_string() ? parseFilter(ext["filter"].get<std::string>()) : std::nullopt;
    if (!filter) fail("filter " + ext["filter"].dump() + " is not NONE, OCTAHEDRAL, QUATERNION or EXPONENTIAL");
    view.filter = *filter;
  }

  // The spec's conditions for a valid extension object.
  const std::uint64_t stride = view.byteStride;
  if (stride == 0) fail("byteStride is 0");
  if (viewJson.contains("byteStride") && viewJson["byteStride"] != Json(stride))
    fail("byteStride " + std::to_string(stride) + " differs from the bufferView's byteStride " + viewJson["byteStride"].dump());
  if (view.count > kMaxDecodedBytes / stride)
    fail("count " + std::to_string(view.count) + " x byteStride " + std::to_string(stride) + " is over the limit of 2 GiB");
  const std::uint64_t decoded = view.count * stride;
  const std::uint64_t parentLength = viewJson.value("byteLength", std::uint64_t(0));
  if (parentLength != decoded)
    fail("the bufferView's byteLength " + std::to_string(parentLength) + " is not byteStride x count (" + std::to_string(decoded) + ")");
  if (view.mode == Mode::attributes && (stride % 4 != 0 || stride > 256))
    fail("byteStride " + std::to_string(stride) + " must be a multiple of 4 and at most 256 in mode ATTRIBUTES");
  if (view.mode != Mode::attributes) {
    if (stride != 2 && stride != 4) fail("byteStride " + std::to_string(stride) + " must be 2 or 4 in mode " + ext["mode"].get<std::string>());
    if (view.filter != Filter::none) fail("filter must be NONE in mode " + ext["mode"].get<std::string>());
  }
  if (view.mode == Mode::triangles && view.count % 3 != 0)
    fail("count " + std::to_string(view.count) + " is not a multiple of 3 in mode TRIANGLES");
  if (view.filter == Filter::octahedral && stride != 4 && stride != 8)
    fail("byteStride " + std::to_string(stride) + " must be 4 or 8 with filter OCTAHEDRAL");
  if (view.filter == Filter::quaternion && stride != 8) fail("byteStride " + std::to_string(stride) + " must be 8 with filter QUATERNION");
  if (view.filter == Filter::exponential && stride % 4 != 0)
    fail("byteStride " + std::to_string(stride) + " must be a multiple of 4 with filter EXPONENTIAL");

  // The compressed bytes: in a buffer that is not a fallback buffer, inside what was loaded.
  const auto& buffers = asset_.model.buffers;
  if (buffer >= buffers.size()) fail("buffer " + std::to_string(buffer) + " does not exist");
  view.buffer = static_cast<int>(buffer);
  if (isMeshoptFallbackBuffer(asset_.json["buffers"][buffer]))
    fail("buffer " + std::to_string(buffer) + " is a fallback buffer, which holds no compressed data");
  const std::uint64_t loaded = buffers[buffer].data.size();
  if (view.byteOffset > loaded || view.byteLength > loaded - view.byteOffset)
    fail("compressed data (offset " + std::to_string(view.byteOffset) + ", " + std::to_string(view.byteLength) +
         " bytes) lies outside buffer " + std::to_string(buffer) + " (" + std::to_string(loaded) + " bytes loaded)");
  if (decoded > view.byteLength * kMaxExpansion)
    fail("claims " + std::to_string(decoded) + " decoded bytes from " + std::to_string(view.byteLength) +
         " compressed ones, more than any meshopt codec expands");
  return view;
}

void ViewDecoder::decode() {
  const MeshoptView view = parse();
  const std::size_t count = static_cast<std::size_t>(view.count), stride = static_cast<std::size_t>(view.byteStride);
  std::vector<unsigned char> decoded(count * stride);
  const unsigned char* source = asset_.model.buffers[view.buffer].data.data() + view.byteOffset;
  const std::size_t sourceSize = static_cast<std::size_t>(view.byteLength);
  int status = 0;
  switch (view.mode) {
    case Mode::attributes: status = meshopt_decodeVertexBuffer(decoded.data(), count, stride, source, sourceSize); break;
    case Mode::triangles: status = meshopt_decodeIndexBuffer(decoded.data(), count, stride, source, sourceSize); break;
    case Mode::indices: status = meshopt_decodeIndexSequence(decoded.data(), count, stride, source, sourceSize); break;
  }
  if (status != 0)
    fail("the compressed stream is malformed or truncated (meshoptimizer error " + std::to_string(status) + ", " +
         std::to_string(sourceSize) + " bytes for " + std::to_string(count) + " elements of " + std::to_string(stride) + " bytes)");
  switch (view.filter) {
    case Filter::none: break;
    case Filter::octahedral: meshopt_decodeFilterOct(decoded.data(), count, stride); break;
    case Filter::quaternion: meshopt_decodeFilterQuat(decoded.data(), count, stride); break;
    case Filter::exponential: meshopt_decodeFilterExp(decoded.data(), count, stride); break;
  }
  // The view now reads the decoded bytes; the JSON (and so the output) keeps the compressed form.
  tinygltf::Buffer buffer;
  buffer.data = std::move(decoded);
  asset_.model.buffers.push_back(std::move(buffer));
  tinygltf::BufferView& modelView = asset_.model.bufferViews[view_];
  modelView.buffer = static_cast<int>(asset_.model.buffers.size()) - 1;
  modelView.byteOffset = 0;
  modelView.byteLength = count * stride;
}

}  // namespace

void decodeMeshoptViews(Asset& asset) {
  const Json& doc = asset.json;
  if (!doc.contains("bufferViews")) return;
  for (std::size_t i = 0; i < doc["bufferViews"].size(); ++i) {
    const Json& view = doc["bufferViews"][i];
    if (view.contains("extensions") && view["extensions"].is_object() && view["extensions"].contains(kMeshoptExtension))
      ViewDecoder(asset, i).decode();
  }
}

}  // namespace tangent::gltf::detail
