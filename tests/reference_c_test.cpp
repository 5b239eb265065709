// SPDX-License-Identifier: MIT
// Randomized differential test against the reference C MikkTSpace (mmikk/MikkTSpace, compiled
// from ../shared/peers/mikktspace by the test build only). The rule is the issue's "randomized
// differential test against the reference C MikkTSpace"; see support/reference_rule.hpp.
//
//   TANGENT_DIFF_BASE_SEED=N   first seed of the run (default kDefaultBaseSeed)
//   TANGENT_DIFF_MESHES=N      meshes per run (default kDefaultMeshes)
//   TANGENT_DIFF_SEED=N        replay that one mesh and print every corner
//   TANGENT_DIFF_ONLY=CASE     meshes allow only that case (a name from the per-case table)
//   TANGENT_DIFF_MODEL=TEXT    (AssimpTestModels) print every corner of primitives whose name contains TEXT
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "read/asset.hpp"
#include "read/primitive.hpp"
#include "support/random_meshes.hpp"
#include "support/reference_rule.hpp"
#include "support/skip_or_fail.hpp"
#include "tangent/tangent.hpp"

namespace fs = std::filesystem;
using tangent::testing::RuleCounts;

namespace {

constexpr std::uint64_t kDefaultBaseSeed = 0x7a6e6e74;
constexpr std::uint64_t kDefaultMeshes = 2000;  // about 4 s here, 16 s under ASan + UBSan
// The generator must keep most corners comparable, or the test compares little.
constexpr double kMinComparedFraction = 0.75;

std::optional<std::uint64_t> envNumber(const char* name) {
  const char* text = std::getenv(name);
  if (text == nullptr || *text == '\0') return std::nullopt;
  return std::strtoull(text, nullptr, 0);
}

// Ours with the default options (glTF's w), one thread; output pre-filled with NaN so an
// untouched corner fails. A throw is returned as the message.
std::vector<float> computeOurs(const tangent::MeshArrays& mesh, std::string& error) {
  std::vector<float> tangents(4 * mesh.indices.size(), std::numeric_limits<float>::quiet_NaN());
  tangent::Options options;
  options.threads = 1;
  try {
    tangent::computeCornerTangents(mesh, tangents, options);
  } catch (const std::exception& e) {
    error = e.what();
  }
  return tangents;
}

const char* testBinary() {
  static std::string path = fs::read_symlink("/proc/self/exe").string();
  return path.c_str();
}

}  // namespace

TEST(ReferenceC, RandomMeshes) {
  const auto replaySeed = envNumber("TANGENT_DIFF_SEED");
  const std::uint64_t baseSeed = replaySeed.value_or(envNumber("TANGENT_DIFF_BASE_SEED").value_or(kDefaultBaseSeed));
  const char* onlyName = std::getenv("TANGENT_DIFF_ONLY");
  const auto only =
      onlyName != nullptr && *onlyName != '\0' ? tangent::testing::parseMeshFeature(onlyName) : std::nullopt;
  if (onlyName != nullptr && *onlyName != '\0' && !only) FAIL() << "TANGENT_DIFF_ONLY=" << onlyName << " names no case";
  const std::string replayPrefix = only ? "TANGENT_DIFF_ONLY=" + std::string(onlyName) + " " : std::string();
  const std::uint64_t meshCount = replaySeed ? 1 : envNumber("TANGENT_DIFF_MESHES").value_or(kDefaultMeshes);
  std::printf(
      "reference C differential: base seed %llu, %llu meshes (TANGENT_DIFF_BASE_SEED, TANGENT_DIFF_MESHES)%s%s\n",
      static_cast<unsigned long long>(baseSeed), static_cast<unsigned long long>(meshCount), only ? ", only " : "",
      only ? onlyName : "");

  const auto start = std::chrono::steady_clock::now();
  RuleCounts total;
  std::array<std::uint64_t, tangent::testing::kMeshFeatureCount> featureMeshes{};
  std::array<RuleCounts, tangent::testing::kMeshFeatureCount> featureCounts{};
  std::array<std::uint64_t, tangent::testing::kMeshFeatureCount> featureFailing{};
  std::vector<std::uint64_t> failingSeeds;
  for (std::uint64_t i = 0; i < meshCount; ++i) {
    const std::uint64_t seed = baseSeed + i;
    const tangent::testing::RandomMesh mesh = tangent::testing::randomMesh(seed, only);
    std::string error;
    const std::vector<float> ours = computeOurs(mesh.arrays(), error);
    const auto result = tangent::testing::applyReferenceRule(mesh.arrays(), ours, seed ^ 0x5eed5eed5eedull);
    total.add(result.counts);
    for (std::size_t f = 0; f < mesh.features.size(); ++f) {
      if (!mesh.features[f]) continue;
      ++featureMeshes[f];
      featureCounts[f].add(result.counts);
    }
    const bool failed = result.counts.failures() > 0 || !error.empty();
    for (std::size_t f = 0; f < mesh.features.size(); ++f) featureFailing[f] += mesh.features[f] && failed ? 1 : 0;
    if (failed) {
      failingSeeds.push_back(seed);
      std::string features;
      for (std::size_t f = 0; f < mesh.features.size(); ++f)
        if (mesh.features[f])
          features += std::string(features.empty() ? "" : ",") +
                      std::string(tangent::testing::toString(static_cast<tangent::testing::MeshFeature>(f)));
      std::printf(
          "FAIL seed %llu [%s]%s%s: %s\n  replay: %sTANGENT_DIFF_SEED=%llu %s --gtest_filter=ReferenceC.RandomMeshes\n",
          static_cast<unsigned long long>(seed), features.c_str(), error.empty() ? "" : " threw: ", error.c_str(),
          result.counts.describe().c_str(), replayPrefix.c_str(), static_cast<unsigned long long>(seed), testBinary());
    }
    if (replaySeed) std::printf("%s", tangent::testing::describeCorners(mesh.arrays(), ours, result).c_str());
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  std::printf(
      "per case: meshes containing it, how many of those fail (and of the meshes without it), their corners:\n");
  for (std::size_t f = 0; f < featureMeshes.size(); ++f) {
    const RuleCounts& c = featureCounts[f];
    const std::uint64_t without = meshCount - featureMeshes[f],
                        failingWithout = failingSeeds.size() - featureFailing[f];
    std::printf(
        "  %-20s %5llu meshes, failing %5.1f%% (without it %5.1f%%), %7llu corners, compared %5.1f%%, undefined %5llu, "
        "unstable %5llu, "
        "ref-mixed-w %5llu, failing corners %llu\n",
        std::string(tangent::testing::toString(static_cast<tangent::testing::MeshFeature>(f))).c_str(),
        static_cast<unsigned long long>(featureMeshes[f]),
        featureMeshes[f] ? 100.0 * static_cast<double>(featureFailing[f]) / static_cast<double>(featureMeshes[f]) : 0.0,
        without ? 100.0 * static_cast<double>(failingWithout) / static_cast<double>(without) : 0.0,
        static_cast<unsigned long long>(c.corners),
        c.corners ? 100.0 * static_cast<double>(c.compared) / static_cast<double>(c.corners) : 0.0,
        static_cast<unsigned long long>(c.undefined), static_cast<unsigned long long>(c.unstable),
        static_cast<unsigned long long>(c.referenceMixedW),
        static_cast<unsigned long long>(c.angleFailures + c.wFailures + c.invalidCorners));
  }
  std::printf("summary (base seed %llu, %.1f s): %s; failing meshes %zu\n", static_cast<unsigned long long>(baseSeed),
              seconds, total.describe().c_str(), failingSeeds.size());

  EXPECT_EQ(total.referenceFailures, 0u) << "the reference skipped corners or failed: the harness is wrong";
  EXPECT_TRUE(failingSeeds.empty()) << failingSeeds.size() << " of " << meshCount
                                    << " meshes break the rule (seeds printed above)";
  EXPECT_EQ(total.invalidCorners, 0u);
  EXPECT_EQ(total.mixedWTriangles, 0u);
  EXPECT_EQ(total.angleFailures, 0u);
  EXPECT_EQ(total.wFailures, 0u);
  if (replaySeed) return;
  // The generator's coverage: most corners are compared, and every case and every class
  // occurs (with a full run's worth of meshes).
  EXPECT_GE(static_cast<double>(total.compared), kMinComparedFraction * static_cast<double>(total.corners));
  if (meshCount >= 1000 && !only) {
    for (std::size_t f = 0; f < featureMeshes.size(); ++f)
      EXPECT_GE(featureMeshes[f], meshCount / 50)
          << "case " << tangent::testing::toString(static_cast<tangent::testing::MeshFeature>(f)) << " too rare";
    EXPECT_GT(total.undefined, 0u);
    EXPECT_GT(total.unstable, 0u);
    EXPECT_GT(total.referenceMixedW, 0u);
  }
}

// Every model of Debian's assimp-testmodels in a format the project reads, loaded the way
// `tangent bake` loads it (OBJ/PLY/OFF through OpenMesh into glTF, UVs top-left), each
// triangle primitive with normals and UVs under the same rule.
TEST(ReferenceC, AssimpTestModels) {
  const fs::path root = "/usr/share/assimp/models";
  if (!fs::is_directory(root)) TANGENT_SKIP_OR_FAIL(root << " is absent: install Debian's assimp-testmodels");
  std::vector<fs::path> files;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    if (!entry.is_regular_file()) continue;
    std::string extension = entry.path().extension().string();
    for (char& ch : extension) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    if (extension == ".gltf" || extension == ".glb" || extension == ".obj" || extension == ".ply" ||
        extension == ".off")
      files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  ASSERT_FALSE(files.empty());

  RuleCounts total;
  const char* detailed = std::getenv("TANGENT_DIFF_MODEL");
  std::vector<std::string> unreadable, failing;
  std::size_t primitives = 0, skippedPrimitives = 0;
  for (const fs::path& file : files) {
    const std::string name = fs::relative(file, root).string();
    tangent::gltf::detail::Asset asset;
    try {
      asset = tangent::gltf::detail::loadAsset(file);
    } catch (const std::exception& e) {
      // A mesh file without UVs is refused on loading: no primitive to compare, not unreadable.
      if (std::string(e.what()).find("has no texture coordinates") != std::string::npos)
        ++skippedPrimitives;
      else
        unreadable.push_back(name + ": " + e.what());
      continue;
    }
    const auto& meshes = asset.json.value("meshes", nlohmann::ordered_json::array());
    for (std::size_t m = 0; m < meshes.size(); ++m) {
      const auto& list = meshes[m].value("primitives", nlohmann::ordered_json::array());
      for (std::size_t p = 0; p < list.size(); ++p) {
        const auto& primitive = list[p];
        const auto needs = tangent::gltf::detail::primitiveNeeds(asset.json, primitive, true);
        const std::string where = name + " mesh " + std::to_string(m) + " primitive " + std::to_string(p);
        const auto& attributes = primitive["attributes"];
        if (!needs.triangles || needs.texCoord < 0 ||
            tangent::gltf::detail::accessorOf(attributes, "NORMAL") < 0 ||
            tangent::gltf::detail::accessorOf(attributes, "TEXCOORD_" + std::to_string(needs.texCoord)) < 0) {
          ++skippedPrimitives;
          continue;
        }
        tangent::gltf::detail::PrimitiveGeometry geometry;
        try {
          geometry = tangent::gltf::detail::readGeometry(asset, primitive, needs, where);
        } catch (const std::exception& e) {
          unreadable.push_back(e.what());  // names the primitive
          continue;
        }
        if (geometry.corners.empty()) {
          ++skippedPrimitives;
          continue;
        }
        ++primitives;
        const tangent::MeshArrays arrays{geometry.positions, geometry.normals, geometry.uvs, geometry.corners};
        std::string error;
        const std::vector<float> ours = computeOurs(arrays, error);
        const auto result = tangent::testing::applyReferenceRule(arrays, ours, 0x5eed);
        total.add(result.counts);
        std::printf("%-60s %s%s%s\n", where.c_str(), result.counts.describe().c_str(),
                    error.empty() ? "" : " threw: ", error.c_str());
        if (result.counts.failures() > 0 || !error.empty()) failing.push_back(where);
        if (detailed != nullptr && where.find(detailed) != std::string::npos)
          std::printf("%s", tangent::testing::describeCorners(arrays, ours, result).c_str());
      }
    }
  }
  for (const auto& line : unreadable) std::printf("not read (not a failure): %s\n", line.c_str());
  std::printf(
      "summary: %zu files, %zu primitives compared, %zu primitives or mesh files without triangles, normals or UVs, "
      "%zu not read; %s\n",
      files.size(), primitives, skippedPrimitives, unreadable.size(), total.describe().c_str());
  ASSERT_GT(primitives, 0u) << "no model with normals and UVs was read";
  EXPECT_EQ(total.referenceFailures, 0u);
  std::string failingList;
  for (const auto& where : failing) failingList += "\n  " + where;
  EXPECT_TRUE(failing.empty()) << failing.size()
                               << " primitives break the rule (per-corner details: TANGENT_DIFF_MODEL=NAME "
                               << testBinary() << " --gtest_filter=ReferenceC.AssimpTestModels):" << failingList;
  EXPECT_EQ(total.invalidCorners, 0u);
  EXPECT_EQ(total.mixedWTriangles, 0u);
  EXPECT_EQ(total.angleFailures, 0u);
  EXPECT_EQ(total.wFailures, 0u);
  EXPECT_GE(static_cast<double>(total.compared), 0.5 * static_cast<double>(total.corners));
}
