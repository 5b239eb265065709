// SPDX-License-Identifier: MIT
// `tangent check`: baked outputs check clean; each negative control is caught by the right
// check; the JUnit output parses as XML with the right failure counts; exit codes.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>

#include "read/accessors.hpp"
#include "read/asset.hpp"
#include "read/primitive.hpp"
#include "support/run_command.hpp"
#include "support/skip_or_fail.hpp"
#include "support/temp_dir.hpp"
#include "support/test_assets.hpp"
#include "tangent/check.hpp"
#include "tangent/gltf.hpp"

namespace {

namespace fs = std::filesystem;
using tangent::gltf::CheckFinding;
using tangent::gltf::FileCheck;
using tangent::testing::TempDir;

fs::path bakedAsset(const TempDir& dir, const std::string& name) {
  const auto all = tangent::testing::makeTestAssets();
  const auto& asset = *std::find_if(all.begin(), all.end(), [&](const auto& a) { return a.name == name; });
  const fs::path input = tangent::testing::writeAsset(asset, dir / "in", true);
  const fs::path output = dir / (name + "-baked.glb");
  tangent::gltf::bakeFile(input, output, {});
  return output;
}

struct TangentView {
  std::vector<float> tangents;  // 4 per vertex
  std::vector<float> positions;
  std::vector<std::uint32_t> corners;
};

// Rewrites primitive (0, p)'s float TANGENT in a GLB file in place through `edit`.
void patchTangents(const fs::path& glb, int primitiveIndex, const std::function<void(TangentView&)>& edit) {
  const auto asset = tangent::gltf::detail::loadAsset(glb);
  const auto& primitive = asset.json["meshes"][0]["primitives"][primitiveIndex];
  const int accessorIndex = primitive["attributes"]["TANGENT"].get<int>();
  const auto& accessor = asset.model.accessors[accessorIndex];
  const auto& view = asset.model.bufferViews[accessor.bufferView];
  TangentView tv;
  tv.tangents = tangent::gltf::detail::toFloats(tangent::gltf::detail::readAccessor(asset.model, accessorIndex, "TANGENT"));
  tv.positions = tangent::gltf::detail::toFloats(
      tangent::gltf::detail::readAccessor(asset.model, primitive["attributes"]["POSITION"].get<int>(), "POSITION"));
  const auto needs = tangent::gltf::detail::primitiveNeeds(asset.json, primitive, false);
  tv.corners = tangent::gltf::detail::readGeometry(asset, primitive, needs, "patch").corners;
  edit(tv);
  std::fstream file(glb, std::ios::in | std::ios::out | std::ios::binary);
  std::uint32_t jsonLength = 0;
  file.seekg(12);
  file.read(reinterpret_cast<char*>(&jsonLength), 4);
  ASSERT_EQ(view.byteStride, 0u);
  file.seekp(static_cast<std::streamoff>(20 + jsonLength + 8 + view.byteOffset + accessor.byteOffset));
  file.write(reinterpret_cast<const char*>(tv.tangents.data()), static_cast<std::streamsize>(tv.tangents.size() * 4));
  ASSERT_TRUE(file.good());
}

const CheckFinding* findingOf(const FileCheck& check, int primitive, const std::string& name) {
  for (const auto& p : check.primitives) {
    if (p.primitive != primitive) continue;
    for (const auto& f : p.findings) {
      if (f.check == name) return &f;
    }
  }
  return nullptr;
}

std::vector<std::string> findingNames(const FileCheck& check) {
  std::vector<std::string> names;
  for (const auto& p : check.primitives)
    for (const auto& f : p.findings) names.push_back(f.check);
  return names;
}

TEST(Check, BakedOutputsAreClean) {
  for (const auto& asset : tangent::testing::makeTestAssets()) {
    TempDir dir;
    const fs::path baked = bakedAsset(dir, asset.name);
    const FileCheck check = tangent::gltf::checkFile(baked, {});
    EXPECT_TRUE(check.error.empty()) << check.error;
    EXPECT_FALSE(check.primitives.empty()) << asset.name;
    for (const auto& p : check.primitives) {
      std::vector<std::string> names;
      for (const auto& f : p.findings) names.push_back(f.check);
      // Bake replaces whatever check would fail (document_features' supplied constant +x
      // tangent on a curved sheet included): every output is clean.
      EXPECT_TRUE(names.empty()) << asset.name << " primitive " << p.primitive << ": " << testing::PrintToString(names);
    }
  }
}

// A primitive that leaves vertices of its buffer undrawn (the poles of a UV sphere, a vertex an
// editor left behind): check compares on the vertices it draws, renumbered, and names the
// buffer's vertices. Bake keeps the buffer (one TANGENT over it), so its output is clean; a
// wrong renumbering of the drawn vertices' positions or UVs (check keeps them in place for a
// single primitive) would show as reference findings.
TEST(Check, UndrawnVerticesOfTheBufferAreLeftOutAndTheRestIsClean) {
  TempDir dir;
  using Json = nlohmann::ordered_json;
  constexpr int n = 7;  // n x n drawn grid; buffer vertices 0 and 9 are never drawn
  const std::vector<std::uint32_t> undrawn = {0, 9};
  std::vector<float> positions, normals, uvs;
  std::vector<std::uint32_t> bufferIndex;  // of grid vertex g
  auto addVertex = [&](float x, float y, float z, float u, float v) {
    const float nx = -0.4f * x, ny = 0.3f * y, length = std::sqrt(nx * nx + ny * ny + 1);
    positions.insert(positions.end(), {x, y, z});
    normals.insert(normals.end(), {nx / length, ny / length, 1 / length});
    uvs.insert(uvs.end(), {u, v});
  };
  for (int g = 0; g < n * n; ++g) {
    while (std::find(undrawn.begin(), undrawn.end(), positions.size() / 3) != undrawn.end())
      addVertex(5.0f + float(positions.size()), -3, 2, 0.9f, 0.05f);  // far off, UVs unlike any drawn
    const float x = float(g % n) / (n - 1), y = float(g / n) / (n - 1);
    bufferIndex.push_back(static_cast<std::uint32_t>(positions.size() / 3));
    addVertex(x, y, 0.2f * x * x - 0.15f * y * y, 0.8f * x + 0.3f * y * y, 1 - y + 0.1f * x);
  }
  std::vector<std::uint32_t> indices;
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const int a = j * n + i;
      for (int g : {a, a + 1, a + n + 1, a, a + n + 1, a + n}) indices.push_back(bufferIndex[g]);
    }
  const std::size_t vertexCount = positions.size() / 3;
  Json low = Json::array(), high = Json::array();
  for (int axis = 0; axis < 3; ++axis) {
    float lo = positions[axis], hi = positions[axis];
    for (std::size_t v = 0; v < vertexCount; ++v)
      lo = std::min(lo, positions[3 * v + axis]), hi = std::max(hi, positions[3 * v + axis]);
    low.push_back(lo), high.push_back(hi);
  }
  std::vector<std::uint8_t> bin;
  auto append = [&](const auto& values) {
    const auto* bytes = reinterpret_cast<const std::uint8_t*>(values.data());
    bin.insert(bin.end(), bytes, bytes + values.size() * sizeof(values[0]));
  };
  append(positions), append(normals), append(uvs), append(indices);
  const std::size_t p = 0, nOffset = 12 * vertexCount, uOffset = 24 * vertexCount, iOffset = 32 * vertexCount;
  const Json doc = {
      {"asset", {{"version", "2.0"}}},
      {"buffers", Json::array({{{"uri", "grid.bin"}, {"byteLength", bin.size()}}})},
      {"bufferViews", Json::array({{{"buffer", 0}, {"byteOffset", p}, {"byteLength", nOffset}},
                                   {{"buffer", 0}, {"byteOffset", nOffset}, {"byteLength", uOffset - nOffset}},
                                   {{"buffer", 0}, {"byteOffset", uOffset}, {"byteLength", iOffset - uOffset}},
                                   {{"buffer", 0}, {"byteOffset", iOffset}, {"byteLength", 4 * indices.size()}}})},
      {"accessors",
       Json::array({{{"bufferView", 0},
                     {"componentType", 5126},
                     {"count", vertexCount},
                     {"type", "VEC3"},
                     {"min", low},
                     {"max", high}},
                    {{"bufferView", 1}, {"componentType", 5126}, {"count", vertexCount}, {"type", "VEC3"}},
                    {{"bufferView", 2}, {"componentType", 5126}, {"count", vertexCount}, {"type", "VEC2"}},
                    {{"bufferView", 3}, {"componentType", 5125}, {"count", indices.size()}, {"type", "SCALAR"}}})},
      {"materials", Json::array({{{"normalTexture", {{"index", 0}}}}})},
      {"textures", Json::array({{{"source", 0}}})},
      {"images", Json::array({{{"uri", "normal.png"}}})},
      {"meshes",
       Json::array({{{"primitives", Json::array({{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}}},
                                                  {"indices", 3},
                                                  {"material", 0}}})}}})},
      {"nodes", Json::array({{{"mesh", 0}}})},
      {"scenes", Json::array({{{"nodes", {0}}}})},
      {"scene", 0}};
  std::ofstream(dir / "grid.bin", std::ios::binary)
      .write(reinterpret_cast<const char*>(bin.data()), static_cast<std::streamsize>(bin.size()));
  std::ofstream(dir / "grid.gltf") << doc.dump();
  std::ofstream(dir / "normal.png") << "never read";
  tangent::gltf::BakeOptions keepImage;  // a .glb would embed the image (and refuse these bytes)
  keepImage.keepExternalImages = true;
  tangent::gltf::bakeFile(dir / "grid.gltf", dir / "baked.glb", keepImage);

  const FileCheck check = tangent::gltf::checkFile(dir / "baked.glb", {});
  ASSERT_TRUE(check.error.empty()) << check.error;
  ASSERT_EQ(check.primitives.size(), 1u);
  EXPECT_EQ(check.primitives[0].vertices, vertexCount);  // the undrawn count too (finite, unit, w)
  EXPECT_EQ(check.primitives[0].triangles, indices.size() / 3);
  EXPECT_TRUE(check.clean()) << testing::PrintToString(findingNames(check));
  EXPECT_EQ(check.primitives[0].referenceUndefined, 0u);

  // One drawn vertex's w flipped: handedness names it by its number in the buffer.
  const std::uint32_t flipped = bufferIndex[2 * n + 3];
  patchTangents(dir / "baked.glb", 0, [&](TangentView& view) { view.tangents[4 * flipped + 3] *= -1; });
  const FileCheck broken = tangent::gltf::checkFile(dir / "baked.glb", {});
  const CheckFinding* handedness = findingOf(broken, 0, "handedness");
  ASSERT_NE(handedness, nullptr) << testing::PrintToString(findingNames(broken));
  EXPECT_EQ(handedness->total, indices.size() / 3);
  ASSERT_FALSE(handedness->worst.empty());
  for (const auto& sample : handedness->worst) {
    unsigned a = 0, b = 0, c = 0;
    ASSERT_EQ(std::sscanf(sample.detail.c_str(), "triangle %*u (vertices %u %u %u)", &a, &b, &c), 3) << sample.detail;
    EXPECT_TRUE(a == flipped || b == flipped || c == flipped) << sample.detail << ", flipped " << flipped;
  }
}

TEST(Check, SharedMirrorTestAsSuppliedIsClean) {
  const fs::path shared = tangent::testing::sharedAssets();
  if (shared.empty()) TANGENT_SKIP_OR_FAIL("../shared/assets is absent: skipping the shared sample assets");
  const FileCheck check = tangent::gltf::checkFile(shared / "NormalTangentMirrorTest.glb", {});
  EXPECT_TRUE(check.clean()) << testing::PrintToString(findingNames(check));
  ASSERT_EQ(check.primitives.size(), 1u);
  const FileCheck missing = tangent::gltf::checkFile(shared / "NormalTangentTest.glb", {});
  ASSERT_NE(findingOf(missing, 0, "present"), nullptr);
}

TEST(CheckNegative, WNegatedOnOneIsland) {
  TempDir dir;
  const fs::path baked = bakedAsset(dir, "interleaved_ubyte");  // 6 mirrored columns of quads
  std::size_t islandTriangles = 0;
  patchTangents(baked, 0, [&](TangentView& tv) {
    std::vector<char> flip(tv.tangents.size() / 4, 0);
    for (std::size_t t = 0; t < tv.corners.size() / 3; ++t) {
      double x = 0;
      for (int k = 0; k < 3; ++k) x += tv.positions[3 * tv.corners[3 * t + k]] / 3;
      if (x < 1.0 / 6) {
        ++islandTriangles;
        for (int k = 0; k < 3; ++k) flip[tv.corners[3 * t + k]] = 1;
      }
    }
    for (std::size_t v = 0; v < flip.size(); ++v)
      if (flip[v]) tv.tangents[4 * v + 3] = -tv.tangents[4 * v + 3];
  });
  const FileCheck check = tangent::gltf::checkFile(baked, {});
  const CheckFinding* handedness = findingOf(check, 0, "handedness");
  ASSERT_NE(handedness, nullptr) << testing::PrintToString(findingNames(check));
  EXPECT_EQ(handedness->failed, islandTriangles);
  EXPECT_EQ(findingOf(check, 0, "w-uniform"), nullptr);  // the island's seam vertices are its own
  EXPECT_NE(findingOf(check, 0, "reference"), nullptr);
}

TEST(CheckNegative, BitangentReversedEverywhere) {
  // What a flipped green channel looks like in the tangents: every w negated.
  TempDir dir;
  const fs::path baked = bakedAsset(dir, "interleaved_ubyte");
  std::size_t triangles = 0;
  patchTangents(baked, 0, [&](TangentView& tv) {
    triangles = tv.corners.size() / 3;
    for (std::size_t v = 0; v < tv.tangents.size() / 4; ++v) tv.tangents[4 * v + 3] = -tv.tangents[4 * v + 3];
  });
  const FileCheck check = tangent::gltf::checkFile(baked, {});
  const CheckFinding* handedness = findingOf(check, 0, "handedness");
  ASSERT_NE(handedness, nullptr);
  EXPECT_EQ(handedness->failed, triangles);
  EXPECT_EQ(handedness->total, triangles);
}

TEST(CheckNegative, TangentsFromTheWrongUvSet) {
  TempDir dir;
  const fs::path baked = bakedAsset(dir, "second_uv_set");  // normal texture on TEXCOORD_1
  const auto asset = tangent::gltf::detail::loadAsset(baked);
  const auto& primitive = asset.json["meshes"][0]["primitives"][0];
  tangent::gltf::detail::PrimitiveNeeds wrong = tangent::gltf::detail::primitiveNeeds(asset.json, primitive, false);
  ASSERT_EQ(wrong.texCoord, 1);
  wrong.texCoord = 0;
  wrong.hasNormalTexture = false;
  const auto geometry = tangent::gltf::detail::readGeometry(asset, primitive, wrong, "wrong set");
  std::vector<float> cornerTangents(geometry.corners.size() * 4);
  tangent::computeCornerTangents({geometry.positions, geometry.normals, geometry.uvs, geometry.corners}, cornerTangents);
  patchTangents(baked, 0, [&](TangentView& tv) {
    for (std::size_t c = 0; c < geometry.corners.size(); ++c)
      std::memcpy(&tv.tangents[4 * geometry.corners[c]], &cornerTangents[4 * c], 16);
  });
  const FileCheck check = tangent::gltf::checkFile(baked, {});
  const CheckFinding* reference = findingOf(check, 0, "reference");
  ASSERT_NE(reference, nullptr) << testing::PrintToString(findingNames(check));
  EXPECT_EQ(reference->failed, reference->total);
  // TEXCOORD_1 is (x, 1 - y) and TEXCOORD_0 is (v1, 1 - u1) = (1 - y, 1 - x)
  // (support/test_assets.cpp): the wrong set's dP/du is -y where the right one's is +x, both
  // with w = +1 (the two Jacobians have the same sign), on a flat grid: 90 degrees at every
  // corner, and w the same.
  EXPECT_NEAR(reference->worst.front().severity, 90.0, 1e-3);
  EXPECT_FALSE(reference->worst.front().wDiffers);
  EXPECT_EQ(findingOf(check, 1, "reference"), nullptr);  // the other primitive is untouched
}

TEST(CheckNegative, NonUnitTangent) {
  TempDir dir;
  const fs::path baked = bakedAsset(dir, "interleaved_ubyte");
  patchTangents(baked, 0, [](TangentView& tv) {
    for (int i = 0; i < 3; ++i) tv.tangents[4 * 3 + i] *= 0.5f;
  });
  const FileCheck check = tangent::gltf::checkFile(baked, {});
  const CheckFinding* unit = findingOf(check, 0, "unit");
  ASSERT_NE(unit, nullptr);
  EXPECT_EQ(unit->failed, 1u);
  EXPECT_EQ(unit->worst.front().element, 3u);
  EXPECT_NE(unit->worst.front().detail.find("vertex 3 |xyz| = 0.5"), std::string::npos) << unit->worst.front().detail;
  EXPECT_EQ(findingNames(check), std::vector<std::string>{"unit"});
}

TEST(CheckNegative, NanInOneTangent) {
  TempDir dir;
  const fs::path baked = bakedAsset(dir, "interleaved_ubyte");
  patchTangents(baked, 0, [](TangentView& tv) { tv.tangents[4 * 5 + 1] = std::numeric_limits<float>::quiet_NaN(); });
  const FileCheck check = tangent::gltf::checkFile(baked, {});
  const CheckFinding* finite = findingOf(check, 0, "finite");
  ASSERT_NE(finite, nullptr);
  EXPECT_EQ(finite->failed, 1u);
  EXPECT_EQ(finite->worst.front().element, 5u);
}

TEST(CheckNegative, WOfOneHalf) {
  TempDir dir;
  const fs::path baked = bakedAsset(dir, "interleaved_ubyte");
  patchTangents(baked, 0, [](TangentView& tv) { tv.tangents[4 * 7 + 3] = 0.5f; });
  const FileCheck check = tangent::gltf::checkFile(baked, {});
  const CheckFinding* w = findingOf(check, 0, "w");
  ASSERT_NE(w, nullptr);
  EXPECT_EQ(w->failed, 1u);
  EXPECT_EQ(w->worst.front().element, 7u);
  EXPECT_NE(findingOf(check, 0, "w-uniform"), nullptr);  // its triangles now mix 0.5 and +-1
}

TEST(CheckNegative, TangentsMissing) {
  TempDir dir;
  const auto all = tangent::testing::makeTestAssets();
  const fs::path input = tangent::testing::writeAsset(all[0], dir.path(), true);  // not baked
  const FileCheck check = tangent::gltf::checkFile(input, {});
  ASSERT_NE(findingOf(check, 0, "present"), nullptr);
  EXPECT_EQ(check.primitives[0].notRun.size(), std::size(tangent::gltf::kCheckNames) - 1);
}

// A triangle strip of two indices draws nothing: bake leaves it without TANGENT, and check
// (the same rule) passes it instead of failing "present" on a file bake just wrote.
TEST(Check, APrimitiveThatDrawsNoTriangleNeedsNoTangentForCheckOrInfo) {
  TempDir dir;
  const fs::path demo = fs::path(TANGENT_SOURCE_DIR) / "data" / "demo";
  auto doc = nlohmann::ordered_json::parse(std::ifstream(demo / "demo.gltf"));
  doc["meshes"][1]["primitives"][0]["mode"] = 5;  // MirroredQuads: a strip of its first two indices
  doc["accessors"][7]["count"] = 2;
  std::ofstream(dir / "in.gltf") << doc.dump();
  for (const char* file : {"demo.bin", "bumps_normal.png"}) fs::copy_file(demo / file, dir / file);
  const auto baked = tangent::gltf::bakeFile(dir / "in.gltf", dir / "out.glb", {});
  ASSERT_EQ(baked.primitives.size(), 3u);
  EXPECT_EQ(baked.primitives[1].action, tangent::gltf::PrimitiveAction::skipped);
  const FileCheck check = tangent::gltf::checkFile(dir / "out.glb", {});
  EXPECT_TRUE(findingNames(check).empty()) << ::testing::PrintToString(findingNames(check));
  ASSERT_EQ(check.primitives.size(), 2u);  // the sphere and the strip (the ground has no normal texture)
  EXPECT_EQ(check.primitives[1].triangles, 0u);
  EXPECT_NE(std::find(check.primitives[1].passed.begin(), check.primitives[1].passed.end(), "present"),
            check.primitives[1].passed.end());
  // info agrees: the strip needs no tangents, the sphere does.
  const auto info = tangent::gltf::describeFile(dir / "out.glb", {});
  EXPECT_EQ(info["meshes"][1]["primitives"][0]["needsTangents"], false) << info["meshes"][1].dump();
  EXPECT_EQ(info["meshes"][0]["primitives"][0]["needsTangents"], true);
}

TEST(CheckNegative, UnreadableFileIsAnErrorNotAFinding) {
  TempDir dir;
  std::ofstream(dir / "broken.gltf") << "{";
  try {
    tangent::gltf::checkFile(dir / "broken.gltf", {});
    FAIL() << "checkFile accepted a file that is not JSON";
  } catch (const tangent::gltf::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("broken.gltf"), std::string::npos) << e.what();
  }
}

using tangent::testing::runCommand;

std::string quoted(const fs::path& path) { return "'" + path.string() + "'"; }

TEST(CheckCli, ExitCodesAndJunitParsesWithTheRightCounts) {
  TempDir dir;
  const fs::path clean = bakedAsset(dir, "interleaved_ubyte");
  const fs::path nonUnit = dir / "non-unit.glb";
  fs::copy_file(clean, nonUnit);
  patchTangents(nonUnit, 0, [](TangentView& tv) {
    for (int i = 0; i < 3; ++i) tv.tangents[i] *= 3;  // same direction, three times too long
  });
  const fs::path missing = tangent::testing::writeAsset(tangent::testing::makeTestAssets()[0], dir / "raw", true);
  const std::string cli = TANGENT_CLI;

  EXPECT_EQ(runCommand(cli + " check " + quoted(clean)).exitCode, 0);
  const auto findings = runCommand(cli + " check " + quoted(clean) + " " + quoted(nonUnit));
  EXPECT_EQ(findings.exitCode, 1);
  EXPECT_NE(findings.output.find("FAIL unit: 1 of"), std::string::npos) << findings.output;
  EXPECT_NE(findings.output.find("non-unit.glb"), std::string::npos);
  EXPECT_EQ(runCommand(cli + " check " + quoted(dir / "nope.glb")).exitCode, 2);
  EXPECT_EQ(runCommand(cli + " check --format yaml " + quoted(clean)).exitCode, 2);
  EXPECT_EQ(runCommand(cli + " check --tolerance -1 " + quoted(clean)).exitCode, 2);

  const fs::path junit = dir / "report.xml";
  EXPECT_EQ(runCommand(cli + " check --format junit -o " + quoted(junit) + " " + quoted(clean) + " " + quoted(nonUnit) + " " +
                       quoted(missing)).exitCode, 1);
  // Parsed by Python's XML parser: a malformed document fails here.
  const std::string count = R"(import sys, xml.etree.ElementTree as ET
root = ET.parse(sys.argv[1]).getroot()
cases = root.findall('.//testcase')
print(len(cases), len(root.findall('.//failure')), len(root.findall('.//skipped')), root.get('failures'),
      ' '.join(c.get('name') for c in cases if c.find('failure') is not None))
)";
  std::ofstream(dir / "count.py") << count;
  const auto parsed = runCommand("python3 " + quoted(dir / "count.py") + " " + quoted(junit));
  ASSERT_EQ(parsed.exitCode, 0) << parsed.output;
  // One case per check and file (docs/check.md): clean, all pass; non-unit, one failure (unit);
  // missing, one failure (present) and every other check skipped (`present` gates the rest).
  const std::size_t checks = std::size(tangent::gltf::kCheckNames);
  EXPECT_EQ(parsed.output, std::to_string(3 * checks) + " 2 " + std::to_string(checks - 1) + " 2 unit present\n");

  const auto json = runCommand(cli + " check --format json " + quoted(nonUnit));
  EXPECT_EQ(json.exitCode, 1);
  const auto report = nlohmann::json::parse(json.output);
  EXPECT_EQ(report["schema"], "libtangent-check/2");
  EXPECT_EQ(report["files"][0]["status"], "findings");
  EXPECT_EQ(report["files"][0]["primitives"][0]["findings"][0]["check"], "unit");
  EXPECT_EQ(report["files"][0]["primitives"][0]["findings"][0]["worst"][0]["element"], 0);
}

}  // namespace
