// SPDX-License-Identifier: MIT
// Compressed mesh data, decoded once at load so that every reader (bake, check, info, the
// viewer's scene) sees plain accessors: KHR_draco_mesh_compression (a primitive's attributes
// and indices in one Draco stream) and EXT_meshopt_compression (a bufferView's bytes in one
// meshopt stream, with a fallback buffer that may hold no data). Only tinygltf's model is
// changed; the document's JSON stays as read, so output keeps what bake does not rewrite.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include "read/asset.hpp"

namespace tangent::gltf::detail {

inline constexpr const char* kDracoExtension = "KHR_draco_mesh_compression";
inline constexpr const char* kMeshoptExtension = "EXT_meshopt_compression";

// Which compressions a primitive's data came through.
struct PrimitiveCompression {
  bool draco = false;    // the primitive has KHR_draco_mesh_compression
  bool meshopt = false;  // one of its accessors lies in an EXT_meshopt_compression bufferView
  bool any() const { return draco || meshopt; }
};

PrimitiveCompression primitiveCompression(const Asset& asset, const nlohmann::ordered_json& primitive);
// Extension names, in a fixed order (the strings info and reports show).
std::vector<std::string> compressionNames(const PrimitiveCompression& compression);

// A buffer tagged `extensions.EXT_meshopt_compression.fallback: true`.
bool isMeshoptFallbackBuffer(const nlohmann::ordered_json& buffer);

// The document tinygltf is given, where compressed data needs it: meshopt fallback buffers
// without a uri get a one-byte placeholder (tinygltf would look for a file), and Draco
// primitives lose "indices" in its copy (tinygltf refuses an index accessor without a
// bufferView; ours read the JSON's). Returns false when nothing needed changing.
bool adaptForLoader(nlohmann::ordered_json& doc);

// Decodes every EXT_meshopt_compression bufferView and every Draco primitive into tinygltf's
// model (new buffers appended; the views and accessors repointed at them). Throws InputError
// naming the file and the element ("bufferViews[3] EXT_meshopt_compression: ...",
// "meshes[0].primitives[1] KHR_draco_mesh_compression: ..."); files using
// KHR_meshopt_compression are refused by name.
void decodeCompressedData(Asset& asset);

// Per decoder (meshopt_decode.cpp, draco_decode.cpp).
void decodeMeshoptViews(Asset& asset);
void decodeDracoPrimitives(Asset& asset);

// After an edit: removes KHR_draco_mesh_compression / EXT_meshopt_compression from
// extensionsUsed and extensionsRequired when no primitive / bufferView uses it any more;
// returns the names removed.
std::vector<std::string> dropUnusedCompressionExtensions(nlohmann::ordered_json& doc);

}  // namespace tangent::gltf::detail
