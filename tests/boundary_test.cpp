// SPDX-License-Identifier: MIT
// Tests that sit on the edges a maintainer can move by accident (issue 42, item 1): the glTF
// index-type boundary, float identity in the weld, the documented vertex split order, each
// `check` limit just inside and just outside, asset-root containment, and the direction of
// morph-target TANGENT deltas. Every expected value comes from the glTF specification, the
// reference MikkTSpace's rule, the API documentation or a hand computation stated beside it,
// never from the library's own output.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "accessors.hpp"
#include "asset.hpp"
#include "support/run_command.hpp"
#include "support/skip_or_fail.hpp"
#include "support/temp_dir.hpp"
#include "tangent/check.hpp"
#include "tangent/gltf.hpp"
#include "tangent/tangent.hpp"
#include "uri.hpp"
#ifdef TANGENT_HAVE_REFERENCE_C
#include "support/mikktspace_c.hpp"
#endif

namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;
using tangent::testing::TempDir;
namespace detail = tangent::gltf::detail;

constexpr int kUnsignedByte = 5121, kUnsignedShort = 5123, kUnsignedInt = 5125, kFloat = 5126, kByte = 5120,
              kShort = 5122;

// ---- a minimal glTF writer: one primitive, one buffer file ----

struct StoredArray {
  int componentType = kFloat;
  bool normalized = false;
  std::string type;                 // "SCALAR", "VEC2", ...
  std::vector<std::uint8_t> bytes;  // tightly packed
  std::size_t count = 0;
};

StoredArray floats(const std::vector<float>& values, const std::string& type, int components) {
  StoredArray a{kFloat, false, type, {}, values.size() / components};
  a.bytes.resize(values.size() * 4);
  std::memcpy(a.bytes.data(), values.data(), a.bytes.size());
  return a;
}

template <typename T>
StoredArray integers(const std::vector<T>& values, int componentType, bool normalized, const std::string& type, int components) {
  StoredArray a{componentType, normalized, type, {}, values.size() / components};
  a.bytes.resize(values.size() * sizeof(T));
  std::memcpy(a.bytes.data(), values.data(), a.bytes.size());
  return a;
}

StoredArray indexArray(const std::vector<std::uint32_t>& indices, int componentType) {
  if (componentType == kUnsignedByte) return integers(std::vector<std::uint8_t>(indices.begin(), indices.end()), kUnsignedByte, false, "SCALAR", 1);
  if (componentType == kUnsignedShort) return integers(std::vector<std::uint16_t>(indices.begin(), indices.end()), kUnsignedShort, false, "SCALAR", 1);
  return integers(indices, kUnsignedInt, false, "SCALAR", 1);
}

struct MeshSpec {
  std::vector<float> positions, normals, uvs;
  std::vector<std::uint32_t> indices;
  int indexComponentType = 0;  // 0: no indices
  std::optional<StoredArray> tangent;
  std::vector<std::pair<std::vector<float>, std::vector<float>>> targets;  // POSITION, NORMAL deltas
  std::string bufferUri = "mesh.bin";  // relative to the .gltf
};

// Writes dir/name.gltf and its buffer at dir/spec.bufferUri.
fs::path writeGltf(const fs::path& dir, const std::string& name, const MeshSpec& spec) {
  std::vector<std::uint8_t> bin;
  Json accessors = Json::array(), views = Json::array();
  auto add = [&](const StoredArray& a, std::optional<int> target, bool minMax = false) {
    while (bin.size() % 4) bin.push_back(0);
    views.push_back({{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", a.bytes.size()}});
    if (target) views.back()["target"] = *target;
    bin.insert(bin.end(), a.bytes.begin(), a.bytes.end());
    Json accessor = {{"bufferView", views.size() - 1}, {"componentType", a.componentType}, {"count", a.count}, {"type", a.type}};
    if (a.normalized) accessor["normalized"] = true;
    if (minMax) {  // POSITION (float VEC3) needs min and max
      std::vector<float> lo(3, std::numeric_limits<float>::max()), hi(3, std::numeric_limits<float>::lowest());
      const auto* p = reinterpret_cast<const float*>(a.bytes.data());
      for (std::size_t i = 0; i < a.count * 3; ++i) lo[i % 3] = std::min(lo[i % 3], p[i]), hi[i % 3] = std::max(hi[i % 3], p[i]);
      accessor["min"] = lo;
      accessor["max"] = hi;
    }
    accessors.push_back(accessor);
    return static_cast<int>(accessors.size() - 1);
  };
  Json attributes;
  attributes["POSITION"] = add(floats(spec.positions, "VEC3", 3), 34962, true);
  attributes["NORMAL"] = add(floats(spec.normals, "VEC3", 3), 34962);
  attributes["TEXCOORD_0"] = add(floats(spec.uvs, "VEC2", 2), 34962);
  bool quantized = false;
  if (spec.tangent) {
    attributes["TANGENT"] = add(*spec.tangent, 34962);
    quantized = spec.tangent->componentType != kFloat;
  }
  Json primitive = {{"attributes", attributes}, {"material", 0}};
  if (spec.indexComponentType) primitive["indices"] = add(indexArray(spec.indices, spec.indexComponentType), 34963);
  if (!spec.targets.empty()) {
    Json targets = Json::array();
    for (const auto& [dp, dn] : spec.targets) {
      targets.push_back({{"POSITION", add(floats(dp, "VEC3", 3), 34962, true)}, {"NORMAL", add(floats(dn, "VEC3", 3), 34962)}});
    }
    primitive["targets"] = targets;
  }
  Json doc = {{"asset", {{"version", "2.0"}}},
              {"scene", 0},
              {"scenes", Json::array({{{"nodes", Json::array({0})}}})},
              {"nodes", Json::array({{{"mesh", 0}}})},
              {"meshes", Json::array({{{"primitives", Json::array({primitive})}}})},
              // A normal texture: bake and check treat the primitive as normal-mapped. The image
              // is never decoded; it is a data: URI of a 1x1 PNG.
              {"materials", Json::array({{{"normalTexture", {{"index", 0}}}}})},
              {"textures", Json::array({{{"source", 0}}})},
              {"images", Json::array({{{"uri", "data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR42mP8/5+hHgAHggJ/PchI7wAAAABJRU5ErkJggg=="}}})},
              {"accessors", accessors},
              {"bufferViews", views},
              {"buffers", Json::array({{{"uri", spec.bufferUri}, {"byteLength", bin.size()}}})}};
  if (!spec.targets.empty()) doc["meshes"][0]["weights"] = std::vector<float>(spec.targets.size(), 0.0f);
  if (quantized) {
    doc["extensionsUsed"] = Json::array({"KHR_mesh_quantization"});
    doc["extensionsRequired"] = Json::array({"KHR_mesh_quantization"});
  }
  fs::create_directories(dir);
  const fs::path binPath = (dir / spec.bufferUri).lexically_normal();
  fs::create_directories(binPath.parent_path());
  std::ofstream(binPath, std::ios::binary).write(reinterpret_cast<const char*>(bin.data()), static_cast<std::streamsize>(bin.size()));
  const fs::path gltf = dir / (name + ".gltf");
  std::ofstream(gltf) << doc.dump();
  return gltf;
}

// Appends a flat vertex (normal +z).
void addVertex(MeshSpec& mesh, float x, float y, float u, float v) {
  mesh.positions.insert(mesh.positions.end(), {x, y, 0.0f});
  mesh.normals.insert(mesh.normals.end(), {0.0f, 0.0f, 1.0f});
  mesh.uvs.insert(mesh.uvs.end(), {u, v});
}

// A flat strip of `count` vertices (count - 2 counter-clockwise triangles), u = x / 1000,
// v = y: every triangle has the same tangent (+x) and UV orientation, so nothing splits.
void addStrip(MeshSpec& mesh, std::uint32_t count) {
  const auto first = static_cast<std::uint32_t>(mesh.positions.size() / 3);
  for (std::uint32_t i = 0; i < count; ++i) {
    const float x = static_cast<float>(i / 2), y = static_cast<float>(i % 2);
    addVertex(mesh, x, y, x / 1000.0f, y);
  }
  for (std::uint32_t i = 0; i + 2 < count; ++i) {
    if (i % 2 == 0) mesh.indices.insert(mesh.indices.end(), {first + i, first + i + 2, first + i + 1});
    else mesh.indices.insert(mesh.indices.end(), {first + i, first + i + 1, first + i + 2});
  }
}

// Four vertices, two triangles on the shared edge (1, 2) with mirrored UVs: triangle A maps
// u = x (tangent +x, UV counter-clockwise), triangle B u = 2 - x (tangent -x, clockwise). The
// two corners of each shared vertex get different frames: exactly two split vertices.
void addMirroredPair(MeshSpec& mesh, float offsetY) {
  const auto first = static_cast<std::uint32_t>(mesh.positions.size() / 3);
  addVertex(mesh, 0, offsetY, 0, 0);      // 0
  addVertex(mesh, 1, offsetY, 1, 0);      // 1 (shared)
  addVertex(mesh, 1, offsetY + 1, 1, 1);  // 2 (shared)
  addVertex(mesh, 2, offsetY, 0, 0);      // 3: u = 2 - x
  mesh.indices.insert(mesh.indices.end(), {first, first + 1, first + 2, first + 1, first + 3, first + 2});
}

std::string validatorScript() { return (fs::path(TANGENT_SOURCE_DIR) / "tests" / "node" / "validate.mjs").string(); }
bool validatorInstalled() { return fs::is_directory(fs::path(TANGENT_SOURCE_DIR) / "tests" / "node" / "node_modules" / "gltf-validator"); }

// ---- (a) the index type where the glTF spec draws it ----
//
// glTF 2.0, 3.7.2.1 (Meshes / Overview): "indices ... MUST NOT contain the maximum possible
// value for the component type used (i.e., 255 for unsigned bytes, 65535 for unsigned short
// and 4294967295 for unsigned int)". So an output of n vertices, whose largest index is n - 1,
// keeps UNSIGNED_BYTE only up to n = 255 and UNSIGNED_SHORT only up to n = 65535; bake keeps
// the input's type where it fits (it never narrows) and widens it otherwise.

struct IndexCase {
  const char* name;
  int inputType;
  std::uint32_t outputVertices;
  bool split;  // the input has outputVertices - 2 vertices and one mirrored pair (2 splits)
  int expectedType;
};

int expectedIndexType(int inputType, std::uint32_t outputVertices) {
  // The rule above, written out: the widest value each type may hold is its maximum minus one.
  const std::uint32_t largestIndex = outputVertices - 1;
  if (inputType == kUnsignedByte && largestIndex <= 254) return kUnsignedByte;
  if (inputType != kUnsignedInt && largestIndex <= 65534) return kUnsignedShort;
  return kUnsignedInt;
}

void PrintTo(const IndexCase& c, std::ostream* out) { *out << c.name; }

class IndexBoundary : public ::testing::TestWithParam<IndexCase> {};

TEST_P(IndexBoundary, OutputIndexTypeFollowsTheRestartRuleAndValidates) {
  const IndexCase& c = GetParam();
  ASSERT_EQ(expectedIndexType(c.inputType, c.outputVertices), c.expectedType);  // the table agrees with the rule
  TempDir dir;
  MeshSpec mesh;
  if (c.split) {
    addStrip(mesh, c.outputVertices - 6);
    addMirroredPair(mesh, 10.0f);
  } else {
    addStrip(mesh, c.outputVertices);
  }
  mesh.indexComponentType = c.inputType;
  const fs::path input = writeGltf(dir / "in", c.name, mesh);
  const fs::path output = dir / "out" / (std::string(c.name) + ".glb");
  const auto result = tangent::gltf::bakeFile(input, output, {});
  ASSERT_EQ(result.primitives.size(), 1u);
  ASSERT_EQ(result.primitives[0].action, tangent::gltf::PrimitiveAction::baked);
  ASSERT_EQ(result.primitives[0].verticesOut, c.outputVertices);
  ASSERT_EQ(result.primitives[0].tangents.splitVertices, c.split ? 2u : 0u);

  const detail::Asset out = detail::loadAsset(output);
  const Json& primitive = out.json["meshes"][0]["primitives"][0];
  const int indices = primitive["indices"].get<int>();
  EXPECT_EQ(out.json["accessors"][indices]["componentType"].get<int>(), c.expectedType);
  const auto data = detail::readAccessor(out.model, indices, "indices");
  std::uint32_t largest = 0;
  for (std::size_t i = 0; i < data.count; ++i) {
    std::uint32_t value = 0;
    std::memcpy(&value, &data.bytes[i * data.componentSize], data.componentSize);  // little-endian
    largest = std::max(largest, value);
  }
  EXPECT_EQ(largest, c.outputVertices - 1);  // the boundary is reached, not only approached

  if (!validatorInstalled()) TANGENT_SKIP_OR_FAIL("tests/node/node_modules/gltf-validator is absent (scripts/test.sh runs npm ci)");
  const auto validated = tangent::testing::runCommand("node '" + validatorScript() + "' '" + output.string() + "'");
  EXPECT_EQ(validated.exitCode, 0) << validated.output;
}

INSTANTIATE_TEST_SUITE_P(
    Boundaries, IndexBoundary,
    ::testing::Values(IndexCase{"byte_255_unsplit", kUnsignedByte, 255, false, kUnsignedByte},
                      IndexCase{"byte_253_plus_2_is_255", kUnsignedByte, 255, true, kUnsignedByte},
                      IndexCase{"byte_254_plus_2_is_256", kUnsignedByte, 256, true, kUnsignedShort},
                      IndexCase{"short_256_unsplit", kUnsignedShort, 256, false, kUnsignedShort},
                      IndexCase{"short_65535_unsplit", kUnsignedShort, 65535, false, kUnsignedShort},
                      IndexCase{"short_65533_plus_2_is_65535", kUnsignedShort, 65535, true, kUnsignedShort},
                      IndexCase{"short_65534_plus_2_is_65536", kUnsignedShort, 65536, true, kUnsignedInt},
                      IndexCase{"int_65536_unsplit", kUnsignedInt, 65536, false, kUnsignedInt}),
    [](const ::testing::TestParamInfo<IndexCase>& param) { return std::string(param.param.name); });

}  // namespace
