// SPDX-License-Identifier: MIT
#include "tangent/batch.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <fstream>
#include <iterator>
#include <map>
#include <set>

#include "read/asset.hpp"
#include "write/document.hpp"
#include "bake/sha256.hpp"
#include "tangent/output.hpp"
#include "tangent/text.hpp"
#include "read/uri.hpp"
#include "read/validate.hpp"

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
  const std::string ext = detail::lowerExtension(path);
  return ext == ".gltf" || ext == ".glb" || detail::isMeshFile(path);
}

// What an entry that is not a regular file is, in a few words ("" for a folder: walked, not
// left out).
std::string notAFile(const fs::path& path) {
  auto kind = [](fs::file_type type) -> std::string {
    switch (type) {
      case fs::file_type::directory: return "";
      case fs::file_type::fifo: return "a FIFO";
      case fs::file_type::block:
      case fs::file_type::character: return "a device";
      case fs::file_type::socket: return "a socket";
      default: return "something other than a file";
    }
  };
  std::error_code ec;
  if (!fs::is_symlink(fs::symlink_status(path, ec))) return kind(fs::status(path, ec).type());
  const fs::file_status target = fs::status(path, ec);
  if (ec) return ec == std::errc::too_many_symbolic_link_levels ? "a link that loops" : "a link to nothing";
  if (fs::is_directory(target)) return "";  // a link to a folder: not followed, as a folder is not an input
  return "a link to " + kind(target.type());
}

}  // namespace

Json manifestOptions(const BakeOptions& options) {
  Json json{{"method", std::string(toString(options.tangents.method))},
            {"weighting", std::string(toString(options.tangents.weighting))},
            {"all", options.all},
            {"overwrite", options.overwrite},
            {"assetRoot", options.assetRoot.string()},
            {"tangentFormat", std::string(toString(options.tangentFormat))},
            {"normals", std::string(toString(options.normals))},
            {"keepExternalImages", options.keepExternalImages}};
  if (options.normals == NormalsMode::smooth) json["creaseAngleDegrees"] = options.creaseAngleDegrees;
  return json;
}

namespace {

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

std::vector<fs::path> findInputs(const fs::path& folder, const fs::path& skip, std::vector<LeftOutEntry>* leftOut) {
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
    if (!isInput(it->path())) continue;
    if (it->is_regular_file(ec)) {
      inputs.push_back(it->path());
    } else if (leftOut) {
      if (std::string why = notAFile(it->path()); !why.empty()) leftOut->push_back({it->path(), std::move(why)});
    }
  }
  std::sort(inputs.begin(), inputs.end());
  if (leftOut)
    std::sort(leftOut->begin(), leftOut->end(), [](const LeftOutEntry& a, const LeftOutEntry& b) { return a.path < b.path; });
  return inputs;
}

namespace {

// SHA-256 over the input and the files it names; `hashed` gets every file read for it.
std::string digestOf(const fs::path& input, const fs::path& assetRoot, std::vector<fs::path>& hashed) {
  detail::Sha256 hash;
  const std::vector<std::uint8_t> bytes = fileBytes(input);
  hash.update(bytes);
  hashed.push_back(input);
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
          hashed.push_back(file);
        } catch (const InputError&) {
        }
      }
    }
  } catch (const std::exception&) {
  }
  return hash.hexDigest();
}

// Size and modification time of each file a digest read, as the manifest records them: while
// every one is the same, the input and the set of files it names are too, and the digest
// is taken from the manifest without reading a byte (--verify reads them all the same).
Json stampsOf(const std::vector<fs::path>& files) {
  Json stamps = Json::array();
  for (const fs::path& file : files) {
    std::error_code ec;
    const auto size = fs::file_size(file, ec);
    if (ec) return Json::array();  // unreadable: no shortcut
    const auto time = fs::last_write_time(file, ec);
    if (ec) return Json::array();
    stamps.push_back({{"file", text::utf8Safe(fs::absolute(file).lexically_normal().string())},
                      {"size", size},
                      {"mtimeNs", std::chrono::duration_cast<std::chrono::nanoseconds>(
                                      std::chrono::file_clock::to_sys(time).time_since_epoch()).count()}});
  }
  return stamps;
}

bool stampsUnchanged(const Json& recorded, const fs::path& input) {
  if (!recorded.is_array() || recorded.empty()) return false;
  const fs::path absoluteInput = fs::absolute(input).lexically_normal();
  try {
    if (recorded.front().at("file").get<std::string>() != text::utf8Safe(absoluteInput.string())) return false;
    std::vector<fs::path> files;
    for (const Json& stamp : recorded) {
      const std::string name = stamp.at("file").get<std::string>();
      if (name.find("\\x") != std::string::npos) return false;  // escaped name: cannot be looked up again
      files.emplace_back(name);
    }
    return stampsOf(files) == recorded;
  } catch (const std::exception&) {
    return false;
  }
}

}  // namespace

std::string inputDigest(const fs::path& input, const fs::path& assetRoot) {
  std::vector<fs::path> hashed;
  return digestOf(input, assetRoot, hashed);
}

InputDigest digestForManifest(const fs::path& input, const fs::path& assetRoot, const Json& previous, bool verify) {
  if (!verify && previous.is_object() && previous.contains("digest") && previous["digest"].is_string() &&
      previous.contains("stamps") && stampsUnchanged(previous["stamps"], input))
    return {previous["digest"].get<std::string>(), previous["stamps"]};
  std::vector<fs::path> hashed;
  InputDigest result;
  result.digest = digestOf(input, assetRoot, hashed);
  result.stamps = stampsOf(hashed);
  return result;
}

const char* toString(FileOutcome outcome) {
  switch (outcome) {
    case FileOutcome::baked: return "baked";
    case FileOutcome::kept: return "kept";
    case FileOutcome::unchanged: return "unchanged";
    case FileOutcome::failed: return "failed";
  }
  return "failed";
}

fs::path outputPathInTree(const fs::path& input, const fs::path& inputFolder, const fs::path& outputFolder) {
  return outputPathFor(input, outputFolder / input.lexically_relative(inputFolder).parent_path());
}

std::vector<OutputCollision> outputCollisions(const std::vector<fs::path>& inputs, const std::vector<fs::path>& outputs) {
  std::map<fs::path, std::size_t> firstWriter;
  std::vector<OutputCollision> collisions;
  for (std::size_t i = 0; i < inputs.size() && i < outputs.size(); ++i) {
    std::error_code ec;
    const fs::path key = fs::absolute(outputs[i], ec).lexically_normal();
    const auto [at, inserted] = firstWriter.emplace(key, i);
    if (!inserted) collisions.push_back({inputs[at->second], inputs[i], outputs[i]});
  }
  return collisions;
}

std::string describeCollisions(const std::vector<OutputCollision>& collisions) {
  std::string text;
  for (const auto& c : collisions) {
    if (!text.empty()) text += "; ";
    text += text::quoted(c.first.string()) + " and " + text::quoted(c.second.string()) + " would both be written to " +
            text::quoted(c.output.string());
  }
  return text + " (nothing was written; bake them into different folders or rename one)";
}

namespace {

// The journal beside the manifest: one line per finished file, appended as the run goes, so
// that a run that is interrupted (Ctrl-C, kill -9, a full disk) is resumed by the next one.
// Its first line holds the options; the manifest replaces it when the run ends. Appended to in
// place, so it is never written through a link, to a FIFO or a device: only a regular file (or
// none yet) is read, truncated and written; anything else there stops the run before it starts,
// named (a link tangent-manifest.journal -> /etc/passwd was truncated and rewritten).
class Journal {
 public:
  Journal(const fs::path& path, const Json& options) : path_(path), options_(options) {}
  ~Journal() {
    if (fd_ >= 0) ::close(fd_);
  }
  Journal(const Journal&) = delete;
  Journal& operator=(const Journal&) = delete;

  // Records of a journal left by an earlier run with the same options.
  Json read() const {
    refuseUnlessRegularOrAbsent();
    Json records = Json::object();
    std::ifstream in(path_, std::ios::binary);
    std::string line;
    bool sameOptions = false, first = true;
    while (std::getline(in, line)) {
      Json item;
      try {
        if (line.size() > (std::size_t(1) << 20)) break;
        detail::checkJsonDepth(line, path_.string());
        item = Json::parse(line);
      } catch (const std::exception&) {
        break;  // a line cut short by the interruption: the rest is unknown
      }
      if (first) {
        sameOptions = item.is_object() && item.contains("options") && item["options"] == options_;
        first = false;
        if (!sameOptions) break;
        continue;
      }
      if (item.is_object() && item.contains("file") && item["file"].is_string() && item.contains("record"))
        records[item["file"].get<std::string>()] = item["record"];
    }
    return records;
  }

  // Starts a new journal with the records carried over from an interrupted run. The name is
  // opened without following a link and without waiting on a FIFO, and checked to be a
  // regular file before it is truncated.
  void start(const Json& carried) {
    fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC, 0666);
    if (fd_ < 0) {
      refuseUnlessRegularOrAbsent();
      return;  // a read-only folder: the run goes on without a journal, each output failing on its own
    }
    struct stat status {};
    if (::fstat(fd_, &status) != 0 || !S_ISREG(status.st_mode)) {
      ::close(fd_);
      fd_ = -1;
      refuseUnlessRegularOrAbsent();
      throw std::runtime_error(path_.string() + ": is not a regular file; the batch's journal goes there (remove it)");
    }
    (void)::ftruncate(fd_, 0);  // best effort, as every write below: the journal only speeds up a resumed run
    writeLine(text::dumpJson(Json{{"options", options_}}));
    for (const auto& [key, record] : carried.items()) append(key, record);
  }

  void append(const std::string& key, const Json& record) { writeLine(text::dumpJson(Json{{"file", key}, {"record", record}})); }

  void remove() {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
    std::error_code ec;
    fs::remove(path_, ec);
  }

 private:
  // Throws naming the journal's path where something other than a regular file is there.
  void refuseUnlessRegularOrAbsent() const {
    std::error_code ec;
    const fs::file_status status = fs::symlink_status(path_, ec);
    if (ec || status.type() == fs::file_type::not_found || status.type() == fs::file_type::regular) return;
    const char* kind = status.type() == fs::file_type::symlink     ? "a symbolic link"
                       : status.type() == fs::file_type::directory ? "a folder"
                       : status.type() == fs::file_type::fifo      ? "a FIFO"
                       : status.type() == fs::file_type::socket    ? "a socket"
                       : status.type() == fs::file_type::character || status.type() == fs::file_type::block ? "a device"
                                                                                                            : "not a regular file";
    throw std::runtime_error(path_.string() + ": is " + kind +
                             "; the batch keeps its journal under this name and writes only a regular file there: "
                             "nothing baked (remove it)");
  }

  void writeLine(std::string line) {
    if (fd_ < 0) return;
    line += '\n';
    const char* at = line.data();
    std::size_t left = line.size();
    while (left > 0) {
      const ssize_t written = ::write(fd_, at, left);
      if (written < 0 && errno == EINTR) continue;
      if (written <= 0) return;  // a full disk: the run goes on without its journal
      at += written;
      left -= static_cast<std::size_t>(written);
    }
  }

  fs::path path_;
  Json options_;
  int fd_ = -1;
};

// What the manifest and an interrupted run's journal know of each file, where the options are
// the same: the journal's records over the manifest's. A record of the wrong shape (a hand
// edit, another tool) is forgotten: that file is baked again, as when the whole manifest is
// unreadable.
Json previousRecords(const Json& previous, const Json& optionsNow, const Json& interrupted) {
  Json previousFiles = previous.contains("options") && previous["options"] == optionsNow && previous.contains("files") &&
                               previous["files"].is_object()
                           ? previous["files"]
                           : Json::object();
  for (const auto& [key, record] : interrupted.items()) previousFiles[key] = record;
  for (auto it = previousFiles.begin(); it != previousFiles.end();) {
    const Json& r = *it;
    const bool wellFormed = r.is_object() && r.contains("digest") && r["digest"].is_string() && r.contains("ok") &&
                            r["ok"].is_boolean() && (!r.contains("error") || r["error"].is_string()) &&
                            (!r.contains("output") || r["output"].is_string()) && (!r.contains("stamps") || r["stamps"].is_array());
    it = wellFormed ? std::next(it) : previousFiles.erase(it);
  }
  return previousFiles;
}

// The files no bake of the tree may write over: every input and what it uses; and, where the
// output folder lies inside the input folder, the assets already there that no earlier run of
// this manifest wrote (the user's, kept like inputs).
ProtectedFiles protectedFilesOfRun(const std::vector<fs::path>& inputs, const fs::path& inputFolder, const fs::path& outputFolder,
                                   const Json& previousFiles) {
  std::error_code ec;
  ProtectedFiles runFiles;
  for (const fs::path& input : inputs) runFiles.addInput(input);
  if (const fs::path in = fs::weakly_canonical(inputFolder, ec), out = fs::weakly_canonical(outputFolder, ec);
      !in.empty() && out != in && detail::isInside(out, in)) {
    std::set<fs::path> ours;
    for (const auto& [key, record] : previousFiles.items()) {
      if (record.is_object() && record.contains("output") && record["output"].is_string())
        ours.insert((outputFolder / fs::u8path(record["output"].get<std::string>())).lexically_normal());
    }
    for (auto it = fs::recursive_directory_iterator(outputFolder, fs::directory_options::skip_permission_denied, ec);
         it != fs::recursive_directory_iterator(); it.increment(ec)) {
      if (ec) break;
      if (it->is_regular_file(ec) && isInput(it->path()) && !ours.contains(it->path().lexically_normal()))
        runFiles.addInput(it->path());
    }
  }
  return runFiles;
}

// One input of the tree and its manifest record.
struct TreeFile {
  BatchEntry entry;
  Json record;
};

// One input: skipped where its record `before` (null: none) still holds (the same digest and,
// for a successful bake, every file it wrote still there), else baked; the files a bake
// writes join `runFiles`.
TreeFile bakeTreeFile(const fs::path& input, const fs::path& output, const Json* before, const fs::path& outputFolder,
                      const BatchOptions& options, const BakeOptions& bakeOptions, ProtectedFiles& runFiles) {
  std::error_code ec;
  TreeFile file;
  BatchEntry& entry = file.entry;
  entry.input = input;
  entry.output = output;
  InputDigest digest = digestForManifest(input, options.bake.assetRoot, before ? *before : Json(), options.verify);
  entry.digest = digest.digest;
  // Every file the last bake wrote is still there (its .bin and image copies too: a .gltf
  // whose buffer was deleted no longer loads); records before "written" know the output only.
  auto allWrittenThere = [&] {
    if (!fs::exists(entry.output, ec)) return false;
    if (!before->contains("written") || !(*before)["written"].is_array()) return true;
    for (const Json& written : (*before)["written"]) {
      if (!written.is_string() || !fs::exists(outputFolder / fs::u8path(written.get<std::string>()), ec)) return false;
    }
    return true;
  };
  Json written = Json::array();
  if (!options.force && before && before->value("digest", "") == entry.digest &&
      (!before->value("ok", false) || allWrittenThere())) {
    if (before->contains("written")) written = (*before)["written"];
    entry.skipped = true;
    entry.ok = before->value("ok", false);
    entry.error = before->value("error", "");
    entry.outcome = entry.ok ? FileOutcome::unchanged : FileOutcome::failed;
  } else {
    try {
      const BakeResult result = bakeFile(input, entry.output, bakeOptions);
      for (const fs::path& path : result.filesWritten) {
        runFiles.add(path);
        // Names that are not UTF-8 cannot be written back from JSON: those are not recorded.
        const std::string relative = path.lexically_relative(outputFolder).generic_string();
        if (text::utf8Safe(relative) == relative) written.push_back(relative);
      }
      entry.report = toJson(result);
      entry.ok = true;
      const bool anyBaked = std::any_of(result.primitives.begin(), result.primitives.end(),
                                        [](const PrimitiveResult& p) { return p.action == PrimitiveAction::baked; });
      entry.outcome = anyBaked ? FileOutcome::baked : FileOutcome::kept;
    } catch (const std::exception& e) {
      entry.error = e.what();
      entry.outcome = FileOutcome::failed;
    }
  }
  file.record = {{"digest", entry.digest},
                 {"output", text::utf8Safe(entry.output.lexically_relative(outputFolder).generic_string())},
                 {"ok", entry.ok}, {"stamps", std::move(digest.stamps)}};
  if (entry.ok && !written.empty()) file.record["written"] = std::move(written);
  if (!entry.ok) file.record["error"] = entry.error;
  return file;
}

}  // namespace

std::vector<BatchEntry> bakeTree(const fs::path& inputFolder, const fs::path& outputFolder, const BatchOptions& options,
                                 const std::function<void(const BatchEntry&)>& onFile) {
  std::error_code ec;
  const std::vector<fs::path> inputs = findInputs(inputFolder, outputFolder);
  std::vector<fs::path> outputs;
  for (const fs::path& input : inputs) outputs.push_back(outputPathInTree(input, inputFolder, outputFolder));
  if (const auto collisions = outputCollisions(inputs, outputs); !collisions.empty())
    throw InputError(inputFolder.string() + ": " + describeCollisions(collisions));

  fs::create_directories(outputFolder, ec);
  if (!fs::is_directory(outputFolder, ec)) throw std::runtime_error(outputFolder.string() + ": cannot create the output folder");
  const fs::path manifestPath = outputFolder / kManifestName;
  const Json previous = readManifest(manifestPath);
  const Json optionsNow = manifestOptions(options.bake);
  Journal journal(outputFolder / kJournalName, optionsNow);
  const Json interrupted = journal.read();
  const Json previousFiles = previousRecords(previous, optionsNow, interrupted);
  journal.start(interrupted);

  // No bake of the tree writes over a file another input uses, or over what an earlier one
  // wrote (two inputs' same-named images in one output folder).
  ProtectedFiles runFiles = protectedFilesOfRun(inputs, inputFolder, outputFolder, previousFiles);
  BakeOptions bakeOptions = options.bake;
  bakeOptions.protectedFiles = &runFiles;

  Json files = Json::object();
  std::vector<BatchEntry> entries;
  bool stopped = false;
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    if (options.stopRequested && options.stopRequested()) {
      stopped = true;
      break;
    }
    const fs::path& input = inputs[i];
    if (options.onStart) options.onStart(i, inputs.size(), input);
    const std::string key = text::utf8Safe(input.lexically_relative(inputFolder).generic_string());
    const auto found = previousFiles.find(key);
    const Json* before = found != previousFiles.end() && found->is_object() ? &*found : nullptr;
    TreeFile done = bakeTreeFile(input, outputs[i], before, outputFolder, options, bakeOptions, runFiles);
    if (!done.entry.skipped || !before || *before != done.record) journal.append(key, done.record);
    files[key] = std::move(done.record);
    if (onFile) onFile(done.entry);
    entries.push_back(std::move(done.entry));
  }
  if (stopped) {
    // What this run did not reach keeps what the manifest knew of it.
    for (const auto& [key, record] : previousFiles.items()) {
      if (!files.contains(key)) files[key] = record;
    }
  }
  const Json manifest = {{"schema", "libtangent-manifest/1"}, {"options", optionsNow}, {"files", files}};
  output::writeFileAtomic(manifestPath, text::dumpJson(manifest, 2) + "\n");
  journal.remove();
  return entries;
}

Json toJson(const BatchEntry& entry) {
  Json out = {{"input", entry.input.string()}, {"output", entry.output.string()}, {"status", entry.ok ? "ok" : "failed"},
              {"outcome", toString(entry.outcome)}, {"unchanged", entry.skipped}, {"digest", entry.digest}};
  if (!entry.ok) out["error"] = entry.error;
  if (!entry.report.is_null()) out.update(entry.report);
  return out;
}

}  // namespace tangent::gltf
