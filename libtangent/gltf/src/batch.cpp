// SPDX-License-Identifier: MIT
#include "tangent/batch.hpp"

#include <algorithm>
#include <fstream>
#include <iterator>

#include "asset.hpp"
#include "document.hpp"
#include "sha256.hpp"
#include "uri.hpp"
#include "validate.hpp"

namespace tangent::gltf {

using Json = nlohmann::ordered_json;
namespace fs = std::filesystem;

namespace {

std::vector<std::uint8_t> fileBytes(const fs::path& path) {
  std::vector<std::uint8_t> bytes;
  detail::readFileInto(path, bytes);  // unreadable: no bytes, as before
  return bytes;
}

bool isInput(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".gltf" || ext == ".glb" || detail::isMeshFile(path);
}

// What changes the output besides the input: the options (threads never do).
Json optionsJson(const BakeOptions& options) {
  return Json{{"method", std::string(toString(options.tangents.method))},
              {"weighting", std::string(toString(options.tangents.weighting))},
              {"all", options.all},
              {"overwrite", options.overwrite},
              {"assetRoot", options.assetRoot.string()}};
}

Json readManifest(const fs::path& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return Json::object();
  try {
    const std::vector<std::uint8_t> bytes = fileBytes(path);
    const std::string text(bytes.begin(), bytes.end());
    detail::checkJsonDepth(text, path.string());
    Json manifest = Json::parse(text);
    if (manifest.is_object() && manifest.value("schema", "") == "libtangent-manifest/1") return manifest;
  } catch (const std::exception&) {
  }
  return Json::object();  // unreadable: everything is baked again and it is rewritten
}

}  // namespace

std::vector<fs::path> findInputs(const fs::path& folder, const fs::path& skip) {
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) throw InputError(folder.string() + ": is not a folder");
  const fs::path skipCanonical = skip.empty() ? fs::path() : fs::weakly_canonical(skip, ec);
  std::vector<fs::path> inputs;
  for (auto it = fs::recursive_directory_iterator(folder, fs::directory_options::skip_permission_denied, ec);
       it != fs::recursive_directory_iterator(); it.increment(ec)) {
    if (ec) break;
    if (!skipCanonical.empty() && it->is_directory(ec) && fs::weakly_canonical(it->path(), ec) == skipCanonical) {
      it.disable_recursion_pending();
      continue;
    }
    if (it->is_regular_file(ec) && isInput(it->path())) inputs.push_back(it->path());
  }
  std::sort(inputs.begin(), inputs.end());
  return inputs;
}

std::string inputDigest(const fs::path& input, const fs::path& assetRoot) {
  detail::Sha256 hash;
  const std::vector<std::uint8_t> bytes = fileBytes(input);
  hash.update(bytes);
  if (detail::isMeshFile(input)) return hash.hexDigest();
  // The files a glTF names: found without loading it (a bad one fails in bake, not here).
  try {
    std::string jsonText;
    if (bytes.size() >= 4 && bytes[0] == 'g' && bytes[1] == 'l' && bytes[2] == 'T' && bytes[3] == 'F') {
      std::span<const std::uint8_t> bin;
      detail::splitGlb(bytes, input.string(), jsonText, bin);
    } else {
      jsonText.assign(bytes.begin(), bytes.end());
    }
    detail::checkJsonDepth(jsonText, input.string());
    const Json doc = Json::parse(jsonText);
    const fs::path root = detail::assetRootFor(input, assetRoot);
    const fs::path baseDir = fs::absolute(input).parent_path();
    for (const char* kind : {"buffers", "images"}) {
      if (!doc.contains(kind) || !doc[kind].is_array()) continue;
      for (const Json& item : doc[kind]) {
        if (!item.is_object() || !item.contains("uri") || !item["uri"].is_string()) continue;
        const std::string uri = item["uri"].get<std::string>();
        if (detail::isDataUri(uri)) continue;
        try {
          const fs::path file = detail::resolveFileUri(uri, baseDir, root, input.string(), kind);
          const std::uint8_t separator = 0;
          hash.update({reinterpret_cast<const std::uint8_t*>(uri.data()), uri.size()});
          hash.update({&separator, 1});
          hash.update(fileBytes(file));
        } catch (const InputError&) {
        }
      }
    }
  } catch (const std::exception&) {
  }
  return hash.hexDigest();
}

std::vector<BatchEntry> bakeTree(const fs::path& inputFolder, const fs::path& outputFolder, const BatchOptions& options,
                                 const std::function<void(const BatchEntry&)>& onFile) {
  std::error_code ec;
  fs::create_directories(outputFolder, ec);
  if (!fs::is_directory(outputFolder, ec)) throw std::runtime_error(outputFolder.string() + ": cannot create the output folder");
  const fs::path manifestPath = outputFolder / kManifestName;
  const Json previous = readManifest(manifestPath);
  const Json optionsNow = optionsJson(options.bake);
  const bool sameOptions = previous.contains("options") && previous["options"] == optionsNow;
  const Json previousFiles = previous.contains("files") && previous["files"].is_object() ? previous["files"] : Json::object();

  Json files = Json::object();
  std::vector<BatchEntry> entries;
  for (const fs::path& input : findInputs(inputFolder, outputFolder)) {
    BatchEntry entry;
    entry.input = input;
    const fs::path relative = input.lexically_relative(inputFolder);
    entry.output = outputPathFor(input, outputFolder / relative.parent_path());
    const std::string key = relative.generic_string();
    entry.digest = inputDigest(input, options.bake.assetRoot);
    const auto before = previousFiles.find(key);
    if (!options.force && sameOptions && before != previousFiles.end() && before->is_object() &&
        before->value("digest", "") == entry.digest && (!before->value("ok", false) || fs::exists(entry.output, ec))) {
      entry.skipped = true;
      entry.ok = before->value("ok", false);
      entry.error = before->value("error", "");
    } else {
      try {
        entry.report = toJson(bakeFile(input, entry.output, options.bake));
        entry.ok = true;
      } catch (const std::exception& e) {
        entry.error = e.what();
      }
    }
    Json record = {{"digest", entry.digest}, {"output", entry.output.lexically_relative(outputFolder).generic_string()},
                   {"ok", entry.ok}};
    if (!entry.ok) record["error"] = entry.error;
    files[key] = std::move(record);
    if (onFile) onFile(entry);
    entries.push_back(std::move(entry));
  }
  const Json manifest = {{"schema", "libtangent-manifest/1"}, {"options", optionsNow}, {"files", files}};
  const std::string text = manifest.dump(2) + "\n";
  detail::writeFileAtomic(manifestPath, std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
  return entries;
}

Json toJson(const BatchEntry& entry) {
  Json out = {{"input", entry.input.string()}, {"output", entry.output.string()}, {"status", entry.ok ? "ok" : "failed"},
              {"unchanged", entry.skipped}, {"digest", entry.digest}};
  if (!entry.ok) out["error"] = entry.error;
  if (!entry.report.is_null()) out.update(entry.report);
  return out;
}

}  // namespace tangent::gltf
