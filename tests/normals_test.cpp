// SPDX-License-Identifier: MIT
// NORMAL as glTF readers treat it (issue 37, item 1): normals further than kNormalLengthKept
// from unit length are normalized before the core sees them, so any nonzero length gives the
// tangents of the unit normal; zero normals keep the core's fallback; check warns (and does not
// fail) on non-unit NORMAL, naming the worst length.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>

#include "read/accessors.hpp"
#include "read/asset.hpp"
#include "read/normals.hpp"
#include "support/temp_dir.hpp"
#include "support/test_assets.hpp"
#include "tangent/check.hpp"
#include "tangent/gltf.hpp"
#include "check/tangent_rules.hpp"

namespace {

namespace fs = std::filesystem;
namespace detail = tangent::gltf::detail;
using tangent::testing::GridMesh;
using tangent::testing::TempDir;

TEST(NormalLengths, NormalizesExactlyThoseBeyondTheThreshold) {
  // By hand: (0, 0, L) has length L. Within 5e-5 of 1 the bits stay; beyond, the result is
  // (0, 0, 1) exactly; zero is counted and left for the core.
  std::vector<float> normals = {0, 0, 1.00004f, 0, 0, 0.99996f, 0, 0, 1.0001f, 0, 0, 0.0625f, 3, 0, 4, 0, 0, 0};
  const std::vector<float> before = normals;
  const detail::NormalLengths found = detail::unitNormals(normals);
  EXPECT_EQ(normals[2], before[2]);
  EXPECT_EQ(normals[5], before[5]);
  EXPECT_EQ(normals[8], 1.0f);
  EXPECT_EQ(normals[11], 1.0f);
  EXPECT_EQ(normals[12], 0.6f);
  EXPECT_EQ(normals[14], 0.8f);
  EXPECT_EQ(normals[17], 0.0f);
  EXPECT_EQ(found.normalized, 3u);
  EXPECT_EQ(found.zero, 1u);
  EXPECT_DOUBLE_EQ(found.worstLength, 5.0);
  EXPECT_FALSE(detail::normalNeedsNormalizing(1 + 4e-5));
  EXPECT_TRUE(detail::normalNeedsNormalizing(1 - 1e-4));
}

// The TANGENT a bake of `mesh` writes, 4 floats per output vertex.
std::vector<float> bakedTangents(const GridMesh& mesh, const fs::path& dir, const std::string& name,
                                 tangent::gltf::BakeResult* result = nullptr) {
  const fs::path input = tangent::testing::writeAsset(tangent::testing::meshAsset(name, mesh), dir / "in", true);
  const fs::path output = dir / (name + "-baked.glb");
  const tangent::gltf::BakeResult baked = tangent::gltf::bakeFile(input, output, {});
  if (result) *result = baked;
  const detail::Asset asset = detail::loadAsset(output);
  const int accessor = asset.json["meshes"][0]["primitives"][0]["attributes"]["TANGENT"].get<int>();
  return detail::toFloats(detail::readAccessor(asset.model, accessor, "TANGENT"));
}

double angleDegrees(const float* a, const float* b) { return detail::angleBetweenDegrees(a, b); }

TEST(NormalLengths, AnyNonzeroLengthGivesTheTangentsOfUnitNormals) {
  TempDir dir;
  const std::vector<std::pair<std::string, GridMesh>> meshes = {{"leaning", tangent::testing::leaningGrid()},
                                                                {"torus", tangent::testing::makeTorus(16, 8)},
                                                                {"sphere", tangent::testing::makeSphere(12, 6)}};
  for (const auto& [name, mesh] : meshes) {
    const std::vector<float> unit = bakedTangents(mesh, dir.path(), name + "-unit");
    for (const double length : {1.0 / 16, 0.5, 1 - 1e-4, 1 + 1e-4, 4.0}) {
      GridMesh scaled = mesh;
      for (float& n : scaled.normals) n = static_cast<float>(n * length);
      const std::string label = name + "-" + std::to_string(length);
      const std::vector<float> tangents = bakedTangents(scaled, dir.path(), label);
      ASSERT_EQ(tangents.size(), unit.size()) << label;
      double worst = 0;
      for (std::size_t v = 0; v < unit.size() / 4; ++v) {
        worst = std::max(worst, angleDegrees(&tangents[4 * v], &unit[4 * v]));
        EXPECT_EQ(tangents[4 * v + 3], unit[4 * v + 3]) << label << " vertex " << v;
      }
      EXPECT_LE(worst, 1e-5) << label;

      // check on the file with the stored (non-unit) NORMAL: clean, with a warning naming the length.
      const tangent::gltf::FileCheck check = tangent::gltf::checkFile(dir / (label + "-baked.glb"), {});
      ASSERT_EQ(check.primitives.size(), 1u) << label;
      const tangent::gltf::PrimitiveCheck& p = check.primitives[0];
      EXPECT_TRUE(check.clean()) << label;
      EXPECT_NEAR(p.worstNormalLength, length, 1e-6) << label;
      EXPECT_EQ(p.normalsNormalized, p.vertices) << label;  // every vertex, split ones included
      ASSERT_EQ(p.warnings.size(), 1u) << label;
      EXPECT_NE(p.warnings[0].find("NORMAL is not unit length"), std::string::npos) << p.warnings[0];
    }
  }
}

TEST(NormalLengths, UnitNormalsAreNotWarnedAbout) {
  TempDir dir;
  bakedTangents(tangent::testing::makeTorus(16, 8), dir.path(), "torus");
  const tangent::gltf::FileCheck check = tangent::gltf::checkFile(dir / "torus-baked.glb", {});
  ASSERT_EQ(check.primitives.size(), 1u);
  EXPECT_TRUE(check.primitives[0].warnings.empty());
  EXPECT_EQ(check.primitives[0].normalsNormalized, 0u);
}

TEST(NormalLengths, ZeroNormalsKeepTheFallback) {
  TempDir dir;
  GridMesh mesh = tangent::testing::makeGrid(4, 4, false);
  const std::uint32_t vertex = mesh.indices[0];
  for (int k = 0; k < 3; ++k) mesh.normals[3 * vertex + k] = 0;
  tangent::gltf::BakeResult result;
  const std::vector<float> tangents = bakedTangents(mesh, dir.path(), "zero", &result);
  ASSERT_EQ(result.primitives.size(), 1u);
  EXPECT_GT(result.primitives[0].tangents.invalidNormals, 0u);
  for (std::size_t v = 0; v < tangents.size() / 4; ++v) {
    EXPECT_NEAR(detail::length3(&tangents[4 * v]), 1.0, 1e-5) << v;
  }
  EXPECT_FALSE(result.warnings.empty());
}

}  // namespace

// ---- bake --normals (issue 37, item 2) ----

namespace generated {

struct Baked {
  std::vector<float> positions, normals;
  std::vector<std::uint32_t> corners;
  tangent::gltf::BakeResult result;
  fs::path output;
};

void readBaked(Baked& baked);

Baked bakeWithoutNormals(const GridMesh& mesh, const fs::path& dir, const std::string& name, tangent::gltf::NormalsMode mode) {
  Baked baked;
  const fs::path input = tangent::testing::writeAsset(tangent::testing::meshAsset(name, mesh, false), dir / "in", true);
  baked.output = dir / (name + "-baked.glb");
  tangent::gltf::BakeOptions options;
  options.normals = mode;
  baked.result = tangent::gltf::bakeFile(input, baked.output, options);
  readBaked(baked);
  return baked;
}

// The baked file's POSITION, NORMAL (when written) and triangle list.
void readBaked(Baked& baked) {
  const detail::Asset asset = detail::loadAsset(baked.output);
  const auto& primitive = asset.json["meshes"][0]["primitives"][0];
  if (!primitive["attributes"].contains("NORMAL")) return;
  baked.positions = detail::toFloats(detail::readAccessor(asset.model, primitive["attributes"]["POSITION"].get<int>(), "POSITION"));
  baked.normals = detail::toFloats(detail::readAccessor(asset.model, primitive["attributes"]["NORMAL"].get<int>(), "NORMAL"));
  const auto indices = detail::readAccessor(asset.model, primitive["indices"].get<int>(), "indices");
  for (const float index : detail::toFloats(indices)) baked.corners.push_back(static_cast<std::uint32_t>(index));
}

TEST(GeneratedNormals, FlatNormalsAreTheFaceNormalsAndCheckClean) {
  TempDir dir;
  const Baked baked = bakeWithoutNormals(tangent::testing::makeTorus(12, 6), dir.path(), "torus", tangent::gltf::NormalsMode::flat);
  ASSERT_EQ(baked.result.primitives.size(), 1u);
  const auto& p = baked.result.primitives[0];
  EXPECT_EQ(p.action, tangent::gltf::PrimitiveAction::baked) << p.reason;
  ASSERT_TRUE(p.normalsGenerated.has_value());
  EXPECT_EQ(*p.normalsGenerated, tangent::gltf::NormalsMode::flat);
  ASSERT_FALSE(baked.normals.empty());
  ASSERT_EQ(baked.corners.size(), 12u * 6 * 6);
  // glTF 2.0 3.7.2.1: counter-clockwise front faces, so the face normal is cross(p1 - p0, p2 - p0).
  for (std::size_t t = 0; t < baked.corners.size() / 3; ++t) {
    const float* p0 = &baked.positions[3 * baked.corners[3 * t]];
    const float* p1 = &baked.positions[3 * baked.corners[3 * t + 1]];
    const float* p2 = &baked.positions[3 * baked.corners[3 * t + 2]];
    const double e1[3] = {double(p1[0]) - p0[0], double(p1[1]) - p0[1], double(p1[2]) - p0[2]};
    const double e2[3] = {double(p2[0]) - p0[0], double(p2[1]) - p0[1], double(p2[2]) - p0[2]};
    double face[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    const double length = std::sqrt(face[0] * face[0] + face[1] * face[1] + face[2] * face[2]);
    for (double& f : face) f /= length;
    for (int k = 0; k < 3; ++k) {
      const float* n = &baked.normals[3 * baked.corners[3 * t + k]];
      for (int i = 0; i < 3; ++i) EXPECT_NEAR(n[i], face[i], 1e-6) << "triangle " << t << " corner " << k;
    }
  }
  const tangent::gltf::FileCheck check = tangent::gltf::checkFile(baked.output, {});
  ASSERT_EQ(check.primitives.size(), 1u);
  EXPECT_TRUE(check.clean());
  const nlohmann::ordered_json report = tangent::gltf::toJson(baked.result);
  EXPECT_EQ(report["primitives"][0]["normalsGenerated"], "flat");
}

TEST(GeneratedNormals, SmoothNormalsOnASphereFollowTheSurface) {
  TempDir dir;
  const Baked baked = bakeWithoutNormals(tangent::testing::makeSphere(32, 16), dir.path(), "sphere", tangent::gltf::NormalsMode::smooth);
  ASSERT_FALSE(baked.normals.empty());
  // A unit sphere about the origin: the analytic normal is the position.
  double worst = 0;
  for (std::size_t v = 0; v < baked.positions.size() / 3; ++v) {
    const double angle = angleDegrees(&baked.normals[3 * v], &baked.positions[3 * v]);
    if (angle > 0.5) ADD_FAILURE() << "vertex " << v << " at (" << baked.positions[3 * v] << ", " << baked.positions[3 * v + 1] << ", " << baked.positions[3 * v + 2] << "): " << angle << " deg";
    worst = std::max(worst, angle);
  }
  EXPECT_LE(worst, 0.5);
  EXPECT_TRUE(tangent::gltf::checkFile(baked.output, {}).clean());
}

TEST(GeneratedNormals, KeepLeavesThePrimitiveAsItIs) {
  TempDir dir;
  const Baked baked = bakeWithoutNormals(tangent::testing::makeTorus(12, 6), dir.path(), "torus", tangent::gltf::NormalsMode::keep);
  ASSERT_EQ(baked.result.primitives.size(), 1u);
  EXPECT_EQ(baked.result.primitives[0].action, tangent::gltf::PrimitiveAction::skipped);
  EXPECT_TRUE(baked.normals.empty());
}

// The .glb at `path` with NORMAL taken out of mesh 0 primitive 0 (the bytes stay; the accessor
// is then unused, which glTF allows).
void removeNormal(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::vector<char> bytes((std::istreambuf_iterator<char>(in)), {});
  in.close();
  std::uint32_t jsonLength = 0;
  std::memcpy(&jsonLength, &bytes[12], 4);
  nlohmann::ordered_json json = nlohmann::ordered_json::parse(bytes.begin() + 20, bytes.begin() + 20 + jsonLength);
  json["meshes"][0]["primitives"][0]["attributes"].erase("NORMAL");
  std::string text = json.dump();
  while (text.size() % 4) text += ' ';
  const std::vector<char> rest(bytes.begin() + 20 + jsonLength, bytes.end());
  const std::uint32_t header[5] = {0x46546C67, 2, static_cast<std::uint32_t>(20 + text.size() + rest.size()),
                                   static_cast<std::uint32_t>(text.size()), 0x4E4F534A};
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(header), sizeof header);
  out << text;
  out.write(rest.data(), static_cast<std::streamsize>(rest.size()));
}

TEST(GeneratedNormals, CheckWithoutNormalUsesTheSpecsFlatNormals) {
  TempDir dir;
  // Tangents baked from flat normals, NORMAL then removed: clean against the spec's flat normals.
  const Baked flat = bakeWithoutNormals(tangent::testing::makeTorus(12, 6), dir.path(), "flat", tangent::gltf::NormalsMode::flat);
  removeNormal(flat.output);
  const tangent::gltf::FileCheck clean = tangent::gltf::checkFile(flat.output, {});
  ASSERT_EQ(clean.primitives.size(), 1u) << "a primitive without NORMAL is checked, not skipped";
  EXPECT_TRUE(clean.clean());
  // Tangents baked from smooth normals, NORMAL removed: they leave the faces' planes.
  const Baked smooth = bakeWithoutNormals(tangent::testing::makeTorus(12, 6), dir.path(), "smooth", tangent::gltf::NormalsMode::smooth);
  removeNormal(smooth.output);
  const tangent::gltf::FileCheck failing = tangent::gltf::checkFile(smooth.output, {});
  ASSERT_EQ(failing.primitives.size(), 1u);
  std::vector<std::string> failed;
  for (const auto& f : failing.primitives[0].findings) failed.push_back(f.check);
  EXPECT_NE(std::find(failed.begin(), failed.end(), "orthogonal"), failed.end());
  EXPECT_NE(std::find(failed.begin(), failed.end(), "reference"), failed.end());
}

// OBJ, PLY and OFF without normals get them as a glTF primitive without NORMAL does (flat by
// default, as glTF 3.7.2.1 asks and as Blender's OBJ importer shades a mesh without normals;
// --normals smooth and keep alike). Two triangles folded along the diagonal (0,0,0)-(1,1,0):
// face normals (0, 0, 1) and (1, -1, 1)/sqrt(3), 54.7 deg apart, within the default crease angle.
const char* kBentObj =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 1\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n";
const char* kBentPly =
    "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nproperty float u\n"
    "property float v\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n"
    "0 0 0 0 0\n1 0 0 1 0\n1 1 0 1 1\n0 1 1 0 1\n3 0 1 2\n3 0 2 3\n";
const char* kBentOff = "STOFF\n4 2 0\n0 0 0 0 0\n1 0 0 1 0\n1 1 0 1 1\n0 1 1 0 1\n3 0 1 2\n3 0 2 3\n";

Baked bakeMeshFile(const fs::path& input, const fs::path& output, tangent::gltf::NormalsMode mode) {
  Baked baked;
  baked.output = output;
  tangent::gltf::BakeOptions options;
  options.normals = mode;
  baked.result = tangent::gltf::bakeFile(input, output, options);
  readBaked(baked);
  return baked;
}

TEST(GeneratedNormals, MeshFilesWithoutNormalsAreFlatByDefault) {
  TempDir dir;
  const double third = 1 / std::sqrt(3.0);
  const double faceNormals[2][3] = {{0, 0, 1}, {third, -third, third}};
  for (const auto& [name, text] : {std::pair{"bent.obj", kBentObj}, std::pair{"bent.ply", kBentPly}, std::pair{"bent.off", kBentOff}}) {
    SCOPED_TRACE(name);
    std::ofstream(dir / name) << text;
    const Baked baked = bakeMeshFile(dir / name, dir / (std::string(name) + ".glb"), tangent::gltf::NormalsMode::flat);
    ASSERT_EQ(baked.result.primitives.size(), 1u);
    const auto& p = baked.result.primitives[0];
    EXPECT_EQ(p.action, tangent::gltf::PrimitiveAction::baked) << p.reason;
    ASSERT_TRUE(p.normalsGenerated.has_value()) << p.reason;
    EXPECT_EQ(*p.normalsGenerated, tangent::gltf::NormalsMode::flat);
    ASSERT_EQ(baked.corners.size(), 6u);
    EXPECT_EQ(baked.positions.size(), 6u * 3);  // the two diagonal vertices split
    for (std::size_t c = 0; c < 6; ++c)
      for (int i = 0; i < 3; ++i) EXPECT_NEAR(baked.normals[3 * baked.corners[c] + i], faceNormals[c / 3][i], 1e-6) << "corner " << c;
    tangent::gltf::CheckOptions every;  // these formats have no materials: every primitive gets tangents
    every.all = true;
    const tangent::gltf::FileCheck check = tangent::gltf::checkFile(baked.output, every);
    ASSERT_EQ(check.primitives.size(), 1u);
    EXPECT_TRUE(check.clean());
  }
}

TEST(GeneratedNormals, MeshFilesWithoutNormalsSmoothOrKept) {
  TempDir dir;
  std::ofstream(dir / "bent.obj") << kBentObj;
  const Baked smooth = bakeMeshFile(dir / "bent.obj", dir / "smooth.glb", tangent::gltf::NormalsMode::smooth);
  ASSERT_EQ(smooth.result.primitives.size(), 1u);
  ASSERT_TRUE(smooth.result.primitives[0].normalsGenerated.has_value());
  EXPECT_EQ(*smooth.result.primitives[0].normalsGenerated, tangent::gltf::NormalsMode::smooth);
  ASSERT_EQ(smooth.positions.size(), 4u * 3);  // nothing split
  // On the diagonal both faces meet with corner angles 45 deg (first) and 60 deg (second) at
  // either end: the normal is their angle-weighted sum, normalized (Thuermer and Wuethrich).
  const double third = 1 / std::sqrt(3.0);
  double sum[3] = {M_PI / 3 * third, -M_PI / 3 * third, M_PI / 4 + M_PI / 3 * third};
  const double length = std::sqrt(sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]);
  for (std::size_t v = 0; v < 4; ++v) {
    const float* position = &smooth.positions[3 * v];
    const bool onDiagonal = position[0] == position[1] && position[2] == 0;
    const double expected[3] = {onDiagonal ? sum[0] / length : position[2] == 0 ? 0 : third,
                                onDiagonal ? sum[1] / length : position[2] == 0 ? 0 : -third,
                                onDiagonal ? sum[2] / length : position[2] == 0 ? 1 : third};
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(smooth.normals[3 * v + i], expected[i], 1e-6) << "vertex " << v;
  }
  tangent::gltf::CheckOptions every;
  every.all = true;
  const tangent::gltf::FileCheck check = tangent::gltf::checkFile(smooth.output, every);
  ASSERT_EQ(check.primitives.size(), 1u);
  EXPECT_TRUE(check.clean());

  const Baked kept = bakeMeshFile(dir / "bent.obj", dir / "kept.glb", tangent::gltf::NormalsMode::keep);
  ASSERT_EQ(kept.result.primitives.size(), 1u);
  EXPECT_EQ(kept.result.primitives[0].action, tangent::gltf::PrimitiveAction::skipped);
  EXPECT_TRUE(kept.normals.empty());
}

}  // namespace generated

// ---- check --identify (issue 37, item 3) ----

namespace identify {

TEST(Identify, NamesTheGeneratorEachBakeUsed) {
  TempDir dir;
  // Jittered UVs and leaning normals, so that the weightings give different frames.
  const fs::path input = tangent::testing::writeAsset(tangent::testing::meshAsset("leaning", tangent::testing::leaningGrid()), dir / "in", true);
  const std::vector<std::pair<std::string, tangent::Options>> generators = {
      {"mikktspace", {tangent::Method::mikktspace, tangent::Weighting::angle}},
      {"lengyel/angle", {tangent::Method::lengyel, tangent::Weighting::angle}},
      {"lengyel/area", {tangent::Method::lengyel, tangent::Weighting::area}},
      {"lengyel/uniform", {tangent::Method::lengyel, tangent::Weighting::uniform}},
      {"flat", {tangent::Method::flat, tangent::Weighting::angle}},
      {"meshopt", {tangent::Method::meshopt, tangent::Weighting::angle}}};
  tangent::gltf::CheckOptions options;
  options.identify = true;
  options.enabled.reset();  // only the identification: a lengyel bake fails the mikktspace reference
  int index = 0;
  for (const auto& [name, method] : generators) {
    tangent::gltf::BakeOptions bake;
    bake.tangents = method;
    const fs::path output = dir / ("leaning-" + std::to_string(index++) + ".glb");
    tangent::gltf::bakeFile(input, output, bake);
    const tangent::gltf::FileCheck check = tangent::gltf::checkFile(output, options);
    ASSERT_EQ(check.primitives.size(), 1u);
    EXPECT_EQ(check.primitives[0].generator, name);
    ASSERT_EQ(check.primitives[0].generators.size(), generators.size());
    EXPECT_EQ(check.primitives[0].generators[0].medianDegrees, 0.0) << name;  // the same computation, the same bits
    EXPECT_GT(check.primitives[0].generators[1].medianDegrees, 0.0) << name;
  }
}

TEST(Identify, RandomlyTurnedTangentsAreNoneOfThese) {
  TempDir dir;
  const fs::path input = tangent::testing::writeAsset(tangent::testing::meshAsset("torus", tangent::testing::makeTorus(16, 8)), dir / "in", true);
  const fs::path output = dir / "torus.glb";
  tangent::gltf::bakeFile(input, output, {});
  // Each stored tangent turned about its normal by a pseudo-random angle of 5 to 85 degrees.
  std::ifstream in(output, std::ios::binary);
  std::vector<char> bytes((std::istreambuf_iterator<char>(in)), {});
  in.close();
  std::uint32_t jsonLength = 0;
  std::memcpy(&jsonLength, &bytes[12], 4);
  const nlohmann::ordered_json json = nlohmann::ordered_json::parse(bytes.begin() + 20, bytes.begin() + 20 + jsonLength);
  const auto& attributes = json["meshes"][0]["primitives"][0]["attributes"];
  auto floatsAt = [&](int accessor) {
    const auto& a = json["accessors"][accessor];
    const auto& view = json["bufferViews"][a["bufferView"].get<int>()];
    return reinterpret_cast<float*>(&bytes[20 + jsonLength + 8 + view.value("byteOffset", 0) + a.value("byteOffset", 0)]);
  };
  float* tangents = floatsAt(attributes["TANGENT"].get<int>());
  const float* normals = floatsAt(attributes["NORMAL"].get<int>());
  const std::size_t count = json["accessors"][attributes["TANGENT"].get<int>()]["count"].get<std::size_t>();
  for (std::size_t v = 0; v < count; ++v) {
    float* t = &tangents[4 * v];
    const float* n = &normals[3 * v];
    const double angle = (5 + 80 * std::fmod(v * 0.618034, 1.0)) / detail::kDegreesPerRadian;
    const double cross[3] = {n[1] * t[2] - n[2] * t[1], n[2] * t[0] - n[0] * t[2], n[0] * t[1] - n[1] * t[0]};
    for (int k = 0; k < 3; ++k) t[k] = static_cast<float>(t[k] * std::cos(angle) + cross[k] * std::sin(angle));
  }
  std::ofstream out(output, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  tangent::gltf::CheckOptions options;
  options.identify = true;
  const tangent::gltf::FileCheck check = tangent::gltf::checkFile(output, options);
  ASSERT_EQ(check.primitives.size(), 1u);
  EXPECT_EQ(check.primitives[0].generator.rfind("none of these (nearest: ", 0), 0u) << check.primitives[0].generator;
  EXPECT_GT(check.primitives[0].generators[0].medianDegrees, tangent::gltf::kIdentifyMedianDegrees);
}

// check --reference NAME: each generator's bake passes `reference` measured against that
// generator and fails it against at least one other (the leaning grid makes them differ).
TEST(Identify, ReferenceMeasuresAgainstTheChosenGenerator) {
  TempDir dir;
  const fs::path input = tangent::testing::writeAsset(tangent::testing::meshAsset("leaning", tangent::testing::leaningGrid()), dir / "in", true);
  int index = 0;
  for (const tangent::gltf::Generator& baked : tangent::gltf::kGenerators) {
    tangent::gltf::BakeOptions bake;
    bake.tangents.method = baked.method;
    bake.tangents.weighting = baked.weighting;
    const fs::path output = dir / ("leaning-" + std::to_string(index++) + ".glb");
    tangent::gltf::bakeFile(input, output, bake);
    int failedAgainstOthers = 0;
    for (const tangent::gltf::Generator& reference : tangent::gltf::kGenerators) {
      const std::string label = tangent::gltf::toString(baked) + " against " + tangent::gltf::toString(reference);
      const std::optional<tangent::gltf::Generator> parsed = tangent::gltf::parseGenerator(tangent::gltf::toString(reference));
      ASSERT_TRUE(parsed.has_value()) << label;
      tangent::gltf::CheckOptions options;
      options.method = parsed->method;
      options.weighting = parsed->weighting;
      const tangent::gltf::FileCheck check = tangent::gltf::checkFile(output, options);
      ASSERT_EQ(check.primitives.size(), 1u) << label;
      bool referenceFailed = false;
      for (const auto& f : check.primitives[0].findings) {
        referenceFailed = referenceFailed || f.check == "reference";
        if (f.check == "reference") {
          EXPECT_NE(f.message.find(tangent::gltf::toString(reference) + " tangents"), std::string::npos) << f.message;
        }
      }
      if (reference == baked) {
        EXPECT_FALSE(referenceFailed) << label;
      } else {
        failedAgainstOthers += referenceFailed;
      }
    }
    EXPECT_GE(failedAgainstOthers, 1) << tangent::gltf::toString(baked);
  }
  EXPECT_FALSE(tangent::gltf::parseGenerator("lengyel/volume").has_value());
  EXPECT_EQ(tangent::gltf::parseGenerator("lengyel"), (tangent::gltf::Generator{tangent::Method::lengyel, tangent::Weighting::angle}));
}

}  // namespace identify
