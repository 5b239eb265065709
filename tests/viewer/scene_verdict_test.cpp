// SPDX-License-Identifier: MIT
// The viewer's display model judges each corner as `tangent check` does (issue 63): loadScene's
// cornerProblems and tangentErrorDegrees are checkCorners' verdicts, their counts are checkFile's
// findings and counts, and where check compared a corner the viewer's fresh tangent is check's
// reference. On the three cases where the viewer's own copy of the verdict disagreed: a corner
// whose w rounding leaves undecided, a primitive without NORMAL with a zero-area triangle, and a
// weighting other than the default.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include "support/run_command.hpp"
#include "support/skip_or_fail.hpp"
#include "support/temp_dir.hpp"
#include "support/test_assets.hpp"
#include "tangent/check.hpp"
#include "tangent/gltf.hpp"
#include "tangent/scene.hpp"
#include "tangent/verdict.hpp"
#include "check/tangent_rules.hpp"

namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;
using tangent::gltf::CheckOptions;
using tangent::gltf::CornerVerdict;
using tangent::gltf::DrawItem;
using tangent::gltf::ReferenceVerdict;
using tangent::testing::TempDir;

struct CornerCounts {
  std::size_t compared = 0, disagrees = 0, unresolved = 0, wUndecided = 0, problems = 0;
};

std::size_t findingCount(const tangent::gltf::PrimitiveCheck& p, const char* check) {
  for (const auto& f : p.findings)
    if (f.check == check) return f.failed;
  return 0;
}

// Every corner of every primitive check judges in `file`, the viewer's answer against check's;
// `counts` sums what check found (void: gtest's ASSERT returns).
void expectViewerJudgesAsCheck(const fs::path& file, const CheckOptions& options, CornerCounts& counts) {
  tangent::gltf::SceneOptions sceneOptions;
  sceneOptions.check = options;
  const tangent::gltf::Scene scene = tangent::gltf::loadScene(file, sceneOptions);
  const tangent::gltf::FileCheck report = tangent::gltf::checkFile(file, options);
  const std::vector<tangent::gltf::PrimitiveVerdicts> verdicts = tangent::gltf::checkCorners(file, options);
  for (const tangent::gltf::PrimitiveCheck& p : report.primitives) {
    SCOPED_TRACE("mesh " + std::to_string(p.mesh) + " primitive " + std::to_string(p.primitive));
    const tangent::gltf::PrimitiveIndex index{p.mesh, p.primitive};
    const auto item = std::find_if(scene.items.begin(), scene.items.end(), [&](const DrawItem& i) { return i.primitive == index; });
    const auto judged = std::find_if(verdicts.begin(), verdicts.end(), [&](const auto& v) { return v.primitive == index; });
    if (judged == verdicts.end()) {
      // present or format failed: no corner judged, none shown as judged.
      EXPECT_FALSE(p.findings.empty());
      if (item != scene.items.end()) {
        EXPECT_TRUE(std::all_of(item->cornerProblems.begin(), item->cornerProblems.end(), [](auto bits) { return bits == 0; }));
      }
      continue;
    }
    ASSERT_NE(item, scene.items.end());
    const std::vector<CornerVerdict>& corners = judged->corners;
    ASSERT_EQ(item->cornerProblems.size(), corners.size());
    std::size_t far = 0, unresolved = 0, undefined = 0, wUndecided = 0;
    std::vector<char> handednessTriangle(corners.size() / 3, 0);
    for (std::size_t c = 0; c < corners.size(); ++c) {
      const CornerVerdict& verdict = corners[c];
      EXPECT_EQ(item->cornerProblems[c], verdict.problems) << "corner " << c;
      EXPECT_EQ(item->tangentErrorDegrees[c], verdict.referenceDegrees) << "corner " << c;
      far += (item->cornerProblems[c] & tangent::gltf::kProblemFarFromReference) != 0;
      if (item->cornerProblems[c] & tangent::gltf::kProblemHandedness) handednessTriangle[c / 3] = 1;
      unresolved += verdict.reference == ReferenceVerdict::unresolved;
      undefined += verdict.reference == ReferenceVerdict::undefined;
      wUndecided += verdict.wUndecided;
      counts.problems += verdict.problems != 0;
      if (verdict.reference != ReferenceVerdict::agrees && verdict.reference != ReferenceVerdict::disagrees) continue;
      // The compare view's fresh set is what check compared with.
      const double angle = tangent::gltf::detail::angleBetweenDegrees(&item->tangents[4 * c], &item->computedTangents[4 * c]);
      EXPECT_EQ(static_cast<float>(angle), verdict.referenceDegrees) << "corner " << c;
      ++counts.compared;
    }
    EXPECT_EQ(far, findingCount(p, "reference"));
    EXPECT_EQ(static_cast<std::size_t>(std::count(handednessTriangle.begin(), handednessTriangle.end(), 1)), findingCount(p, "handedness"));
    EXPECT_EQ(unresolved, p.referenceUnresolved);
    EXPECT_EQ(undefined, p.referenceUndefined);
    EXPECT_EQ(wUndecided, p.referenceWUndecided);
    counts.disagrees += far;
    counts.unresolved += unresolved;
    counts.wUndecided += wUndecided;
  }
}

// A baked UV sphere, and NormalTangentMirrorTest where ../shared/assets has it, through gltfpack
// -vt 8: 8-bit UVs leave the UV orientation of many small triangles undecided. check compares
// their corners on the angle alone where w agrees and calls the others unresolved; the viewer's
// copy flagged one corner of NormalTangentMirrorTest's as far from the reference.
TEST(SceneVerdict, AWUndecidedAfterRoundingIsJudgedAsCheckJudgesIt) {
  if (tangent::testing::runCommand("command -v gltfpack").exitCode != 0)
    TANGENT_SKIP_OR_FAIL("gltfpack is not installed (scripts/install-deps.sh): the rounded-UV case was not tested");
  TempDir dir;
  std::vector<fs::path> sources = {
      tangent::testing::writeAsset(tangent::testing::meshAsset("sphere", tangent::testing::makeSphere(64, 64)), dir / "in", true)};
  if (const fs::path shared = tangent::testing::sharedAssets(); !shared.empty())
    sources.push_back(shared / "NormalTangentMirrorTest.glb");
  for (const fs::path& source : sources) {
    SCOPED_TRACE(source.string());
    const fs::path baked = dir / (source.stem().string() + "-baked.glb"), packed = dir / (source.stem().string() + "-vt8.glb");
    tangent::gltf::bakeFile(source, baked, {});
    const auto pack = tangent::testing::runCommand("gltfpack -i '" + baked.string() + "' -o '" + packed.string() + "' -vt 8");
    ASSERT_EQ(pack.exitCode, 0) << pack.output;
    CornerCounts counts;
    expectViewerJudgesAsCheck(packed, tangent::gltf::viewerCheckOptions(), counts);
    EXPECT_GT(counts.wUndecided, 0u) << "no corner compared with its w undecided";
    EXPECT_GT(counts.unresolved, 0u) << "no corner left unresolved";
    EXPECT_GT(counts.compared, 0u);
  }
}

// A grid with a zero-area triangle (three points on a line, with UV area), baked with flat
// normals and then stripped of NORMAL: check judges it against the flat normals bake generated
// (withGeneratedNormals, +Z for the zero-area triangle), and so does the viewer now, where it
// computed its own float face normals (zero for that triangle).
TEST(SceneVerdict, APrimitiveWithoutNormalWithAZeroAreaTriangleIsJudgedAsCheckJudgesIt) {
  TempDir dir;
  tangent::testing::GridMesh mesh = tangent::testing::makeGrid(4, 4, false);
  const auto first = static_cast<std::uint32_t>(mesh.positions.size() / 3);
  for (int k = 0; k < 3; ++k) {
    mesh.positions.insert(mesh.positions.end(), {0.25f * float(k), 2.0f, 0.0f});
    mesh.normals.insert(mesh.normals.end(), {0.0f, 0.0f, 1.0f});
  }
  mesh.uvs.insert(mesh.uvs.end(), {0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 1.0f});
  mesh.indices.insert(mesh.indices.end(), {first, first + 1, first + 2});
  const fs::path source = tangent::testing::writeAsset(tangent::testing::meshAsset("flat", mesh, false), dir / "in", false);
  const fs::path baked = dir / "flat.gltf";
  tangent::gltf::bakeFile(source, baked, {});
  Json doc = Json::parse(std::ifstream(baked));
  for (Json& primitive : doc["meshes"][0]["primitives"]) primitive["attributes"].erase("NORMAL");
  std::ofstream(baked) << doc.dump();

  CornerCounts counts;
  expectViewerJudgesAsCheck(baked, tangent::gltf::viewerCheckOptions(), counts);
  EXPECT_GT(counts.compared, 0u);
  const tangent::gltf::Scene scene = tangent::gltf::loadScene(baked);
  ASSERT_EQ(scene.items.size(), 1u);
  const DrawItem& item = scene.items[0];
  const std::size_t last = item.positions.size() / 9 - 1;  // the zero-area triangle, last as written
  ASSERT_EQ(tangent::gltf::detail::areaTimesTwo(&item.positions[9 * last], &item.positions[9 * last + 3], &item.positions[9 * last + 6]), 0.0);
  for (int k = 0; k < 3; ++k)
    EXPECT_EQ(std::vector<float>(&item.normals[9 * last + 3 * k], &item.normals[9 * last + 3 * k + 3]), (std::vector<float>{0, 0, 1}));
}

// Every generated test asset, baked and then stripped of NORMAL: the viewer reads the geometry as
// check does (the normal texture's KHR_texture_transform applied: it read raw UVs without NORMAL)
// and judges with check's rounding allowance (it had none without NORMAL).
TEST(SceneVerdict, EveryGeneratedAssetWithoutNormalIsJudgedAsCheckJudgesIt) {
  TempDir dir;
  CornerCounts counts;
  for (const tangent::testing::TestAsset& asset : tangent::testing::makeTestAssets()) {
    SCOPED_TRACE(asset.name);
    const fs::path source = tangent::testing::writeAsset(asset, dir / "in", false);
    const fs::path baked = dir / (asset.name + "-baked.gltf");
    tangent::gltf::bakeFile(source, baked, {});
    Json doc = Json::parse(std::ifstream(baked));
    for (Json& mesh : doc["meshes"])
      for (Json& primitive : mesh["primitives"]) primitive["attributes"].erase("NORMAL");
    std::ofstream(baked) << doc.dump();
    expectViewerJudgesAsCheck(baked, tangent::gltf::viewerCheckOptions(), counts);
  }
  EXPECT_GT(counts.compared, 0u);
  EXPECT_GT(counts.problems, 0u) << "smooth-normal bakes judged against flat normals flag nothing: the fixture tests nothing";
}

// check --reference lengyel/area on a bake with that weighting: clean, and the viewer, given the
// same options, agrees corner for corner; its fresh tangents are lengyel/area's, not MikkTSpace's.
TEST(SceneVerdict, ANonDefaultWeightingIsJudgedAsCheckJudgesIt) {
  TempDir dir;
  const fs::path source =
      tangent::testing::writeAsset(tangent::testing::meshAsset("leaning", tangent::testing::leaningGrid()), dir / "in", true);
  const fs::path baked = dir / "leaning-area.glb";
  tangent::gltf::BakeOptions bake;
  bake.tangents.method = tangent::Method::lengyel;
  bake.tangents.weighting = tangent::Weighting::area;
  tangent::gltf::bakeFile(source, baked, bake);
  CheckOptions options = tangent::gltf::viewerCheckOptions();
  options.method = tangent::Method::lengyel;
  options.weighting = tangent::Weighting::area;
  ASSERT_TRUE(tangent::gltf::checkFile(baked, options).clean());
  CornerCounts area, mikktspace;
  expectViewerJudgesAsCheck(baked, options, area);
  EXPECT_EQ(area.problems, 0u);
  EXPECT_GT(area.compared, 0u);
  // Against MikkTSpace the same bake differs somewhere, and the viewer says so where check does.
  expectViewerJudgesAsCheck(baked, tangent::gltf::viewerCheckOptions(), mikktspace);
  EXPECT_GT(mikktspace.disagrees, 0u) << "the weightings give the same frames here: the fixture tests nothing";
}

}  // namespace
