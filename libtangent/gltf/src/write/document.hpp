// SPDX-License-Identifier: MIT
// Editing a glTF document for output: new accessors appended, then on finish the accessors and
// bufferViews the edit orphaned are dropped, every reference renumbered, and all surviving
// buffer data packed into one buffer (the GLB BIN chunk or one .bin file). The edits are in
// document.cpp, the packing in pack.cpp, the images in images.cpp, the writers in write.cpp.
#pragma once

#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <span>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "read/asset.hpp"
#include "tangent/bulk_buffer.hpp"
#include "tangent/gltf.hpp"
#include "tangent/output.hpp"

namespace tangent::gltf::detail {

constexpr int kArrayBuffer = 34962;
constexpr int kElementArrayBuffer = 34963;

// The data of a new bufferView: bytes, or an array kept as it is (tangents, and 32-bit indices
// as the core wrote them, are not copied into bytes to be written).
class ViewBytes {
 public:
  template <typename Array>
    requires(!std::is_same_v<Array, ViewBytes>)
  ViewBytes(Array array) : data_(std::move(array)) {}  // NOLINT: implicit on purpose
  std::span<const std::uint8_t> bytes() const {
    return std::visit(
        [](const auto& array) {
          return std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(array.data()),
                                               array.size() * sizeof(array[0]));
        },
        data_);
  }

 private:
  std::variant<std::vector<std::uint8_t>, std::vector<float>, BulkVector<std::uint32_t>> data_;
};

// What a write puts on disk besides its output: the folders image copies go into, created at
// once, and the copies themselves, staged as temporaries beside their destinations (a copy
// may replace an earlier one there). keep(), given the output staged the same way, renames the
// copies and then the output into place as one (output::commitAll); destroyed before keep()
// succeeds (the output could not be written: a full disk, an error; or a rename failed), the
// temporaries and the new folders are removed again, newest first, so that a failed bake
// leaves the disk as it found it. Each path is guarded against signals as a temporary is. A
// folder is removed only where empty.
class CreatedFiles {
 public:
  CreatedFiles() = default;
  CreatedFiles(const CreatedFiles&) = delete;
  CreatedFiles& operator=(const CreatedFiles&) = delete;
  ~CreatedFiles();
  // The folders of `folder` that do not exist yet, created and added.
  void createFolders(const std::filesystem::path& folder);
  // `bytes` written to a temporary beside `path`, renamed over it by keep().
  void stage(const std::filesystem::path& path, std::span<const std::uint8_t> bytes);
  bool staged(const std::filesystem::path& path) const;
  // The staged copies, then `output`, renamed into place; everything stays. Where a rename
  // fails, throws std::runtime_error naming that file, with every copy and the output put
  // back as they were (the error says so).
  void keep(output::StagedFile& output);

 private:
  std::vector<std::filesystem::path> folders_;
  std::vector<std::unique_ptr<output::TemporaryGuard>> guards_;
  std::vector<std::unique_ptr<output::StagedFile>> staged_;
  std::set<std::filesystem::path> stagedPaths_;  // the paths of staged_: staged() in log time
};

class OutputDocument {
 public:
  explicit OutputDocument(Asset& asset);

  nlohmann::ordered_json& json() { return asset_.json; }

  // Appends an accessor (its JSON without bufferView/byteOffset) stored in a new bufferView.
  // Vertex data (kArrayBuffer) whose element size is not a multiple of 4 is padded to a
  // 4-byte byteStride, as the spec requires of vertex attributes.
  int addAccessor(nlohmann::ordered_json accessor, ViewBytes bytes, std::size_t elementSize, int target);

  // Writes `output` (.glb, or .gltf plus a .bin beside it) atomically; returns bytes written.
  // Nothing is written over the input, the files it uses or `runFiles` (a run's other files;
  // may be null): InputError before anything is written, or another name for the .bin.
  // A .glb is one self-contained file (its images embedded, embedImages) unless
  // `keepExternalImages`: then, as a .gltf's, its external images are copied beside it.
  std::uint64_t write(const std::filesystem::path& output, const ProtectedFiles* runFiles = nullptr,
                      bool keepExternalImages = false);

  // What write() put in place: the output, its .bin, and the image copies beside it (staged, or
  // already there with the same bytes).
  const std::vector<std::filesystem::path>& filesWritten() const { return filesWritten_; }

  // Compression extensions write() took out of extensionsUsed/Required (nothing used them).
  const std::vector<std::string>& extensionsRemoved() const { return extensionsRemoved_; }

 private:
  // Appends a bufferView of buffer 0 holding `bytes` (byteStride and target where not 0);
  // returns its index.
  int addBufferView(ViewBytes bytes, std::size_t byteStride, int target);
  void dropOrphans();
  // Every image with a uri (a file the loader let through, or a base64 data: URI) moved into a
  // new bufferView, byte for byte, with its mimeType (declared, else from the bytes; refused,
  // naming /images/N, where neither says): a .glb then needs no file beside it. Images whose
  // file is missing or whose data: URI is not base64 (loading warned) are left as they are.
  void embedImages();
  // Lays every bufferView out in one buffer (4-byte aligned) and returns that buffer's bytes
  // as pieces of the memory they are in (loaded buffers, new views, padding): no copy.
  // EXT_meshopt_compression views keep their compressed bytes (in that buffer) and lie in a
  // second, data-less fallback buffer where the input required the extension, else their
  // decoded bytes stay in the first buffer as the fallback data.
  std::vector<std::span<const std::uint8_t>> packBuffers();
  // External images inside the input's folder are copied beside the output (same relative
  // path); others (a wider --asset-root) are referred to relative to the output. A copy that
  // would go where the output writes one of `outputFiles` (itself, its .bin) is refused.
  void placeImages(const std::filesystem::path& outputDir, const std::vector<std::filesystem::path>& outputFiles,
                   CreatedFiles& created);
  // write()'s two kinds of output, once the buffers are packed into `bin`: a .glb, or a .gltf
  // with its .bin (under a free name) beside it; each returns the bytes written.
  std::uint64_t writeGlb(const std::filesystem::path& output, const std::vector<std::span<const std::uint8_t>>& bin,
                         bool keepExternalImages);
  std::uint64_t writeGltf(const std::filesystem::path& output, const std::vector<std::span<const std::uint8_t>>& bin);
  // Whether `path` is the input, a file it uses (as loaded) or one of runFiles_.
  bool isProtected(const std::filesystem::path& path) const;

  Asset& asset_;
  std::set<int> accessorsBefore_;
  std::set<int> bufferViewsBefore_;
  std::vector<ViewBytes> newViewBytes_;  // data of bufferViews added by us
  std::size_t firstNewView_ = 0;
  std::vector<int> loadedViewOf_;  // after dropOrphans: the loaded (model) index of each old view
  std::vector<std::string> extensionsRemoved_;
  ProtectedFiles inputFiles_;                     // the input and what it uses, as loaded
  const ProtectedFiles* runFiles_ = nullptr;      // write()'s
  std::vector<std::filesystem::path> filesWritten_;
  std::filesystem::path outputPath_;               // write()'s output, as the caller spelled it
};

// Visits every place the document references an accessor / a bufferView by index.
void forEachAccessorRef(nlohmann::ordered_json& doc, const std::function<void(nlohmann::ordered_json&)>& visit);
void forEachBufferViewRef(nlohmann::ordered_json& doc, const std::function<void(nlohmann::ordered_json&)>& visit);

// Reads a whole file with one sized read into `out`; false where it cannot be opened or read.
bool readFileInto(const std::filesystem::path& path, std::vector<std::uint8_t>& out);

// Writes bytes (or pieces, one after another) to a temporary file beside `path`, then renames
// it over `path`.
void writeFileAtomic(const std::filesystem::path& path, std::span<const std::uint8_t> bytes);
void writeFileAtomic(const std::filesystem::path& path, const std::vector<std::span<const std::uint8_t>>& pieces);

// Files the document reads besides itself (external buffers and images), absolute.
std::vector<std::filesystem::path> referencedFiles(const Asset& asset);

}  // namespace tangent::gltf::detail
