// SPDX-License-Identifier: MIT
// What a primitive is and needs, and reading the geometry tangents are computed from:
// shared by bake, check and info.
#pragma once

#include <nlohmann/json.hpp>

#include "read/accessors.hpp"
#include "read/asset.hpp"
#include "read/normals.hpp"
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace tangent::gltf::detail {

// A material feature that reads the tangent frame: the normal texture (glTF 2.0 3.9.3),
// KHR_materials_clearcoat's clearcoatNormalTexture, KHR_materials_anisotropy (its direction is
// given in the tangent frame, with or without a texture).
enum class FrameConsumer { normalTexture, clearcoatNormalTexture, anisotropy };
const char* toString(FrameConsumer consumer);  // "normalTexture", "clearcoatNormalTexture", "anisotropy"

struct ConsumerUse {
  FrameConsumer consumer = FrameConsumer::normalTexture;
  int texCoord = 0;                  // the UV set its texture samples (TEXCOORD_0 without a texture)
  bool texCoordFromTransform = false;  // KHR_texture_transform overrode texCoord
  bool sampled = false;              // it has a texture (anisotropy may have none)
};

struct PrimitiveNeeds {
  bool triangles = false;        // mode 4, 5 or 6
  // Some material feature reads the frame (consumers is not empty): a normal texture, a
  // clearcoat normal texture or anisotropy.
  bool hasNormalTexture = false;
  int texCoord = -1;             // UV set the first consumer samples, -1 when none
  bool texCoordFromTransform = false;  // KHR_texture_transform overrode texCoord
  std::string why;               // human-readable: why tangents are (not) needed
  // Every consumer, the one TANGENT follows first: the normal texture, else the clearcoat
  // normal texture, else anisotropy (the core spec computes tangents from the normal texture's
  // UV set; the extensions read the same TANGENT).
  std::vector<ConsumerUse> consumers;
  // "" or, where another consumer samples another UV set or through another
  // KHR_texture_transform (one TANGENT cannot serve both), which: a warning of bake and check.
  std::string otherFrames;
};

PrimitiveNeeds primitiveNeeds(const nlohmann::ordered_json& doc, const nlohmann::ordered_json& primitive, bool all);

// The KHR_texture_transform of the texture TANGENT follows (the first consumer's), or null:
// the UVs tangents are computed from are turned by it.
const nlohmann::ordered_json* frameTextureTransform(const nlohmann::ordered_json& doc, const nlohmann::ordered_json& primitive);

// The one rule for whether tangents are computed for a primitive: triangles and a UV set to
// bake from. bake computes them, check judges them, info says "needs tangents".
inline bool bakesTangents(const PrimitiveNeeds& needs) { return needs.triangles && needs.texCoord >= 0; }

// Why, as bake and info say it: needs.why, or for a mesh file (OBJ/PLY/OFF, `all` given to
// primitiveNeeds) that every mesh is baked.
std::string bakeReason(const PrimitiveNeeds& needs, bool fromMeshFile);

// The one rule for a normal texture on a UV set the primitive does not have (a broken file:
// bake and info refuse it, check reports a finding): what is wrong, or "" when nothing is.
std::string missingUvSet(const nlohmann::ordered_json& primitive, const PrimitiveNeeds& needs);
// Likewise for a primitive that needs tangents (triangles and a UV set to bake from) and has
// no POSITION: what is wrong, or "".
std::string missingPosition(const nlohmann::ordered_json& primitive, const PrimitiveNeeds& needs);

// The accessor type the spec gives an attribute semantic (POSITION and NORMAL VEC3,
// TEXCOORD_n VEC2, morph target deltas alike), or 0 where it leaves the type open or the
// stored-tangent checks judge it (TANGENT). verifyMeshData refuses any other type.
int requiredAttributeType(const std::string& semantic);

// Triangle list (3 vertex indices per triangle) from glTF modes 4, 5 and 6 (spec 3.7.2.1);
// stitching triangles of joined strips (a repeated index) draw nothing and are left out.
std::vector<std::uint32_t> triangleList(int mode, std::vector<std::uint32_t> vertices);

// What tangents of a primitive are computed from, as a string: two primitives with the same key
// get the same tangents, vertex split and rebuilt accessors, so bake and check compute them
// once and bake writes them once (CAD scenes draw one geometry in 1e4-1e5 primitives). The
// key holds every attribute and morph target accessor but TANGENT, the indices, the mode, the
// KHR_draco_mesh_compression object, the UV set and the normal texture's KHR_texture_transform;
// the material otherwise does not matter. The caller adds the options, which are per file.
std::string sameInputKey(const nlohmann::ordered_json& doc, const nlohmann::ordered_json& primitive, const PrimitiveNeeds& needs);
// sameInputKey without the indices and the mode: primitives with the same key draw from one
// vertex buffer, each with its own indices (the usual layout of CAD and architecture exporters:
// one buffer for a whole model, one indices accessor per part), so the vertex attributes are
// read once for all of them.
std::string sameVertexKey(const nlohmann::ordered_json& doc, const nlohmann::ordered_json& primitive, const PrimitiveNeeds& needs);

// Threads for computing a primitive of `corners` corners when `requested` were asked for (0:
// all): one below kCornersPerExtraThread, where starting a thread arena costs more than the
// work (a 2-triangle primitive took 100 us on two threads, 2 us on one). The core's output
// never depends on the count.
constexpr std::size_t kCornersPerExtraThread = 1 << 14;
unsigned threadsFor(std::size_t corners, unsigned requested);

// "mesh 0 'Name' primitive 1"
std::string primitiveLabel(const nlohmann::ordered_json& doc, int mesh, int primitive);

// The accessor index stored under `name`, or -1.
int accessorOf(const nlohmann::ordered_json& object, const std::string& name);

// A VEC2/VEC3 float-like accessor's values; checks type and, when expectedCount is not 0, count.
std::vector<float> readVectors(const tinygltf::Model& model, int accessor, int components, std::size_t expectedCount,
                               const std::string& where);

// KHR_texture_transform as a 2x3 column-major matrix: uv' = (m0 u + m2 v + m4, m1 u + m3 v + m5),
// T * R * S with R = [cos sin; -sin cos] (rows): the transpose of the GLSL listing in the
// extension's README, which rotates counter-clockwise in a v-up frame while glTF's v points
// down (KhronosGroup/glTF#1563, where Blender's importer and Babylon.js are reported to agree).
// The current Khronos Sample Viewer builds this same matrix. (TextureTransformTest, whose green
// marker shows the intended direction, is not in ../shared/assets, so not checked here.)
std::array<double, 6> textureTransformMatrix(const nlohmann::ordered_json& transform);

// KHR_texture_transform applied to UVs (textureTransformMatrix).
void applyTextureTransform(std::vector<float>& uvs, const nlohmann::ordered_json& transform);

struct PrimitiveGeometry {
  std::size_t vertexCount = 0;
  std::vector<float> positions;
  std::vector<float> normals;           // as glTF readers see them: normalized (unitNormals)
  NormalLengths normalLengths;          // what NORMAL stored, before unitNormals
  std::vector<float> uvs;               // as the normal texture samples them (transform applied)
  std::vector<std::uint32_t> corners;   // triangle list, 3 vertex indices per triangle
  int mode = 4;
  int indexComponentType = 5123;        // of the original indices (UNSIGNED_SHORT when none)
};

// POSITION, NORMAL (unitNormals applied) and the normal texture's UV set (needs.texCoord) of a
// primitive; throws InputError naming `where` and the accessor when one is missing or malformed.
// With normalOptional, a primitive without NORMAL gives empty normals instead (bake --normals).
PrimitiveGeometry readGeometry(const Asset& asset, const nlohmann::ordered_json& primitive, const PrimitiveNeeds& needs,
                               const std::string& where, bool normalOptional = false);
// readGeometry in two steps, for primitives that share a vertex buffer (sameVertexKey): the
// vertex attributes (corners left empty), read once for all of them...
PrimitiveGeometry readVertices(const Asset& asset, const nlohmann::ordered_json& primitive, const PrimitiveNeeds& needs,
                               const std::string& where, bool normalOptional = false);
// ...and each primitive's triangle list, mode and index component type, into `geometry`
// (whose vertexCount bounds the indices): time in the primitive's indices only.
void readCorners(const Asset& asset, const nlohmann::ordered_json& primitive, const std::string& where,
                 PrimitiveGeometry& geometry);

// The part of a shared vertex buffer one primitive draws: the vertices its corners use, in
// ascending order, and its corners renumbered into that list.
struct UsedVertices {
  std::vector<std::uint32_t> vertices;  // input vertex of each used vertex
  std::vector<std::uint32_t> corners;   // 3 per triangle, indices into `vertices`
};
inline constexpr std::uint32_t kNoSlot = 0xffffffffu;
// `slotOf` has an entry per vertex of the buffer, each kNoSlot on entry and again on return: one
// allocation for all the primitives of a buffer, so the time is in the corners, not the buffer.
UsedVertices usedVertices(const std::vector<std::uint32_t>& corners, std::vector<std::uint32_t>& slotOf);
// The used vertices' positions, normals and UVs, with the renumbered corners: a geometry of its
// own, whose vertex v is the buffer's vertex used.vertices[v] (mode and index type left to the
// caller).
PrimitiveGeometry gatherGeometry(const PrimitiveGeometry& buffer, const UsedVertices& used);
// The same in place, for the last part read from a buffer: `buffer` keeps only the used
// vertices (moved down in order, the arrays shortened) and takes the renumbered corners from
// `used`; equal, value for value, to what gatherGeometry gives, without a second copy.
void keepUsedVertices(PrimitiveGeometry& buffer, UsedVertices& used);

// Every mesh primitive's accessors against the bytes loaded (ranges, sparse targets, equal
// attribute counts, indices < vertex count), copying nothing: loadAsset runs it (after
// decoding compressed data, so compressed primitives are checked alike), so bake,
// check, info and the viewer refuse the same files. Throws InputError naming the accessor.
void verifyMeshData(const Asset& asset);

}  // namespace tangent::gltf::detail
