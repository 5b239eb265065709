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

}  // namespace

bool OutputDocument::isProtected(const std::filesystem::path& path) const {
  return inputFiles_.contains(path) || (runFiles_ && runFiles_->contains(path));
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

namespace {

std::uint64_t bytesIn(const std::vector<std::span<const std::uint8_t>>& pieces) {
  std::uint64_t total = 0;
  for (const auto& piece : pieces) total += piece.size();
  return total;
}

}  // namespace

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
  const bool glb = requested.extension() == ".glb";  // the kind asked for (writeTargetOf: a link's target has it too)
  if (glb && !keepExternalImages) embedImages();  // new views: before the buffers are packed
  const std::vector<std::span<const std::uint8_t>> bin = packBuffers();
  return glb ? writeGlb(output, bin, keepExternalImages) : writeGltf(output, bin);
}

std::uint64_t OutputDocument::writeGlb(const std::filesystem::path& output, const std::vector<std::span<const std::uint8_t>>& bin,
                                       bool keepExternalImages) {
  const std::uint64_t binBytes = bytesIn(bin);
  // Image copies are staged and go into place with the output, as one, once it is written.
  CreatedFiles created;
  // Refused before anything is written, images included.
  output::checkGlbFits(output, 0, binBytes);
  if (keepExternalImages) placeImages(std::filesystem::absolute(output).parent_path(), {output}, created);
  const std::string json = text::dumpJson(asset_.json);
  output::checkGlbFits(output, json.size(), binBytes);
  // Written from the pieces' own memory: no whole copy of the file.
  std::vector<std::uint8_t> frame;
  const auto pieces = glbPieces(json, bin, frame);
  output::StagedFile written(output, pieces);
  created.keep(written);
  filesWritten_.push_back(output);
  return bytesIn(pieces);
}

std::uint64_t OutputDocument::writeGltf(const std::filesystem::path& output, const std::vector<std::span<const std::uint8_t>>& bin) {
  namespace fs = std::filesystem;
  const fs::path outputDir = fs::absolute(output).parent_path();
  Json& doc = asset_.json;
  // Image copies are staged and go into place with the output, as one, once it is written.
  CreatedFiles created;
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
  return bytesIn(bin) + text.size();
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
