// SPDX-License-Identifier: MIT
// OutputDocument's edits (document.hpp): accessors and bufferViews appended, then those the
// edit orphaned dropped and every reference renumbered.
#include <cstring>
#include <functional>
#include <set>

#include "write/document.hpp"

namespace tangent::gltf::detail {

using Json = nlohmann::ordered_json;

namespace {

void visitIfIndex(Json& parent, const char* key, const std::function<void(Json&)>& visit) {
  if (parent.is_object()) {
    auto it = parent.find(key);
    if (it != parent.end() && it->is_number_integer()) visit(*it);
  }
}

void visitValuesOf(Json& object, const std::function<void(Json&)>& visit) {
  if (!object.is_object()) return;
  for (auto& [name, value] : object.items()) {
    if (value.is_number_integer()) visit(value);
  }
}

// "bufferView" keys anywhere inside an extensions object (e.g. KHR_draco_mesh_compression).
void visitExtensionBufferViews(Json& node, bool insideExtensions, const std::function<void(Json&)>& visit) {
  if (node.is_object()) {
    for (auto& [key, value] : node.items()) {
      if (insideExtensions && key == "bufferView" && value.is_number_integer()) visit(value);
      else visitExtensionBufferViews(value, insideExtensions || key == "extensions", visit);
    }
  } else if (node.is_array()) {
    for (auto& value : node) visitExtensionBufferViews(value, insideExtensions, visit);
  }
}

std::set<int> collect(Json& doc, void (*walker)(Json&, const std::function<void(Json&)>&)) {
  std::set<int> found;
  walker(doc, [&](Json& ref) { found.insert(ref.get<int>()); });
  return found;
}

// Drops array entries whose index is in `orphans` and renumbers the references.
void dropAndRenumber(Json& doc, const char* arrayName, const std::set<int>& orphans,
                     void (*walker)(Json&, const std::function<void(Json&)>&)) {
  if (orphans.empty() || !doc.contains(arrayName)) return;
  Json& array = doc[arrayName];
  std::vector<int> newIndex(array.size(), -1);
  Json kept = Json::array();
  for (std::size_t i = 0; i < array.size(); ++i) {
    if (orphans.count(static_cast<int>(i))) continue;
    newIndex[i] = static_cast<int>(kept.size());
    kept.push_back(std::move(array[i]));
  }
  array = std::move(kept);
  walker(doc, [&](Json& ref) {
    const int old = ref.get<int>();
    if (old >= 0 && old < static_cast<int>(newIndex.size())) ref = newIndex[old];
  });
}

}  // namespace

void forEachAccessorRef(Json& doc, const std::function<void(Json&)>& visit) {
  if (doc.contains("meshes")) {
    for (auto& mesh : doc["meshes"]) {
      if (!mesh.contains("primitives")) continue;
      for (auto& primitive : mesh["primitives"]) {
        if (primitive.contains("attributes")) visitValuesOf(primitive["attributes"], visit);
        visitIfIndex(primitive, "indices", visit);
        if (primitive.contains("targets")) {
          for (auto& target : primitive["targets"]) visitValuesOf(target, visit);
        }
      }
    }
  }
  if (doc.contains("skins")) {
    for (auto& skin : doc["skins"]) visitIfIndex(skin, "inverseBindMatrices", visit);
  }
  if (doc.contains("animations")) {
    for (auto& animation : doc["animations"]) {
      if (!animation.contains("samplers")) continue;
      for (auto& sampler : animation["samplers"]) {
        visitIfIndex(sampler, "input", visit);
        visitIfIndex(sampler, "output", visit);
      }
    }
  }
  if (doc.contains("nodes")) {
    for (auto& node : doc["nodes"]) {
      if (node.contains("extensions") && node["extensions"].contains("EXT_mesh_gpu_instancing")) {
        auto& instancing = node["extensions"]["EXT_mesh_gpu_instancing"];
        if (instancing.contains("attributes")) visitValuesOf(instancing["attributes"], visit);
      }
    }
  }
}

void forEachBufferViewRef(Json& doc, const std::function<void(Json&)>& visit) {
  if (doc.contains("accessors")) {
    for (auto& accessor : doc["accessors"]) {
      visitIfIndex(accessor, "bufferView", visit);
      if (accessor.contains("sparse")) {
        auto& sparse = accessor["sparse"];
        if (sparse.contains("indices")) visitIfIndex(sparse["indices"], "bufferView", visit);
        if (sparse.contains("values")) visitIfIndex(sparse["values"], "bufferView", visit);
      }
    }
  }
  if (doc.contains("images")) {
    for (auto& image : doc["images"]) visitIfIndex(image, "bufferView", visit);
  }
  visitExtensionBufferViews(doc, false, visit);
}

OutputDocument::OutputDocument(Asset& asset) : asset_(asset) {
  accessorsBefore_ = collect(asset_.json, forEachAccessorRef);
  bufferViewsBefore_ = collect(asset_.json, forEachBufferViewRef);
  firstNewView_ = asset_.json.contains("bufferViews") ? asset_.json["bufferViews"].size() : 0;
  inputFiles_.add(asset_.path);
  for (const auto& file : referencedFiles(asset_)) inputFiles_.add(file);
}

int OutputDocument::addAccessor(Json accessor, ViewBytes bytes, std::size_t elementSize, int target) {
  Json& doc = asset_.json;
  std::size_t stride = 0;
  if (target == kArrayBuffer && elementSize % 4 != 0) {
    stride = (elementSize + 3) & ~std::size_t(3);
    const std::span<const std::uint8_t> packed = bytes.bytes();
    const std::size_t count = packed.size() / elementSize;
    std::vector<std::uint8_t> padded(count * stride, 0);
    for (std::size_t i = 0; i < count; ++i) std::memcpy(&padded[i * stride], &packed[i * elementSize], elementSize);
    bytes = std::move(padded);
  }
  const int viewIndex = addBufferView(std::move(bytes), stride, target);
  if (!doc.contains("accessors")) doc["accessors"] = Json::array();
  Json placed = Json::object();
  placed["bufferView"] = viewIndex;
  for (auto& [key, value] : accessor.items()) placed[key] = value;
  doc["accessors"].push_back(std::move(placed));
  return static_cast<int>(doc["accessors"].size()) - 1;
}

int OutputDocument::addBufferView(ViewBytes bytes, std::size_t byteStride, int target) {
  Json& doc = asset_.json;
  if (!doc.contains("bufferViews")) doc["bufferViews"] = Json::array();
  Json view = Json::object();
  view["buffer"] = 0;
  view["byteLength"] = bytes.bytes().size();
  if (byteStride != 0) view["byteStride"] = byteStride;
  if (target != 0) view["target"] = target;
  doc["bufferViews"].push_back(std::move(view));
  newViewBytes_.push_back(std::move(bytes));
  return static_cast<int>(doc["bufferViews"].size()) - 1;
}

void OutputDocument::dropOrphans() {
  Json& doc = asset_.json;
  const std::set<int> accessorsAfter = collect(doc, forEachAccessorRef);
  std::set<int> orphanAccessors;
  for (int a : accessorsBefore_) {
    if (!accessorsAfter.count(a)) orphanAccessors.insert(a);
  }
  dropAndRenumber(doc, "accessors", orphanAccessors, forEachAccessorRef);

  const std::set<int> viewsAfter = collect(doc, forEachBufferViewRef);
  std::set<int> orphanViews;
  for (int v : bufferViewsBefore_) {
    if (!viewsAfter.count(v)) orphanViews.insert(v);
  }
  // Keep our bookkeeping of new views in step with the renumbering.
  std::size_t droppedBeforeNew = 0;
  for (int v : orphanViews) {
    if (static_cast<std::size_t>(v) < firstNewView_) ++droppedBeforeNew;
  }
  loadedViewOf_.clear();
  for (std::size_t v = 0; v < firstNewView_; ++v) {
    if (!orphanViews.count(static_cast<int>(v))) loadedViewOf_.push_back(static_cast<int>(v));
  }
  dropAndRenumber(doc, "bufferViews", orphanViews, forEachBufferViewRef);
  firstNewView_ -= droppedBeforeNew;
}

}  // namespace tangent::gltf::detail
