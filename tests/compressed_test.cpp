// SPDX-License-Identifier: MIT
// Compressed input (KHR_draco_mesh_compression, EXT_meshopt_compression), on files that
// gltf-transform (tests/node, pinned) makes from a generated asset: the viewer's scene loads
// them like their source, and hostile compressed data is refused with an InputError naming
// the file and the element, one test per defect. tests/compressed/roundtrip.py covers bake,
// check, info and the validator on real compressor output.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>

#include "support/run_command.hpp"
#include "support/skip_or_fail.hpp"
#include "support/temp_dir.hpp"
#include "support/test_assets.hpp"
#include "tangent/gltf.hpp"
#include "tangent/scene.hpp"

namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;
using tangent::testing::TempDir;

const fs::path kGltfTransform = fs::path(TANGENT_SOURCE_DIR) / "tests/node/node_modules/.bin/gltf-transform";

struct Glb {
  Json json;
  std::vector<std::uint8_t> bin;
};

Glb readGlb(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::uint32_t jsonLength = 0, binLength = 0;
  std::memcpy(&jsonLength, &bytes[12], 4);
  Glb glb;
  glb.json = Json::parse(bytes.begin() + 20, bytes.begin() + 20 + jsonLength);
  const std::size_t binStart = 20 + jsonLength;
  if (binStart + 8 <= bytes.size()) {
    std::memcpy(&binLength, &bytes[binStart], 4);
    glb.bin.assign(bytes.begin() + static_cast<std::ptrdiff_t>(binStart + 8),
                   bytes.begin() + static_cast<std::ptrdiff_t>(binStart + 8 + binLength));
  }
  return glb;
}

void writeGlb(const fs::path& path, const Glb& glb) {
  std::string json = glb.json.dump();
  json.resize((json.size() + 3) & ~std::size_t(3), ' ');
  std::vector<std::uint8_t> bin = glb.bin;
  bin.resize((bin.size() + 3) & ~std::size_t(3), 0);
  const std::uint32_t header[5] = {0x46546C67, 2, static_cast<std::uint32_t>(28 + json.size() + bin.size()),
                                   static_cast<std::uint32_t>(json.size()), 0x4E4F534A};
  const std::uint32_t binHeader[2] = {static_cast<std::uint32_t>(bin.size()), 0x004E4942};
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(header), sizeof header);
  out << json;
  out.write(reinterpret_cast<const char*>(binHeader), sizeof binHeader);
  out.write(reinterpret_cast<const char*>(bin.data()), static_cast<std::streamsize>(bin.size()));
}

// The generated interleaved asset (a mirrored grid, ubyte indices) and its gltf-transform
// draco and meshopt copies.
struct CompressedFiles {
  fs::path source, draco, meshopt;
};

std::optional<CompressedFiles> makeCompressed(const TempDir& dir) {
  CompressedFiles files;
  files.source = tangent::testing::writeAsset(tangent::testing::makeTestAssets().front(), dir.path(), true);
  files.draco = dir / "draco.glb";
  files.meshopt = dir / "meshopt.glb";
  for (const auto& [command, output] : {std::pair{"draco", files.draco}, std::pair{"meshopt", files.meshopt}}) {
    const auto run = tangent::testing::runCommand(kGltfTransform.string() + " " + command + " '" + files.source.string() + "' '" +
                                                  output.string() + "'");
    if (run.exitCode != 0) {
      ADD_FAILURE() << "gltf-transform " << command << " failed:\n" << run.output;
      return std::nullopt;
    }
  }
  return files;
}

#define REQUIRE_GLTF_TRANSFORM()                                                                        \
  if (!fs::exists(kGltfTransform)) {                                                                    \
    TANGENT_SKIP_OR_FAIL(kGltfTransform << " is absent: run scripts/test.sh (npm ci in tests/node)"); \
  }

TEST(CompressedInput, SceneLoadsDracoAndMeshoptLikeTheSource) {
  REQUIRE_GLTF_TRANSFORM();
  TempDir dir;
  const auto files = makeCompressed(dir);
  ASSERT_TRUE(files);
  const tangent::gltf::Scene plain = tangent::gltf::loadScene(files->source);
  ASSERT_FALSE(plain.items.empty());
  for (const fs::path& compressed : {files->draco, files->meshopt}) {
    SCOPED_TRACE(compressed.filename().string());
    const tangent::gltf::Scene scene = tangent::gltf::loadScene(compressed);
    ASSERT_EQ(scene.items.size(), plain.items.size());
    for (std::size_t i = 0; i < scene.items.size(); ++i) {
      EXPECT_EQ(scene.items[i].positions.size(), plain.items[i].positions.size());
      EXPECT_EQ(scene.items[i].hasUvs, plain.items[i].hasUvs);
    }
    // World bounds agree to the compressors' position quantization (14 bits and more).
    for (int axis = 0; axis < 3; ++axis) {
      const double size = plain.boundsMax[axis] - plain.boundsMin[axis] + 1e-6;
      EXPECT_NEAR(scene.boundsMin[axis], plain.boundsMin[axis], 1e-3 * size);
      EXPECT_NEAR(scene.boundsMax[axis], plain.boundsMax[axis], 1e-3 * size);
    }
  }
}

// Writes a mutated copy of `compressed` and expects info and bake to refuse it with a message
// that starts with the file and contains `fragment` (bake writing nothing).
void expectRefused(const TempDir& dir, const fs::path& compressed, const std::function<void(Glb&)>& mutate,
                   const std::string& fragment) {
  Glb glb = readGlb(compressed);
  mutate(glb);
  const fs::path input = dir / "hostile.glb";
  writeGlb(input, glb);
  try {
    tangent::gltf::describeFile(input);
    ADD_FAILURE() << "info accepted it; expected: " << fragment;
  } catch (const tangent::gltf::InputError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(input.string() + ": ", 0), 0u) << message;
    EXPECT_NE(message.find(fragment), std::string::npos) << message << "\nexpected: " << fragment;
  }
  const fs::path output = dir / "out.glb";
  EXPECT_THROW(tangent::gltf::bakeFile(input, output, {}), tangent::gltf::InputError);
  EXPECT_FALSE(fs::exists(output));
}

int dracoView(const Glb& glb) {
  return glb.json["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["bufferView"].get<int>();
}

// The first bufferView compressed in mode `mode`.
int meshoptView(const Glb& glb, const std::string& mode) {
  const Json& views = glb.json["bufferViews"];
  for (std::size_t i = 0; i < views.size(); ++i) {
    if (views[i].contains("extensions") && views[i]["extensions"]["EXT_meshopt_compression"]["mode"] == mode)
      return static_cast<int>(i);
  }
  return -1;
}

class HostileCompressed : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!fs::exists(kGltfTransform)) {
      TANGENT_SKIP_OR_FAIL(kGltfTransform << " is absent: run scripts/test.sh (npm ci in tests/node)");
    }
    files_ = makeCompressed(dir_);
    ASSERT_TRUE(files_);
  }
  TempDir dir_;
  std::optional<CompressedFiles> files_;
};

TEST_F(HostileCompressed, DracoStreamTruncated) {
  const int view = dracoView(readGlb(files_->draco));
  expectRefused(dir_, files_->draco, [](Glb& glb) {
    Json& length = glb.json["bufferViews"][dracoView(glb)]["byteLength"];
    length = length.get<int>() / 2;
  }, "meshes[0].primitives[0] KHR_draco_mesh_compression: the Draco stream in bufferView " + std::to_string(view) +
         " cannot be decoded");
}

TEST_F(HostileCompressed, DracoPositionCountWrong) {
  const Glb glb = readGlb(files_->draco);
  const int position = glb.json["meshes"][0]["primitives"][0]["attributes"]["POSITION"].get<int>();
  const int count = glb.json["accessors"][position]["count"].get<int>();
  expectRefused(dir_, files_->draco, [&](Glb& g) { g.json["accessors"][position]["count"] = count + 1; },
                "meshes[0].primitives[0] KHR_draco_mesh_compression: POSITION: accessor " + std::to_string(position) +
                    " has count " + std::to_string(count + 1) + ", the Draco stream decodes " + std::to_string(count) + " vertices");
}

TEST_F(HostileCompressed, DracoIndexCountWrong) {
  const Glb glb = readGlb(files_->draco);
  const int indices = glb.json["meshes"][0]["primitives"][0]["indices"].get<int>();
  const int count = glb.json["accessors"][indices]["count"].get<int>();
  expectRefused(dir_, files_->draco, [&](Glb& g) { g.json["accessors"][indices]["count"] = count - 3; },
                "meshes[0].primitives[0] KHR_draco_mesh_compression: indices: accessor " + std::to_string(indices) +
                    " has count " + std::to_string(count - 3) + ", the Draco stream decodes " + std::to_string(count / 3) + " triangles");
}

TEST_F(HostileCompressed, DracoUnknownAttributeId) {
  expectRefused(dir_, files_->draco, [](Glb& glb) {
    glb.json["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["attributes"]["POSITION"] = 99;
  }, "meshes[0].primitives[0] KHR_draco_mesh_compression: POSITION: the Draco stream has no attribute with unique id 99");
}

TEST_F(HostileCompressed, MeshoptStreamTruncated) {
  const int view = meshoptView(readGlb(files_->meshopt), "ATTRIBUTES");
  ASSERT_GE(view, 0);
  expectRefused(dir_, files_->meshopt, [view](Glb& glb) {
    glb.json["bufferViews"][view]["extensions"]["EXT_meshopt_compression"]["byteLength"] = 20;
  }, "bufferViews[" + std::to_string(view) + "] EXT_meshopt_compression: the compressed stream is malformed or truncated");
}

TEST_F(HostileCompressed, MeshoptIndexStreamTruncated) {
  const int view = meshoptView(readGlb(files_->meshopt), "TRIANGLES");
  ASSERT_GE(view, 0);
  expectRefused(dir_, files_->meshopt, [view](Glb& glb) {
    Json& length = glb.json["bufferViews"][view]["extensions"]["EXT_meshopt_compression"]["byteLength"];
    length = length.get<int>() / 2;
  }, "bufferViews[" + std::to_string(view) + "] EXT_meshopt_compression: the compressed stream is malformed or truncated");
}

// A count the parent view and the fallback buffer agree with, far beyond what the compressed
// bytes can hold: refused before anything that size is allocated.
TEST_F(HostileCompressed, MeshoptHugeClaimedCount) {
  const int view = meshoptView(readGlb(files_->meshopt), "ATTRIBUTES");
  ASSERT_GE(view, 0);
  expectRefused(dir_, files_->meshopt, [view](Glb& glb) {
    Json& parent = glb.json["bufferViews"][view];
    Json& extension = parent["extensions"]["EXT_meshopt_compression"];
    const std::int64_t count = 1 << 24, length = count * extension["byteStride"].get<std::int64_t>();
    extension["count"] = count;
    parent["byteLength"] = length;
    parent["byteOffset"] = 0;
    glb.json["buffers"][parent["buffer"].get<int>()]["byteLength"] = length;
  }, "bufferViews[" + std::to_string(view) + "] EXT_meshopt_compression: claims ");
}

TEST_F(HostileCompressed, MeshoptCountDisagreesWithView) {
  const int view = meshoptView(readGlb(files_->meshopt), "ATTRIBUTES");
  ASSERT_GE(view, 0);
  expectRefused(dir_, files_->meshopt, [view](Glb& glb) {
    Json& count = glb.json["bufferViews"][view]["extensions"]["EXT_meshopt_compression"]["count"];
    count = count.get<int>() + 1;
  }, "bufferViews[" + std::to_string(view) + "] EXT_meshopt_compression: the bufferView's byteLength ");
}

TEST_F(HostileCompressed, MeshoptUnknownMode) {
  const int view = meshoptView(readGlb(files_->meshopt), "ATTRIBUTES");
  ASSERT_GE(view, 0);
  expectRefused(dir_, files_->meshopt, [view](Glb& glb) {
    glb.json["bufferViews"][view]["extensions"]["EXT_meshopt_compression"]["mode"] = "STRIPS";
  }, "bufferViews[" + std::to_string(view) + "] EXT_meshopt_compression: mode 'STRIPS' is not ATTRIBUTES, TRIANGLES or INDICES");
}

TEST_F(HostileCompressed, MeshoptFilterOnIndices) {
  const int view = meshoptView(readGlb(files_->meshopt), "TRIANGLES");
  ASSERT_GE(view, 0);
  expectRefused(dir_, files_->meshopt, [view](Glb& glb) {
    glb.json["bufferViews"][view]["extensions"]["EXT_meshopt_compression"]["filter"] = "OCTAHEDRAL";
  }, "bufferViews[" + std::to_string(view) + "] EXT_meshopt_compression: filter must be NONE in mode TRIANGLES");
}

TEST_F(HostileCompressed, MeshoptSourceIsFallbackBuffer) {
  const Glb glb = readGlb(files_->meshopt);
  const int view = meshoptView(glb, "ATTRIBUTES");
  ASSERT_GE(view, 0);
  const int fallback = glb.json["bufferViews"][view]["buffer"].get<int>();
  ASSERT_TRUE(glb.json["buffers"][fallback]["extensions"]["EXT_meshopt_compression"]["fallback"].get<bool>());
  expectRefused(dir_, files_->meshopt, [view, fallback](Glb& g) {
    g.json["bufferViews"][view]["extensions"]["EXT_meshopt_compression"]["buffer"] = fallback;
  }, "bufferViews[" + std::to_string(view) + "] EXT_meshopt_compression: buffer " + std::to_string(fallback) +
         " is a fallback buffer, which holds no compressed data");
}

// Indices decoded fine, but beyond the vertices the (shortened) attribute accessors hold.
TEST_F(HostileCompressed, MeshoptIndicesOutOfRangeAfterDecoding) {
  const Glb glb = readGlb(files_->meshopt);
  const Json& primitive = glb.json["meshes"][0]["primitives"][0];
  const int indices = primitive["indices"].get<int>();
  const int count = glb.json["accessors"][primitive["attributes"]["POSITION"].get<int>()]["count"].get<int>();
  expectRefused(dir_, files_->meshopt, [&](Glb& g) {
    for (const auto& [name, accessor] : g.json["meshes"][0]["primitives"][0]["attributes"].items())
      g.json["accessors"][accessor.get<int>()]["count"] = count - 1;
  }, "indices (accessor " + std::to_string(indices) + "): index " + std::to_string(count - 1));
}

}  // namespace
