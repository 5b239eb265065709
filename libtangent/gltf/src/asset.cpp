#include "asset.hpp"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <iterator>

#include "tangent/gltf.hpp"

namespace tangent::gltf::detail {
namespace {

constexpr std::uint32_t kGlbMagic = 0x46546C67;      // "glTF"
constexpr std::uint32_t kChunkJson = 0x4E4F534A;     // "JSON"
constexpr std::uint32_t kChunkBin = 0x004E4942;      // "BIN\0"

std::uint32_t readU32(const std::uint8_t* p) {
  std::uint32_t v;
  std::memcpy(&v, p, 4);
  return v;
}

void appendU32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  const auto* p = reinterpret_cast<const std::uint8_t*>(&v);
  out.insert(out.end(), p, p + 4);
}

std::vector<std::uint8_t> readFileBytes(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(path.string() + ": no such file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string() + ": cannot be opened for reading");
  return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(in), {});
}

bool noImageDecoding(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
  return true;  // bake carries image bytes through untouched
}

using Json = nlohmann::ordered_json;

[[noreturn]] void shapeError(const std::string& label, const std::string& pointer, const char* expected) {
  throw InputError(label + ": " + pointer + " must be " + expected);
}

void requireIndex(const Json& object, const char* key, const std::string& label, const std::string& pointer) {
  if (object.contains(key) && !object[key].is_number_integer()) shapeError(label, pointer + "/" + key, "an integer");
}

// The parts of the document bake reads or renumbers must have the types the spec gives them,
// so later code can index them without surprises.
void checkShape(const Json& doc, const std::string& label) {
  for (const char* key : {"accessors", "animations", "buffers", "bufferViews", "cameras", "images", "materials", "meshes",
                          "nodes", "samplers", "scenes", "skins", "textures"}) {
    if (!doc.contains(key)) continue;
    if (!doc[key].is_array()) shapeError(label, std::string("/") + key, "an array");
    for (std::size_t i = 0; i < doc[key].size(); ++i) {
      if (!doc[key][i].is_object()) shapeError(label, "/" + std::string(key) + "/" + std::to_string(i), "an object");
    }
  }
  for (const char* key : {"extensionsUsed", "extensionsRequired"}) {
    if (doc.contains(key) && !doc[key].is_array()) shapeError(label, std::string("/") + key, "an array");
  }
  const auto indexMap = [&](const Json& map, const std::string& pointer) {
    if (!map.is_object()) shapeError(label, pointer, "an object");
    for (const auto& [name, value] : map.items()) {
      if (!value.is_number_integer()) shapeError(label, pointer + "/" + name, "an accessor index");
    }
  };
  if (doc.contains("meshes")) {
    for (std::size_t m = 0; m < doc["meshes"].size(); ++m) {
      const Json& mesh = doc["meshes"][m];
      const std::string meshPointer = "/meshes/" + std::to_string(m);
      if (!mesh.contains("primitives") || !mesh["primitives"].is_array()) shapeError(label, meshPointer + "/primitives", "an array");
      for (std::size_t p = 0; p < mesh["primitives"].size(); ++p) {
        const Json& primitive = mesh["primitives"][p];
        const std::string pointer = meshPointer + "/primitives/" + std::to_string(p);
        if (!primitive.is_object()) shapeError(label, pointer, "an object");
        if (!primitive.contains("attributes")) shapeError(label, pointer + "/attributes", "present");
        indexMap(primitive["attributes"], pointer + "/attributes");
        for (const char* key : {"indices", "material", "mode"}) requireIndex(primitive, key, label, pointer);
        if (primitive.contains("targets")) {
          if (!primitive["targets"].is_array()) shapeError(label, pointer + "/targets", "an array");
          for (std::size_t t = 0; t < primitive["targets"].size(); ++t)
            indexMap(primitive["targets"][t], pointer + "/targets/" + std::to_string(t));
        }
      }
    }
  }
  if (doc.contains("materials")) {
    for (std::size_t i = 0; i < doc["materials"].size(); ++i) {
      const Json& material = doc["materials"][i];
      if (!material.contains("normalTexture")) continue;
      const std::string pointer = "/materials/" + std::to_string(i) + "/normalTexture";
      if (!material["normalTexture"].is_object()) shapeError(label, pointer, "an object");
      requireIndex(material["normalTexture"], "index", label, pointer);
      requireIndex(material["normalTexture"], "texCoord", label, pointer);
    }
  }
  if (doc.contains("bufferViews")) {
    for (std::size_t i = 0; i < doc["bufferViews"].size(); ++i) {
      for (const char* key : {"buffer", "byteOffset", "byteLength", "byteStride"})
        requireIndex(doc["bufferViews"][i], key, label, "/bufferViews/" + std::to_string(i));
    }
  }
}

}  // namespace

bool isMeshFile(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".obj" || ext == ".ply" || ext == ".off";
}

void splitGlb(std::span<const std::uint8_t> bytes, const std::string& label, std::string& json,
              std::span<const std::uint8_t>& bin) {
  if (bytes.size() < 20) throw InputError(label + ": GLB is truncated (" + std::to_string(bytes.size()) + " bytes)");
  if (readU32(bytes.data()) != kGlbMagic) throw InputError(label + ": not a GLB file (bad magic)");
  if (readU32(bytes.data() + 4) != 2) throw InputError(label + ": GLB version " + std::to_string(readU32(bytes.data() + 4)) + " is not 2");
  const std::uint32_t length = readU32(bytes.data() + 8);
  if (length > bytes.size()) throw InputError(label + ": GLB header says " + std::to_string(length) + " bytes, file has " + std::to_string(bytes.size()));
  const std::uint32_t jsonLength = readU32(bytes.data() + 12);
  if (readU32(bytes.data() + 16) != kChunkJson || jsonLength > length - 20)
    throw InputError(label + ": GLB first chunk is not a valid JSON chunk");
  json.assign(reinterpret_cast<const char*>(bytes.data() + 20), jsonLength);
  bin = {};
  const std::size_t next = 20 + static_cast<std::size_t>(jsonLength);
  if (next + 8 <= length && readU32(bytes.data() + next + 4) == kChunkBin) {
    const std::uint32_t binLength = readU32(bytes.data() + next);
    if (binLength > length - next - 8) throw InputError(label + ": GLB BIN chunk overruns the file");
    bin = bytes.subspan(next + 8, binLength);
  }
}

std::vector<std::span<const std::uint8_t>> glbPieces(const std::string& json, std::span<const std::uint8_t> bin,
                                                     std::vector<std::uint8_t>& frame) {
  const std::size_t jsonPadding = (4 - json.size() % 4) % 4, binPadding = (4 - bin.size() % 4) % 4;
  const std::size_t total = 12 + 8 + json.size() + jsonPadding + (bin.empty() ? 0 : 8 + bin.size() + binPadding);
  // frame: file header + JSON chunk header (20), JSON padding, BIN chunk header (8), BIN padding.
  frame.clear();
  appendU32(frame, kGlbMagic);
  appendU32(frame, 2);
  appendU32(frame, static_cast<std::uint32_t>(total));
  appendU32(frame, static_cast<std::uint32_t>(json.size() + jsonPadding));
  appendU32(frame, kChunkJson);
  frame.resize(frame.size() + jsonPadding, ' ');
  appendU32(frame, static_cast<std::uint32_t>(bin.size() + binPadding));
  appendU32(frame, kChunkBin);
  frame.resize(frame.size() + binPadding, 0);
  const std::uint8_t* f = frame.data();
  std::vector<std::span<const std::uint8_t>> pieces = {
      {f, 20}, {reinterpret_cast<const std::uint8_t*>(json.data()), json.size()}, {f + 20, jsonPadding}};
  if (!bin.empty()) pieces.insert(pieces.end(), {{f + 20 + jsonPadding, 8}, bin, {f + 28 + jsonPadding, binPadding}});
  return pieces;
}

std::vector<std::uint8_t> makeGlb(const std::string& json, std::span<const std::uint8_t> bin) {
  std::vector<std::uint8_t> frame;
  std::vector<std::uint8_t> out;
  for (const auto& piece : glbPieces(json, bin, frame)) out.insert(out.end(), piece.begin(), piece.end());
  return out;
}

Asset loadAsset(const std::filesystem::path& path) {
  Asset asset;
  asset.path = path;
  const std::string label = path.string();
  std::vector<std::uint8_t> bytes;
  if (isMeshFile(path)) {
    if (!std::filesystem::is_regular_file(path)) throw InputError(label + ": no such file");
    bytes = meshFileToGlb(path);
    asset.fromMeshFile = true;
  } else {
    bytes = readFileBytes(path);
  }
  asset.binary = bytes.size() >= 4 && readU32(bytes.data()) == kGlbMagic;

  std::string jsonText;
  if (asset.binary) {
    std::span<const std::uint8_t> bin;
    splitGlb(bytes, label, jsonText, bin);
  } else {
    jsonText.assign(bytes.begin(), bytes.end());
  }
  try {
    asset.json = nlohmann::ordered_json::parse(jsonText);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(label + ": not valid glTF JSON: " + e.what());
  }
  if (!asset.json.is_object()) throw InputError(label + ": glTF JSON must be an object");
  checkShape(asset.json, label);

  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(noImageDecoding, nullptr);
  std::string err, warn;
  const std::string baseDir = path.parent_path().string();
  bool ok = false;
  try {
    ok = asset.binary ? loader.LoadBinaryFromMemory(&asset.model, &err, &warn, bytes.data(),
                                                    static_cast<unsigned int>(bytes.size()), baseDir)
                      : loader.LoadASCIIFromString(&asset.model, &err, &warn, jsonText.data(),
                                                   static_cast<unsigned int>(jsonText.size()), baseDir);
  } catch (const std::exception& e) {
    err = e.what();
  }
  if (!ok) {
    while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
    throw InputError(label + ": cannot be loaded: " + (err.empty() ? std::string("unknown tinygltf error") : err));
  }
  if (!warn.empty()) asset.warnings.push_back(label + ": " + warn);
  return asset;
}

}  // namespace tangent::gltf::detail
