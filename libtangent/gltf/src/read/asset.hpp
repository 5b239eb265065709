// SPDX-License-Identifier: MIT
// Loading an asset: the original JSON (kept for output, so nothing unmodelled is lost) and
// tinygltf's model (buffers and accessors for decoding). Images are never decoded.
#pragma once

#include <tiny_gltf.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <vector>

namespace tangent::gltf::detail {

struct Asset {
  std::filesystem::path path;   // the input file
  std::filesystem::path root;   // canonical folder its buffers and images must stay inside
  bool binary = false;          // GLB container
  bool fromMeshFile = false;    // converted from OBJ/PLY/OFF
  nlohmann::ordered_json json;  // the document as read
  tinygltf::Model model;
  std::vector<std::string> warnings;
};

std::string lowerExtension(const std::filesystem::path& path);  // ".GLB" -> ".glb"
bool isMeshFile(const std::filesystem::path& path);  // .obj, .ply, .off

// Throws InputError naming the file on anything unreadable or malformed. `assetRoot`: the
// folder buffer and image URIs may not leave (empty: the file's own folder).
Asset loadAsset(const std::filesystem::path& path, const std::filesystem::path& assetRoot = {});
// The same from bytes already read (`path` names the file and its folder in messages and for
// URIs); the fuzz targets call it.
Asset loadAssetBytes(std::vector<std::uint8_t> bytes, const std::filesystem::path& path,
                     const std::filesystem::path& assetRoot, bool fromMeshFile);

// OBJ/PLY/OFF read through OpenMesh, returned as an in-memory GLB (mesh_file.cpp).
std::vector<std::uint8_t> meshFileToGlb(const std::filesystem::path& path);

// The checks of a GLB's 20-byte header against the file's size (magic, version, total
// length, the JSON chunk inside the file and within kMaxJsonBytes); returns the JSON chunk's
// length. Throws InputError naming `label`.
std::uint64_t checkGlbHeader(std::span<const std::uint8_t> header, std::uint64_t fileBytes, const std::string& label);
// Parses a GLB container; returns the JSON chunk text and the BIN chunk (may be empty).
void splitGlb(std::span<const std::uint8_t> bytes, const std::string& label, std::string& json,
              std::span<const std::uint8_t>& bin);

// A GLB container as pieces to write one after another: headers and padding (kept in
// `frame`), the JSON chunk and the BIN chunk's bytes (pointing into json and binPieces, whose
// pieces are the chunk one after another).
std::vector<std::span<const std::uint8_t>> glbPieces(const std::string& json,
                                                     const std::vector<std::span<const std::uint8_t>>& binPieces,
                                                     std::vector<std::uint8_t>& frame);

// A GLB container in one block (the pieces joined).
std::vector<std::uint8_t> makeGlb(const std::string& json, std::span<const std::uint8_t> bin);

}  // namespace tangent::gltf::detail
