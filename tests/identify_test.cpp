// SPDX-License-Identifier: MIT
// `tangent check --identify` as a confusion matrix (issue 37): files whose tangents come from
// each generator the library has (bake --method/--weighting) and from the peers in
// ../shared/peers compiled beside the tests (the reference MikkTSpace C, meshoptimizer 1.2's
// meshopt_generateTangents in its compatible and default modes, through tools/bench/peers.cpp),
// each identified. The library's bakes must name themselves; the reference C and meshoptimizer's
// compatible mode (which aims at MikkTSpace's results) must be named mikktspace, and its
// default mode meshopt (the library's own writing of that weighting). Beside the matrix: npm
// `mikktspace` through `gltf-transform tangents` is named mikktspace. (Tangents turned about
// their normals are "none of these": Identify.RandomlyTurnedTangentsAreNoneOfThese.)
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstdio>
#include <map>
#include <tuple>

#include "peers.hpp"
#include "support/run_command.hpp"
#include "support/skip_or_fail.hpp"
#include "support/temp_dir.hpp"
#include "support/test_assets.hpp"
#include "tangent/check.hpp"
#include "tangent/gltf.hpp"

namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;
using tangent::testing::GridMesh;
using tangent::testing::TempDir;

// `mesh` with one xyzw per corner (`cornerTangents`, glTF's w) as a normal-mapped GLB: a vertex
// per distinct (vertex, tangent), so that every corner keeps the tangent the peer gave it.
fs::path writeWithCornerTangents(const GridMesh& mesh, const std::vector<float>& cornerTangents, const fs::path& dir,
                                 const std::string& name) {
  GridMesh split;
  std::vector<float> tangents;
  std::map<std::tuple<std::uint32_t, std::uint32_t, std::uint32_t, std::uint32_t, std::uint32_t>, std::uint32_t> vertexOf;
  for (std::size_t c = 0; c < mesh.indices.size(); ++c) {
    const std::uint32_t v = mesh.indices[c];
    const float* t = &cornerTangents[4 * c];
    const auto key = std::make_tuple(v, std::bit_cast<std::uint32_t>(t[0]), std::bit_cast<std::uint32_t>(t[1]),
                                     std::bit_cast<std::uint32_t>(t[2]), std::bit_cast<std::uint32_t>(t[3]));
    const auto [at, added] = vertexOf.try_emplace(key, static_cast<std::uint32_t>(split.positions.size() / 3));
    if (added) {
      split.positions.insert(split.positions.end(), &mesh.positions[3 * v], &mesh.positions[3 * v] + 3);
      split.normals.insert(split.normals.end(), &mesh.normals[3 * v], &mesh.normals[3 * v] + 3);
      split.uvs.insert(split.uvs.end(), &mesh.uvs[2 * v], &mesh.uvs[2 * v] + 2);
      tangents.insert(tangents.end(), t, t + 4);
    }
    split.indices.push_back(at->second);
  }
  tangent::testing::TestAsset asset = tangent::testing::meshAsset(name, split);
  while (asset.bin.size() % 4) asset.bin.push_back(0);
  const std::size_t offset = asset.bin.size();
  const auto* bytes = reinterpret_cast<const std::uint8_t*>(tangents.data());
  asset.bin.insert(asset.bin.end(), bytes, bytes + tangents.size() * 4);
  asset.json["buffers"][0]["byteLength"] = asset.bin.size();
  asset.json["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", tangents.size() * 4}, {"target", 34962}});
  asset.json["accessors"].push_back(
      {{"bufferView", asset.json["bufferViews"].size() - 1}, {"componentType", 5126}, {"count", tangents.size() / 4}, {"type", "VEC4"}});
  asset.json["meshes"][0]["primitives"][0]["attributes"]["TANGENT"] = asset.json["accessors"].size() - 1;
  return tangent::testing::writeAsset(asset, dir, true);
}

TEST(IdentifyConfusion, EachGeneratorAndPeerIsNamed) {
  TempDir dir;
  const bool havePeers = !tangent::bench::peers().empty();
  tangent::gltf::CheckOptions options;
  options.identify = true;
  options.enabled.reset();  // only the identification
  std::string matrix;
  int mislabelled = 0;
  for (const auto& [meshName, mesh] : {std::pair{std::string("leaning"), tangent::testing::leaningGrid()},
                                       std::pair{std::string("torus"), tangent::testing::makeTorus(24, 12)}}) {
    // Which file came from which source, and what it must be called.
    std::vector<std::tuple<std::string, fs::path, std::string>> files;
    const fs::path input = tangent::testing::writeAsset(tangent::testing::meshAsset(meshName, mesh), dir / "in", true);
    int index = 0;
    for (const tangent::gltf::Generator& generator : tangent::gltf::kGenerators) {
      tangent::gltf::BakeOptions bake;
      bake.tangents.method = generator.method;
      bake.tangents.weighting = generator.weighting;
      const fs::path output = dir / (meshName + "-" + std::to_string(index++) + ".glb");
      tangent::gltf::bakeFile(input, output, bake);
      files.emplace_back(tangent::gltf::toString(generator), output, tangent::gltf::toString(generator));
    }
    for (const tangent::bench::Peer peer : tangent::bench::peers()) {
      std::vector<float> corners(mesh.indices.size() * 4);
      tangent::bench::runPeer(peer, {mesh.positions, mesh.normals, mesh.uvs, mesh.indices}, corners);
      for (std::size_t c = 0; c < mesh.indices.size(); ++c) corners[4 * c + 3] = -corners[4 * c + 3];  // fSign -> glTF's w
      const std::string name(tangent::bench::toString(peer));
      std::string safe = name;
      std::replace(safe.begin(), safe.end(), '/', '-');
      const fs::path file = writeWithCornerTangents(mesh, corners, dir / "peers", meshName + "-" + safe);
      files.emplace_back(name, file, peer == tangent::bench::Peer::meshoptDefault ? "meshopt" : "mikktspace");
    }
    for (const auto& [source, file, expected] : files) {
      const tangent::gltf::FileCheck check = tangent::gltf::checkFile(file, options);
      ASSERT_TRUE(check.error.empty()) << check.error;
      ASSERT_EQ(check.primitives.size(), 1u) << file;
      const auto& p = check.primitives[0];
      char line[256];
      std::snprintf(line, sizeof line, "%-8s %-18s -> %s (median %.3g deg; next: %s, %.3g deg)\n", meshName.c_str(), source.c_str(),
                    p.generator.c_str(), p.generators.empty() ? -1.0 : p.generators[0].medianDegrees,
                    p.generators.size() < 2 ? "-" : p.generators[1].name.c_str(), p.generators.size() < 2 ? -1.0 : p.generators[1].medianDegrees);
      matrix += line;
      EXPECT_EQ(p.generator, expected) << source << " on " << meshName;
      mislabelled += p.generator != expected;
    }
  }
  std::printf("identification (source -> named):\n%s", matrix.c_str());
  EXPECT_EQ(mislabelled, 0);
  if (!havePeers) TANGENT_SKIP_OR_FAIL("../shared/peers is absent: " << tangent::bench::peersNote() << "; only the library's generators identified");
}

tangent::gltf::PrimitiveCheck identifyOne(const fs::path& file) {
  tangent::gltf::CheckOptions options;
  options.identify = true;
  options.enabled.reset();
  const tangent::gltf::FileCheck check = tangent::gltf::checkFile(file, options);
  EXPECT_TRUE(check.error.empty()) << check.error;
  EXPECT_EQ(check.primitives.size(), 1u) << file;
  return check.primitives.empty() ? tangent::gltf::PrimitiveCheck{} : check.primitives[0];
}

// glTF-Transform's `tangents` command, which runs npm `mikktspace` (the reference C compiled to
// WebAssembly; pinned in tests/node), on the generated meshes: named mikktspace.
TEST(IdentifyConfusion, NpmMikktspaceThroughGltfTransformIsMikktspace) {
  const fs::path cli = fs::path(TANGENT_SOURCE_DIR) / "tests/node/node_modules/.bin/gltf-transform";
  if (!fs::exists(cli)) TANGENT_SKIP_OR_FAIL("tests/node/node_modules is absent (npm ci): gltf-transform tangents not run");
  TempDir dir;
  for (const auto& [meshName, mesh] : {std::pair{std::string("leaning"), tangent::testing::leaningGrid()},
                                       std::pair{std::string("torus"), tangent::testing::makeTorus(24, 12)}}) {
    const fs::path input = tangent::testing::writeAsset(tangent::testing::meshAsset(meshName, mesh), dir.path() / "in", true);
    const fs::path output = dir.path() / (meshName + "-gltf-transform.glb");
    const auto run = tangent::testing::runCommand("'" + cli.string() + "' tangents '" + input.string() + "' '" + output.string() + "'");
    ASSERT_EQ(run.exitCode, 0) << run.output;
    const tangent::gltf::PrimitiveCheck p = identifyOne(output);
    EXPECT_EQ(p.generator, "mikktspace") << meshName;
    std::printf("%-8s gltf-transform tangents -> %s (median %.3g deg)\n", meshName.c_str(), p.generator.c_str(),
                p.generators.empty() ? -1.0 : p.generators.front().medianDegrees);
  }
}

}  // namespace
