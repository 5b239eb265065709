// SPDX-License-Identifier: MIT
// Baking folder trees: every glTF, OBJ, PLY and OFF file under a folder, each into the same
// relative path under an output folder, one failure never stopping the rest, with a manifest
// (OUTPUT/tangent-manifest.json) of input digests so that a re-run skips what is unchanged.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tangent/gltf.hpp"

namespace tangent::gltf {

inline constexpr const char* kManifestName = "tangent-manifest.json";
// Beside the manifest while a run goes on: a line per finished file, so that an interrupted run
// is resumed; merged into the manifest when the run ends.
inline constexpr const char* kJournalName = "tangent-manifest.journal";

struct BatchOptions {
  BakeOptions bake;
  bool force = false;   // bake everything, whatever the manifest says
  bool verify = false;  // hash every input, even where size and modification time are unchanged
  // Asked before each file; true: stop there (the manifest records what was done).
  std::function<bool()> stopRequested;
  // Called before each file: its index among `total` and its path (a progress display).
  std::function<void(std::size_t index, std::size_t total, const std::filesystem::path& input)> onStart;
};

// The manifest's "options" record: what changes an output besides its input (threads never do);
// a run whose options differ from the manifest's bakes everything again.
nlohmann::ordered_json manifestOptions(const BakeOptions& options);

// A checked value of the option table into `options` (force, verify, and bake's options into
// options.bake); false when the option is not one of bake_tree's.
bool applyBatchOption(BatchOptions& options, const options::Option& option, std::string_view value);

// What a run did with a file: baked (some primitive got tangents), kept (written, but every
// primitive kept its tangents or needed none), unchanged (skipped: the manifest's digest
// matches and the output is there), failed.
enum class FileOutcome { baked, kept, unchanged, failed };
const char* toString(FileOutcome outcome);

struct BatchEntry {
  std::filesystem::path input, output;
  bool ok = false;          // baked (now or, when skipped, last time)
  bool skipped = false;     // input, the files it names and the options unchanged since the manifest
  std::string error;        // why it failed
  FileOutcome outcome = FileOutcome::failed;
  std::string digest;       // SHA-256 of the input and every file it names (buffers, images)
  nlohmann::ordered_json report;  // toJson(BakeResult) when baked in this run
};

// An entry under a folder that has an input's name (.gltf, .glb, .obj, .ply, .off) but is not
// a regular file, nor a link to one: findInputs leaves it out, and says why here.
struct LeftOutEntry {
  std::filesystem::path path;
  std::string why;  // "a FIFO", "a link to nothing", "a link to a device", ...
};

// The bakeable files under `folder` (recursively, sorted; symbolic links to folders are not
// followed), leaving out everything under `skip` (the output folder when it lies inside).
// `leftOut`, where given, gets the entries named as inputs that are not files (sorted).
std::vector<std::filesystem::path> findInputs(const std::filesystem::path& folder, const std::filesystem::path& skip = {},
                                              std::vector<LeftOutEntry>* leftOut = nullptr);

// SHA-256 over the input's bytes and those of every buffer and image it names inside its
// asset root (hex). The manifest also records each such file's size and modification time: a
// re-run in which none changed takes the digest from there (BatchOptions::verify: never).
std::string inputDigest(const std::filesystem::path& input, const std::filesystem::path& assetRoot = {});

// Where bakeTree writes `input`, found under `inputFolder`: the same relative path under
// `outputFolder`, with outputPathFor's name.
std::filesystem::path outputPathInTree(const std::filesystem::path& input, const std::filesystem::path& inputFolder,
                                       const std::filesystem::path& outputFolder);

// Two inputs of one run whose outputs are the same file (m.glb, m.obj and m.ply all become
// m.glb; a/x.glb and b/x.glb in one --out-dir).
struct OutputCollision {
  std::filesystem::path first, second, output;
};
// Every input after the first that maps to an output an earlier one has (outputs[i] is
// inputs[i]'s), in input order.
std::vector<OutputCollision> outputCollisions(const std::vector<std::filesystem::path>& inputs,
                                              const std::vector<std::filesystem::path>& outputs);
// One message for them all, naming both inputs of each and the output.
std::string describeCollisions(const std::vector<OutputCollision>& collisions);

// The manifest's record of an input's contents: its digest, and the size and modification
// time of every file the digest read ("stamps"). Where `previous` (the input's record in the
// manifest, or null) has stamps that all still hold, its digest is taken as it is, without
// reading a byte; `verify` reads every file all the same.
struct InputDigest {
  std::string digest;
  nlohmann::ordered_json stamps;
};
InputDigest digestForManifest(const std::filesystem::path& input, const std::filesystem::path& assetRoot,
                              const nlohmann::ordered_json& previous, bool verify = false);

// Bakes the tree (refused as a whole, before anything is written, when two inputs would write
// the same output); `onFile` is called after each file. Each finished file is recorded in the
// journal at once; the manifest is written (atomically) at the end, also when
// `stopRequested` stopped the run early (then files not reached keep their earlier records).
std::vector<BatchEntry> bakeTree(const std::filesystem::path& inputFolder, const std::filesystem::path& outputFolder,
                                 const BatchOptions& options, const std::function<void(const BatchEntry&)>& onFile = {});

// One entry as the CLI's --report writes it.
nlohmann::ordered_json toJson(const BatchEntry& entry);

}  // namespace tangent::gltf
