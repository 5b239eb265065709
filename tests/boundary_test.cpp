// SPDX-License-Identifier: MIT
// Tests that sit on the edges a maintainer can move by accident (issue 42, item 1): the glTF
// index-type boundary, float identity in the weld, the documented vertex split order, each
// `check` limit just inside and just outside, asset-root containment, and the direction of
// morph-target TANGENT deltas. Every expected value comes from the glTF specification, the
// reference MikkTSpace's rule, the API documentation or a hand computation stated beside it,
// never from the library's own output.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "read/accessors.hpp"
#include "read/asset.hpp"
#include "support/run_command.hpp"
#include "support/skip_or_fail.hpp"
#include "support/temp_dir.hpp"
#include "tangent/check.hpp"
#include "tangent/gltf.hpp"
#include "tangent/tangent.hpp"
#include "read/uri.hpp"
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


// ---- (b) float identity in the weld ----
//
// The reference MikkTSpace (mikktspace.c, MergeVertsFast/MergeVertsSlow) takes two corners as
// one vertex when position, normal and UV compare equal as floats: `vP.x == vP2.x && ...`.
// So -0.0 and +0.0 are the same vertex, and a NaN is never equal to anything, itself (the same
// bits) included. The mesh: triangle A (0, 1, 2) and triangle B (3, 4, 5) on the edge
// P = (0, 0, 0), Q = (0, 1, 0), flat with normal +z, each with its own copy of P and Q.
// A maps u = x, v = y: dP/du = (1, 0, 0). B's third corner S = (-1, 0, 0) has UV (-1, 0.5):
// u = x, v = y - x / 2, so dP/du = (1, 1/2, 0), direction (2, 1, 0) / sqrt(5); both UV
// orientations are counter-clockwise (glTF w = -1). Welded, the corners at P and Q form one
// group with A and B (they share the edge P-Q); A's and B's angles are 90 deg at P and 45 deg at
// Q, equal weights, so every corner at P and Q gets normalize((1, 0, 0) + (2, 1, 0) / sqrt(5)).
// Not welded, each corner keeps its own triangle's direction.

struct WeldMesh {
  std::vector<float> positions{0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 0, 0, 1, 0, -1, 0, 0};
  std::vector<float> normals{0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
  std::vector<float> uvs{0, 0, 1, 0, 0, 1, 0, 0, 0, 1, -1, 0.5f};
  std::vector<std::uint32_t> indices{0, 1, 2, 3, 4, 5};
  tangent::MeshArrays arrays() const { return {positions, normals, uvs, indices}; }
};

std::vector<float> cornerTangentsOf(const WeldMesh& mesh) {
  std::vector<float> tangents(mesh.indices.size() * 4, std::nanf(""));
  tangent::computeCornerTangents(mesh.arrays(), tangents);
  return tangents;
}

const double kInvSqrt5 = 1.0 / std::sqrt(5.0);
const std::array<double, 3> kTangentA{1, 0, 0}, kTangentB{2 * kInvSqrt5, kInvSqrt5, 0};
std::array<double, 3> weldedTangent() {
  std::array<double, 3> sum{kTangentA[0] + kTangentB[0], kTangentA[1] + kTangentB[1], 0};
  const double length = std::hypot(sum[0], sum[1]);
  return {sum[0] / length, sum[1] / length, 0};
}

void expectTangent(const std::vector<float>& tangents, std::size_t corner, const std::array<double, 3>& expected, const std::string& what) {
  SCOPED_TRACE(what + ", corner " + std::to_string(corner));
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(tangents[4 * corner + i], expected[i], 1e-6) << "component " << i;
  EXPECT_EQ(tangents[4 * corner + 3], -1.0f);
}

// Corners 0, 2 (A at P, Q) and 3, 4 (B at P, Q).
void expectWelded(const std::vector<float>& t, const std::string& what) {
  for (std::size_t c : {0u, 2u, 3u, 4u}) expectTangent(t, c, weldedTangent(), what + " (welded)");
  expectTangent(t, 1, kTangentA, what);
  expectTangent(t, 5, kTangentB, what);
}
// Only Q's corners: P's copies carry a NaN normal there, replaced by the library (its tangent
// is not what this test is about).
void expectNotWeldedAtQ(const std::vector<float>& t, const std::string& what) {
  expectTangent(t, 2, kTangentA, what + " (A at Q, not welded)");
  expectTangent(t, 4, kTangentB, what + " (B at Q, not welded)");
}

TEST(WeldIdentity, SignedZerosWeldAsTheReferenceDoes) {
  {
    WeldMesh mesh;  // the copies identical: welded
    expectWelded(cornerTangentsOf(mesh), "identical copies");
  }
  {
    WeldMesh mesh;  // B's copies of P and Q at x = -0.0 (an exporter's seam): welded all the same
    mesh.positions[3 * 3] = -0.0f;
    mesh.positions[3 * 4] = -0.0f;
    expectWelded(cornerTangentsOf(mesh), "position x = -0.0");
  }
  {
    WeldMesh mesh;  // UV u = -0.0 on B's side of the seam, and a -0.0 normal component
    mesh.uvs[2 * 3] = -0.0f;
    mesh.uvs[2 * 4] = -0.0f;
    mesh.normals[3 * 3 + 1] = -0.0f;
    expectWelded(cornerTangentsOf(mesh), "u = -0.0, normal y = -0.0");
  }
  {
    WeldMesh mesh;  // a real difference (one ulp) does not weld: the test can tell the two apart
    mesh.uvs[2 * 4] = std::nextafter(0.0f, 1.0f);
    const auto t = cornerTangentsOf(mesh);
    expectTangent(t, 2, kTangentA, "one ulp apart at Q");
    expectTangent(t, 4, kTangentB, "one ulp apart at Q");
  }
}

TEST(WeldIdentity, NanNeverWeldsNotEvenWithTheSameBits) {
  for (const std::uint32_t payloadB : {0x7fc00000u, 0x7fc00001u, 0xffc00000u}) {
    WeldMesh mesh;
    mesh.normals[3 * 0] = std::bit_cast<float>(0x7fc00000u);  // A's copy of P
    mesh.normals[3 * 3] = std::bit_cast<float>(payloadB);     // B's copy of P
    char what[64];
    std::snprintf(what, sizeof what, "NaN normals 0x7fc00000 and 0x%08x", payloadB);
    const auto t = cornerTangentsOf(mesh);
    expectNotWeldedAtQ(t, what);
    for (float value : t) EXPECT_TRUE(std::isfinite(value)) << what;  // the documented promise
  }
}

#ifdef TANGENT_HAVE_REFERENCE_C
// The reference C itself on the same meshes: the hand-computed expectations above are what it
// computes (every corner of the signed-zero meshes; Q's corners of the NaN mesh).
TEST(WeldIdentity, ReferenceCAgreesWithTheHandComputedWeld) {
  auto referenceTangent = [](const WeldMesh& mesh, std::size_t corner) {
    const auto frames = tangent::testing::referenceCornerFrames(mesh.arrays());
    EXPECT_FALSE(frames.empty());
    std::array<double, 3> t{};
    if (frames.empty()) return t;
    for (int i = 0; i < 3; ++i) t[i] = frames[corner].tangent[i];
    return t;
  };
  auto near = [](const std::array<double, 3>& a, const std::array<double, 3>& b) {
    return std::abs(a[0] - b[0]) < 1e-5 && std::abs(a[1] - b[1]) < 1e-5 && std::abs(a[2] - b[2]) < 1e-5;
  };
  WeldMesh signedZero;
  signedZero.positions[3 * 3] = -0.0f;
  signedZero.positions[3 * 4] = -0.0f;
  signedZero.uvs[2 * 3] = -0.0f;
  signedZero.uvs[2 * 4] = -0.0f;
  for (std::size_t c : {0u, 2u, 3u, 4u}) EXPECT_TRUE(near(referenceTangent(signedZero, c), weldedTangent())) << "corner " << c;
  WeldMesh sameNan;
  sameNan.normals[3 * 0] = std::bit_cast<float>(0x7fc00000u);
  sameNan.normals[3 * 3] = std::bit_cast<float>(0x7fc00000u);
  EXPECT_TRUE(near(referenceTangent(sameNan, 2), kTangentA));
  EXPECT_TRUE(near(referenceTangent(sameNan, 4), kTangentB));
}
#endif

// ---- (c) the documented vertex split order ----

// Vertices in the z = 0 plane with the normal +z, added one at a time (the split-order tests).
struct PlaneVertices {
  std::vector<float> positions, normals, uvs;
  void add(float x, float y, float u, float v) {
    positions.insert(positions.end(), {x, y, 0});
    normals.insert(normals.end(), {0, 0, 1});
    uvs.insert(uvs.end(), {u, v});
  }
  std::uint32_t count() const { return static_cast<std::uint32_t>(positions.size() / 3); }
};

// tangent.hpp, CornerOutputs::cornerVertex: "Corners of input vertex v that got the same
// tangent bits as v's first corner (in corner order) keep vertex v; every other distinct
// tangent of v becomes a new vertex, numbered from the input vertex count up (in order of
// first corner)." The mesh: two flat stars whose triangles share only their centre, each
// triangle's UVs a rotation of (x, y) (UV orientation kept, glTF w = -1 everywhere), so each
// triangle's tangent is the rotation's dP/du:
//   vertices 0-4:  star 2, centre 0: triangles T3 = (0, 1, 2) with u = x (+x) and
//                  T4 = (0, 3, 4) with u = -x (-x);
//   vertices 5-11: star 1, centre 5: T0 = (5, 6, 7) u = x (+x), T1 = (5, 8, 9) u = -x (-x),
//                  T2 = (5, 10, 11) u = y (+y);
// triangles in the order T0, T1, T2, T3, T4 (corners 0-2, 3-5, 6-8, 9-11, 12-14).
// Vertex 5's corners are 0 (+x), 3 (-x), 6 (+y): corner 0 keeps 5; -x (first corner 3) and
// +y (first corner 6) are new. Vertex 0's corners are 9 (+x) and 12 (-x): corner 9 keeps 0;
// -x (first corner 12) is new. New vertices from 12 up in order of first corner: 3 -> 12,
// 6 -> 13, 12 -> 14. (Numbered by input vertex instead, vertex 0's copy would come first; by
// tangent value, +y before -x.)
TEST(SplitOrder, FirstCornerKeepsTheVertexAndNewOnesFollowInOrderOfFirstCorner) {
  PlaneVertices mesh;
  // Star 2 around (10, 0): T3 in the first quadrant (u = x, v = y), T4 in the third (u = -x, v = -y).
  mesh.add(10, 0, 0, 0);
  mesh.add(11, 0, 1, 0), mesh.add(10, 1, 0, 1);
  mesh.add(9, 0, 1, 0), mesh.add(10, -1, 0, 1);
  // Star 1 around the origin: T0 first quadrant (u = x, v = y), T1 third (u = -x, v = -y),
  // T2 fourth (u = y, v = -x: dP/du = +y).
  mesh.add(0, 0, 0, 0);
  mesh.add(1, 0, 1, 0), mesh.add(0, 1, 0, 1);
  mesh.add(-1, 0, 1, 0), mesh.add(0, -1, 0, 1);
  mesh.add(0, -1, -1, 0), mesh.add(1, 0, 0, -1);
  const std::vector<std::uint32_t> indices{5, 6, 7, 5, 8, 9, 5, 10, 11, 0, 1, 2, 0, 3, 4};
  std::vector<float> tangents(indices.size() * 4);
  std::vector<std::uint32_t> cornerVertex(indices.size(), 0xDEADBEEFu);  // garbage: untouched output shows
  tangent::TangentWorkspace workspace;
  const auto report = tangent::computeCornerTangents({mesh.positions, mesh.normals, mesh.uvs, indices}, {tangents, {}, cornerVertex}, {}, workspace);
  // The frames the order is built on, by hand (each triangle's own dP/du; no two share an edge).
  const std::array<std::array<float, 3>, 5> triangleTangent{{{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {1, 0, 0}, {-1, 0, 0}}};
  for (std::size_t c = 0; c < indices.size(); ++c) {
    for (int i = 0; i < 3; ++i) ASSERT_NEAR(tangents[4 * c + i], triangleTangent[c / 3][i], 1e-6) << "corner " << c;
    ASSERT_EQ(tangents[4 * c + 3], -1.0f) << "corner " << c;
  }
  EXPECT_EQ(report.splitVertices, 3u);
  EXPECT_EQ(report.outputVertices, 15u);
  const std::vector<std::uint32_t> expected{5, 6, 7, 12, 8, 9, 13, 10, 11, 0, 1, 2, 14, 3, 4};
  for (std::size_t c = 0; c < indices.size(); ++c) EXPECT_EQ(cornerVertex[c], expected[c]) << "corner " << c;
}

// The same rule inside one input vertex with the triangles in the other order: the first
// corner is now T2's (+y), so +y keeps vertex 5 and -x, +x follow in order of first corner.
TEST(SplitOrder, ReorderedTrianglesMoveWhichTangentKeepsTheVertex) {
  PlaneVertices mesh;
  mesh.add(0, 0, 0, 0);
  mesh.add(1, 0, 1, 0), mesh.add(0, 1, 0, 1);    // +x
  mesh.add(-1, 0, 1, 0), mesh.add(0, -1, 0, 1);  // -x
  mesh.add(0, -1, -1, 0), mesh.add(1, 0, 0, -1); // +y
  const std::vector<std::uint32_t> indices{0, 5, 6, 0, 3, 4, 0, 1, 2};  // +y, -x, +x
  std::vector<float> tangents(indices.size() * 4);
  std::vector<std::uint32_t> cornerVertex(indices.size(), 0xDEADBEEFu);
  tangent::TangentWorkspace workspace;
  tangent::computeCornerTangents({mesh.positions, mesh.normals, mesh.uvs, indices}, {tangents, {}, cornerVertex}, {}, workspace);
  const std::vector<std::uint32_t> expected{0, 5, 6, 7, 3, 4, 8, 1, 2};
  for (std::size_t c = 0; c < indices.size(); ++c) EXPECT_EQ(cornerVertex[c], expected[c]) << "corner " << c;
}

// The same rule for a vertex with few corners and with many (the split groups a bucket of up
// to 16 corners without a sort, a larger one with it): a fan of triangles that share only
// vertex 0, triangle k scaled by k + 1 (no two weld) and with the tangent +x, -x or +y in an
// order where the new ones by first corner (-x, +y) are not in the order of their bits (+y first).
TEST(SplitOrder, FewAndManyCornersOfAVertexFollowTheSameRule) {
  for (const std::size_t triangles : {5u, 16u, 17u, 40u}) {
    PlaneVertices mesh;
    mesh.add(0, 0, 0, 0);
    std::vector<std::uint32_t> indices;
    std::vector<int> direction;  // 0: +x, 1: -x, 2: +y
    for (std::size_t k = 0; k < triangles; ++k) {
      const float s = static_cast<float>(k + 1);
      const int d = static_cast<int>(k % 3);
      const auto first = mesh.count();
      if (d == 0) mesh.add(s, 0, s, 0), mesh.add(0, s, 0, s);         // u = x
      else if (d == 1) mesh.add(-s, 0, s, 0), mesh.add(0, -s, 0, s);  // u = -x
      else mesh.add(0, -s, -s, 0), mesh.add(s, 0, 0, -s);             // u = y
      indices.insert(indices.end(), {0, first, first + 1});
      direction.push_back(d);
    }
    const auto vertexCount = mesh.count();
    std::vector<float> tangents(indices.size() * 4);
    std::vector<std::uint32_t> cornerVertex(indices.size(), 0xDEADBEEFu);
    tangent::TangentWorkspace workspace;
    const auto report = tangent::computeCornerTangents({mesh.positions, mesh.normals, mesh.uvs, indices}, {tangents, {}, cornerVertex}, {}, workspace);
    // Vertex 0: its first corner's tangent keeps it, each other new one is numbered from the
    // vertex count up in order of first corner; every outer vertex has one corner and keeps it.
    std::array<std::uint32_t, 3> numberOf{~0u, ~0u, ~0u};
    numberOf[direction[0]] = 0;
    std::uint32_t next = vertexCount;
    for (std::size_t k = 0; k < triangles; ++k) {
      const int d = direction[k];
      const std::array<float, 3> expectedTangent = d == 0 ? std::array<float, 3>{1, 0, 0}
                                                   : d == 1 ? std::array<float, 3>{-1, 0, 0}
                                                            : std::array<float, 3>{0, 1, 0};
      for (int i = 0; i < 3; ++i) ASSERT_NEAR(tangents[4 * (3 * k) + i], expectedTangent[i], 1e-6) << triangles << " triangle " << k;
      if (numberOf[d] == ~0u) numberOf[d] = next++;
      EXPECT_EQ(cornerVertex[3 * k], numberOf[d]) << triangles << " triangles, corner " << 3 * k;
      EXPECT_EQ(cornerVertex[3 * k + 1], indices[3 * k + 1]);
      EXPECT_EQ(cornerVertex[3 * k + 2], indices[3 * k + 2]);
    }
    EXPECT_EQ(report.splitVertices, next - vertexCount) << triangles;
    EXPECT_EQ(report.splitVertices, 2u) << triangles;
  }
}


// ---- (d) each `check` limit, just inside and just outside, per component type ----
//
// docs/check.md, "Limits per component type": a normalized component decodes as c/127 (BYTE)
// or c/32767 (SHORT) and may be rounded to b significant bits first (SHORT: 10 accepted, BYTE:
// 8), so one component is off by at most 0.5/(2^(b-1)-1) plus half a storage step, the error
// vector by |e| <= sqrt(3) times that; `unit` accepts | |xyz| - 1 | <= |e| (float: 1e-3);
// `orthogonal` accepts the tolerance (1 deg) plus asin(|e|) of TANGENT and of NORMAL (float:
// 0); `reference` the same plus an allowance for rounded positions and UVs, 0 for float ones.
// The limits below are that formula, written out here; the stored vectors are searched for
// among the integers of each type so that their decoded value lies just inside and just
// outside it. The mesh is a flat quad (normal +z, u = x, v = y): the reference tangent is
// (1, 0, 0) with glTF w = -1.

enum class Stored { float32, normalizedShort, normalizedByte };
const char* nameOf(Stored s) { return s == Stored::float32 ? "float" : s == Stored::normalizedShort ? "SHORT" : "BYTE"; }
int maxOf(Stored s) { return s == Stored::normalizedShort ? 32767 : 127; }

double vectorErrorBound(Stored s) {  // |e|, from the documented formula
  switch (s) {
    case Stored::float32: return 0;
    case Stored::normalizedShort: return std::sqrt(3.0) * (0.5 / ((1 << (10 - 1)) - 1) + 0.5 / 32767);
    case Stored::normalizedByte: return std::sqrt(3.0) * (0.5 / ((1 << (8 - 1)) - 1));
  }
  return 0;
}
double unitLimit(Stored s) { return s == Stored::float32 ? 1e-3 : vectorErrorBound(s); }
double directionLimitDegrees(Stored s) { return std::asin(vectorErrorBound(s)) * 180 / M_PI; }
// Checked against the digits docs/check.md prints (1.72e-3, 0.0986 deg, 6.82e-3, 0.391 deg).
TEST(CheckLimits, TheFormulaGivesTheDocumentedTable) {
  EXPECT_NEAR(unitLimit(Stored::normalizedShort), 1.72e-3, 0.005e-3);
  EXPECT_NEAR(directionLimitDegrees(Stored::normalizedShort), 0.0986, 0.00005);
  EXPECT_NEAR(unitLimit(Stored::normalizedByte), 6.82e-3, 0.005e-3);
  EXPECT_NEAR(directionLimitDegrees(Stored::normalizedByte), 0.391, 0.0005);
}

struct Candidate {
  std::array<double, 3> stored{};   // float value, or the integers
  std::array<double, 3> decoded{};  // what a reader sees
};

Candidate decode(Stored s, std::array<double, 3> stored) {
  Candidate c{stored, stored};
  if (s != Stored::float32)
    for (double& x : c.decoded) x = std::max(x / maxOf(s), -1.0);
  return c;
}

// The candidates just inside and just outside `limit` of `measure`, among `vectors`.
std::pair<Candidate, Candidate> around(Stored s, double limit, const std::vector<std::array<double, 3>>& vectors,
                                       const std::function<double(const std::array<double, 3>&)>& measure) {
  Candidate inside, outside;
  double best = -1, worst = std::numeric_limits<double>::max();
  for (const auto& v : vectors) {
    const Candidate c = decode(s, v);
    const double m = measure(c.decoded);
    if (m <= limit && m > best) best = m, inside = c;
    if (m > limit && m < worst) worst = m, outside = c;
  }
  // Close enough to the limit that a limit 10% looser or tighter changes the verdict.
  EXPECT_GT(best, 0.9 * limit) << nameOf(s);
  EXPECT_LT(worst, 1.1 * limit) << nameOf(s);
  return {inside, outside};
}

double lengthOf(const std::array<double, 3>& v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }
double unitDeviation(const std::array<double, 3>& v) { return std::abs(lengthOf(v) - 1); }
double outOfPlaneDegrees(const std::array<double, 3>& v) { return std::asin(std::abs(v[2]) / lengthOf(v)) * 180 / M_PI; }
double inPlaneDegrees(const std::array<double, 3>& v) { return std::atan2(std::abs(v[1]), v[0]) * 180 / M_PI; }

// Integer vectors to search: near-unit ones, spread over the directions the measure needs.
std::vector<std::array<double, 3>> integerVectors(Stored s, int axis) {
  std::vector<std::array<double, 3>> out;
  const int m = maxOf(s);
  const int span = s == Stored::normalizedShort ? 1200 : 127;
  for (int a = m - (s == Stored::normalizedShort ? 120 : 20); a <= m; ++a)
    for (int b = 0; b <= span; ++b)
      for (int c = 0; c <= (s == Stored::normalizedByte ? 20 : 0); ++c) {
        std::array<double, 3> v{double(a), 0, 0};
        v[axis] = b;
        if (c) v[axis == 1 ? 2 : 1] = c;
        out.push_back(v);
      }
  return out;
}

std::vector<std::array<double, 3>> unitCandidates(Stored s) {
  if (s == Stored::float32) {
    std::vector<std::array<double, 3>> out;
    for (double d : {0.999e-3, 1.001e-3}) out.push_back({1 + d, 0, 0}), out.push_back({1 - d, 0, 0});
    return out;
  }
  std::vector<std::array<double, 3>> out = integerVectors(s, 1);
  const int m = maxOf(s);
  for (int a = m * 7 / 10; a <= m; ++a) out.push_back({double(a), double(a), 0});  // over-long diagonals
  return out;
}
std::vector<std::array<double, 3>> angleCandidates(Stored s, int axis, double limitDegrees) {
  if (s == Stored::float32) {
    std::vector<std::array<double, 3>> out;
    for (double d : {-0.01, 0.01}) {
      const double a = (limitDegrees + d) * M_PI / 180;
      std::array<double, 3> v{std::cos(a), 0, 0};
      v[axis] = std::sin(a);
      out.push_back(v);
    }
    return out;
  }
  return integerVectors(s, axis);
}

fs::path quadWithTangent(const fs::path& dir, Stored s, const std::array<double, 3>& stored, const std::string& name) {
  MeshSpec mesh;
  addVertex(mesh, 0, 0, 0, 0), addVertex(mesh, 1, 0, 1, 0), addVertex(mesh, 1, 1, 1, 1), addVertex(mesh, 0, 1, 0, 1);
  mesh.indices = {0, 1, 2, 0, 2, 3};
  mesh.indexComponentType = kUnsignedShort;
  if (s == Stored::float32) {
    std::vector<float> t;
    for (int v = 0; v < 4; ++v) t.insert(t.end(), {float(stored[0]), float(stored[1]), float(stored[2]), -1.0f});
    mesh.tangent = floats(t, "VEC4", 4);
  } else if (s == Stored::normalizedShort) {
    std::vector<std::int16_t> t;
    for (int v = 0; v < 4; ++v)
      t.insert(t.end(), {std::int16_t(stored[0]), std::int16_t(stored[1]), std::int16_t(stored[2]), std::int16_t(-32767)});
    mesh.tangent = integers(t, kShort, true, "VEC4", 4);
  } else {
    std::vector<std::int8_t> t;
    for (int v = 0; v < 4; ++v)
      t.insert(t.end(), {std::int8_t(stored[0]), std::int8_t(stored[1]), std::int8_t(stored[2]), std::int8_t(-127)});
    mesh.tangent = integers(t, kByte, true, "VEC4", 4);
  }
  return writeGltf(dir, name, mesh);
}

// Whether `check` finds nothing on the quad with this stored tangent (only it and the gates run).
bool passes(const fs::path& dir, Stored s, const Candidate& c, tangent::gltf::CheckId check, const std::string& name) {
  const fs::path file = quadWithTangent(dir, s, c.stored, name);
  tangent::gltf::CheckOptions options;
  options.enabled.reset();
  options.enabled.set(static_cast<std::size_t>(tangent::gltf::CheckId::present));
  options.enabled.set(static_cast<std::size_t>(tangent::gltf::CheckId::format));
  options.enabled.set(static_cast<std::size_t>(check));
  const auto result = tangent::gltf::checkFile(file, options);
  EXPECT_EQ(result.primitives.size(), 1u);
  if (result.primitives.empty()) return false;
  const auto& passed = result.primitives[0].passed;
  return std::find(passed.begin(), passed.end(), tangent::gltf::toString(check)) != passed.end() &&
         result.primitives[0].findings.empty();
}

std::string show(const Candidate& c) {
  char text[160];
  std::snprintf(text, sizeof text, "stored (%.9g, %.9g, %.9g) decoded (%.9g, %.9g, %.9g)", c.stored[0], c.stored[1], c.stored[2],
                c.decoded[0], c.decoded[1], c.decoded[2]);
  return text;
}

class CheckLimit : public ::testing::TestWithParam<Stored> {};

TEST_P(CheckLimit, UnitJustInsideAndJustOutside) {
  const Stored s = GetParam();
  TempDir dir;
  // Both sides of 1: too short and too long.
  for (const bool longer : {false, true}) {
    std::vector<std::array<double, 3>> side;
    for (const auto& v : unitCandidates(s)) {
      const double length = lengthOf(decode(s, v).decoded);
      if ((length > 1) == longer && length != 1) side.push_back(v);
    }
    const auto [inside, outside] = around(s, unitLimit(s), side, unitDeviation);
    EXPECT_TRUE(passes(dir.path(), s, inside, tangent::gltf::CheckId::unit, "in")) << nameOf(s) << " " << show(inside);
    EXPECT_FALSE(passes(dir.path(), s, outside, tangent::gltf::CheckId::unit, "out")) << nameOf(s) << " " << show(outside);
  }
}

TEST_P(CheckLimit, OrthogonalJustInsideAndJustOutside) {
  const Stored s = GetParam();
  const double limit = 1.0 + directionLimitDegrees(s);  // default tolerance 1 deg, float normal
  TempDir dir;
  const auto [inside, outside] = around(s, limit, angleCandidates(s, 2, limit), outOfPlaneDegrees);
  EXPECT_TRUE(passes(dir.path(), s, inside, tangent::gltf::CheckId::orthogonal, "in")) << nameOf(s) << " " << show(inside);
  EXPECT_FALSE(passes(dir.path(), s, outside, tangent::gltf::CheckId::orthogonal, "out")) << nameOf(s) << " " << show(outside);
}

TEST_P(CheckLimit, ReferenceJustInsideAndJustOutside) {
  const Stored s = GetParam();
  const double limit = 1.0 + directionLimitDegrees(s);  // float positions and UVs: no allowance
  TempDir dir;
  const auto [inside, outside] = around(s, limit, angleCandidates(s, 1, limit), inPlaneDegrees);
  EXPECT_TRUE(passes(dir.path(), s, inside, tangent::gltf::CheckId::reference, "in")) << nameOf(s) << " " << show(inside);
  EXPECT_FALSE(passes(dir.path(), s, outside, tangent::gltf::CheckId::reference, "out")) << nameOf(s) << " " << show(outside);
}

INSTANTIATE_TEST_SUITE_P(ComponentTypes, CheckLimit,
                         ::testing::Values(Stored::float32, Stored::normalizedShort, Stored::normalizedByte),
                         [](const ::testing::TestParamInfo<Stored>& param) { return std::string(nameOf(param.param)); });

// ---- (e) folder containment (the asset root) ----
//
// docs/security.md: a buffer URI "must ... stay inside the asset root after `..`,
// percent-encoding and symbolic links are resolved". Inside means below it as a path, by whole
// components: ../asset2/ is a sibling of asset/, not inside it, though its name starts with
// "asset"; names are compared as they are (Linux file names are case-sensitive).

TEST(Containment, IsInsideComparesWholeComponents) {
  using detail::isInside;
  EXPECT_TRUE(isInside("/x/asset/mesh.bin", "/x/asset"));
  EXPECT_TRUE(isInside("/x/asset/mesh.bin", "/x/asset/"));
  EXPECT_TRUE(isInside("/x/asset", "/x/asset"));
  EXPECT_TRUE(isInside("/x/asset/a/b", "/x/asset/"));
  EXPECT_FALSE(isInside("/x/asset2/mesh.bin", "/x/asset"));
  EXPECT_FALSE(isInside("/x/asset2/mesh.bin", "/x/asset/"));
  EXPECT_FALSE(isInside("/x/asset2", "/x/asset"));
  EXPECT_FALSE(isInside("/x/assetmesh.bin", "/x/asset"));
  EXPECT_FALSE(isInside("/x/Asset/mesh.bin", "/x/asset"));
  EXPECT_FALSE(isInside("/x", "/x/asset"));
}

MeshSpec smallQuad(const std::string& bufferUri) {
  MeshSpec mesh;
  addVertex(mesh, 0, 0, 0, 0), addVertex(mesh, 1, 0, 1, 0), addVertex(mesh, 1, 1, 1, 1), addVertex(mesh, 0, 1, 0, 1);
  mesh.indices = {0, 1, 2, 0, 2, 3};
  mesh.indexComponentType = kUnsignedShort;
  mesh.bufferUri = bufferUri;
  return mesh;
}

// Bakes and says whether it was refused; a refusal leaves no output.
bool refused(const fs::path& input, const fs::path& output, const fs::path& assetRoot = {}) {
  tangent::gltf::BakeOptions options;
  options.assetRoot = assetRoot;
  try {
    tangent::gltf::bakeFile(input, output, options);
  } catch (const tangent::gltf::InputError&) {
    EXPECT_FALSE(fs::exists(output));
    return true;
  }
  return false;
}

TEST(Containment, SiblingWhoseNameStartsWithTheAssetFolderIsOutside) {
  TempDir dir;
  fs::create_directories(dir / "asset");
  const fs::path input = writeGltf(dir / "asset", "scene", smallQuad("../asset2/mesh.bin"));
  ASSERT_TRUE(fs::exists(dir / "asset2" / "mesh.bin"));
  EXPECT_TRUE(refused(input, dir / "out" / "a.glb"));
  EXPECT_TRUE(refused(input, dir / "out" / "b.glb", dir / "asset"));
  EXPECT_TRUE(refused(input, dir / "out" / "c.glb", dir.path() / "asset/"));   // trailing separator
  EXPECT_TRUE(refused(input, dir / "out" / "d.glb", dir.path() / "asset//"));
  EXPECT_TRUE(refused(input, dir / "out" / "e.glb", dir.path() / "asset/."));
  // The control: the parent folder as the root contains both, and the same file bakes.
  EXPECT_FALSE(refused(input, dir / "out" / "f.glb", dir.path()));
  EXPECT_FALSE(refused(input, dir / "out" / "g.glb", dir.path() / ""));
}

TEST(Containment, TrailingSeparatorsAndDotSegmentsInsideAreAccepted) {
  TempDir dir;
  const fs::path input = writeGltf(dir / "asset", "scene", smallQuad("sub/../mesh.bin"));
  ASSERT_TRUE(fs::exists(dir / "asset" / "mesh.bin"));
  EXPECT_FALSE(refused(input, dir / "out" / "a.glb"));
  EXPECT_FALSE(refused(input, dir / "out" / "b.glb", dir.path() / "asset/"));
  EXPECT_FALSE(refused(input, dir / "out" / "c.glb", dir.path() / "asset//"));
}

TEST(Containment, OtherCaseIsAnotherFolder) {
  TempDir dir;
  const fs::path input = writeGltf(dir / "asset", "scene", smallQuad("../ASSET/mesh.bin"));
  ASSERT_TRUE(fs::exists(dir / "ASSET" / "mesh.bin"));
  if (fs::exists(dir / "asset" / "mesh.bin")) GTEST_SKIP() << "case-insensitive file system";
  EXPECT_TRUE(refused(input, dir / "out" / "a.glb"));
}

// `..` after a symbolic link: asset/link -> outside/deep, so asset/link/../mesh.bin is the
// file outside/mesh.bin for the file system. Nothing outside the root may be read: with no
// asset/mesh.bin there is nothing the URI may legally name, so the bake is refused.
TEST(Containment, DotDotAfterASymbolicLinkDoesNotReadOutside) {
  TempDir dir;
  fs::create_directories(dir / "outside" / "deep");
  fs::create_directories(dir / "asset");
  fs::create_directory_symlink(dir / "outside" / "deep", dir / "asset" / "link");
  const fs::path written = writeGltf(dir / "outside", "scene", smallQuad("mesh.bin"));
  auto doc = nlohmann::json::parse(std::ifstream(written));
  doc["buffers"][0]["uri"] = "link/../mesh.bin";
  const fs::path input = dir / "asset" / "scene.gltf";
  std::ofstream(input) << doc.dump();
  ASSERT_TRUE(fs::exists(dir / "asset" / "link" / ".." / "mesh.bin"));  // the file system's reading
  ASSERT_FALSE(fs::exists(dir / "asset" / "mesh.bin"));
  EXPECT_TRUE(refused(input, dir / "out" / "a.glb"));
  // A link leading out directly.
  fs::copy_file(dir / "outside" / "mesh.bin", dir / "outside" / "deep" / "mesh.bin");
  doc["buffers"][0]["uri"] = "link/mesh.bin";
  std::ofstream(dir / "asset" / "direct.gltf") << doc.dump();
  EXPECT_TRUE(refused(dir / "asset" / "direct.gltf", dir / "out" / "b.glb"));
  // The control: the same links with the outside folder inside a wider root are followed.
  EXPECT_FALSE(refused(dir / "asset" / "direct.gltf", dir / "out" / "c.glb", dir.path()));
}

// ---- (f) morph-target TANGENT deltas ----
//
// glTF 2.0, 3.7.2.2 (Morph Targets): a target's attribute is a displacement; the morphed
// TANGENT is base + sum of weight * delta, so delta = tangent of the morphed shape minus the
// base tangent. The base: a flat 3x3-vertex grid, normal +z, u = x, v = y: tangent (1, 0, 0),
// w = -1. The target rotates the whole grid by 60 deg about +y (R: x -> (cos, 0, -sin),
// z -> (sin, 0, cos)): POSITION delta R p - p, NORMAL delta R n - n. The morphed shape's
// tangent is R (1, 0, 0) = (cos 60, 0, -sin 60), so delta = (cos 60 - 1, 0, -sin 60) =
// (-1/2, 0, -sqrt(3)/2), of length 2 sin 30 = 1.
// At weight w the shape is (I + w (R - I)) p, still a plane with u = x, so its tangent is
// (I + w (R - I)) (1, 0, 0) normalized, which is base + w delta normalized: the direction is
// exact (a renderer normalizes), within float rounding of the stored values (1e-6 rad).
TEST(MorphTangents, RotatedPlaneDeltaIsMorphedMinusBase) {
  const double angle = 60 * M_PI / 180, c = std::cos(angle), s = std::sin(angle);
  MeshSpec mesh;
  std::vector<float> dp, dn;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      const float x = float(i), y = float(j);
      addVertex(mesh, x, y, x, y);
      dp.insert(dp.end(), {float(x * c - x), 0.0f, float(-x * s)});
      dn.insert(dn.end(), {float(s), 0.0f, float(c - 1)});
    }
  for (std::uint32_t j = 0; j < 2; ++j)
    for (std::uint32_t i = 0; i < 2; ++i) {
      const std::uint32_t a = 3 * j + i;
      mesh.indices.insert(mesh.indices.end(), {a, a + 1, a + 4, a, a + 4, a + 3});
    }
  mesh.indexComponentType = kUnsignedShort;
  mesh.targets.push_back({dp, dn});
  TempDir dir;
  const fs::path input = writeGltf(dir / "in", "morph", mesh);
  const auto result = tangent::gltf::bakeFile(input, dir / "out" / "morph.glb", {});
  ASSERT_EQ(result.primitives[0].action, tangent::gltf::PrimitiveAction::baked);
  const detail::Asset out = detail::loadAsset(dir / "out" / "morph.glb");
  const Json& primitive = out.json["meshes"][0]["primitives"][0];
  ASSERT_TRUE(primitive["targets"][0].contains("TANGENT"));
  const auto base = detail::toFloats(detail::readAccessor(out.model, primitive["attributes"]["TANGENT"].get<int>(), "TANGENT"));
  const auto delta = detail::toFloats(detail::readAccessor(out.model, primitive["targets"][0]["TANGENT"].get<int>(), "delta"));
  ASSERT_EQ(base.size(), 9u * 4);
  ASSERT_EQ(delta.size(), 9u * 3);
  for (std::size_t v = 0; v < 9; ++v) {
    SCOPED_TRACE("vertex " + std::to_string(v));
    EXPECT_NEAR(base[4 * v], 1, 1e-6);
    EXPECT_NEAR(base[4 * v + 1], 0, 1e-6);
    EXPECT_NEAR(base[4 * v + 2], 0, 1e-6);
    EXPECT_EQ(base[4 * v + 3], -1.0f);
    EXPECT_NEAR(delta[3 * v], c - 1, 1e-6);  // -0.5
    EXPECT_NEAR(delta[3 * v + 1], 0, 1e-6);
    EXPECT_NEAR(delta[3 * v + 2], -s, 1e-6);  // -0.866
    for (const double w : {0.0, 0.5, 1.0}) {
      std::array<double, 3> blended, analytic{1 + w * (c - 1), 0, -w * s};
      for (int i = 0; i < 3; ++i) blended[i] = base[4 * v + i] + w * delta[3 * v + i];
      const double la = lengthOf(analytic), lb = lengthOf(blended);
      double dot = 0;
      for (int i = 0; i < 3; ++i) dot += analytic[i] / la * blended[i] / lb;
      EXPECT_LT(std::acos(std::min(1.0, dot)), 1e-5) << "weight " << w;
      EXPECT_NEAR(lb, la, 1e-6) << "weight " << w;  // the very vector, not only its direction
    }
  }
}

}  // namespace
