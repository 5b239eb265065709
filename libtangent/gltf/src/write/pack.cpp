// SPDX-License-Identifier: MIT
// OutputDocument::packBuffers (document.hpp): every bufferView laid out in one buffer.
#include <algorithm>

#include "read/compression.hpp"
#include "write/document.hpp"

namespace tangent::gltf::detail {

using Json = nlohmann::ordered_json;

namespace {

// doc.buffers after packing: one buffer of `size` bytes (the first buffer's JSON, name and
// extras kept) and, where views moved there, the meshopt fallback buffer of `fallbackSize` bytes
// (the first fallback buffer's JSON).
void setPackedBuffers(Json& doc, std::size_t size, std::size_t fallbackSize) {
  Json buffer = Json::object(), fallback = Json::object();
  bool fallbackFound = false;
  if (doc.contains("buffers")) {
    for (auto it = doc["buffers"].rbegin(); it != doc["buffers"].rend(); ++it) {
      if (isMeshoptFallbackBuffer(*it)) {
        fallback = *it;
        fallbackFound = true;
      } else {
        buffer = *it;
      }
    }
  }
  buffer.erase("uri");
  buffer["byteLength"] = size;
  doc["buffers"] = Json::array({buffer});
  if (fallbackSize > 0) {
    fallback.erase("uri");
    fallback["byteLength"] = fallbackSize;
    if (!fallbackFound) fallback["extensions"][kMeshoptExtension]["fallback"] = true;
    doc["buffers"].push_back(std::move(fallback));
  }
}

// The bytes of an input buffer view as loaded. validateDocument checked types and declared
// sizes; the loaded bytes may still be fewer.
std::span<const std::uint8_t> loadedViewBytes(const Json& view, const std::vector<tinygltf::Buffer>& buffers,
                                              const std::filesystem::path& path, std::size_t index) {
  const std::int64_t bufferIndex = view.value("buffer", std::int64_t(-1));
  const std::int64_t offset = view.value("byteOffset", std::int64_t(0));
  const std::int64_t viewLength = view.value("byteLength", std::int64_t(0));
  if (bufferIndex < 0 || bufferIndex >= static_cast<std::int64_t>(buffers.size()) || offset < 0 || viewLength < 0 ||
      static_cast<std::uint64_t>(offset) > buffers[bufferIndex].data.size() ||
      static_cast<std::uint64_t>(viewLength) > buffers[bufferIndex].data.size() - static_cast<std::uint64_t>(offset))
    throw InputError(path.string() + ": /bufferViews/" + std::to_string(index) + ": lies outside the bytes loaded for its buffer");
  return {buffers[bufferIndex].data.data() + offset, static_cast<std::size_t>(viewLength)};
}

}  // namespace

std::vector<std::span<const std::uint8_t>> OutputDocument::packBuffers() {
  static constexpr std::uint8_t kZeros[4] = {0, 0, 0, 0};
  Json& doc = asset_.json;
  std::vector<std::span<const std::uint8_t>> packed;
  std::size_t size = 0;
  auto padTo = [&](std::size_t remainder) {
    const std::size_t padding = (remainder + 4 - size % 4) % 4;
    if (padding > 0) packed.push_back({kZeros, padding});
    size += padding;
  };
  if (!doc.contains("bufferViews")) return packed;
  Json& views = doc["bufferViews"];
  const auto& buffers = asset_.model.buffers;
  const bool meshoptRequired = doc.contains("extensionsRequired") && doc["extensionsRequired"].is_array() &&
                               std::find(doc["extensionsRequired"].begin(), doc["extensionsRequired"].end(),
                                         Json(kMeshoptExtension)) != doc["extensionsRequired"].end();
  std::size_t fallbackSize = 0;  // of the data-less fallback buffer
  for (std::size_t i = 0; i < views.size(); ++i) {
    Json& view = views[i];
    const std::uint8_t* source = nullptr;
    std::size_t length = 0;
    std::size_t alignTo = 0;  // keep the old offset modulo 4 so accessor alignment survives
    const bool meshopt = i < firstNewView_ && view.contains("extensions") && view["extensions"].is_object() &&
                         view["extensions"].contains(kMeshoptExtension);
    if (meshopt) {
      // The compressed bytes (checked when decoded) go into the packed buffer...
      Json& extension = view["extensions"][kMeshoptExtension];
      const auto& compressed = buffers[extension["buffer"].get<std::size_t>()].data;
      padTo(0);
      packed.push_back({compressed.data() + extension.value("byteOffset", std::size_t(0)), extension["byteLength"].get<std::size_t>()});
      extension["buffer"] = 0;
      extension["byteOffset"] = size;
      size += extension["byteLength"].get<std::size_t>();
      const std::size_t viewLength = view["byteLength"].get<std::size_t>();
      if (meshoptRequired) {
        // ...and the view itself into the fallback buffer, which holds no data.
        fallbackSize = (fallbackSize + 3) & ~std::size_t(3);
        view["buffer"] = 1;
        if (fallbackSize == 0) view.erase("byteOffset");
        else view["byteOffset"] = fallbackSize;
        fallbackSize += viewLength;
        continue;
      }
      // ...and, where loaders may ignore the extension, the decoded bytes as fallback data.
      const tinygltf::BufferView& decoded = asset_.model.bufferViews[loadedViewOf_[i]];
      source = buffers[decoded.buffer].data.data() + decoded.byteOffset;
      length = viewLength;
    } else if (i >= firstNewView_) {
      const std::span<const std::uint8_t> bytes = newViewBytes_[i - firstNewView_].bytes();
      source = bytes.data();
      length = bytes.size();
    } else {
      const std::span<const std::uint8_t> bytes = loadedViewBytes(view, buffers, asset_.path, i);
      source = bytes.data();
      length = bytes.size();
      alignTo = static_cast<std::size_t>(view.value("byteOffset", std::int64_t(0)) % 4);
    }
    padTo(alignTo);
    view["buffer"] = 0;
    if (size == 0) view.erase("byteOffset");
    else view["byteOffset"] = size;
    if (length > 0) packed.push_back({source, length});
    size += length;
  }
  padTo(0);

  setPackedBuffers(doc, size, fallbackSize);
  if (views.empty()) {
    doc.erase("bufferViews");
    doc.erase("buffers");
  }
  return packed;
}

}  // namespace tangent::gltf::detail
