// SPDX-License-Identifier: MIT
#include "read/asset.hpp"

#include <cctype>
#include <climits>
#include <algorithm>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string_view>

#include "tangent/gltf.hpp"
#include "tangent/input_file.hpp"
#include "tangent/text.hpp"
#include "read/compression.hpp"
#include "write/document.hpp"
#include "read/primitive.hpp"
#include "read/uri.hpp"
#include "read/validate.hpp"

namespace tangent::gltf {

std::uintmax_t requireInputFile(const std::filesystem::path& path, const char* kind) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec == std::errc::filename_too_long)
    throw InputError(text::quoted(path.string()) + ": the name is too long (" + std::to_string(path.string().size()) +
                     " bytes; the system allows " + std::to_string(PATH_MAX) + " in a path and " + std::to_string(NAME_MAX) +
                     " in one of its names)");
  const std::string name = path.string();  // escaped where it is printed, as every message
  if (!std::filesystem::exists(status)) throw InputError(name + ": no such file");
  if (std::filesystem::is_directory(status)) throw InputError(name + ": is a directory, not " + kind);
  if (!std::filesystem::is_regular_file(status))
    throw InputError(name + ": is not a regular file (a FIFO, socket or device is not read: it may block or never end)");
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) throw InputError(name + ": its size cannot be read (" + ec.message() + ")");
  if (size >= kMaxInputBytes)
    throw InputError(name + ": is " + std::to_string(size) + " bytes; inputs are limited to 4 GiB");
  return size;
}

}  // namespace tangent::gltf

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
  const std::uintmax_t size = requireInputFile(path, "a glTF file");
  // A GLB's header is checked before the file is read: a chunk it cannot hold is refused
  // without reading gigabytes first.
  if (std::ifstream head(path, std::ios::binary); head) {
    std::uint8_t header[20] = {};
    head.read(reinterpret_cast<char*>(header), sizeof header);
    if (head.gcount() == sizeof header && readU32(header) == kGlbMagic) checkGlbHeader(header, size, path.string());
  }
  std::vector<std::uint8_t> bytes;
  if (!readFileInto(path, bytes)) throw InputError(path.string() + ": cannot be opened for reading");
  return bytes;
}

using Json = nlohmann::ordered_json;

// tinygltf reads buffers and images through these: every path is checked against the asset
// root again, so no file outside it is opened whatever tinygltf makes of a URI.
struct FileAccess {
  std::filesystem::path root;
};

std::filesystem::path containedFile(const std::string& path, const FileAccess& access) {
  std::error_code ec;
  const std::filesystem::path resolved = std::filesystem::weakly_canonical(std::filesystem::absolute(path, ec), ec);
  if (ec || !isInside(resolved, access.root) || !std::filesystem::is_regular_file(resolved, ec)) return {};
  return resolved;
}

bool fileExists(const std::string& path, void* user) {
  return !containedFile(path, *static_cast<const FileAccess*>(user)).empty();
}

std::string expandFilePath(const std::string& path, void*) { return path; }

bool readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  const std::filesystem::path file = containedFile(path, *static_cast<const FileAccess*>(user));
  if (file.empty()) {
    if (err) *err += "refused to read " + path + ": not a regular file inside the asset root\n";
    return false;
  }
  if (!readFileInto(file, *out)) {
    if (err) *err += "cannot read " + path + "\n";
    return false;
  }
  return true;
}

bool writeWholeFile(std::string* err, const std::string& path, const std::vector<unsigned char>&, void*) {
  if (err) *err += "loading never writes (" + path + ")\n";
  return false;
}

// Buffer and image URIs against the containment rule, before tinygltf opens anything. Images
// are carried through and never given to tinygltf: their URIs are checked here alone. A
// missing image file (inside the root), a data: URI that is not base64 (checked without
// decoding it) or an image with no data at all (gltfpack writes one when it cannot find the
// image file) is a warning in `warnings`.
// Extensions an asset may require that the tools read correctly: the geometry ones they decode,
// and those that only concern images, materials, lights or the scene's metadata (what bake,
// check and info read from a mesh is the same with or without them). A required extension not
// here may change what the vertex data means (a vendor's mesh compression: its plain accessors
// hold nothing), so loading stops there, as glTF 2.0 3.12 asks of a loader that lacks one.
bool readsCorrectlyWith(const std::string& name) {
  static const char* const kKnown[] = {
      "KHR_draco_mesh_compression", "EXT_meshopt_compression", "KHR_meshopt_compression", "KHR_mesh_quantization",
      "KHR_texture_transform", "EXT_mesh_gpu_instancing", "KHR_texture_basisu", "EXT_texture_webp", "EXT_texture_avif",
      "MSFT_texture_dds", "KHR_lights_punctual", "EXT_lights_image_based", "KHR_xmp_json_ld", "KHR_animation_pointer",
      "KHR_node_visibility", "KHR_node_selectability", "KHR_node_hoverability", "MSFT_lod",
      // Custom shaders for materials (archived; the draft's name too, as assimp's test models have it).
      "KHR_techniques_webgl", "KHR_technique_webgl"};
  if (name.rfind("KHR_materials_", 0) == 0) return true;  // shading only
  return std::find(std::begin(kKnown), std::end(kKnown), name) != std::end(kKnown);
}

void checkRequiredExtensions(const Json& doc, const std::string& label) {
  auto it = doc.find("extensionsRequired");
  if (it == doc.end()) return;  // validateDocument checked that it is an array of strings
  for (std::size_t i = 0; i < it->size(); ++i) {
    const std::string name = (*it)[i].get<std::string>();
    if (!readsCorrectlyWith(name))
      throw InputError(label + ": /extensionsRequired/" + std::to_string(i) + ": " + text::quoted(name) +
                       " is required to load this asset, and libtangent does not support it (what it changes in the "
                       "meshes is unknown, so nothing is read)");
  }
}

void checkUris(const Json& doc, const std::filesystem::path& baseDir, const std::filesystem::path& root, const std::string& label,
               std::vector<std::string>& warnings) {
  for (const char* kind : {"buffers", "images"}) {
    if (!doc.contains(kind)) continue;
    const bool buffers = std::string(kind) == "buffers";
    for (std::size_t i = 0; i < doc[kind].size(); ++i) {
      const Json& item = doc[kind][i];
      const std::string what = "/" + std::string(kind) + "/" + std::to_string(i);
      if (!item.contains("uri")) {
        if (!buffers && !item.contains("bufferView"))
          warnings.push_back(label + ": images[" + std::to_string(i) +
                             "] has neither uri nor bufferView (no image data; a tool could not find the file?): left as it is");
        continue;
      }
      const std::string& uri = item["uri"].get_ref<const std::string&>();
      if (isDataUri(uri)) {
        // Buffers: decoded in loaderDocument. An image that is not base64 is carried through as
        // before (nothing here reads it), with a warning, as viewers will not decode it.
        if (!buffers) {
          try {
            checkDataUri(uri, label + ": " + what + " uri");
          } catch (const InputError& e) {
            warnings.push_back(std::string(e.what()) + ": the image is left as it is");
          }
        }
        continue;
      }
      try {
        const std::filesystem::path file = resolveFileUri(uri, baseDir, root, label, what);
        std::error_code ec;
        const std::uintmax_t size = std::filesystem::file_size(file, ec);
        const auto declared = item.value("byteLength", std::int64_t(0));
        if (buffers && !ec && size < static_cast<std::uintmax_t>(declared))
          throw InputError(label + ": " + what + ": byteLength is " + std::to_string(declared) + " but '" + text::quoted(uri) + "' has " +
                           std::to_string(size) + " bytes");
      } catch (const MissingFileError& e) {
        if (buffers) throw;
        warnings.push_back(std::string(e.what()) + ": the image is left as it is");
      }
    }
  }
}

// The members of a document tinygltf needs (see loadAssetBytes), with each buffer in a data:
// URI decoded into `decoded` (by buffer index; empty for the others) and replaced by a
// one-byte placeholder. validateDocument checked the buffers' types and byteLength.
Json loaderDocument(const Json& doc, const std::string& label, std::vector<std::vector<std::uint8_t>>& decoded) {
  Json subset = Json::object();
  for (const char* key : {"asset", "extensionsUsed", "extensionsRequired", "bufferViews", "accessors"}) {
    if (doc.contains(key)) subset[key] = doc[key];
  }
  if (!doc.contains("buffers")) return subset;
  subset["buffers"] = Json::array();
  decoded.assign(doc["buffers"].size(), {});
  for (std::size_t i = 0; i < doc["buffers"].size(); ++i) {
    const Json& buffer = doc["buffers"][i];
    const auto uri = buffer.find("uri");
    if (uri == buffer.end() || !uri->is_string() || !isDataUri(uri->get_ref<const std::string&>())) {
      subset["buffers"].push_back(buffer);
      continue;
    }
    const std::string what = label + ": /buffers/" + std::to_string(i) + " uri";
    decoded[i] = decodeDataUri(uri->get_ref<const std::string&>(), what);
    const auto byteLength = buffer.value("byteLength", std::uint64_t(0));
    if (decoded[i].size() < byteLength)
      throw InputError(what + ": the data: URI holds " + std::to_string(decoded[i].size()) + " bytes, byteLength is " +
                       std::to_string(byteLength));
    decoded[i].resize(byteLength);
    Json placeholder = Json::object();
    placeholder["byteLength"] = 1;
    placeholder["uri"] = "data:application/octet-stream;base64,AA==";
    subset["buffers"].push_back(std::move(placeholder));
  }
  return subset;
}

// `bytes` (a GLB whose BIN chunk is `bin`) with `json` as its JSON chunk: written over the old
// chunk, padded with spaces, where it fits (a subset of the document always does), so that
// the BIN chunk is not copied; else the container is built anew and `bin` points into it.
void replaceGlbJson(std::vector<std::uint8_t>& bytes, const std::string& json, std::span<const std::uint8_t>& bin) {
  const std::size_t chunkLength = readU32(bytes.data() + 12);
  if (json.size() <= chunkLength) {
    std::memcpy(bytes.data() + 20, json.data(), json.size());
    std::memset(bytes.data() + 20 + json.size(), ' ', chunkLength - json.size());
    return;
  }
  std::vector<std::uint8_t> rebuilt = makeGlb(json, bin);
  bytes = std::move(rebuilt);
  std::string ignored;
  splitGlb(bytes, "", ignored, bin);
}

}  // namespace

std::string lowerExtension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

bool isMeshFile(const std::filesystem::path& path) {
  const std::string ext = lowerExtension(path);
  return ext == ".obj" || ext == ".ply" || ext == ".off";
}

std::uint64_t checkGlbHeader(std::span<const std::uint8_t> header, std::uint64_t fileBytes, const std::string& label) {
  if (readU32(header.data()) != kGlbMagic) throw InputError(label + ": not a GLB file (bad magic)");
  if (readU32(header.data() + 4) != 2) throw InputError(label + ": GLB version " + std::to_string(readU32(header.data() + 4)) + " is not 2");
  const std::uint64_t length = readU32(header.data() + 8);
  if (length > fileBytes || length < 20)
    throw InputError(label + ": GLB header says " + std::to_string(length) + " bytes, file has " + std::to_string(fileBytes));
  const std::uint64_t jsonLength = readU32(header.data() + 12);
  if (readU32(header.data() + 16) != kChunkJson || jsonLength > length - 20)
    throw InputError(label + ": GLB first chunk is not a valid JSON chunk");
  if (jsonLength > kMaxJsonBytes)
    throw InputError(label + ": GLB JSON chunk is " + std::to_string(jsonLength) + " bytes; JSON is limited to " +
                     std::to_string(kMaxJsonBytes));
  return jsonLength;
}

void splitGlb(std::span<const std::uint8_t> bytes, const std::string& label, std::string& json,
              std::span<const std::uint8_t>& bin) {
  if (bytes.size() < 20) throw InputError(label + ": GLB is truncated (" + std::to_string(bytes.size()) + " bytes)");
  const std::uint64_t jsonLength = checkGlbHeader(bytes.first(20), bytes.size(), label);
  const std::uint64_t length = readU32(bytes.data() + 8);
  json.assign(reinterpret_cast<const char*>(bytes.data() + 20), jsonLength);
  bin = {};
  const std::size_t next = 20 + static_cast<std::size_t>(jsonLength);
  if (next + 8 <= length && readU32(bytes.data() + next + 4) == kChunkBin) {
    const std::uint64_t binLength = readU32(bytes.data() + next);
    if (binLength > length - next - 8) throw InputError(label + ": GLB BIN chunk overruns the file");
    bin = bytes.subspan(next + 8, binLength);
  }
}

std::vector<std::span<const std::uint8_t>> glbPieces(const std::string& json,
                                                     const std::vector<std::span<const std::uint8_t>>& binPieces,
                                                     std::vector<std::uint8_t>& frame) {
  std::size_t binSize = 0;
  for (const auto& piece : binPieces) binSize += piece.size();
  const std::size_t jsonPadding = (4 - json.size() % 4) % 4, binPadding = (4 - binSize % 4) % 4;
  const std::size_t total = 12 + 8 + json.size() + jsonPadding + (binSize == 0 ? 0 : 8 + binSize + binPadding);
  // frame: file header + JSON chunk header (20), JSON padding, BIN chunk header (8), BIN padding.
  frame.clear();
  appendU32(frame, kGlbMagic);
  appendU32(frame, 2);
  appendU32(frame, static_cast<std::uint32_t>(total));
  appendU32(frame, static_cast<std::uint32_t>(json.size() + jsonPadding));
  appendU32(frame, kChunkJson);
  frame.resize(frame.size() + jsonPadding, ' ');
  appendU32(frame, static_cast<std::uint32_t>(binSize + binPadding));
  appendU32(frame, kChunkBin);
  frame.resize(frame.size() + binPadding, 0);
  const std::uint8_t* f = frame.data();
  std::vector<std::span<const std::uint8_t>> pieces = {
      {f, 20}, {reinterpret_cast<const std::uint8_t*>(json.data()), json.size()}, {f + 20, jsonPadding}};
  if (binSize > 0) {
    pieces.push_back({f + 20 + jsonPadding, 8});
    for (const auto& piece : binPieces) {
      if (!piece.empty()) pieces.push_back(piece);
    }
    pieces.push_back({f + 28 + jsonPadding, binPadding});
  }
  return pieces;
}

std::vector<std::uint8_t> makeGlb(const std::string& json, std::span<const std::uint8_t> bin) {
  std::vector<std::uint8_t> frame;
  std::vector<std::uint8_t> out;
  for (const auto& piece : glbPieces(json, {bin}, frame)) out.insert(out.end(), piece.begin(), piece.end());
  return out;
}

Asset loadAsset(const std::filesystem::path& path, const std::filesystem::path& assetRoot) {
  const std::string label = path.string();
  if (isMeshFile(path)) {
    requireInputFile(path, "a mesh file");
    return loadAssetBytes(meshFileToGlb(path), path, assetRoot, true);
  }
  return loadAssetBytes(readFileBytes(path), path, assetRoot, false);
}

Asset loadAssetBytes(std::vector<std::uint8_t> bytes, const std::filesystem::path& path,
                     const std::filesystem::path& assetRoot, bool fromMeshFile) {
  Asset asset;
  asset.path = path;
  asset.root = assetRootFor(path, assetRoot);
  asset.fromMeshFile = fromMeshFile;
  const std::string label = path.string();
  if (bytes.size() >= gltf::kMaxInputBytes) throw InputError(label + ": inputs are limited to 4 GiB");
  asset.binary = bytes.size() >= 4 && readU32(bytes.data()) == kGlbMagic;
  if (bytes.empty()) throw InputError(label + ": is empty (0 bytes), not glTF");
  if (!asset.binary && lowerExtension(path) == ".glb")
    throw InputError(label + ": not a GLB file (it does not begin with the bytes 'glTF')");

  // A .gltf is parsed from the bytes read and they are freed after: no copy of the text.
  std::string jsonText;
  std::span<const std::uint8_t> bin;
  if (asset.binary) splitGlb(bytes, label, jsonText, bin);
  const std::string_view text = asset.binary ? std::string_view(jsonText)
                                             : std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  checkJsonDepth(text, label);
  try {
    asset.json = nlohmann::ordered_json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(label + ": not valid glTF JSON: " + text::quoted(e.what()));  // it quotes the text it stopped at
  }
  if (asset.binary) std::string().swap(jsonText);
  else std::vector<std::uint8_t>().swap(bytes);
  if (!asset.json.is_object()) throw InputError(label + ": glTF JSON must be an object");
  validateDocument(asset.json, label);
  checkRequiredExtensions(asset.json, label);
  const std::filesystem::path baseDir = std::filesystem::absolute(path).parent_path();
  if (!isInside(assetRootFor(path, {}), asset.root))
    throw InputError(label + ": the asset root " + asset.root.string() + " does not contain the file's folder");
  checkUris(asset.json, baseDir, asset.root, label, asset.warnings);
  // tinygltf is given only what is decoded through it (buffers, views, accessors): the scene is
  // read from asset.json. With the whole document it parsed and copied 1e5 meshes and nodes a
  // second time (38% of `check` on 64k primitives). Images are not given either: it read every
  // image file and decoded every data: URI image only for a callback that dropped the bytes.
  // Compressed data: a document it accepts (see adaptForLoader); the data is decoded below.
  // Buffers in data: URIs are decoded here, not by tinygltf, which kept several copies of the
  // text (a 100 MB URI took 1.4 GB) and answered a URI that is not base64 with "File not found".
  std::vector<std::vector<std::uint8_t>> dataUriBuffers;
  {
    nlohmann::ordered_json forLoader = loaderDocument(asset.json, label, dataUriBuffers);
    adaptForLoader(forLoader);
    jsonText = forLoader.dump();
    if (asset.binary) replaceGlbJson(bytes, jsonText, bin);
  }

  tinygltf::TinyGLTF loader;
  FileAccess access{asset.root};
  loader.SetFsCallbacks({fileExists, expandFilePath, readWholeFile, writeWholeFile, &access});
  std::string err, warn;
  bool ok = false;
  try {
    ok = asset.binary ? loader.LoadBinaryFromMemory(&asset.model, &err, &warn, bytes.data(),
                                                    static_cast<unsigned int>(bytes.size()), baseDir.string())
                      : loader.LoadASCIIFromString(&asset.model, &err, &warn, jsonText.data(),
                                                   static_cast<unsigned int>(jsonText.size()), baseDir.string());
  } catch (const std::exception& e) {
    err = e.what();
  }
  if (!ok) {
    while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
    throw InputError(label + ": cannot be loaded: " + (err.empty() ? std::string("unknown tinygltf error") : text::quoted(err)));
  }
  if (!warn.empty()) asset.warnings.push_back(label + ": " + warn);
  for (std::size_t i = 0; i < dataUriBuffers.size(); ++i) {
    if (!dataUriBuffers[i].empty()) asset.model.buffers[i].data = std::move(dataUriBuffers[i]);
  }
  decodeCompressedData(asset);
  verifyMeshData(asset);
  return asset;
}

}  // namespace tangent::gltf::detail
