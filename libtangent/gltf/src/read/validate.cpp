// SPDX-License-Identifier: MIT
// validateDocument and checkJsonDepth (validate.hpp); the document's top level, buffers,
// bufferViews and accessors (Validator, validator.hpp).
#include "read/validate.hpp"

#include <cstdint>
#include <string>

#include "read/validator.hpp"

namespace tangent::gltf::detail {

void checkJsonDepth(std::string_view text, const std::string& label, const char* what) {
  if (text.size() > kMaxJsonBytes)
    throw InputError(label + ": " + what + " is " + std::to_string(text.size()) + " bytes; the limit is " +
                     std::to_string(kMaxJsonBytes));
  std::size_t depth = 0;
  bool inString = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (inString) {
      if (c == '\\') ++i;
      else if (c == '"') inString = false;
      continue;
    }
    if (c == '"') {
      inString = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonDepth)
        throw InputError(label + ": " + what + " nests deeper than " + std::to_string(kMaxJsonDepth) +
                         " levels (at byte " + std::to_string(i) + ")");
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
}

namespace {

// Sizes beyond these are refused before any arithmetic: products of a count (< 2^32) and a
// stride (< 256) then fit 64 bits with room to spare.
constexpr std::int64_t kMaxByteLength = std::int64_t(1) << 40;
constexpr std::int64_t kMaxCount = (std::int64_t(1) << 32) - 1;

int componentBytesOf(std::int64_t componentType) {
  switch (componentType) {
    case 5120: case 5121: return 1;
    case 5122: case 5123: return 2;
    case 5125: case 5126: return 4;
    default: return 0;
  }
}

}  // namespace

void Validator::topLevel() {
  if (!doc_.contains("asset") || !doc_["asset"].is_object()) fail("/asset", "is required and must be an object");
  const Json* version = member(doc_["asset"], "version", "/asset", &Json::is_string, "a string");
  if (!version) fail("/asset/version", "is required");
  if (version->get<std::string>().rfind("2.", 0) != 0) fail("/asset/version", "is " + version->dump() + "; only glTF 2.x is read (glTF 1.0 files need converting first)");
  for (const char* key : {"accessors", "animations", "buffers", "bufferViews", "cameras", "images", "materials", "meshes",
                          "nodes", "samplers", "scenes", "skins", "textures"}) {
    auto it = doc_.find(key);
    if (it == doc_.end()) continue;
    if (!it->is_array()) fail(std::string("/") + key, "must be an array");
    for (std::size_t i = 0; i < it->size(); ++i) {
      if (!(*it)[i].is_object()) fail("/" + std::string(key) + "/" + std::to_string(i), "must be an object");
    }
  }
  for (const char* key : {"extensionsUsed", "extensionsRequired"}) {
    auto it = doc_.find(key);
    if (it == doc_.end()) continue;
    if (!it->is_array()) fail(std::string("/") + key, "must be an array");
    for (std::size_t i = 0; i < it->size(); ++i) {
      if (!(*it)[i].is_string()) fail("/" + std::string(key) + "/" + std::to_string(i), "must be a string");
    }
  }
  reference(doc_, "scene", "", "scenes");
}

void Validator::buffers() {
  for (std::size_t i = 0; i < count("buffers"); ++i) {
    const Json& buffer = doc_["buffers"][i];
    const std::string pointer = "/buffers/" + std::to_string(i);
    integer(buffer, "byteLength", pointer, 1, kMaxByteLength, true);
    member(buffer, "uri", pointer, &Json::is_string, "a string");
  }
}

void Validator::bufferViews() {
  viewLength_.assign(count("bufferViews"), 0);
  viewStride_.assign(count("bufferViews"), 0);
  for (std::size_t i = 0; i < count("bufferViews"); ++i) {
    const Json& view = doc_["bufferViews"][i];
    const std::string pointer = "/bufferViews/" + std::to_string(i);
    const std::int64_t buffer = reference(view, "buffer", pointer, "buffers", true);
    const std::int64_t offset = integer(view, "byteOffset", pointer, 0, kMaxByteLength, false);
    const std::int64_t length = integer(view, "byteLength", pointer, 1, kMaxByteLength, true);
    const std::int64_t stride = integer(view, "byteStride", pointer, 4, 252, false);
    if (stride % 4 != 0) fail(join(pointer, "byteStride"), std::to_string(stride) + " is not a multiple of 4");
    const std::int64_t bufferLength = at("buffers", buffer).value("byteLength", std::int64_t(0));
    if (offset + length > bufferLength)
      fail(pointer, "byteOffset " + std::to_string(offset) + " + byteLength " + std::to_string(length) +
                        " overruns buffer " + std::to_string(buffer) + " (byteLength " + std::to_string(bufferLength) + ")");
    viewLength_[i] = length;
    viewStride_[i] = stride;
  }
}

// Bytes [offset, offset + span) must lie inside bufferView `view`.
void Validator::inView(std::int64_t view, std::int64_t offset, std::int64_t span, const std::string& pointer, const char* what) const {
  if (offset + span > viewLength_[static_cast<std::size_t>(view)])
    fail(pointer, std::string(what) + " need bytes " + std::to_string(offset) + " to " + std::to_string(offset + span) +
                      " of bufferView " + std::to_string(view) + ", which has " +
                      std::to_string(viewLength_[static_cast<std::size_t>(view)]));
}

void Validator::accessors() {
  accessorCount_.assign(count("accessors"), 0);
  for (std::size_t i = 0; i < count("accessors"); ++i) {
    const Json& accessor = doc_["accessors"][i];
    const std::string pointer = "/accessors/" + std::to_string(i);
    const std::int64_t componentType = integer(accessor, "componentType", pointer, 0, 1 << 16, true);
    const int componentSize = componentBytesOf(componentType);
    if (componentSize == 0)
      fail(join(pointer, "componentType"), std::to_string(componentType) + " is not a glTF component type");
    const Json* type = member(accessor, "type", pointer, &Json::is_string, "a string");
    if (!type) fail(join(pointer, "type"), "is required");
    const int components = componentsOf(type->get<std::string>());
    if (components == 0) fail(join(pointer, "type"), type->dump() + " is not a glTF accessor type");
    const std::int64_t elements = integer(accessor, "count", pointer, 1, kMaxCount, true);
    accessorCount_[i] = elements;
    const std::int64_t elementSize = std::int64_t(componentSize) * components;
    const std::int64_t view = reference(accessor, "bufferView", pointer, "bufferViews");
    const std::int64_t offset = integer(accessor, "byteOffset", pointer, 0, kMaxByteLength, false);
    if (offset % componentSize != 0)
      fail(join(pointer, "byteOffset"), std::to_string(offset) + " is not a multiple of the component size " +
                                            std::to_string(componentSize));
    if (view >= 0) {
      const std::int64_t stride = viewStride_[static_cast<std::size_t>(view)];
      if (stride != 0 && stride < elementSize)
        fail(pointer, "bufferView " + std::to_string(view) + " has byteStride " + std::to_string(stride) + ", less than the " +
                          std::to_string(elementSize) + "-byte elements");
      inView(view, offset, (stride ? stride : elementSize) * (elements - 1) + elementSize, pointer, "its elements");
    }
    if (const Json* sparse = objectMember(accessor, "sparse", pointer)) {
      const std::string sp = join(pointer, "sparse");
      const std::int64_t sparseCount = integer(*sparse, "count", sp, 1, elements, true);
      const Json* indices = objectMember(*sparse, "indices", sp);
      const Json* values = objectMember(*sparse, "values", sp);
      if (!indices) fail(join(sp, "indices"), "is required");
      if (!values) fail(join(sp, "values"), "is required");
      const std::string ip = join(sp, "indices"), vp = join(sp, "values");
      const std::int64_t indexType = integer(*indices, "componentType", ip, 0, 1 << 16, true);
      if (indexType != 5121 && indexType != 5123 && indexType != 5125)
        fail(join(ip, "componentType"), std::to_string(indexType) + " is not an unsigned integer type");
      const std::int64_t indexView = reference(*indices, "bufferView", ip, "bufferViews", true);
      const std::int64_t indexOffset = integer(*indices, "byteOffset", ip, 0, kMaxByteLength, false);
      inView(indexView, indexOffset, sparseCount * componentBytesOf(indexType), ip, "the sparse indices");
      const std::int64_t valueView = reference(*values, "bufferView", vp, "bufferViews", true);
      const std::int64_t valueOffset = integer(*values, "byteOffset", vp, 0, kMaxByteLength, false);
      inView(valueView, valueOffset, sparseCount * elementSize, vp, "the sparse values");
    }
  }
}

void validateDocument(const Json& doc, const std::string& label) { Validator(doc, label).run(); }

}  // namespace tangent::gltf::detail
