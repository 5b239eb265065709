// SPDX-License-Identifier: MIT
// The `tangent` command as a pipeline calls it: exit codes, messages, malformed files from
// Debian's assimp-testmodels, no partial outputs, inputs never written.
#include <gtest/gtest.h>

#include <algorithm>

#include <array>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "support/run_command.hpp"
#include "support/skip_or_fail.hpp"
#include "support/temp_dir.hpp"
#include "support/test_assets.hpp"

namespace {

namespace fs = std::filesystem;
using tangent::testing::TempDir;

using CliRun = tangent::testing::CommandResult;

CliRun tangentCli(const std::string& arguments) { return tangent::testing::runCommand(std::string(TANGENT_CLI) + " " + arguments); }

std::string quoted(const fs::path& path) { return "'" + path.string() + "'"; }

std::vector<char> fileBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<char>(std::istreambuf_iterator<char>(in), {});
}

TEST(Cli, UsageErrorsExit2) {
  EXPECT_EQ(tangentCli("").exitCode, 2);
  EXPECT_EQ(tangentCli("frobnicate").exitCode, 2);
  EXPECT_EQ(tangentCli("bake").exitCode, 2);
  EXPECT_EQ(tangentCli("bake a.glb").exitCode, 2);  // no -o / --out-dir
  EXPECT_EQ(tangentCli("bake a.glb b.glb -o c.glb").exitCode, 2);
  EXPECT_EQ(tangentCli("bake a.glb -o c.glb --method mikk").exitCode, 2);
  EXPECT_EQ(tangentCli("bake a.glb -o c.glb --weighting heavy").exitCode, 2);
  EXPECT_EQ(tangentCli("bake a.glb -o c.glb --bogus").exitCode, 2);
  const CliRun help = tangentCli("bake --help");
  EXPECT_EQ(help.exitCode, 0);
  EXPECT_NE(help.output.find("--weighting"), std::string::npos);
}

TEST(Cli, MissingInputExit1AndNamesIt) {
  TempDir dir;
  const CliRun run = tangentCli("bake " + quoted(dir / "nope.glb") + " -o " + quoted(dir / "out.glb"));
  EXPECT_EQ(run.exitCode, 1);
  EXPECT_NE(run.output.find("nope.glb: no such file"), std::string::npos) << run.output;
  EXPECT_FALSE(fs::exists(dir / "out.glb"));
}

TEST(Cli, BakeWritesReportAndLeavesInputAlone) {
  TempDir dir;
  const auto assets = tangent::testing::makeTestAssets();
  const fs::path a = tangent::testing::writeAsset(assets[0], dir / "in", true);
  const fs::path b = tangent::testing::writeAsset(assets[3], dir / "in", false);
  const auto aBefore = fileBytes(a), bBefore = fileBytes(b);
  const CliRun run = tangentCli("bake " + quoted(a) + " " + quoted(b) + " --out-dir " + quoted(dir / "out") + " --report " + quoted(dir / "report.json"));
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_TRUE(fs::exists(dir / "out" / a.filename()));
  EXPECT_TRUE(fs::exists(dir / "out" / b.filename()));
  EXPECT_EQ(aBefore, fileBytes(a));
  EXPECT_EQ(bBefore, fileBytes(b));
  std::ifstream reportFile(dir / "report.json");
  const auto report = nlohmann::json::parse(reportFile);
  ASSERT_EQ(report.size(), 2u);
  EXPECT_EQ(report[0]["status"], "ok");
  EXPECT_EQ(report[0]["primitives"][0]["action"], "baked");
  // interleaved_ubyte is makeGrid(6, 6, mirrored columns): 7 x 7 = 49 vertices; u runs
  // 0,1,0,1... across the vertex columns, so the quads on either side of each of the 5
  // interior columns mirror each other and its 7 vertices need two frames: 35 more.
  const auto& primitive = report[0]["primitives"][0];
  EXPECT_EQ(primitive["tangents"]["splitVertices"].get<int>(), 35);
  EXPECT_EQ(primitive["verticesIn"].get<int>(), 49);
  EXPECT_EQ(primitive["verticesOut"].get<int>(), 84);
  EXPECT_EQ(report[0]["primitives"][0]["tangents"]["method"], "mikktspace");
}

// More threads than the machine runs: the same bytes as one thread, and no warning from the
// thread pool about workers it will not grant (64 is more than any machine CI runs on).
TEST(Cli, MoreThreadsThanTheMachineBakeTheSameBytesQuietly) {
  TempDir dir;
  const auto assets = tangent::testing::makeTestAssets();
  const fs::path in = tangent::testing::writeAsset(assets[0], dir / "in", true);
  const CliRun one = tangentCli("bake " + quoted(in) + " -o " + quoted(dir / "one.glb") + " --quiet --threads 1");
  ASSERT_EQ(one.exitCode, 0) << one.output;
  const CliRun many = tangentCli("bake " + quoted(in) + " -o " + quoted(dir / "many.glb") + " --quiet --threads 64");
  ASSERT_EQ(many.exitCode, 0) << many.output;
  EXPECT_EQ(many.output, "");
  EXPECT_EQ(fileBytes(dir / "one.glb"), fileBytes(dir / "many.glb"));
}

TEST(Cli, OneBadInputFailsOnlyItself) {
  TempDir dir;
  const auto assets = tangent::testing::makeTestAssets();
  const fs::path good = tangent::testing::writeAsset(assets[0], dir / "in", true);
  std::ofstream(dir / "in" / "bad.gltf") << "{\"asset\": 5}";
  const CliRun run = tangentCli("bake " + quoted(good) + " " + quoted(dir / "in" / "bad.gltf") + " --out-dir " + quoted(dir / "out") + " --quiet");
  EXPECT_EQ(run.exitCode, 1);
  EXPECT_NE(run.output.find("bad.gltf"), std::string::npos) << run.output;
  EXPECT_TRUE(fs::exists(dir / "out" / good.filename()));
  EXPECT_FALSE(fs::exists(dir / "out" / "bad.gltf"));
}

TEST(Cli, InfoDescribesNeeds) {
  TempDir dir;
  const auto assets = tangent::testing::makeTestAssets();
  const fs::path input = tangent::testing::writeAsset(assets[6], dir.path(), true);  // document_features
  const CliRun run = tangentCli("info " + quoted(input));
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("needs tangents"), std::string::npos);
  EXPECT_NE(run.output.find("no normalTexture"), std::string::npos);
  EXPECT_NE(run.output.find("mode 0 is not triangles"), std::string::npos);
  const CliRun json = tangentCli("info --json " + quoted(input));
  ASSERT_EQ(json.exitCode, 0);
  const auto parsed = nlohmann::json::parse(json.output);
  EXPECT_EQ(parsed["meshes"][0]["primitives"][0]["needsTangents"], true);
  EXPECT_EQ(parsed["meshes"][0]["primitives"][4]["hasTangents"], true);
}

// Malformed files from Debian's assimp-testmodels, each with the answer its defect calls for:
// exit 1 with a message naming the file and the defect, or, where the defect is in nothing the
// baker reads or writes anew, a clean bake (exit 0); never a crash, never a partial output,
// never a temporary file left behind.
TEST(Cli, MalformedFilesFromAssimpTestModels) {
  const fs::path root = "/usr/share/assimp/models/glTF2";
  if (!fs::is_directory(root)) TANGENT_SKIP_OR_FAIL(root << " is absent: install Debian's assimp-testmodels");
  struct Case {
    const char* file;
    int exitCode;
    const char* phrase;  // in the message (exit 1) or the summary (exit 0)
  };
  const Case cases[] = {
      {"IndexOutOfRange/IndexOutOfRange.gltf", 1, "index 255 at position 0 is out of range"},  // 24 vertices
      {"IndexOutOfRange/AllIndicesOutOfRange.gltf", 1, "index 65535 at position 0 is out of range"},
      {"MissingBin/BoxTextured.gltf", 1, "names a file that does not exist"},
      {"wrongTypes/badNumber.gltf", 1, "/materials/0/normalTexture/index: is required"},  // only a (string) scale
      {"wrongTypes/badExtension.gltf", 1, "KHR_texture_transform: must be an object"},
      {"wrongTypes/badObject.gltf", 1, "/materials/0/pbrMetallicRoughness: must be an object"},
      {"wrongTypes/badUint.gltf", 1, "refers to textures -1, which does not exist"},
      {"wrongTypes/badArray.gltf", 1, "/meshes/0/primitives: must be an array"},
      {"SchemaFailures/sceneWrongType.gltf", 1, "/scene: must be an index into scenes"},
      {"IncorrectVertexArrays/Cube.gltf", 1, "overruns buffer 0"},
      // A node's "name": 42: names are carried as they are, the mesh bakes.
      {"wrongTypes/badString.gltf", 0, "1 baked"},
      // Infinite positions or broken normals, but no TEXCOORD_0: nothing to bake, even with --all.
      {"BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb", 0, "1 skipped"},
      {"BoxBadNormals-glTF-Binary/BoxBadNormals.glb", 0, "1 skipped"}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.file);
    TempDir dir;
    const fs::path output = dir / ("out" + fs::path(c.file).extension().string());
    const CliRun run = tangentCli("bake " + quoted(root / c.file) + " -o " + quoted(output) + " --all");
    std::printf("%-50s exit %d: %s", c.file, run.exitCode, run.output.empty() ? "\n" : run.output.substr(0, run.output.find('\n') + 1).c_str());
    EXPECT_EQ(run.exitCode, c.exitCode) << run.output;
    EXPECT_NE(run.output.find(c.phrase), std::string::npos) << run.output;
    if (c.exitCode == 1) {
      EXPECT_NE(run.output.find("error: "), std::string::npos) << run.output;
      EXPECT_NE(run.output.find(fs::path(c.file).filename().string()), std::string::npos) << run.output;
      EXPECT_TRUE(fs::is_empty(dir.path())) << "partial output left";
    } else {
      EXPECT_TRUE(fs::exists(output));
    }
    for (const auto& entry : fs::directory_iterator(dir.path()))
      EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos) << entry.path();
  }
}

// Every model of Debian's assimp-testmodels the baker reads (glTF, OBJ, PLY, OFF), baked with
// --all, checks clean with check --all: one w per triangle, unit and orthogonal frames, the
// reference agreeing. Files the baker refuses are listed, never a failure of this test.
TEST(Cli, EveryAssimpTestModelBakedWithAllChecksClean) {
  const fs::path root = "/usr/share/assimp/models";
  if (!fs::is_directory(root)) TANGENT_SKIP_OR_FAIL(root << " is absent: install Debian's assimp-testmodels");
  int baked = 0, refused = 0;
  std::vector<std::string> failures;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    if (!entry.is_regular_file()) continue;
    std::string extension = entry.path().extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
    if (extension != ".gltf" && extension != ".glb" && extension != ".obj" && extension != ".ply" && extension != ".off") continue;
    if (entry.file_size() > 20u << 20) continue;  // the few huge scans: minutes under the sanitizers
    TempDir dir;
    const fs::path output = dir / "out.glb";
    const CliRun bake = tangentCli("bake " + quoted(entry.path()) + " -o " + quoted(output) + " --all -q");
    if (bake.exitCode != 0 || !fs::exists(output)) {
      ++refused;
      continue;
    }
    ++baked;
    const CliRun check = tangentCli("check --all " + quoted(output));
    if (check.exitCode != 0) failures.push_back(entry.path().string() + ":\n" + check.output.substr(0, 600));
  }
  std::printf("assimp-testmodels: %d baked and checked, %d refused by bake\n", baked, refused);
  // A regression pin, not a derived value: 37 is how many bake accepted with
  // assimp-testmodels 5.2.5 when this was written (a floor, so that a new refusal fails here
  // while a newly accepted model does not); the rest are glTF 1.0, Draco, refused as malformed
  // (indices out of range, references to nothing, node cycles, a PLY header with free text:
  // see tests/malformed), or OBJ files whose faces refer to no "vt" (OBJ/regr01.obj,
  // OBJ/multiple_spaces.obj: their UVs were uninitialized memory until they were refused).
  EXPECT_GE(baked, 37);
  for (const auto& failure : failures) ADD_FAILURE() << "check --all fails on the bake of " << failure;
}

}  // namespace
