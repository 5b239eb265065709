// SPDX-License-Identifier: MIT
// glTF adapter: round trip of every attribute of every corner, JSON kept outside the touched
// accessors, accessor forms, splitting, UV-set choice, and the shared sample assets.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <random>
#include <set>
#include <span>
#include <string>

#include "read/accessors.hpp"
#include "read/asset.hpp"
#include "write/document.hpp"
#include "read/primitive.hpp"
#include "support/reference.hpp"
#include "support/skip_or_fail.hpp"
#include "support/temp_dir.hpp"
#include "support/test_assets.hpp"
#include "tangent/gltf.hpp"

namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;
using tangent::gltf::detail::Asset;
using tangent::gltf::detail::loadAsset;
using tangent::gltf::detail::readAccessor;
using tangent::testing::TempDir;

std::vector<std::uint32_t> cornersOf(const Asset& asset, const Json& primitive) {
  const std::size_t vertexCount = asset.model.accessors[primitive["attributes"]["POSITION"].get<int>()].count;
  std::vector<std::uint32_t> sequence;
  if (primitive.contains("indices")) {
    sequence = tangent::gltf::detail::toIndices(readAccessor(asset.model, primitive["indices"].get<int>(), "indices"), vertexCount, "indices");
  } else {
    for (std::uint32_t i = 0; i < vertexCount; ++i) sequence.push_back(i);
  }
  return tangent::gltf::detail::triangleList(primitive.value("mode", 4), sequence);
}

// Every attribute (and morph-target attribute) of every corner has the same bytes.
void expectSameCorners(const Asset& in, const Json& inPrimitive, const Asset& out, const Json& outPrimitive, const std::string& label) {
  const auto inCorners = cornersOf(in, inPrimitive);
  const auto outCorners = cornersOf(out, outPrimitive);
  ASSERT_EQ(inCorners.size(), outCorners.size()) << label;
  auto compare = [&](const Json& inAttributes, const Json& outAttributes, const std::string& where) {
    for (auto& [name, ref] : inAttributes.items()) {
      if (name == "TANGENT" && outAttributes.contains("TANGENT") && ref != outAttributes["TANGENT"]) continue;  // recomputed
      ASSERT_TRUE(outAttributes.contains(name)) << where << " lost " << name;
      const auto a = readAccessor(in.model, ref.get<int>(), name);
      const auto b = readAccessor(out.model, outAttributes[name].get<int>(), name);
      ASSERT_EQ(a.componentType, b.componentType) << where << " " << name;
      ASSERT_EQ(a.type, b.type) << where << " " << name;
      ASSERT_EQ(a.normalized, b.normalized) << where << " " << name;
      const std::size_t size = a.elementSize();
      // Every corner's vertex inside both accessors (an attribute left at the input's count
      // after a split would otherwise be read past its end).
      const std::uint32_t inLast = *std::max_element(inCorners.begin(), inCorners.end());
      const std::uint32_t outLast = *std::max_element(outCorners.begin(), outCorners.end());
      ASSERT_LE((std::size_t(inLast) + 1) * size, a.bytes.size()) << where << " " << name;
      ASSERT_LE((std::size_t(outLast) + 1) * size, b.bytes.size()) << where << " " << name << " has too few elements";
      for (std::size_t c = 0; c < inCorners.size(); ++c) {
        ASSERT_EQ(0, std::memcmp(&a.bytes[inCorners[c] * size], &b.bytes[outCorners[c] * size], size))
            << where << " " << name << " corner " << c;
      }
    }
  };
  compare(inPrimitive["attributes"], outPrimitive["attributes"], label);
  if (inPrimitive.contains("targets")) {
    for (std::size_t t = 0; t < inPrimitive["targets"].size(); ++t)
      compare(inPrimitive["targets"][t], outPrimitive["targets"][t], label + " target " + std::to_string(t));
  }
}

std::string bytesKey(const std::vector<std::uint8_t>& bytes) {
  return std::to_string(bytes.size()) + ":" + std::to_string(std::hash<std::string_view>{}(
                                                  std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size())));
}

// The document with accessor and bufferView references replaced by their content, storage
// arrays removed, and baked primitives reduced to their attribute names.
// `generatedNormals`: baked primitives that had no NORMAL, whose generated one is left out too.
Json canonical(const Asset& asset, const std::vector<std::pair<int, int>>& touched,
               const std::vector<std::pair<int, int>>& generatedNormals = {}) {
  Json doc = asset.json;
  for (auto [m, p] : touched) {
    Json& primitive = doc["meshes"][m]["primitives"][p];
    const bool generated = std::find(generatedNormals.begin(), generatedNormals.end(), std::pair{m, p}) != generatedNormals.end();
    auto namesOnly = [&](Json& attributes) {
      attributes.erase("TANGENT");  // written by the bake (an input TANGENT check fails is replaced)
      if (generated) attributes.erase("NORMAL");
      for (auto& [name, ref] : attributes.items()) ref = nullptr;
    };
    namesOnly(primitive["attributes"]);
    if (primitive.contains("targets"))
      for (auto& target : primitive["targets"]) namesOnly(target);
    primitive.erase("indices");
    primitive.erase("mode");
  }
  tangent::gltf::detail::forEachAccessorRef(doc, [&](Json& ref) {
    const int index = ref.get<int>();
    const auto data = readAccessor(asset.model, index, "accessor");
    ref = "accessor " + std::to_string(data.componentType) + "/" + std::to_string(data.type) + "/" + bytesKey(data.bytes);
  });
  if (doc.contains("images")) {
    for (auto& image : doc["images"]) {
      if (!image.contains("bufferView")) continue;
      const auto& view = asset.model.bufferViews[image["bufferView"].get<int>()];
      const auto& buffer = asset.model.buffers[view.buffer].data;
      image["bufferView"] = bytesKey(std::vector<std::uint8_t>(buffer.begin() + view.byteOffset, buffer.begin() + view.byteOffset + view.byteLength));
    }
  }
  doc.erase("accessors");
  doc.erase("bufferViews");
  doc.erase("buffers");
  return doc;
}

struct BakeCase {
  tangent::testing::TestAsset asset;
  bool glb;
};

class RoundTrip : public ::testing::TestWithParam<int> {};

TEST_P(RoundTrip, EveryCornerAndAllOtherJsonKept) {
  const auto assets = tangent::testing::makeTestAssets();
  for (const auto& testAsset : {assets[static_cast<std::size_t>(GetParam())]}) {
    for (bool glb : {false, true}) {
      SCOPED_TRACE(testAsset.name + (glb ? ".glb" : ".gltf"));
      TempDir dir;
      const fs::path input = tangent::testing::writeAsset(testAsset, dir / "in", glb);
      const fs::path output = dir / "out" / input.filename();
      const tangent::gltf::BakeResult result = tangent::gltf::bakeFile(input, output, {});
      const Asset in = loadAsset(input);
      const Asset out = loadAsset(output);
      std::vector<std::pair<int, int>> touched, generatedNormals;
      for (const auto& p : result.primitives) {
        if (p.action == tangent::gltf::PrimitiveAction::baked) touched.emplace_back(p.mesh, p.primitive);
        if (p.normalsGenerated) generatedNormals.emplace_back(p.mesh, p.primitive);
      }
      ASSERT_FALSE(touched.empty());
      for (const auto& p : result.primitives) {
        const Json& inPrimitive = in.json["meshes"][p.mesh]["primitives"][p.primitive];
        const Json& outPrimitive = out.json["meshes"][p.mesh]["primitives"][p.primitive];
        if (p.action != tangent::gltf::PrimitiveAction::baked) continue;
        ASSERT_TRUE(outPrimitive["attributes"].contains("TANGENT"));
        expectSameCorners(in, inPrimitive, out, outPrimitive, "mesh " + std::to_string(p.mesh) + " primitive " + std::to_string(p.primitive));
        const auto tangents = tangent::gltf::detail::toFloats(readAccessor(out.model, outPrimitive["attributes"]["TANGENT"].get<int>(), "TANGENT"));
        EXPECT_EQ(tangents.size(), 4 * p.verticesOut);
        for (std::size_t v = 0; v < p.verticesOut; ++v) {
          const float* t = &tangents[4 * v];
          ASSERT_NEAR(std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]), 1.0f, 1e-6);
          ASSERT_TRUE(t[3] == 1.0f || t[3] == -1.0f);
        }
      }
      EXPECT_EQ(canonical(in, touched), canonical(out, touched, generatedNormals));
      EXPECT_EQ(out.json["buffers"].size(), 1u);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(GeneratedAssets, RoundTrip, ::testing::Range(0, static_cast<int>(tangent::testing::makeTestAssets().size())),
                         [](const ::testing::TestParamInfo<int>& param) {
                           return tangent::testing::makeTestAssets()[static_cast<std::size_t>(param.param)].name;
                         });

const tangent::testing::TestAsset& assetNamed(const std::vector<tangent::testing::TestAsset>& all, const std::string& name) {
  return *std::find_if(all.begin(), all.end(), [&](const auto& a) { return a.name == name; });
}

tangent::gltf::BakeResult bakeGenerated(const std::string& name, const TempDir& dir, Asset& out, bool glb = true) {
  const auto all = tangent::testing::makeTestAssets();
  const fs::path input = tangent::testing::writeAsset(assetNamed(all, name), dir / "in", glb);
  const fs::path output = dir / "out" / input.filename();
  auto result = tangent::gltf::bakeFile(input, output, {});
  out = loadAsset(output);
  return result;
}

TEST(Bake, MirroredColumnsSplitAndIndicesWiden) {
  TempDir dir;
  Asset out;
  const auto result = bakeGenerated("many_splits", dir, out);
  ASSERT_EQ(result.primitives[0].action, tangent::gltf::PrimitiveAction::baked);
  EXPECT_EQ(result.primitives[0].verticesIn, 201u * 301u);
  EXPECT_EQ(result.primitives[0].verticesOut, 201u * 301u + 199u * 301u);  // every interior column splits
  EXPECT_EQ(result.primitives[0].tangents.splitVertices, 199u * 301u);
  const int indices = out.json["meshes"][0]["primitives"][0]["indices"].get<int>();
  EXPECT_EQ(out.json["accessors"][indices]["componentType"], 5125);
}

TEST(Bake, SmallIndexTypeKeptWhenItFits) {
  TempDir dir;
  Asset out;
  bakeGenerated("interleaved_ubyte", dir, out);
  const int indices = out.json["meshes"][0]["primitives"][0]["indices"].get<int>();
  EXPECT_EQ(out.json["accessors"][indices]["componentType"], 5121);
}

TEST(Bake, QuantizedAttributesStayQuantizedAndAligned) {
  TempDir dir;
  Asset out;
  bakeGenerated("quantized", dir, out);
  const Json& attributes = out.json["meshes"][0]["primitives"][0]["attributes"];
  EXPECT_EQ(out.json["accessors"][attributes["POSITION"].get<int>()]["componentType"], 5122);
  EXPECT_EQ(out.json["accessors"][attributes["NORMAL"].get<int>()]["normalized"], true);
  const int view = out.json["accessors"][attributes["POSITION"].get<int>()]["bufferView"].get<int>();
  EXPECT_EQ(out.json["bufferViews"][view]["byteStride"], 8);
  EXPECT_EQ(out.json["extensionsRequired"], Json::array({"KHR_mesh_quantization"}));
}

TEST(Bake, NormalTextureUvSetAndTextureTransformChooseTheFrame) {
  TempDir dir;
  Asset out;
  const auto result = bakeGenerated("second_uv_set", dir, out);
  ASSERT_EQ(result.primitives[0].texCoord, 1);
  ASSERT_EQ(result.primitives[1].texCoord, 1);  // KHR_texture_transform overrides texCoord 0
  auto firstTangent = [&](int primitive) {
    const Json& p = out.json["meshes"][0]["primitives"][primitive];
    return tangent::gltf::detail::toFloats(readAccessor(out.model, p["attributes"]["TANGENT"].get<int>(), "TANGENT"));
  };
  const auto plain = firstTangent(0);
  const auto rotated = firstTangent(1);
  // The grid is flat (normal +z). TEXCOORD_1 is (u, v) = (x, 1 - y): dP/du = +x, and with v
  // running down (glTF) the frame is right-handed, w = +1 (TEXCOORD_0 is turned 90 degrees
  // and would give y).
  // The transform (rotation r = 0.5, scale 2) maps uv to u' = 2 (cos r u + sin r v),
  // v' = 2 (-sin r u + cos r v) (as three.js's setUvTransform does). With u = x, v = 1 - y:
  // d(u', v')/d(x, y) = 2 [cos r, -sin r; -sin r, -cos r], whose inverse has the first column
  // d(x, y)/du' = (cos r, -sin r) / 2: the tangent turns by -r about the normal, and the
  // transform's determinant (+4) keeps w.
  ASSERT_EQ(plain.size(), rotated.size());
  const double r = 0.5;
  for (std::size_t v = 0; v < plain.size() / 4; ++v) {
    SCOPED_TRACE("vertex " + std::to_string(v));
    EXPECT_NEAR(plain[4 * v], 1.0, 1e-6);
    EXPECT_NEAR(plain[4 * v + 1], 0.0, 1e-6);
    EXPECT_NEAR(plain[4 * v + 2], 0.0, 1e-6);
    EXPECT_EQ(plain[4 * v + 3], 1.0f);
    const float* t = &rotated[4 * v];
    // Signed angle from the plain frame to the rotated one about +z.
    const double signedAngle = std::atan2(plain[4 * v] * t[1] - plain[4 * v + 1] * t[0],
                                          plain[4 * v] * t[0] + plain[4 * v + 1] * t[1]);
    EXPECT_NEAR(signedAngle, -r, 1e-4);
    EXPECT_NEAR(t[0], std::cos(r), 1e-4);
    EXPECT_NEAR(t[1], -std::sin(r), 1e-4);
    EXPECT_NEAR(t[2], 0.0, 1e-6);
    EXPECT_EQ(t[3], 1.0f);
  }
}

// A target's TANGENT deltas are the tangents of the morphed shape (the target at weight 1)
// minus the base ones (docs/cli.md). The expected deltas come from the reference MikkTSpace
// (npm mikktspace, tests/support/reference.hpp) run on the base shape and on each morphed
// shape, corner by corner, the morphed normals normalized first (the reference projects with
// the normal as given, "is normalized already" in mikktspace.c; ours projects onto the plane
// of the raw normal, the same plane). The asset's targets shear the grid (z += 0.2 (t + 1) x)
// and tilt its normals by -0.1 (t + 1) in x. Ours and the reference agree within 0.01 deg per
// tangent (mikktspace_test.cpp), so a delta within 2 sin(0.01 deg) < 4e-4.
TEST(Bake, MorphTargetsGetTangentDeltas) {
  TempDir dir;
  Asset out;
  bakeGenerated("morph_targets", dir, out);
  const Json& primitive = out.json["meshes"][0]["primitives"][0];
  ASSERT_EQ(primitive["targets"].size(), 2u);
  auto floatsOf = [&](const Json& attributes, const char* name) {
    return tangent::gltf::detail::toFloats(readAccessor(out.model, attributes[name].get<int>(), name));
  };
  const auto positions = floatsOf(primitive["attributes"], "POSITION"), normals = floatsOf(primitive["attributes"], "NORMAL"),
             uvs = floatsOf(primitive["attributes"], "TEXCOORD_0");
  const auto corners = cornersOf(out, primitive);
  std::vector<tangent::testing::CornerArrays> shapes{tangent::testing::deindex("base", {positions, normals, uvs, corners})};
  for (std::size_t t = 0; t < 2; ++t) {
    const Json& target = primitive["targets"][t];
    ASSERT_TRUE(target.contains("TANGENT"));
    EXPECT_EQ(out.json["accessors"][target["TANGENT"].get<int>()]["type"], "VEC3");
    auto morphedPositions = positions, morphedNormals = normals;
    const auto dp = floatsOf(target, "POSITION"), dn = floatsOf(target, "NORMAL");
    for (std::size_t i = 0; i < positions.size(); ++i) morphedPositions[i] += dp[i], morphedNormals[i] += dn[i];
    for (std::size_t v = 0; v < morphedNormals.size() / 3; ++v) {
      float* n = &morphedNormals[3 * v];
      const float length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      for (int i = 0; i < 3; ++i) n[i] /= length;
    }
    shapes.push_back(tangent::testing::deindex("target " + std::to_string(t), {morphedPositions, morphedNormals, uvs, corners}));
  }
  const auto reference = tangent::testing::referenceTangents(shapes);
  ASSERT_EQ(reference.size(), 3u);
  for (std::size_t t = 0; t < 2; ++t) {
    SCOPED_TRACE("target " + std::to_string(t));
    const auto deltas = floatsOf(primitive["targets"][t], "TANGENT");
    double largest = 0;
    for (std::size_t c = 0; c < corners.size(); ++c) {
      for (int i = 0; i < 3; ++i) {
        const double expected = double(reference[t + 1][4 * c + i]) - reference[0][4 * c + i];
        ASSERT_NEAR(deltas[3 * corners[c] + i], expected, 4e-4) << "corner " << c << " component " << i;
        largest = std::max(largest, std::abs(expected));
      }
    }
    EXPECT_GT(largest, 0.05);  // the shape really changes the frame: the comparison is not vacuous
  }
  EXPECT_EQ(out.json["meshes"][0]["weights"], Json::array({0.5, 0.0}));
}

TEST(Bake, PrimitivesThatNeedNothingAreLeftAlone) {
  TempDir dir;
  Asset out;
  const auto result = bakeGenerated("document_features", dir, out);
  ASSERT_EQ(result.primitives.size(), 5u);
  EXPECT_EQ(result.primitives[0].action, tangent::gltf::PrimitiveAction::baked);
  EXPECT_EQ(result.primitives[1].action, tangent::gltf::PrimitiveAction::skipped);  // no normal texture
  EXPECT_EQ(result.primitives[2].action, tangent::gltf::PrimitiveAction::skipped);  // points
  // No NORMAL: flat normals generated and written (glTF 2.0 3.7.2.1), tangents from them;
  // --normals keep leaves it as it is.
  EXPECT_EQ(result.primitives[3].action, tangent::gltf::PrimitiveAction::baked);
  EXPECT_EQ(result.primitives[3].normalsGenerated, tangent::gltf::NormalsMode::flat);
  EXPECT_TRUE(out.json["meshes"][0]["primitives"][3]["attributes"].contains("NORMAL"));
  {
    const auto all = tangent::testing::makeTestAssets();
    const fs::path input = tangent::testing::writeAsset(assetNamed(all, "document_features"), dir / "keep-in", true);
    tangent::gltf::BakeOptions keep;
    keep.normals = tangent::gltf::NormalsMode::keep;
    const auto kept = tangent::gltf::bakeFile(input, dir / "keep.glb", keep);
    EXPECT_EQ(kept.primitives[3].action, tangent::gltf::PrimitiveAction::skipped);
    EXPECT_NE(kept.primitives[3].reason.find("NORMAL"), std::string::npos);
  }
  // Its supplied TANGENT, constant +x on a curved sheet, is unit with w = +-1 but leaves the
  // tangent plane: check fails it, so bake replaces it and says which checks failed.
  EXPECT_EQ(result.primitives[4].action, tangent::gltf::PrimitiveAction::baked);
  EXPECT_EQ(result.primitives[4].failedChecks, (std::vector<std::string>{"orthogonal", "reference"}));
  EXPECT_EQ(result.primitives[4].reason.rfind("existing TANGENT fails tangent check (orthogonal: ", 0), 0u) << result.primitives[4].reason;
  const Json& primitives = out.json["meshes"][0]["primitives"];
  EXPECT_FALSE(primitives[1]["attributes"].contains("TANGENT"));
  EXPECT_FALSE(primitives[2]["attributes"].contains("TANGENT"));
  EXPECT_EQ(primitives[0]["extras"]["primitiveNote"], "keep me");
}

TEST(Bake, OverwriteRecomputesValidTangents) {
  TempDir dir;
  const auto all = tangent::testing::makeTestAssets();
  const fs::path input = tangent::testing::writeAsset(assetNamed(all, "document_features"), dir / "in", true);
  tangent::gltf::bakeFile(input, dir / "once.glb", {});
  // A second bake keeps what the first wrote (check passes it) unless --overwrite.
  EXPECT_EQ(tangent::gltf::bakeFile(dir / "once.glb", dir / "twice.glb", {}).primitives[0].action, tangent::gltf::PrimitiveAction::kept);
  tangent::gltf::BakeOptions options;
  options.overwrite = true;
  const auto result = tangent::gltf::bakeFile(dir / "once.glb", dir / "out.glb", options);
  EXPECT_EQ(result.primitives[0].action, tangent::gltf::PrimitiveAction::baked);
  EXPECT_EQ(result.primitives[0].reason, "TANGENT recomputed (--overwrite)");
  EXPECT_EQ(result.primitives[4].action, tangent::gltf::PrimitiveAction::baked);
}

TEST(Bake, AllBakesPrimitivesWithoutNormalTexture) {
  TempDir dir;
  const auto all = tangent::testing::makeTestAssets();
  const fs::path input = tangent::testing::writeAsset(assetNamed(all, "document_features"), dir / "in", true);
  tangent::gltf::BakeOptions options;
  options.all = true;
  const auto result = tangent::gltf::bakeFile(input, dir / "out.glb", options);
  EXPECT_EQ(result.primitives[1].action, tangent::gltf::PrimitiveAction::baked);
}

TEST(Bake, GltfAndGlbConvertBothWays) {
  TempDir dir;
  const auto all = tangent::testing::makeTestAssets();
  const fs::path gltfIn = tangent::testing::writeAsset(assetNamed(all, "interleaved_ubyte"), dir / "in", false);
  tangent::gltf::bakeFile(gltfIn, dir / "a.glb", {});
  tangent::gltf::bakeFile(dir / "a.glb", dir / "b.gltf", {});
  EXPECT_TRUE(fs::exists(dir / "b.bin"));
  const Asset b = loadAsset(dir / "b.gltf");
  EXPECT_EQ(b.json["buffers"][0]["uri"], "b.bin");
  EXPECT_FALSE(b.binary);
}

// Bytes appended to a test asset's buffer as a new bufferView (4-byte aligned); its index.
int appendView(tangent::testing::TestAsset& asset, const void* data, std::size_t size) {
  while (asset.bin.size() % 4) asset.bin.push_back(0);
  const std::size_t offset = asset.bin.size();
  const auto* bytes = static_cast<const std::uint8_t*>(data);
  asset.bin.insert(asset.bin.end(), bytes, bytes + size);
  while (asset.bin.size() % 4) asset.bin.push_back(0);
  asset.json["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", size}});
  asset.json["buffers"][0]["byteLength"] = asset.bin.size();
  return static_cast<int>(asset.json["bufferViews"].size()) - 1;
}

// The first primitive's indices rewritten as UNSIGNED_INT.
tangent::testing::TestAsset withWideIndices(tangent::testing::TestAsset asset) {
  Json& primitive = asset.json["meshes"][0]["primitives"][0];
  Json& accessor = asset.json["accessors"][primitive["indices"].get<int>()];
  const Json& view = asset.json["bufferViews"][accessor["bufferView"].get<int>()];
  const std::size_t size = accessor["componentType"] == 5121 ? 1 : 2;
  const std::size_t first = view.value("byteOffset", std::size_t(0)) + accessor.value("byteOffset", std::size_t(0));
  std::vector<std::uint32_t> wide(accessor["count"].get<std::size_t>());
  for (std::size_t i = 0; i < wide.size(); ++i) {
    std::uint16_t value = 0;
    std::memcpy(&value, &asset.bin[first + i * size], size);  // little-endian
    wide[i] = value;
  }
  accessor = {{"bufferView", appendView(asset, wide.data(), wide.size() * 4)}, {"componentType", 5125}, {"count", wide.size()}, {"type", "SCALAR"}};
  return asset;
}

// The same values, with POSITION of every primitive given one sparse substitution of vertex 0
// by its own value: bake reads such an accessor by decoding it (readGeometry), never in place.
tangent::testing::TestAsset decodedNotInPlace(tangent::testing::TestAsset asset) {
  std::set<int> done;
  for (Json& mesh : asset.json["meshes"]) {
    for (Json& primitive : mesh["primitives"]) {
      const int index = primitive["attributes"]["POSITION"].get<int>();
      if (!done.insert(index).second) continue;
      Json& accessor = asset.json["accessors"][index];
      const Json& view = asset.json["bufferViews"][accessor["bufferView"].get<int>()];
      const std::size_t first = view.value("byteOffset", std::size_t(0)) + accessor.value("byteOffset", std::size_t(0));
      std::uint8_t vertex0[12];
      std::memcpy(vertex0, &asset.bin[first], sizeof vertex0);
      const std::uint8_t zero = 0;
      const int indexView = appendView(asset, &zero, 1);
      const int valueView = appendView(asset, vertex0, sizeof vertex0);
      accessor["sparse"] = {{"count", 1}, {"indices", {{"bufferView", indexView}, {"componentType", 5121}}}, {"values", {{"bufferView", valueView}}}};
    }
  }
  return asset;
}

// Every baked TANGENT, as bytes, and each primitive's vertex counts.
std::vector<std::string> bakedTangents(const tangent::testing::TestAsset& asset, const fs::path& dir) {
  const fs::path input = tangent::testing::writeAsset(asset, dir / "in", true);
  const tangent::gltf::BakeResult result = tangent::gltf::bakeFile(input, dir / "out.glb", {});
  const Asset out = loadAsset(dir / "out.glb");
  std::vector<std::string> found;
  for (const auto& p : result.primitives) {
    if (p.action != tangent::gltf::PrimitiveAction::baked) continue;
    const Json& primitive = out.json["meshes"][p.mesh]["primitives"][p.primitive];
    const auto tangents = readAccessor(out.model, primitive["attributes"]["TANGENT"].get<int>(), "TANGENT");
    found.push_back(std::to_string(p.verticesIn) + " -> " + std::to_string(p.verticesOut) + ": " + bytesKey(tangents.bytes));
  }
  return found;
}

// Bake reads float attributes and 16/32-bit indices where they lie in the loaded buffer
// (packed or interleaved) and decodes every other form; both must give the same bits.
TEST(Bake, AttributesReadInPlaceGiveTheBitsOfDecodedOnes) {
  const auto all = tangent::testing::makeTestAssets();
  using tangent::testing::meshAsset;
  const tangent::testing::TestAsset sphere = meshAsset("sphere", tangent::testing::makeSphere(24, 12));  // uint16, packed
  const tangent::testing::TestAsset mirrored = meshAsset("mirrored", tangent::testing::makeGrid(9, 7, true));
  for (const tangent::testing::TestAsset& asset :
       {sphere, withWideIndices(sphere), mirrored, withWideIndices(mirrored),
        withWideIndices(assetNamed(all, "interleaved_ubyte"))}) {  // float attributes 32 bytes apart
    SCOPED_TRACE(asset.name);
    TempDir inPlace, decoded;
    const std::vector<std::string> a = bakedTangents(asset, inPlace.path());
    ASSERT_FALSE(a.empty());
    EXPECT_EQ(a, bakedTangents(decodedNotInPlace(asset), decoded.path()));
  }
}

std::vector<char> fileBytes(const fs::path& path);

TEST(Bake, ExternalImagesAreCopiedBesideTheOutput) {
  TempDir dir;
  const fs::path demo = fs::path(TANGENT_SOURCE_DIR) / "data" / "demo" / "demo.gltf";
  ASSERT_TRUE(fs::exists(demo));
  const fs::path output = dir / "nested" / "deeper" / "demo.gltf";
  tangent::gltf::bakeFile(demo, output, {});
  const Asset out = loadAsset(output);  // the default asset root: the output's own folder
  const std::string uri = out.json["images"][0]["uri"].get<std::string>();
  EXPECT_EQ(uri, "bumps_normal.png");
  // The image bytes are never decoded or rewritten: a byte-for-byte copy.
  EXPECT_EQ(fileBytes(output.parent_path() / uri), fileBytes(demo.parent_path() / "bumps_normal.png"));
}

// A copy an earlier bake left beside the output is not written again (each write is a flush to
// disk); one that differs from the input's image is replaced. (.glb outputs that keep their
// images external: by default a .glb embeds them.)
TEST(Bake, ImageCopiesAlreadyBesideTheOutputAreNotRewritten) {
  TempDir dir;
  const fs::path demo = fs::path(TANGENT_SOURCE_DIR) / "data" / "demo" / "demo.gltf";
  const fs::path image = dir / "bumps_normal.png";
  tangent::gltf::BakeOptions keep;
  keep.keepExternalImages = true;
  tangent::gltf::bakeFile(demo, dir / "a.glb", keep);
  ASSERT_EQ(fileBytes(image), fileBytes(demo.parent_path() / "bumps_normal.png"));
  struct stat before {};
  ASSERT_EQ(::stat(image.c_str(), &before), 0);
  tangent::gltf::bakeFile(demo, dir / "b.glb", keep);
  struct stat after {};
  ASSERT_EQ(::stat(image.c_str(), &after), 0);
  EXPECT_EQ(before.st_ino, after.st_ino) << "rewritten (a new file renamed into place)";
  std::ofstream(image, std::ios::binary) << "not the image";
  tangent::gltf::bakeFile(demo, dir / "c.glb", keep);
  EXPECT_EQ(fileBytes(image), fileBytes(demo.parent_path() / "bumps_normal.png"));
}

TEST(Bake, ImagesOutsideTheInputFolderAreReferredToWhereTheyAre) {
  TempDir dir;
  const fs::path demo = fs::path(TANGENT_SOURCE_DIR) / "data" / "demo" / "demo.gltf";
  // The texture one folder up, reachable only with a wider asset root.
  fs::create_directories(dir / "asset" / "scene");
  fs::copy_file(demo.parent_path() / "bumps_normal.png", dir / "asset" / "bumps_normal.png");
  auto doc = nlohmann::ordered_json::parse(std::ifstream(demo));
  ASSERT_EQ(doc["images"][0]["uri"], "bumps_normal.png");
  doc["images"][0]["uri"] = "../bumps_normal.png";
  for (auto& buffer : doc["buffers"]) {
    const std::string name = buffer["uri"].get<std::string>();
    fs::copy_file(demo.parent_path() / name, dir / "asset" / "scene" / name);
  }
  std::ofstream(dir / "asset" / "scene" / "demo.gltf") << doc.dump();
  const fs::path input = dir / "asset" / "scene" / "demo.gltf";
  EXPECT_THROW(tangent::gltf::bakeFile(input, dir / "out" / "demo.gltf", {}), tangent::gltf::InputError);
  EXPECT_FALSE(fs::exists(dir / "out" / "demo.gltf"));
  tangent::gltf::BakeOptions options;
  options.assetRoot = dir / "asset";
  tangent::gltf::bakeFile(input, dir / "asset" / "out" / "demo.gltf", options);
  const Asset out = loadAsset(dir / "asset" / "out" / "demo.gltf", dir / "asset");
  EXPECT_EQ(out.json["images"][0]["uri"], "../bumps_normal.png");
}

std::vector<char> fileBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<char>(std::istreambuf_iterator<char>(in), {});
}

TEST(BakeErrors, RefusesToWriteOverTheInput) {
  TempDir dir;
  const auto all = tangent::testing::makeTestAssets();
  const fs::path written = tangent::testing::writeAsset(assetNamed(all, "sparse"), dir.path(), false);
  const fs::path input = dir / "a.gltf";  // a.gltf reads sparse.bin
  fs::rename(written, input);
  const auto before = fileBytes(input);
  const auto binBefore = fileBytes(dir / "sparse.bin");
  EXPECT_THROW(tangent::gltf::bakeFile(input, input, {}), tangent::gltf::InputError);
  // A .gltf output whose .bin would replace the input's buffer file.
  EXPECT_THROW(tangent::gltf::bakeFile(input, dir / "sparse.gltf", {}), tangent::gltf::InputError);
  EXPECT_NO_THROW(tangent::gltf::bakeFile(input, dir / "other.gltf", {}));
  EXPECT_EQ(before, fileBytes(input));
  EXPECT_EQ(binBefore, fileBytes(dir / "sparse.bin"));
  EXPECT_TRUE(fs::exists(dir / "other.bin"));
}

// The demo asset (demo.gltf, demo.bin, bumps_normal.png) copied into `folder`, its JSON changed
// by `edit`, written as `name`; returns its path.
fs::path demoCopy(const fs::path& folder, const std::string& name,
                  const std::function<void(nlohmann::ordered_json&)>& edit = [](nlohmann::ordered_json&) {}) {
  const fs::path demo = fs::path(TANGENT_SOURCE_DIR) / "data" / "demo";
  fs::create_directories(folder);
  auto doc = nlohmann::ordered_json::parse(std::ifstream(demo / "demo.gltf"));
  for (const char* file : {"demo.bin", "bumps_normal.png"})
    if (!fs::exists(folder / file)) fs::copy_file(demo / file, folder / file);
  edit(doc);
  std::ofstream(folder / name) << doc.dump();
  return folder / name;
}

// A split rewrites the indices; the accessor written keeps the name, extras and extensions of
// the one it replaces, as carried attributes keep theirs.
TEST(Bake, RewrittenIndicesKeepTheirNameExtrasAndExtensions) {
  TempDir dir;
  const fs::path input = demoCopy(dir.path(), "in.gltf", [](auto& doc) {
    auto& indices = doc["accessors"][doc["meshes"][1]["primitives"][0]["indices"].template get<std::size_t>()];
    indices["name"] = "quad indices";
    indices["extras"] = {{"lod", 0}};
    indices["extensions"] = {{"VENDOR_x", {{"a", 1}}}};
    doc["extensionsUsed"] = {"VENDOR_x"};
  });
  const auto result = tangent::gltf::bakeFile(input, dir / "out.gltf", {});
  ASSERT_GT(result.primitives[1].verticesOut, result.primitives[1].verticesIn) << "no split: the test needs one";
  const Asset out = loadAsset(dir / "out.gltf");
  const auto& indices = out.json["accessors"][out.json["meshes"][1]["primitives"][0]["indices"].get<std::size_t>()];
  EXPECT_EQ(indices.value("name", ""), "quad indices");
  EXPECT_EQ(indices["extras"], Json({{"lod", 0}}));
  EXPECT_EQ(indices["extensions"], Json({{"VENDOR_x", {{"a", 1}}}}));
}

// A TANGENT that bake replaces (here recomputed with --overwrite) passes its name and extras on.
TEST(Bake, AReplacedTangentKeepsItsNameAndExtras) {
  TempDir dir;
  const fs::path input = demoCopy(dir.path(), "in.gltf");
  tangent::gltf::bakeFile(input, dir / "once.gltf", {});
  auto doc = nlohmann::ordered_json::parse(std::ifstream(dir / "once.gltf"));
  const std::size_t tangent = doc["meshes"][0]["primitives"][0]["attributes"]["TANGENT"].get<std::size_t>();
  doc["accessors"][tangent]["name"] = "sphere tangents";
  doc["accessors"][tangent]["extras"] = {{"baker", "someone"}};
  std::ofstream(dir / "named.gltf") << doc.dump();
  tangent::gltf::BakeOptions options;
  options.overwrite = true;
  const auto result = tangent::gltf::bakeFile(dir / "named.gltf", dir / "twice.glb", options);
  ASSERT_EQ(result.primitives[0].action, tangent::gltf::PrimitiveAction::baked);
  const Asset out = loadAsset(dir / "twice.glb");
  const auto& accessor = out.json["accessors"][out.json["meshes"][0]["primitives"][0]["attributes"]["TANGENT"].get<std::size_t>()];
  EXPECT_EQ(accessor.value("name", ""), "sphere tangents");
  EXPECT_EQ(accessor["extras"], Json({{"baker", "someone"}}));
}

// A .gltf output's buffer goes under STEM.N.bin where STEM.bin is the previous output's; never
// under a name the input itself uses (the input here reads out.1.bin).
TEST(BakeErrors, ANumberedBufferNameIsNeverAnInputsFile) {
  TempDir dir;
  const fs::path input = demoCopy(dir.path(), "in.gltf", [](auto& doc) { doc["buffers"][0]["uri"] = "out.1.bin"; });
  fs::rename(dir / "demo.bin", dir / "out.1.bin");
  const auto before = fileBytes(dir / "out.1.bin");
  tangent::gltf::bakeFile(input, dir / "out.gltf", {});
  EXPECT_EQ(loadAsset(dir / "out.gltf").json["buffers"][0]["uri"], "out.bin");
  tangent::gltf::bakeFile(input, dir / "out.gltf", {});  // out.bin is the previous output's
  EXPECT_EQ(loadAsset(dir / "out.gltf").json["buffers"][0]["uri"], "out.2.bin");
  EXPECT_EQ(before, fileBytes(dir / "out.1.bin"));
  EXPECT_FALSE(fs::exists(dir / "out.bin")) << "the previous output's buffer, used by nothing now";
  EXPECT_NO_THROW(loadAsset(input));
}

// A .gltf of the user's beside the output that shares the previous output's .bin keeps it: the
// rebake neither removes it nor writes its new buffer there.
TEST(BakeErrors, APreviousBufferAnotherGltfUsesIsKept) {
  TempDir dir;
  const fs::path input = demoCopy(dir.path(), "in.gltf");
  fs::create_directories(dir / "o");
  tangent::gltf::bakeFile(input, dir / "o" / "out.gltf", {});
  ASSERT_EQ(loadAsset(dir / "o" / "out.gltf").json["buffers"][0]["uri"], "out.bin");
  fs::copy_file(dir / "o" / "out.gltf", dir / "o" / "user.gltf");
  const auto shared = fileBytes(dir / "o" / "out.bin");
  tangent::gltf::bakeFile(input, dir / "o" / "out.gltf", {});
  EXPECT_EQ(loadAsset(dir / "o" / "out.gltf").json["buffers"][0]["uri"], "out.1.bin");
  ASSERT_TRUE(fs::exists(dir / "o" / "out.bin")) << "user.gltf's buffer was removed";
  EXPECT_EQ(shared, fileBytes(dir / "o" / "out.bin"));
  tangent::gltf::bakeFile(input, dir / "o" / "out.gltf", {});  // out.bin is user.gltf's, out.1.bin the previous output's
  EXPECT_EQ(loadAsset(dir / "o" / "out.gltf").json["buffers"][0]["uri"], "out.2.bin");
  EXPECT_EQ(shared, fileBytes(dir / "o" / "out.bin"));
  EXPECT_FALSE(fs::exists(dir / "o" / "out.1.bin")) << "the previous output's buffer, used by nothing now";
  EXPECT_NO_THROW(loadAsset(dir / "o" / "user.gltf"));
}

// The same with the neighbour naming the .bin in other spellings: a .glb's JSON chunk, a JSON
// escape, a percent-encoded dot (each decoded before comparing).
TEST(BakeErrors, APreviousBufferIsKeptWhateverTheNeighbourSpellsIt) {
  auto glb = [](const std::string& json) {
    std::string padded = json;
    while (padded.size() % 4) padded += ' ';
    std::string out = "glTF";
    auto u32 = [&](std::uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); };
    u32(2);
    u32(static_cast<std::uint32_t>(12 + 8 + padded.size()));
    u32(static_cast<std::uint32_t>(padded.size()));
    out += "JSON" + padded;
    return out;
  };
  const std::string buffer = R"("byteLength": 4, "uri": )";
  const std::pair<const char*, std::string> neighbours[] = {
      {"user.glb", glb(R"({"asset": {"version": "2.0"}, "buffers": [{)" + buffer + R"("out.bin"}]})")},
      {"user.gltf", R"({"asset": {"version": "2.0"}, "buffers": [{)" + buffer + R"("\u006fut.bin"}]})"},
      {"user.gltf", R"({"asset": {"version": "2.0"}, "buffers": [{)" + buffer + R"("out%2ebin"}]})"}};
  for (const auto& [name, bytes] : neighbours) {
    SCOPED_TRACE(bytes);
    TempDir dir;
    const fs::path input = demoCopy(dir.path(), "in.gltf");
    fs::create_directories(dir / "o");
    tangent::gltf::bakeFile(input, dir / "o" / "out.gltf", {});
    std::ofstream(dir / "o" / name, std::ios::binary) << bytes;
    const auto shared = fileBytes(dir / "o" / "out.bin");
    tangent::gltf::bakeFile(input, dir / "o" / "out.gltf", {});
    tangent::gltf::bakeFile(input, dir / "o" / "out.gltf", {});
    ASSERT_TRUE(fs::exists(dir / "o" / "out.bin")) << name << "'s buffer was removed";
    EXPECT_EQ(shared, fileBytes(dir / "o" / "out.bin"));
    EXPECT_NE(loadAsset(dir / "o" / "out.gltf").json["buffers"][0]["uri"], "out.bin");
  }
}

// An image copied beside the output under its relative path would land on another image the
// input uses (n.png copied into sub/, where the input's sub/n.png is): refused, nothing written.
TEST(BakeErrors, AnImageCopyNeverReplacesAnotherImageTheInputUses) {
  TempDir dir;
  const fs::path input = demoCopy(dir.path(), "model.gltf", [](auto& doc) {
    doc["images"].push_back({{"uri", "sub/bumps_normal.png"}});
    doc["textures"].push_back({{"source", 1}});
    doc["materials"][1]["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 1}};
  });
  fs::create_directories(dir / "sub");
  std::ofstream(dir / "sub" / "bumps_normal.png") << "a different image";
  const auto before = fileBytes(dir / "sub" / "bumps_normal.png");
  try {
    tangent::gltf::bakeFile(input, dir / "sub" / "baked.gltf", {});
    FAIL() << "no error";
  } catch (const tangent::gltf::InputError& e) {
    EXPECT_NE(std::string(e.what()).find((dir / "sub" / "bumps_normal.png").string()), std::string::npos) << e.what();
  }
  EXPECT_EQ(before, fileBytes(dir / "sub" / "bumps_normal.png"));
  EXPECT_FALSE(fs::exists(dir / "sub" / "baked.gltf"));
  EXPECT_FALSE(fs::exists(dir / "sub" / "baked.bin"));
}

// A run of several bakes (the command line's several inputs, a tree): no bake writes over a
// file another input uses, even one baked later, nor over a different image an earlier bake of
// the run copied to the same place; the same image copied twice is fine.
TEST(BakeErrors, ARunNeverWritesOverAnotherInputsFilesOrItsOwnEarlierCopies) {
  TempDir dir;
  // a/first.gltf reads its buffer from out/second.bin, which second.gltf's output would write.
  const fs::path first = demoCopy(dir / "a", "first.gltf", [](auto& doc) { doc["buffers"][0]["uri"] = "../out/second.bin"; });
  fs::create_directories(dir / "out");
  fs::rename(dir / "a" / "demo.bin", dir / "out" / "second.bin");
  const fs::path second = demoCopy(dir / "b", "second.gltf");
  std::ofstream(dir / "b" / "bumps_normal.png", std::ios::binary | std::ios::app) << "x";  // b's image differs from a's
  const fs::path third = demoCopy(dir / "c", "third.gltf");  // c's image is a's
  const auto firstBin = fileBytes(dir / "out" / "second.bin");

  tangent::gltf::ProtectedFiles run;
  for (const fs::path& input : {first, second, third}) run.addInput(input);
  tangent::gltf::BakeOptions options;
  options.assetRoot = dir.path();
  options.protectedFiles = &run;
  auto bake = [&](const fs::path& input) {
    const auto result = tangent::gltf::bakeFile(input, dir / "out" / input.filename(), options);
    for (const fs::path& file : result.filesWritten) run.add(file);
    return result;
  };
  const auto baked = bake(first);
  EXPECT_TRUE(std::find(baked.filesWritten.begin(), baked.filesWritten.end(), dir / "out" / "bumps_normal.png") != baked.filesWritten.end());
  EXPECT_THROW(bake(second), tangent::gltf::InputError);  // its image differs from first's copy
  EXPECT_EQ(fileBytes(dir / "out" / "bumps_normal.png"), fileBytes(dir / "a" / "bumps_normal.png"));
  EXPECT_FALSE(fs::exists(dir / "out" / "second.gltf"));
  EXPECT_NO_THROW(bake(third));  // the same image: nothing to write
  EXPECT_EQ(firstBin, fileBytes(dir / "out" / "second.bin"));
  EXPECT_NO_THROW(loadAsset(first, dir.path()));

  // second.gltf with its own image, into another folder: its buffer is not out2/second.bin if
  // an input uses that name.
  fs::create_directories(dir / "out2");
  fs::copy_file(dir / "out" / "second.bin", dir / "out2" / "second.bin");
  run.add(dir / "out2" / "second.bin");
  const auto result = tangent::gltf::bakeFile(second, dir / "out2" / "second.gltf", options);
  EXPECT_EQ(loadAsset(dir / "out2" / "second.gltf").json["buffers"][0]["uri"], "second.1.bin");
  EXPECT_EQ(firstBin, fileBytes(dir / "out2" / "second.bin"));
  EXPECT_EQ(result.filesWritten.size(), 3u);  // second.gltf, second.1.bin, bumps_normal.png
}

// A required extension the tools do not know may change what the vertex data means (a vendor's
// mesh compression whose plain accessors hold nothing): refused, naming it. Before, the bake
// wrote tangents made from zeros and kept the requirement. Required extensions that concern
// only images, materials or lights load.
TEST(BakeErrors, AnUnknownRequiredExtensionIsRefusedByName) {
  TempDir dir;
  const fs::path input = demoCopy(dir.path(), "in.gltf", [](auto& doc) {
    doc["extensionsUsed"] = {"KHR_materials_emissive_strength", "VENDOR_mesh_compression"};
    doc["extensionsRequired"] = {"KHR_materials_emissive_strength", "VENDOR_mesh_compression"};
  });
  try {
    tangent::gltf::bakeFile(input, dir / "out.glb", {});
    FAIL() << "no error";
  } catch (const tangent::gltf::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/extensionsRequired/1: VENDOR_mesh_compression"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(dir / "out.glb"));
  const fs::path known = demoCopy(dir.path(), "known.gltf", [](auto& doc) {
    doc["extensionsUsed"] = {"KHR_materials_emissive_strength", "KHR_texture_basisu"};
    doc["extensionsRequired"] = {"KHR_materials_emissive_strength", "KHR_texture_basisu"};
  });
  tangent::gltf::bakeFile(known, dir / "known.glb", {});
  EXPECT_EQ(loadAsset(dir / "known.glb").json["extensionsRequired"].size(), 2u);
}

TEST(BakeErrors, AttributeCountMismatchNamesTheAccessor) {
  TempDir dir;
  auto all = tangent::testing::makeTestAssets();
  auto asset = assetNamed(all, "interleaved_ubyte");
  asset.json["accessors"][asset.json["meshes"][0]["primitives"][0]["attributes"]["NORMAL"].get<int>()]["count"] = 10;
  const fs::path input = tangent::testing::writeAsset(asset, dir / "in", true);
  try {
    tangent::gltf::bakeFile(input, dir / "out.glb", {});
    FAIL() << "no error";
  } catch (const tangent::gltf::InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("interleaved_ubyte.glb"), std::string::npos) << message;
    EXPECT_NE(message.find("mesh 0 'Interleaved' primitive 0"), std::string::npos) << message;
    EXPECT_NE(message.find("NORMAL"), std::string::npos) << message;
    EXPECT_NE(message.find("accessor 1"), std::string::npos) << message;
  }
  EXPECT_FALSE(fs::exists(dir / "out.glb"));
}

TEST(BakeErrors, IndexOutOfRange) {
  TempDir dir;
  auto all = tangent::testing::makeTestAssets();
  auto asset = assetNamed(all, "strips_and_fans");
  // The fan's indices reach vertex 12; shrink its attributes to 5 vertices.
  for (const char* name : {"POSITION", "NORMAL", "TEXCOORD_0"})
    asset.json["accessors"][asset.json["meshes"][0]["primitives"][1]["attributes"][name].get<int>()]["count"] = 5;
  const fs::path input = tangent::testing::writeAsset(asset, dir / "in", false);
  EXPECT_THROW(tangent::gltf::bakeFile(input, dir / "out.gltf", {}), tangent::gltf::InputError);
  EXPECT_FALSE(fs::exists(dir / "out.gltf"));
  EXPECT_FALSE(fs::exists(dir / "out.bin"));
}

TEST(BakeErrors, NotGltf) {
  TempDir dir;
  std::ofstream(dir / "junk.gltf") << "{ not json";
  EXPECT_THROW(tangent::gltf::bakeFile(dir / "junk.gltf", dir / "out.gltf", {}), tangent::gltf::InputError);
  std::ofstream(dir / "junk.glb") << "glTF but not really";
  EXPECT_THROW(tangent::gltf::bakeFile(dir / "junk.glb", dir / "out.glb", {}), tangent::gltf::InputError);
  EXPECT_THROW(tangent::gltf::bakeFile(dir / "missing.glb", dir / "out.glb", {}), tangent::gltf::InputError);
  EXPECT_THROW(tangent::gltf::bakeFile(dir / "junk.gltf", dir / "out.txt", {}), tangent::gltf::InputError);
}

TEST(MeshFiles, ObjBakesToGlb) {
  TempDir dir;
  std::ofstream(dir / "quad.obj") << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                                     "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                                     "vn 0 0 1\n"
                                     "f 1/1/1 2/2/1 3/3/1 4/4/1\n";
  const fs::path output = tangent::gltf::outputPathFor(dir / "quad.obj", dir / "out");
  EXPECT_EQ(output.filename(), "quad.glb");
  const auto result = tangent::gltf::bakeFile(dir / "quad.obj", output, {});
  ASSERT_EQ(result.primitives.size(), 1u);
  EXPECT_EQ(result.primitives[0].action, tangent::gltf::PrimitiveAction::baked);
  const Asset out = loadAsset(output);
  const Json& primitive = out.json["meshes"][0]["primitives"][0];
  const auto tangents = tangent::gltf::detail::toFloats(readAccessor(out.model, primitive["attributes"]["TANGENT"].get<int>(), "TANGENT"));
  // OBJ's v points up; in glTF (v down) the same frame has tangent +x and w = +1.
  EXPECT_NEAR(tangents[0], 1.0f, 1e-6);
  EXPECT_EQ(tangents[3], 1.0f);
}

// "vt" lines that no face refers to are no UVs: OpenMesh still reports texture coordinates
// and leaves the UVs unset, which the bake read as whatever the memory held (output that
// changed from run to run, as on assimp-testmodels' OBJ/regr01.obj). Refused, naming the face
// where only some faces have them.
TEST(MeshFiles, ObjFacesWithoutTexcoordsAreRefused) {
  TempDir dir;
  const std::string quad = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\n";
  std::ofstream(dir / "unreferenced.obj") << quad << "f 1//1 2//1 3//1\nf 1//1 3//1 4//1\n";
  std::ofstream(dir / "partly.obj") << quad << "f 1/1/1 2/2/1 3/3/1\nf 1//1 3//1 4//1\n";
  const std::pair<const char*, const char*> cases[] = {{"unreferenced.obj", "has no texture coordinates"},
                                                       {"partly.obj", "face 2 (1-based) has no texture coordinate"}};
  for (const auto& [name, message] : cases) {
    SCOPED_TRACE(name);
    try {
      tangent::gltf::bakeFile(dir / name, dir / "out.glb", {});
      ADD_FAILURE() << "baked";
    } catch (const tangent::gltf::InputError& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(dir / "out.glb"));
  }
}

// An OBJ's numbers that do not parse (nan, 1e39) were skipped by OpenMesh and every later index
// named another vertex (exit 0, wrong triangles): refused naming the line. And "vn" lines that
// no face uses ("f v/vt") left NORMAL as memory OpenMesh never set (invalid, different bytes each
// run): without a normal on every vertex the primitive has none and bake generates them.
TEST(MeshFiles, ObjNumbersThatDoNotParseAndUnusedNormals) {
  TempDir dir;
  const std::string uvs = "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n";
  for (const char* bad : {"nan 0 0", "1e39 0 0", "1 0"}) {
    SCOPED_TRACE(bad);
    std::ofstream(dir / "bad.obj") << "v 0 0 0\nv " << bad << "\nv 1 1 0\nv 0 1 0\n" << uvs << "f 1/1 3/3 4/4\n";
    try {
      tangent::gltf::bakeFile(dir / "bad.obj", dir / "bad.glb", {});
      ADD_FAILURE() << "baked";
    } catch (const tangent::gltf::InputError& e) {
      EXPECT_NE(std::string(e.what()).find("bad.obj: OBJ line 2: vertex"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(dir / "bad.glb"));
  }
  std::ofstream(dir / "unused.obj") << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n" << uvs << "vn 0 0 1\nf 1/1 2/2 3/3 4/4\n";
  std::vector<std::vector<char>> runs;
  for (int run = 0; run < 2; ++run) {
    const auto result = tangent::gltf::bakeFile(dir / "unused.obj", dir / "unused.glb", {});
    ASSERT_TRUE(result.primitives[0].normalsGenerated.has_value());
    runs.push_back(fileBytes(dir / "unused.glb"));
  }
  EXPECT_EQ(runs[0], runs[1]);
  const Asset out = loadAsset(dir / "unused.glb");
  const auto& primitive = out.json["meshes"][0]["primitives"][0];
  const auto normals = tangent::gltf::detail::readAccessor(out.model, primitive["attributes"]["NORMAL"].get<int>(), "NORMAL");
  ASSERT_EQ(normals.count, 4u);
  for (std::size_t v = 0; v < normals.count; ++v) {
    float n[3];
    std::memcpy(n, normals.bytes.data() + v * 12, 12);
    EXPECT_EQ(n[0], 0.0f);
    EXPECT_EQ(n[1], 0.0f);
    EXPECT_EQ(std::abs(n[2]), 1.0f);
  }
}

// PLY and OFF, read by our own readers like OBJ: the same quad gives the same frame.
TEST(MeshFiles, PlyAndOffBakeToGlb) {
  TempDir dir;
  std::ofstream(dir / "quad.off") << "STNOFF\n4 2 0\n0 0 0 0 0 1 0 0\n1 0 0 0 0 1 1 0\n1 1 0 0 0 1 1 1\n0 1 0 0 0 1 0 1\n"
                                     "3 0 1 2\n3 0 2 3\n";
  std::ofstream(dir / "quad.ply") << "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                                     "property float nx\nproperty float ny\nproperty float nz\nproperty float u\nproperty float v\n"
                                     "element face 2\nproperty list uchar int vertex_indices\nend_header\n"
                                     "0 0 0 0 0 1 0 0\n1 0 0 0 0 1 1 0\n1 1 0 0 0 1 1 1\n0 1 0 0 0 1 0 1\n3 0 1 2\n3 0 2 3\n";
  for (const char* name : {"quad.off", "quad.ply"}) {
    SCOPED_TRACE(name);
    const fs::path output = tangent::gltf::outputPathFor(dir / name, dir / "out");
    const auto result = tangent::gltf::bakeFile(dir / name, output, {});
    ASSERT_EQ(result.primitives.size(), 1u);
    EXPECT_EQ(result.primitives[0].action, tangent::gltf::PrimitiveAction::baked);
    EXPECT_NE(result.primitives[0].reason.find("OBJ/PLY/OFF"), std::string::npos) << result.primitives[0].reason;
    const Asset out = loadAsset(output);
    const Json& primitive = out.json["meshes"][0]["primitives"][0];
    EXPECT_EQ(out.model.accessors[primitive["attributes"]["POSITION"].get<int>()].count, 4u);  // UVs and normals kept per vertex
    const auto tangents = tangent::gltf::detail::toFloats(readAccessor(out.model, primitive["attributes"]["TANGENT"].get<int>(), "TANGENT"));
    EXPECT_NEAR(tangents[0], 1.0f, 1e-6);
    EXPECT_EQ(tangents[3], 1.0f);
  }
}

// OFF's keyword is optional (Geomview), and ModelNet's files glue the vertex count to it
// ("OFF490 518 0"): both were refused ("expected an OFF keyword"). Each now reads as the file
// with its keyword line: the same GLB, or the same refusal of a file without UVs.
TEST(MeshFiles, OffWithoutItsKeywordOrWithTheCountGluedReadsAsWithIt) {
  TempDir dir;
  const std::string body = "0 0 0 0 0\n1 0 0 1 0\n1 1 0 1 1\n0 1 0 0 1\n3 0 1 2\n3 0 2 3\n";
  fs::create_directories(dir / "keyword");  // one name in two folders: the name is written into the GLB
  fs::create_directories(dir / "glued");
  std::ofstream(dir / "keyword" / "q.off") << "STOFF\n4 2 0\n" << body;
  std::ofstream(dir / "glued" / "q.off") << "STOFF4 2 0\n" << body;
  tangent::gltf::bakeFile(dir / "keyword" / "q.off", dir / "keyword.glb", {});
  tangent::gltf::bakeFile(dir / "glued" / "q.off", dir / "glued.glb", {});
  auto bytes = [](const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  };
  EXPECT_EQ(bytes(dir / "glued.glb"), bytes(dir / "keyword.glb"));
  const std::string plain = "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n";
  std::ofstream(dir / "a.off") << "OFF\n4 2 0\n" << plain;
  std::ofstream(dir / "b.off") << "4 2 0\n" << plain;
  std::ofstream(dir / "c.off") << "OFF4 2\n" << plain;
  auto refusal = [&](const char* name) {
    try {
      tangent::gltf::bakeFile(dir / name, dir / (std::string(name) + ".glb"), {});
    } catch (const tangent::gltf::InputError& e) {
      return std::string(e.what()).substr((dir / name).string().size());
    }
    return std::string("no error");
  };
  EXPECT_NE(refusal("a.off").find("no texture coordinates"), std::string::npos) << refusal("a.off");
  EXPECT_EQ(refusal("b.off"), refusal("a.off"));
  EXPECT_EQ(refusal("c.off"), refusal("a.off"));
}

// PLY as its writers spell it: UV properties named texture_u/texture_v, a per-corner texcoord
// list (MeshLab's wedge UVs, a seam through a shared vertex), either binary byte order. Each
// bakes like the plain ASCII u/v quad of PlyAndOffBakeToGlb.
TEST(MeshFiles, PlyUvNamesCornerUvsAndByteOrdersAreRead) {
  TempDir dir;
  const float vertices[4][8] = {{0, 0, 0, 0, 0, 1, 0, 0}, {1, 0, 0, 0, 0, 1, 1, 0}, {1, 1, 0, 0, 0, 1, 1, 1}, {0, 1, 0, 0, 0, 1, 0, 1}};
  auto header = [](const char* format, const char* u, const char* v, const char* count) {
    return std::string("ply\nformat ") + format + " 1.0\ncomment made by a test\nelement vertex 4\nproperty float x\nproperty float y\n" +
           "property float z\nproperty float nx\nproperty float ny\nproperty float nz\nproperty float " + u + "\nproperty float " + v +
           "\nelement face 2\nproperty list " + count + " int vertex_indices\nend_header\n";
  };
  std::string ascii = header("ascii", "texture_u", "texture_v", "uchar");
  for (const auto& row : vertices) {
    for (float x : row) ascii += std::to_string(x) + " ";
    ascii += "\n";
  }
  ascii += "3 0 1 2\n3 0 2 3\n";
  std::ofstream(dir / "names.ply", std::ios::binary) << ascii;
  for (const bool big : {false, true}) {
    std::string binary = header(big ? "binary_big_endian" : "binary_little_endian", "s", "t", "ushort");
    auto put = [&](const void* data, std::size_t bytes) {
      std::string chunk(static_cast<const char*>(data), bytes);
      if (big == (std::endian::native == std::endian::little)) std::reverse(chunk.begin(), chunk.end());
      binary += chunk;
    };
    for (const auto& row : vertices) {
      for (const float& x : row) put(&x, 4);
    }
    const std::int32_t faces[2][3] = {{0, 1, 2}, {0, 2, 3}};
    for (const auto& face : faces) {
      const std::uint16_t three = 3;
      put(&three, 2);
      for (const std::int32_t& index : face) put(&index, 4);
    }
    std::ofstream(dir / (big ? "big.ply" : "little.ply"), std::ios::binary) << binary;
  }
  std::vector<float> first;
  for (const char* name : {"names.ply", "little.ply", "big.ply"}) {
    SCOPED_TRACE(name);
    const fs::path output = tangent::gltf::outputPathFor(dir / name, dir / "out");
    tangent::gltf::bakeFile(dir / name, output, {});
    const Asset out = loadAsset(output);
    const Json& attributes = out.json["meshes"][0]["primitives"][0]["attributes"];
    EXPECT_EQ(out.model.accessors[attributes["POSITION"].get<int>()].count, 4u);
    const auto uvs = tangent::gltf::detail::toFloats(readAccessor(out.model, attributes["TEXCOORD_0"].get<int>(), "TEXCOORD_0"));
    EXPECT_EQ(uvs, (std::vector<float>{0, 1, 1, 1, 1, 0, 0, 0}));  // v flipped for glTF
    const auto tangents = tangent::gltf::detail::toFloats(readAccessor(out.model, attributes["TANGENT"].get<int>(), "TANGENT"));
    if (first.empty()) first = tangents;
    EXPECT_EQ(tangents, first);
    EXPECT_NEAR(tangents[0], 1.0f, 1e-6);
  }

  // Corner UVs: vertex 0 has UV (0,0) in the first face and (0.5,0) in the second, so it splits.
  std::ofstream(dir / "wedge.ply", std::ios::binary)
      << "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nelement face 2\n"
         "property list uchar int vertex_indices\nproperty list uchar float texcoord\nend_header\n"
         "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2 6 0 0 1 0 1 1\n3 0 2 3 6 0.5 0 1 1 0 1\n";
  const fs::path output = tangent::gltf::outputPathFor(dir / "wedge.ply", dir / "out");
  tangent::gltf::bakeFile(dir / "wedge.ply", output, {});
  const Asset out = loadAsset(output);
  const Json& primitive = out.json["meshes"][0]["primitives"][0];
  const auto& attributes = primitive["attributes"];
  ASSERT_EQ(out.model.accessors[attributes["POSITION"].get<int>()].count, 5u);
  const auto uvs = tangent::gltf::detail::toFloats(readAccessor(out.model, attributes["TEXCOORD_0"].get<int>(), "TEXCOORD_0"));
  const auto positions = tangent::gltf::detail::toFloats(readAccessor(out.model, attributes["POSITION"].get<int>(), "POSITION"));
  tangent::gltf::detail::AccessorData indexHeader;
  const auto indices = tangent::gltf::detail::readIndices(out.model, primitive["indices"].get<int>(), 5, "indices", indexHeader);
  ASSERT_EQ(indices.size(), 6u);
  const float expected[6][4] = {{0, 0, 0, 1}, {1, 0, 1, 1}, {1, 1, 1, 0}, {0, 0, 0.5f, 1}, {1, 1, 1, 0}, {0, 1, 0, 0}};
  for (std::size_t k = 0; k < 6; ++k) {
    SCOPED_TRACE(k);
    const std::uint32_t i = indices[k];
    EXPECT_EQ(positions[3 * i], expected[k][0]);
    EXPECT_EQ(positions[3 * i + 1], expected[k][1]);
    EXPECT_EQ(uvs[2 * i], expected[k][2]);
    EXPECT_EQ(uvs[2 * i + 1], expected[k][3]);
  }
}

// info says of a mesh file what bake does with it: every mesh with UVs needs tangents (it said
// "no tangents needed - no normalTexture", and then bake baked it).
TEST(MeshFiles, InfoSaysWhatBakeDoes) {
  TempDir dir;
  std::ofstream(dir / "tri.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n";
  const auto info = tangent::gltf::describeFile(dir / "tri.obj", {});
  const auto baked = tangent::gltf::bakeFile(dir / "tri.obj", dir / "tri.glb", {});
  ASSERT_EQ(baked.primitives.size(), 1u);
  EXPECT_EQ(baked.primitives[0].action, tangent::gltf::PrimitiveAction::baked);
  const auto& primitive = info["meshes"][0]["primitives"][0];
  EXPECT_EQ(primitive["needsTangents"], true) << primitive.dump();
  const std::string why = primitive["why"].get<std::string>();
  EXPECT_EQ(baked.primitives[0].reason.rfind(why, 0), 0u) << why << " | " << baked.primitives[0].reason;  // bake adds the normals it made
  EXPECT_NE(why.find("OBJ/PLY/OFF"), std::string::npos) << why;
}

// A face that makes the mesh non-manifold (a third face on one edge) keeps the normals and UVs
// the file gave its vertices (OpenMesh's half-edge mesh put it on copies of them that had
// neither, so the file was refused for a vertex without UVs, and NORMAL was dropped).
TEST(MeshFiles, NonManifoldFacesKeepTheirVerticesNormalsAndUvs) {
  TempDir dir;
  std::ofstream(dir / "fin.ply") << "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\nproperty float z\n"
                                    "property float nx\nproperty float ny\nproperty float nz\nproperty float s\nproperty float t\n"
                                    "element face 3\nproperty list uchar int vertex_indices\nend_header\n"
                                    "0 0 0 0 0 1 0 0\n1 0 0 0 0 1 1 0\n0 1 0 0 0 1 0 1\n0 -1 0 0 0 1 0 0.5\n0.5 0 1 0 1 0 0.5 0.5\n"
                                    "3 0 1 2\n3 1 0 3\n3 0 1 4\n";
  tangent::gltf::bakeFile(dir / "fin.ply", dir / "fin.glb", {});
  const Asset out = loadAsset(dir / "fin.glb");
  const Json& attributes = out.json["meshes"][0]["primitives"][0]["attributes"];
  ASSERT_TRUE(attributes.contains("NORMAL")) << attributes.dump();
  const auto positions = tangent::gltf::detail::toFloats(readAccessor(out.model, attributes["POSITION"].get<int>(), "POSITION"));
  const auto normals = tangent::gltf::detail::toFloats(readAccessor(out.model, attributes["NORMAL"].get<int>(), "NORMAL"));
  const auto uvs = tangent::gltf::detail::toFloats(readAccessor(out.model, attributes["TEXCOORD_0"].get<int>(), "TEXCOORD_0"));
  const float file[5][8] = {{0, 0, 0, 0, 0, 1, 0, 0}, {1, 0, 0, 0, 0, 1, 1, 0}, {0, 1, 0, 0, 0, 1, 0, 1}, {0, -1, 0, 0, 0, 1, 0, 0.5f},
                            {0.5f, 0, 1, 0, 1, 0, 0.5f, 0.5f}};
  std::size_t matched = 0;
  for (std::size_t v = 0; v < positions.size() / 3; ++v) {
    for (const auto& f : file) {
      if (positions[3 * v] != f[0] || positions[3 * v + 1] != f[1] || positions[3 * v + 2] != f[2]) continue;
      ++matched;
      EXPECT_EQ(normals[3 * v + 1], f[4]) << "vertex " << v;
      EXPECT_EQ(normals[3 * v + 2], f[5]) << "vertex " << v;
      EXPECT_EQ(uvs[2 * v], f[6]) << "vertex " << v;
      EXPECT_EQ(uvs[2 * v + 1], 1.0f - f[7]) << "vertex " << v;
    }
  }
  EXPECT_EQ(matched, positions.size() / 3);
}

// The triangles a bake of `file` wrote to `glb` (one primitive): positions, and each
// triangle's first corner and signed area in the (x, y) plane.
struct BakedTriangles {
  std::vector<float> positions;
  std::vector<std::uint32_t> indices;
  std::size_t count() const { return indices.size() / 3; }
  const float* corner(std::size_t t, int k) const { return &positions[3 * indices[3 * t + static_cast<std::size_t>(k)]]; }
  double area(std::size_t t) const {
    const float *a = corner(t, 0), *b = corner(t, 1), *c = corner(t, 2);
    return ((double(b[0]) - a[0]) * (double(c[1]) - a[1]) - (double(b[1]) - a[1]) * (double(c[0]) - a[0])) / 2;
  }
};
BakedTriangles bakeTriangles(const fs::path& file, const fs::path& glb) {
  tangent::gltf::bakeFile(file, glb, {});
  const Asset out = loadAsset(glb);
  const Json& primitive = out.json["meshes"][0]["primitives"][0];
  BakedTriangles baked;
  baked.positions = tangent::gltf::detail::toFloats(readAccessor(out.model, primitive["attributes"]["POSITION"].get<int>(), "POSITION"));
  tangent::gltf::detail::AccessorData header;
  baked.indices = tangent::gltf::detail::readIndices(out.model, primitive["indices"].get<int>(), baked.positions.size() / 3, "indices", header);
  return baked;
}

// A hard edge: two faces share a vertex but each corner names its own normal (`f v/vt/vn`), as
// Blender writes flat-shaded and marked-sharp edges. OpenMesh's reader kept one normal per
// vertex, the last a face gave it, so the floor's corners on the fold got the wall's normal and
// the shading rounded over an edge the artist made sharp. Each corner keeps its own now: the
// fold's vertices are split by normal alone (their UVs agree), and every corner's normal is its
// face's.
TEST(MeshFiles, ObjCornersKeepTheirOwnNormalsAcrossAHardEdge) {
  TempDir dir;
  std::ofstream(dir / "fold.obj") << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 1 0 1\nv 1 1 1\n"
                                     "vt 0 0\nvt 0.5 0\nvt 0.5 1\nvt 0 1\nvt 1 0\nvt 1 1\n"
                                     "vn 0 0 1\nvn 1 0 0\n"
                                     "f 1/1/1 2/2/1 3/3/1 4/4/1\n"
                                     "f 2/2/2 3/3/2 6/6/2 5/5/2\n";
  const BakedTriangles baked = bakeTriangles(dir / "fold.obj", dir / "fold.glb");
  ASSERT_EQ(baked.count(), 4u);
  EXPECT_EQ(baked.positions.size() / 3, 8u);  // 6 vertices, the fold's two once per face
  const Asset out = loadAsset(dir / "fold.glb");
  const auto normals = tangent::gltf::detail::toFloats(
      readAccessor(out.model, out.json["meshes"][0]["primitives"][0]["attributes"]["NORMAL"].get<int>(), "NORMAL"));
  ASSERT_EQ(normals.size(), baked.positions.size());
  for (std::size_t t = 0; t < baked.count(); ++t) {
    // The face's normal from its corners: the floor (z = 0) faces +z, the wall (x = 1) +x.
    const bool floor = baked.corner(t, 0)[2] == 0 && baked.corner(t, 1)[2] == 0 && baked.corner(t, 2)[2] == 0;
    for (int k = 0; k < 3; ++k) {
      SCOPED_TRACE("triangle " + std::to_string(t) + " corner " + std::to_string(k));
      const float* n = &normals[3 * baked.indices[3 * t + static_cast<std::size_t>(k)]];
      EXPECT_EQ(n[0], floor ? 0.0f : 1.0f);
      EXPECT_EQ(n[1], 0.0f);
      EXPECT_EQ(n[2], floor ? 1.0f : 0.0f);
    }
  }
}

// A face whose corners mix `v/vt` and `v` (not strictly OBJ, but written): the bare corner takes
// the UV its vertex has on another face. OpenMesh's reader handed the face's UVs out around
// its corners in turn, so a bare corner got its neighbour's and the next ones shifted (here a
// triangle of no UV area and two vertices split for nothing, exit 0).
TEST(MeshFiles, ObjCornersWithoutATexcoordTakeTheirVertexsFromAnotherFace) {
  TempDir dir;
  std::ofstream(dir / "mixed.obj") << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                                      "f 1/1 2/2 3/3\nf 1 3/3 4/4\n";
  const BakedTriangles baked = bakeTriangles(dir / "mixed.obj", dir / "mixed.glb");
  ASSERT_EQ(baked.count(), 2u);
  EXPECT_EQ(baked.positions.size() / 3, 4u);
  const Asset out = loadAsset(dir / "mixed.glb");
  const auto uvs = tangent::gltf::detail::toFloats(
      readAccessor(out.model, out.json["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"].get<int>(), "TEXCOORD_0"));
  ASSERT_EQ(uvs.size() / 2, baked.positions.size() / 3);
  for (std::size_t v = 0; v < uvs.size() / 2; ++v) {  // each vertex's UV is its (x, y), v flipped
    EXPECT_EQ(uvs[2 * v], baked.positions[3 * v]) << v;
    EXPECT_EQ(uvs[2 * v + 1], 1.0f - baked.positions[3 * v + 1]) << v;
  }
}

// A concave n-gon (a U of area 7) is cut into ears: every triangle faces the polygon's way and
// together they cover its area once. A fan from its first corner folded two triangles over the
// gap of the U. A convex one stays a fan from its first corner.
TEST(MeshFiles, ConcavePolygonsAreCutIntoEarsConvexOnesFanned) {
  TempDir dir;
  std::ofstream(dir / "u.obj") << "v 0 0 0\nv 3 0 0\nv 3 3 0\nv 2 3 0\nv 2 1 0\nv 1 1 0\nv 1 3 0\nv 0 3 0\n"
                                  "vt 0 0\nvt 1 0\nvt 1 1\nvt 0.6 1\nvt 0.6 0.3\nvt 0.3 0.3\nvt 0.3 1\nvt 0 1\nvn 0 0 1\n"
                                  "f 1/1/1 2/2/1 3/3/1 4/4/1 5/5/1 6/6/1 7/7/1 8/8/1\n"
                                  "v 5 0 0\nv 7 0 0\nv 8 1 0\nv 7 2 0\nv 5 2 0\nvt 0 0\nvt 1 0\nvt 1 0.5\nvt 1 1\nvt 0 1\n"
                                  "f 9/9/1 10/10/1 11/11/1 12/12/1 13/13/1\n";
  const BakedTriangles baked = bakeTriangles(dir / "u.obj", dir / "u.glb");
  ASSERT_EQ(baked.count(), 6u + 3u);
  double area[2] = {0, 0};
  for (std::size_t t = 0; t < baked.count(); ++t) {
    EXPECT_GT(baked.area(t), 0.0) << "triangle " << t << " is folded over";
    area[baked.corner(t, 0)[0] >= 5 ? 1 : 0] += baked.area(t);
  }
  EXPECT_DOUBLE_EQ(area[0], 7.0);
  EXPECT_DOUBLE_EQ(area[1], 5.0);
  // The pentagon, convex: fanned from its first corner, (5,0).
  for (std::size_t t = 6; t < 9; ++t) EXPECT_EQ(baked.corner(t, 0)[0], 5.0f);
}

// A zero-width spike into a notch turns by zero, as a straight corner does: it is not convex,
// so not fanned (the fan folded a triangle over the notch).
TEST(MeshFiles, ASpikeIsNotTakenForConvex) {
  TempDir dir;
  std::ofstream(dir / "spike.obj") << "v 0 0 0\nv 4 0 0\nv 4 4 0\nv 2 2 0\nv 2 0.5 0\nv 2 2 0\nv 0 4 0\n"
                                      "vt 0 0\nvt 1 0\nvt 1 1\nvt 0.5 0.5\nvt 0.5 0.1\nvt 0.5 0.5\nvt 0 1\nvn 0 0 1\n"
                                      "f 1/1/1 2/2/1 3/3/1 4/4/1 5/5/1 6/6/1 7/7/1\n";
  const BakedTriangles baked = bakeTriangles(dir / "spike.obj", dir / "spike.glb");
  double covered = 0;
  for (std::size_t t = 0; t < baked.count(); ++t) {
    EXPECT_GE(baked.area(t), 0.0) << "triangle " << t << " is folded over";
    covered += std::fabs(baked.area(t));
  }
  EXPECT_DOUBLE_EQ(covered, 12.0);  // the square less the notch's triangle
}

// Random star-shaped polygons (simple, mostly concave, 5 to 60 corners, tilted out of every
// axis plane): each one's triangles face its way and cover its area once.
TEST(MeshFiles, RandomConcavePolygonsAreCoveredOnce) {
  TempDir dir;
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::ofstream obj(dir / "stars.obj");
  obj << "vt 0 0\nvt 1 0\nvt 0 1\n";
  std::vector<double> expectedArea;
  std::size_t vertices = 0;
  for (int polygon = 0; polygon < 40; ++polygon) {
    const int n = 5 + static_cast<int>(unit(random) * 56);
    std::vector<double> angles(static_cast<std::size_t>(n));
    for (double& a : angles) a = unit(random) * 6.283185307179586;
    std::sort(angles.begin(), angles.end());
    double area = 0, previous[2] = {0, 0}, first[2] = {0, 0};
    for (int k = 0; k < n; ++k) {
      const double r = 0.3 + 0.7 * unit(random);
      const double x = r * std::cos(angles[static_cast<std::size_t>(k)]), y = r * std::sin(angles[static_cast<std::size_t>(k)]);
      // In the plane spanned by (1, 0, 0.5) and (0, 1, 0.25), shifted along z per polygon.
      obj << "v " << x << " " << y << " " << 0.5 * x + 0.25 * y + polygon << "\n";
      if (k > 0) area += previous[0] * y - previous[1] * x;
      else first[0] = x, first[1] = y;
      previous[0] = x, previous[1] = y;
    }
    area += previous[0] * first[1] - previous[1] * first[0];
    expectedArea.push_back(area / 2);  // in the (x, y) projection
    obj << "f";
    for (int k = 0; k < n; ++k) obj << " " << vertices + static_cast<std::size_t>(k) + 1 << "/" << (k % 3) + 1;
    obj << "\n";
    vertices += static_cast<std::size_t>(n);
  }
  obj.close();
  const BakedTriangles baked = bakeTriangles(dir / "stars.obj", dir / "stars.glb");
  ASSERT_EQ(baked.indices.size(), 3 * (vertices - 2 * expectedArea.size()));
  std::vector<double> area(expectedArea.size(), 0.0);
  for (std::size_t t = 0; t < baked.count(); ++t) {
    const float* a = baked.corner(t, 0);
    const auto polygon = static_cast<std::size_t>(std::lround(a[2] - 0.5 * a[0] - 0.25 * a[1]));
    EXPECT_GE(baked.area(t), -5e-10) << "polygon " << polygon << " triangle " << t << " is folded over";
    area[polygon] += baked.area(t);
  }
  for (std::size_t p = 0; p < area.size(); ++p) EXPECT_NEAR(area[p], expectedArea[p], 1e-4) << "polygon " << p;
}

// A face that visits a vertex twice: a triangle written as a quad with its last corner
// repeated ("1 2 3 3"), and a hexagon pinched at one vertex ("4 5 6 4 7 8", two triangles),
// whose two visits have different UVs (OBJ, PLY). OpenMesh refused such faces (PLY, OFF:
// dropped silently) or, in an OBJ, dropped the repeat but not its UV, so the face's UVs landed
// on the wrong corners. Each is now the simple polygons it is made of, every corner with the
// UV the file gave it (the pinch's first triangle its first visit's, the second its second's).
TEST(MeshFiles, FacesThatVisitAVertexTwiceKeepEveryCornersUv) {
  TempDir dir;
  const float vertices[8][4] = {{0, 0, 0, 0},   {1, 0, 1, 0},      {1, 1, 1, 1},      {3, 0, 0.2f, 0.2f},
                                {4, 0, 0.4f, 0.2f}, {4, 1, 0.4f, 0.4f}, {2, 1, 0.1f, 0.4f}, {2, 0, 0.1f, 0.2f}};
  const std::vector<std::vector<int>> faces = {{0, 1, 2, 2}, {3, 4, 5, 3, 6, 7}};
  const float secondVisit[2] = {0.3f, 0.1f};  // vertex 3's UV at its second visit (OBJ vt 9, a PLY corner UV)
  std::string obj, plyVertices, plyFaces, off = "STOFF\n8 2 0\n";
  for (const auto& v : vertices) {
    const std::string xyz = std::to_string(v[0]) + " " + std::to_string(v[1]) + " 0";
    const std::string uv = std::to_string(v[2]) + " " + std::to_string(v[3]);
    obj += "v " + xyz + "\nvt " + uv + "\n";
    plyVertices += xyz + "\n";
    off += xyz + " " + uv + "\n";
  }
  obj += "vt " + std::to_string(secondVisit[0]) + " " + std::to_string(secondVisit[1]) + "\nvn 0 0 1\n";
  for (const auto& face : faces) {
    obj += "f";
    plyFaces += std::to_string(face.size());
    off += std::to_string(face.size());
    for (std::size_t c = 0; c < face.size(); ++c) {
      const int k = face[c];
      const bool second = face.size() == 6 && c == 3;
      obj += " " + std::to_string(k + 1) + "/" + std::to_string(second ? 9 : k + 1) + "/1";
      plyFaces += " " + std::to_string(k), off += " " + std::to_string(k);
    }
    plyFaces += " " + std::to_string(2 * face.size());  // MeshLab's per-corner UVs
    for (std::size_t c = 0; c < face.size(); ++c) {
      const int k = face[c];
      const bool second = face.size() == 6 && c == 3;
      plyFaces += " " + std::to_string(second ? secondVisit[0] : vertices[k][2]) + " " + std::to_string(second ? secondVisit[1] : vertices[k][3]);
    }
    obj += "\n", plyFaces += "\n", off += "\n";
  }
  std::ofstream(dir / "twice.obj") << obj;
  std::ofstream(dir / "twice.off") << off;
  std::ofstream(dir / "twice.ply") << "ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\nproperty float y\nproperty float z\n"
                                      "element face 2\nproperty list uchar int vertex_indices\nproperty list uchar float texcoord\nend_header\n" +
                                          plyVertices + plyFaces;
  for (const char* name : {"twice.obj", "twice.ply", "twice.off"}) {
    SCOPED_TRACE(name);
    const fs::path glb = dir / (std::string(name) + ".glb");
    const BakedTriangles baked = bakeTriangles(dir / name, glb);
    ASSERT_EQ(baked.count(), 3u);
    double area = 0;
    for (std::size_t t = 0; t < baked.count(); ++t) {
      EXPECT_GT(baked.area(t), 0.0) << "triangle " << t;
      area += baked.area(t);
    }
    EXPECT_DOUBLE_EQ(area, 1.5);
    const Asset out = loadAsset(glb);
    const Json& attributes = out.json["meshes"][0]["primitives"][0]["attributes"];
    const auto uvs = tangent::gltf::detail::toFloats(readAccessor(out.model, attributes["TEXCOORD_0"].get<int>(), "TEXCOORD_0"));
    const bool twoUvs = std::string(name) != "twice.off";  // OFF's UVs are per vertex
    for (std::size_t t = 0; t < baked.count(); ++t) {
      const bool secondPiece = baked.corner(t, 0)[0] == 2 || baked.corner(t, 1)[0] == 2 || baked.corner(t, 2)[0] == 2;
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t v = baked.indices[3 * t + static_cast<std::size_t>(k)];
        const auto* file = std::find_if(std::begin(vertices), std::end(vertices), [&](const float* f) {
          return f[0] == baked.positions[3 * v] && f[1] == baked.positions[3 * v + 1];
        });
        ASSERT_NE(file, std::end(vertices)) << "vertex " << v;
        const bool second = twoUvs && secondPiece && (*file)[0] == 3;
        EXPECT_FLOAT_EQ(uvs[2 * v], second ? secondVisit[0] : (*file)[2]) << "triangle " << t << " vertex " << v;
        EXPECT_FLOAT_EQ(uvs[2 * v + 1], 1.0f - (second ? secondVisit[1] : (*file)[3])) << "triangle " << t << " vertex " << v;
      }
    }
  }
}

// Petals: triangles that share one vertex and no edge. Read into an OpenMesh half-edge mesh,
// each face looked for its new edges among that vertex's outgoing half-edges: quadratic in the
// petals (15,000 took 1.7 s, 40,000 12.9 s; 400,000 would take about 20 minutes). In the
// sanitizer build (Debug, several times slower) a tenth of them, which checks the same path
// for memory errors.
#ifdef __SANITIZE_ADDRESS__
constexpr std::uint32_t kPetals = 40'000;
#else
constexpr std::uint32_t kPetals = 400'000;
#endif
TEST(MeshFiles, ManyFacesMeetingOnlyAtOneVertexAreReadInLinearTime) {
  TempDir dir;
  std::string ply = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(2 * kPetals + 1) +
                    "\nproperty float x\nproperty float y\nproperty float z\nproperty float s\nproperty float t\n"
                    "element face " + std::to_string(kPetals) + "\nproperty list uchar int vertex_indices\nend_header\n";
  auto put = [&](auto value) { ply.append(reinterpret_cast<const char*>(&value), sizeof value); };
  // The centre, then each petal's two rim vertices on the unit circle, half a step apart; UV =
  // (1 + x, 1 + y) / 2, so every tangent is +x.
  auto vertex = [&](float x, float y) { put(x), put(y), put(0.0f), put(0.5f + 0.5f * x), put(0.5f + 0.5f * y); };
  vertex(0, 0);
  const double step = 2 * 3.141592653589793 / kPetals;
  for (std::uint32_t i = 0; i < kPetals; ++i) {
    vertex(static_cast<float>(std::cos(i * step)), static_cast<float>(std::sin(i * step)));
    vertex(static_cast<float>(std::cos((i + 0.5) * step)), static_cast<float>(std::sin((i + 0.5) * step)));
  }
  for (std::uint32_t i = 0; i < kPetals; ++i) put(std::uint8_t{3}), put(0), put(static_cast<std::int32_t>(2 * i + 1)), put(static_cast<std::int32_t>(2 * i + 2));
  std::ofstream(dir / "petals.ply", std::ios::binary) << ply;
  const BakedTriangles baked = bakeTriangles(dir / "petals.ply", dir / "petals.glb");
  ASSERT_EQ(baked.count(), kPetals);
  std::size_t notAtCentre = 0;  // each petal's first corner is the centre
  for (std::size_t t = 0; t < baked.count(); ++t) notAtCentre += baked.corner(t, 0)[0] != 0 || baked.corner(t, 0)[1] != 0;
  EXPECT_EQ(notAtCentre, 0u);
  const Asset out = loadAsset(dir / "petals.glb");
  const Json& attributes = out.json["meshes"][0]["primitives"][0]["attributes"];
  const auto uvs = tangent::gltf::detail::toFloats(readAccessor(out.model, attributes["TEXCOORD_0"].get<int>(), "TEXCOORD_0"));
  const auto tangents = tangent::gltf::detail::toFloats(readAccessor(out.model, attributes["TANGENT"].get<int>(), "TANGENT"));
  const std::size_t vertices = baked.positions.size() / 3;
  ASSERT_EQ(uvs.size(), 2 * vertices);
  ASSERT_EQ(tangents.size(), 4 * vertices);
  std::size_t wrongUv = 0, off = 0;
  for (std::size_t v = 0; v < vertices; ++v) {
    wrongUv += uvs[2 * v] != 0.5f + 0.5f * baked.positions[3 * v] || uvs[2 * v + 1] != 1.0f - (0.5f + 0.5f * baked.positions[3 * v + 1]);
    off += !(tangents[4 * v] > 0.999f);  // within 2.5 degrees of +x
  }
  EXPECT_EQ(wrongUv, 0u);
  EXPECT_EQ(off, 0u);
}

// A binary PLY with a NaN coordinate gave a GLB with "min": [null, ...] and NaN data (validator
// errors, exit 0): refused naming the vertex.
TEST(MeshFiles, NonFiniteValuesInAPlyAreRefusedNamingTheVertex) {
  TempDir dir;
  std::string ply = "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                    "property float z\nproperty float u\nproperty float v\nelement face 1\n"
                    "property list uchar int vertex_indices\nend_header\n";
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float vertices[4][5] = {{0, 0, 0, 0, 0}, {1, 0, 0, 1, 0}, {1, nan, 0, 1, 1}, {0, 1, 0, 0, 1}};
  ply.append(reinterpret_cast<const char*>(vertices), sizeof vertices);
  const std::int32_t face[4] = {0, 1, 2, 3};
  ply.push_back(4);
  ply.append(reinterpret_cast<const char*>(face), sizeof face);
  std::ofstream(dir / "nan.ply", std::ios::binary) << ply;
  try {
    tangent::gltf::bakeFile(dir / "nan.ply", dir / "nan.glb", {});
    FAIL() << "baked";
  } catch (const tangent::gltf::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("nan.ply: vertex 3 (1-based)"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(dir / "nan.glb"));
}

// NormalTangentMirrorTest carries Blender's MikkTSpace tangents in glTF's convention.
TEST(SharedAssets, MirrorTestHandednessMatchesSuppliedTangents) {
  const fs::path shared = tangent::testing::sharedAssets();
  if (shared.empty()) TANGENT_SKIP_OR_FAIL("../shared/assets is absent: skipping the shared sample assets");
  const Asset asset = loadAsset(shared / "NormalTangentMirrorTest.glb");
  const Json& primitive = asset.json["meshes"][0]["primitives"][0];
  const auto& attributes = primitive["attributes"];
  const std::size_t n = asset.model.accessors[attributes["POSITION"].get<int>()].count;
  auto floats = [&](const char* name) { return tangent::gltf::detail::toFloats(readAccessor(asset.model, attributes[name].get<int>(), name)); };
  const auto positions = floats("POSITION"), normals = floats("NORMAL"), uvs = floats("TEXCOORD_0"), supplied = floats("TANGENT");
  const auto corners = cornersOf(asset, primitive);
  std::vector<float> computed(corners.size() * 4);
  tangent::computeCornerTangents({positions, normals, uvs, corners}, computed, {});
  std::size_t wMismatch = 0;
  std::vector<double> angles;
  for (std::size_t c = 0; c < corners.size(); ++c) {
    const float* s = &supplied[4 * corners[c]];
    const float* t = &computed[4 * c];
    if (s[3] != t[3]) ++wMismatch;
    const double dot = (s[0] * t[0] + s[1] * t[1] + s[2] * t[2]) / std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
    angles.push_back(std::acos(std::clamp(dot, -1.0, 1.0)) * 180 / M_PI);
  }
  std::sort(angles.begin(), angles.end());
  std::printf("NormalTangentMirrorTest, mikktspace vs supplied: %zu vertices, %zu corners, median %.4f deg, p99 %.4f deg, max %.4f deg, w mismatches %zu\n",
              n, corners.size(), angles[angles.size() / 2], angles[angles.size() * 99 / 100], angles.back(), wMismatch);
  EXPECT_EQ(wMismatch, 0u);
}

TEST(SharedAssets, BothAssetsBakeWithTangentsOnEveryNormalMappedPrimitive) {
  const fs::path shared = tangent::testing::sharedAssets();
  if (shared.empty()) TANGENT_SKIP_OR_FAIL("../shared/assets is absent: skipping the shared sample assets");
  for (const char* name : {"NormalTangentTest.glb", "NormalTangentMirrorTest.glb"}) {
    TempDir dir;
    tangent::gltf::BakeOptions options;
    options.overwrite = true;
    const auto result = tangent::gltf::bakeFile(shared / name, dir / name, options);
    const Asset out = loadAsset(dir / name);
    for (const auto& p : result.primitives) {
      const Json& primitive = out.json["meshes"][p.mesh]["primitives"][p.primitive];
      const auto needs = tangent::gltf::detail::primitiveNeeds(out.json, primitive, false);
      if (needs.hasNormalTexture) {
        EXPECT_EQ(p.action, tangent::gltf::PrimitiveAction::baked) << name;
        EXPECT_TRUE(primitive["attributes"].contains("TANGENT")) << name;
      }
    }
  }
}

// Image copies go into place with the output, as one: where a copy's rename fails after the
// checks up front (a folder appeared there), the copies already renamed are put back, the
// folders made for them removed, and the output is not written; the error names the copy.
TEST(CreatedFiles, ARenameThatFailsLeavesTheCopiesAndTheOutputAsTheyWere) {
  TempDir dir;
  auto text = [](const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), {});
  };
  auto bytes = [](const std::string& s) { return std::span(reinterpret_cast<const std::uint8_t*>(s.data()), s.size()); };
  std::ofstream(dir / "out.glb") << "earlier output";
  fs::create_directory(dir / "old");
  std::ofstream(dir / "old" / "a.png") << "earlier copy";
  const std::string copy = "new copy", output = "new output";
  try {
    tangent::gltf::detail::CreatedFiles created;
    created.createFolders(dir / "tex" / "deep");
    created.stage(dir / "tex" / "deep" / "n.png", bytes(copy));
    created.stage(dir / "old" / "a.png", bytes(copy));
    created.stage(dir / "old" / "b.png", bytes(copy));
    fs::create_directories(dir / "old" / "b.png" / "inside");
    tangent::output::StagedFile written(dir / "out.glb", {bytes(output)});
    created.keep(written);
    FAIL() << "an image copy went over a folder";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find((dir / "old" / "b.png").string()), std::string::npos) << message;
    EXPECT_NE(message.find((dir / "out.glb").string() + " was not written"), std::string::npos) << message;
  }
  EXPECT_EQ(text(dir / "out.glb"), "earlier output");
  EXPECT_EQ(text(dir / "old" / "a.png"), "earlier copy");
  std::vector<std::string> left;
  for (const auto& entry : fs::recursive_directory_iterator(dir.path()))
    left.push_back(entry.path().lexically_relative(dir.path()).generic_string());
  std::sort(left.begin(), left.end());
  EXPECT_EQ(left, (std::vector<std::string>{"old", "old/a.png", "old/b.png", "old/b.png/inside", "out.glb"}));
}

// Many image copies (a scene with hundreds of textures): each staged path is known as staged,
// no other is, and keep() puts every copy in place with the output.
TEST(CreatedFiles, ManyCopiesAreEachStagedOnceAndKept) {
  TempDir dir;
  const std::string copy = "copy", output = "output";
  const auto bytes = std::span(reinterpret_cast<const std::uint8_t*>(copy.data()), copy.size());
  constexpr int kCopies = 300;
  {
    tangent::gltf::detail::CreatedFiles created;
    created.createFolders(dir / "tex");
    for (int i = 0; i < kCopies; i += 2) created.stage(dir / "tex" / (std::to_string(i) + ".png"), bytes);
    for (int i = 0; i < kCopies; ++i)
      EXPECT_EQ(created.staged(dir / "tex" / (std::to_string(i) + ".png")), i % 2 == 0) << i;
    EXPECT_FALSE(created.staged(dir / "0.png"));
    tangent::output::StagedFile written(dir / "out.glb", {std::span(reinterpret_cast<const std::uint8_t*>(output.data()), output.size())});
    created.keep(written);
    EXPECT_FALSE(created.staged(dir / "tex" / "0.png"));  // kept: nothing is staged any more
  }
  std::size_t files = 0;
  for (const auto& entry : fs::directory_iterator(dir / "tex")) {
    ++files;
    std::ifstream in(entry.path(), std::ios::binary);
    EXPECT_EQ(std::string((std::istreambuf_iterator<char>(in)), {}), copy) << entry.path();
  }
  EXPECT_EQ(files, std::size_t(kCopies / 2));
}

}  // namespace
