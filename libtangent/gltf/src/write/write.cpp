// SPDX-License-Identifier: MIT
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <map>
#include <optional>
#include <set>

#include "read/compression.hpp"
#include "write/document.hpp"
#include "tangent/gltf.hpp"
#include "tangent/output.hpp"
#include "tangent/text.hpp"
#include "read/uri.hpp"
#include "read/validate.hpp"

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

bool isRelativeFileUri(const std::string& uri) {
  return !uri.empty() && !isDataUri(uri) && uri.find("://") == std::string::npos && uri.front() != '/';
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

// The .bin files an existing .gltf at `output` refers to that bake's naming gives (STEM.bin,
// STEM.N.bin) and that lie beside it; empty when there is no such file or it cannot be read.
std::vector<std::filesystem::path> binsOfPreviousOutput(const std::filesystem::path& output) {
  namespace fs = std::filesystem;
  std::vector<fs::path> bins;
  std::error_code ec;
  if (!fs::is_regular_file(output, ec) || fs::file_size(output, ec) > (std::uintmax_t(64) << 20)) return bins;
  std::vector<std::uint8_t> bytes;
  if (!readFileInto(output, bytes)) return bins;
  try {
    const std::string text(bytes.begin(), bytes.end());
    checkJsonDepth(text, output.string());
    const Json previous = Json::parse(text);
    if (!previous.is_object() || !previous.contains("buffers") || !previous["buffers"].is_array()) return bins;
    const std::string stem = output.stem().string();
    for (const Json& buffer : previous["buffers"]) {
      if (!buffer.is_object() || !buffer.contains("uri") || !buffer["uri"].is_string()) continue;
      const std::string name = percentDecode(buffer["uri"].get<std::string>());
      const bool ours = name == stem + ".bin" ||
                        (name.size() > stem.size() + 5 && name.rfind(stem + ".", 0) == 0 && name.ends_with(".bin") &&
                         std::all_of(name.begin() + static_cast<std::ptrdiff_t>(stem.size()) + 1, name.end() - 4,
                                     [](char c) { return c >= '0' && c <= '9'; }));
      if (ours) bins.push_back(output.parent_path() / name);
    }
  } catch (const std::exception&) {
    bins.clear();
  }
  return bins;
}

std::string gltfJsonText(const std::filesystem::path& path);
std::vector<std::filesystem::path> filesNamedBy(const Json& doc, const std::filesystem::path& dir);

// What the .gltf and .glb files beside `output`, other than it, name (buffer and image uris,
// decoded, as `output`'s folder / name): a file of the user's that shares the previous
// output's .bin keeps it. A neighbour that cannot be read or parsed names what it names
// unknown: then every file that exists counts as named (kept, and no new file goes there),
// never every name there could be.
struct NamedBeside {
  std::set<std::filesystem::path> files;
  bool unknown = false;  // some neighbour (or the folder) could not be read
  bool names(const std::filesystem::path& path) const {
    std::error_code ec;
    return files.count(path.lexically_normal()) > 0 || (unknown && std::filesystem::exists(std::filesystem::symlink_status(path, ec)));
  }
};

NamedBeside filesNamedBeside(const std::filesystem::path& output) {
  namespace fs = std::filesystem;
  const fs::path folder = output.parent_path().empty() ? fs::path(".") : output.parent_path();
  NamedBeside named;
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; it != end; it.increment(ec)) {
    if (ec) break;
    const fs::path& path = it->path();
    const std::string extension = lowerExtension(path);
    if ((extension != ".gltf" && extension != ".glb") || path.filename() == output.filename()) continue;
    std::error_code fileError;
    if (!it->is_regular_file(fileError)) continue;
    const std::string text = gltfJsonText(path);
    if (text.empty()) {
      named.unknown = true;
      continue;
    }
    try {
      checkJsonDepth(text, path.string());
      for (const fs::path& file : filesNamedBy(Json::parse(text), folder)) named.files.insert(file.lexically_normal());
    } catch (const std::exception&) {
      named.unknown = true;
    }
  }
  if (ec) named.unknown = true;
  return named;
}

// Whether `path` is a regular file (not a link) holding exactly `bytes` (false where it cannot
// be read).
bool holdsBytes(const std::filesystem::path& path, const std::vector<std::uint8_t>& bytes) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(std::filesystem::symlink_status(path, ec)) || std::filesystem::file_size(path, ec) != bytes.size() ||
      ec)
    return false;
  std::vector<std::uint8_t> present;
  return readFileInto(path, present) && present == bytes;
}

// STEM.bin, or STEM.1.bin, STEM.2.bin... : the first that the previous .gltf does not use,
// that is not `taken` (a file of this run's, or one another .gltf beside the output uses) and
// that names nothing there yet (a file no glTF names may still be the user's: never replaced).
// Bounded: a folder where the first kMaxBinNames are all taken is refused, saying so.
constexpr int kMaxBinNames = 10000;
std::filesystem::path freeBinName(const std::filesystem::path& output, const std::vector<std::filesystem::path>& previousBins,
                                  const std::function<bool(const std::filesystem::path&)>& taken) {
  std::filesystem::path candidate = output;
  candidate.replace_extension(".bin");
  auto occupied = [&](const std::filesystem::path& path) {
    std::error_code ec;
    return std::find(previousBins.begin(), previousBins.end(), path) != previousBins.end() || taken(path) ||
           std::filesystem::exists(std::filesystem::symlink_status(path, ec));
  };
  for (int n = 1; occupied(candidate); ++n) {
    if (n >= kMaxBinNames)
      throw std::runtime_error(output.string() + ": no free name for its .bin: " + output.stem().string() + ".bin and " +
                               output.stem().string() + ".1.bin to ." + std::to_string(kMaxBinNames - 1) +
                               ".bin are all in use beside it (or named by a .gltf there)");
    candidate = output;
    candidate.replace_extension("." + std::to_string(n) + ".bin");
  }
  return candidate;
}

// The media type an image's bytes begin with, among those glTF and its image extensions put
// in a .glb (PNG, JPEG: glTF 2.0 3.9; WebP: EXT_texture_webp; KTX2: KHR_texture_basisu); empty
// for any other.
std::string imageTypeOfBytes(std::span<const std::uint8_t> bytes) {
  auto startsWith = [&](std::size_t at, std::initializer_list<std::uint8_t> magic) {
    return bytes.size() >= at + magic.size() &&
           std::equal(magic.begin(), magic.end(), bytes.begin() + static_cast<std::ptrdiff_t>(at));
  };
  if (startsWith(0, {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A})) return "image/png";
  if (startsWith(0, {0xFF, 0xD8, 0xFF})) return "image/jpeg";
  if (startsWith(0, {'R', 'I', 'F', 'F'}) && startsWith(8, {'W', 'E', 'B', 'P'})) return "image/webp";
  if (startsWith(0, {0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB, 0x0D, 0x0A, 0x1A, 0x0A})) return "image/ktx2";
  return {};
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

bool OutputDocument::isProtected(const std::filesystem::path& path) const {
  return inputFiles_.contains(path) || (runFiles_ && runFiles_->contains(path));
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

CreatedFiles::~CreatedFiles() {
  staged_.clear();  // the temporaries first: they may lie in the new folders
  for (auto it = folders_.rbegin(); it != folders_.rend(); ++it) {
    std::error_code ignored;
    std::filesystem::remove(*it, ignored);  // only where empty
  }
}

void CreatedFiles::createFolders(const std::filesystem::path& folder) {
  namespace fs = std::filesystem;
  std::vector<fs::path> missing;  // deepest first
  std::error_code ec;
  for (fs::path at = folder; !at.empty() && !fs::exists(at, ec); at = at.parent_path()) {
    missing.push_back(at);
    if (at == at.parent_path()) break;
  }
  for (auto it = missing.rbegin(); it != missing.rend(); ++it) {
    if (!fs::create_directory(*it, ec)) continue;
    folders_.push_back(*it);
    guards_.push_back(std::make_unique<output::TemporaryGuard>(*it));
  }
}

void CreatedFiles::stage(const std::filesystem::path& path, std::span<const std::uint8_t> bytes) {
  staged_.push_back(std::make_unique<output::StagedFile>(path, std::vector{bytes}));
  stagedPaths_.insert(path);
}

bool CreatedFiles::staged(const std::filesystem::path& path) const { return stagedPaths_.contains(path); }

void CreatedFiles::keep(output::StagedFile& output) {
  std::vector<output::StagedFile*> files;
  for (const auto& file : staged_) files.push_back(file.get());
  files.push_back(&output);
  try {
    output::commitAll(files);
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string(e.what()) + "; " + output.path().string() + " was not written" +
                             (staged_.empty() ? "" : ", and the image copies beside it are as they were"));
  }
  staged_.clear();
  stagedPaths_.clear();
  folders_.clear();
  guards_.clear();
}

void OutputDocument::placeImages(const std::filesystem::path& outputDir, const std::vector<std::filesystem::path>& outputFiles,
                                 CreatedFiles& created) {
  namespace fs = std::filesystem;
  const fs::path inputDir = assetRootFor(asset_.path, {});
  std::error_code ec;
  const fs::path targetDir = fs::weakly_canonical(outputDir, ec);
  if (fs::equivalent(inputDir, targetDir, ec)) return;
  std::vector<fs::path> written;  // outputFiles as the targets below are spelled
  for (const fs::path& file : outputFiles) written.push_back(targetDir / file.filename());
  Json& doc = asset_.json;
  if (!doc.contains("images")) return;
  for (auto& image : doc["images"]) {
    if (!image.contains("uri") || !image["uri"].is_string()) continue;
    const std::string uri = image["uri"].get<std::string>();
    if (!isRelativeFileUri(uri)) continue;
    const fs::path source = fs::weakly_canonical(inputDir / percentDecode(uri), ec);
    if (ec || !fs::is_regular_file(source, ec)) continue;  // missing: kept as written (loading warned)
    if (isInside(source, inputDir)) {
      // Beside the output under the same relative path, so the output is self-contained and
      // passes the default asset root; never over a file the input uses.
      const fs::path relative = source.lexically_relative(inputDir);
      const fs::path target = targetDir / relative;
      if (fs::exists(target, ec) && fs::equivalent(target, source, ec)) continue;
      // The copy is renamed over `target` only after the output is written: what would make
      // that fail is refused before anything is written.
      if (fs::is_directory(fs::symlink_status(target, ec)))
        throw std::runtime_error(target.string() + ": is a directory, where bake would copy an image the input uses");
      if (std::find(written.begin(), written.end(), target.lexically_normal()) != written.end())
        throw std::runtime_error(target.string() + ": the output is written there, where bake would also copy an image the input "
                                 "uses; choose another output name");
      created.createFolders(target.parent_path());
      std::vector<std::uint8_t> bytes;
      if (!readFileInto(source, bytes)) throw std::runtime_error(source.string() + ": cannot be read to copy beside the output");
      // A copy an earlier bake left there is not written again: each write is a flush to disk,
      // and in a folder baked over and over they took longer than reading the buffers. One
      // that differs is replaced with the output, once that is written (CreatedFiles::keep).
      if (!created.staged(target)) {
        if (!holdsBytes(target, bytes)) {
          if (isProtected(target))
            throw InputError(target.string() + ": bake would copy the input's image " + source.string() +
                             " there, over a different file that an input of this run uses or that the run has written "
                             "(nothing was written; bake into another folder)");
          created.stage(target, bytes);
        }
        // Staged or already there with these bytes: a file the output needs beside it, spelled
        // as the output is.
        filesWritten_.push_back(outputPath_.parent_path() / relative);
      }
      image["uri"] = text::uriPath(relative.generic_string());
    } else {
      // Outside the input's folder (allowed by --asset-root): referred to where it is.
      image["uri"] = text::uriPath(source.lexically_relative(targetDir).generic_string());
    }
  }
}

void OutputDocument::embedImages() {
  namespace fs = std::filesystem;
  Json& doc = asset_.json;
  if (!doc.contains("images")) return;
  const std::string label = asset_.path.string();
  const fs::path baseDir = fs::absolute(asset_.path).parent_path();
  for (std::size_t i = 0; i < doc["images"].size(); ++i) {
    const std::string what = "/images/" + std::to_string(i);
    std::string uri, mimeType;
    {
      const Json& image = doc["images"][i];
      if (!image.contains("uri") || !image["uri"].is_string()) continue;
      uri = image["uri"].get<std::string>();
      if (image.contains("mimeType") && image["mimeType"].is_string())
        mimeType = image["mimeType"].get<std::string>();
    }
    std::vector<std::uint8_t> bytes;
    if (isDataUri(uri)) {
      try {
        bytes = decodeDataUri(uri, label + ": " + what + " uri");
      } catch (const InputError&) {
        continue;  // not base64: carried through as it is (loading warned)
      }
    } else {
      // The loader's rule and resolver: inside the asset root, or refused there already.
      fs::path file;
      try {
        file = resolveFileUri(uri, baseDir, asset_.root, label, what);
      } catch (const MissingFileError&) {
        continue;  // missing: kept as written (loading warned)
      }
      if (!readFileInto(file, bytes))
        throw InputError(label + ": " + what + ": " + file.string() + " cannot be read to embed it in the .glb");
    }
    if (mimeType.empty()) mimeType = imageTypeOfBytes(bytes);
    if (mimeType.empty())
      throw InputError(label + ": " + what +
                       ": has no mimeType and its bytes are not PNG, JPEG, WebP or KTX2, so it cannot be embedded in "
                       "a .glb (which needs one); write a .gltf, or keep the image external");
    const int view = addBufferView(std::move(bytes), 0, 0);
    Json& image = doc["images"][i];  // after the insertion into bufferViews
    image.erase("uri");
    image["bufferView"] = view;
    image["mimeType"] = mimeType;
  }
}

std::uint64_t OutputDocument::write(const std::filesystem::path& requested, const ProtectedFiles* runFiles,
                                    bool keepExternalImages) {
  namespace fs = std::filesystem;
  // A link to a file is written at its target, and the .bin and image copies go beside that.
  const output::WriteTarget target = output::writeTargetOf(requested);
  const fs::path output = target.kind == output::WriteTarget::Kind::replace ? target.file : requested;
  runFiles_ = runFiles;
  outputPath_ = output;
  filesWritten_.clear();
  if (isProtected(output))
    throw InputError(output.string() + ": is a file that an input of this run uses or that the run has written; bake never " +
                     "writes over one (choose another output name or folder)");
  dropOrphans();
  extensionsRemoved_ = dropUnusedCompressionExtensions(asset_.json);
  const bool glb = output.extension() == ".glb";
  if (glb && !keepExternalImages) embedImages();  // new views: before the buffers are packed
  const std::vector<std::span<const std::uint8_t>> bin = packBuffers();
  const fs::path outputDir = fs::absolute(output).parent_path();
  Json& doc = asset_.json;
  std::uint64_t binBytes = 0;
  for (const auto& piece : bin) binBytes += piece.size();
  // Image copies are staged and go into place with the output, as one, once it is written.
  CreatedFiles created;
  if (glb) {
    // Refused before anything is written, images included.
    output::checkGlbFits(output, 0, binBytes);
    if (keepExternalImages) placeImages(outputDir, {output}, created);
    const std::string json = text::dumpJson(doc);
    output::checkGlbFits(output, json.size(), binBytes);
    // Written from the pieces' own memory: no whole copy of the file.
    std::vector<std::uint8_t> frame;
    const auto pieces = glbPieces(json, bin, frame);
    output::StagedFile written(output, pieces);
    created.keep(written);
    filesWritten_.push_back(output);
    std::uint64_t total = 0;
    for (const auto& piece : pieces) total += piece.size();
    return total;
  }
  // The .bin's name first: no image copy may go there.
  const std::vector<fs::path> previousBins = bin.empty() ? std::vector<fs::path>{} : binsOfPreviousOutput(output);
  // Read once, before anything is written: what the other glTF files beside the output name.
  const NamedBeside namedBeside = bin.empty() ? NamedBeside{} : filesNamedBeside(output);
  auto usedBeside = [&](const fs::path& path) {
    const fs::path folder = output.parent_path().empty() ? fs::path(".") : output.parent_path();
    return namedBeside.names(folder / path.filename());
  };
  const fs::path binPath =
      bin.empty() ? fs::path()
                  : freeBinName(output, previousBins, [&](const fs::path& path) { return isProtected(path) || usedBeside(path); });
  placeImages(outputDir, bin.empty() ? std::vector<fs::path>{output} : std::vector<fs::path>{output, binPath}, created);
  if (bin.empty()) {
    const std::string text = text::dumpJson(doc, 2) + "\n";
    output::StagedFile written(output, {std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size())});
    created.keep(written);
    filesWritten_.push_back(output);
    return text.size();
  }
  // A .gltf and its .bin are one file in two: the new .bin goes under a name the previous
  // .gltf does not use (nor any protected file, freeBinName), so that until the .gltf is
  // renamed into place the previous pair is whole, and after it the new one is.
  doc["buffers"][0]["uri"] = text::uriPath(binPath.filename().string());
  const std::string text = text::dumpJson(doc, 2) + "\n";
  writeFileAtomic(binPath, bin);
  try {
    output::StagedFile written(output, {std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size())});
    created.keep(written);
  } catch (...) {
    if (std::find(previousBins.begin(), previousBins.end(), binPath) == previousBins.end()) {
      std::error_code ignored;
      fs::remove(binPath, ignored);
    }
    throw;
  }
  filesWritten_.push_back(output);
  filesWritten_.push_back(binPath);
  // The previous .bin, now used by nothing we wrote: removed unless a file of this run or
  // another .gltf or .glb beside the output names it.
  for (const fs::path& previous : previousBins) {
    std::error_code ec;
    if (previous != binPath && !isProtected(previous) && !usedBeside(previous)) fs::remove(previous, ec);
  }
  return binBytes + text.size();
}

bool readFileInto(const std::filesystem::path& path, std::vector<std::uint8_t>& out) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) return false;
  const std::streamoff size = in.tellg();
  if (size < 0) return false;
  out.resize(static_cast<std::size_t>(size));
  in.seekg(0);
  in.read(reinterpret_cast<char*>(out.data()), size);
  // A file that shrank while read is short: the bytes read are all there is.
  out.resize(static_cast<std::size_t>(in.gcount()));
  return !in.bad();
}

void writeFileAtomic(const std::filesystem::path& path, std::span<const std::uint8_t> bytes) {
  output::writeFileAtomic(path, {bytes});
}

void writeFileAtomic(const std::filesystem::path& path, const std::vector<std::span<const std::uint8_t>>& pieces) {
  output::writeFileAtomic(path, pieces);
}

namespace {

// The files that the buffers and images of `doc` (a glTF in `dir`) name by relative URI.
std::vector<std::filesystem::path> filesNamedBy(const Json& doc, const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> files;
  if (!doc.is_object()) return files;
  for (const char* kind : {"buffers", "images"}) {
    if (!doc.contains(kind) || !doc[kind].is_array()) continue;
    for (const auto& item : doc[kind]) {
      if (!item.is_object() || !item.contains("uri") || !item["uri"].is_string()) continue;
      const std::string uri = item["uri"].get<std::string>();
      if (isRelativeFileUri(uri)) files.push_back((dir / percentDecode(uri)).lexically_normal());
    }
  }
  return files;
}

// The JSON of a .gltf, or of a .glb's first chunk (read alone: the binary chunk is not), as
// text; empty where the file cannot be read or is neither.
std::string gltfJsonText(const std::filesystem::path& path) {
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  std::ifstream in(path, std::ios::binary);
  if (ec || !in) return {};
  char header[20] = {};
  in.read(header, sizeof header);
  const auto u32 = [&](int at) {
    std::uint32_t value = 0;
    std::memcpy(&value, header + at, 4);
    return value;
  };
  if (in.gcount() == sizeof header && std::memcmp(header, "glTF", 4) == 0) {
    if (std::memcmp(header + 16, "JSON", 4) != 0 || u32(12) > kMaxJsonBytes || u32(12) > size - sizeof header) return {};
    std::string text(u32(12), '\0');
    in.read(text.data(), static_cast<std::streamsize>(text.size()));
    if (in.gcount() != static_cast<std::streamsize>(text.size())) return {};
    return text;
  }
  if (size > kMaxJsonBytes) return {};  // no glTF we could read: what it names is unknown
  std::vector<std::uint8_t> bytes;
  if (!readFileInto(path, bytes)) return {};
  return std::string(bytes.begin(), bytes.end());
}

}  // namespace

std::vector<std::filesystem::path> referencedFiles(const Asset& asset) {
  return filesNamedBy(asset.json, std::filesystem::absolute(asset.path).parent_path());
}

}  // namespace tangent::gltf::detail

namespace tangent::gltf {

namespace {

std::optional<std::pair<std::uint64_t, std::uint64_t>> fileIdentity(const std::filesystem::path& path) {
  struct stat status {};
  if (::stat(path.c_str(), &status) != 0) return std::nullopt;
  return std::pair<std::uint64_t, std::uint64_t>(status.st_dev, status.st_ino);
}

}  // namespace

void ProtectedFiles::add(const std::filesystem::path& path) {
  if (const auto id = fileIdentity(path)) files_.insert(*id);
}

void ProtectedFiles::addInput(const std::filesystem::path& input) {
  add(input);
  if (const std::string extension = detail::lowerExtension(input); extension != ".gltf" && extension != ".glb")
    return;  // OBJ, PLY, OFF: one file
  const std::string text = detail::gltfJsonText(input);
  if (text.empty()) return;
  try {
    detail::checkJsonDepth(text, input.string());
    const nlohmann::ordered_json doc = nlohmann::ordered_json::parse(text);
    for (const auto& file : detail::filesNamedBy(doc, std::filesystem::absolute(input).parent_path())) add(file);
  } catch (const std::exception&) {
    // Not glTF JSON (an OBJ, PLY or OFF input, or a broken file): the input alone.
  }
}

bool ProtectedFiles::contains(const std::filesystem::path& path) const {
  const auto id = fileIdentity(path);
  return id && files_.contains(*id);
}

}  // namespace tangent::gltf
