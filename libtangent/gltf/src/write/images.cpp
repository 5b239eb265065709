// SPDX-License-Identifier: MIT
// The images of a written document (document.hpp): copied beside a .gltf (or a .glb that keeps
// them external), or embedded in a .glb.
#include <algorithm>
#include <initializer_list>

#include "read/uri.hpp"
#include "tangent/text.hpp"
#include "write/document.hpp"

namespace tangent::gltf::detail {

using Json = nlohmann::ordered_json;

namespace {

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

}  // namespace tangent::gltf::detail
