// SPDX-License-Identifier: MIT
// tangent-view's fidelity fixes of issue 64 (item 3), headless under Xvfb like
// screenshot_test.cpp: shadows without acne or terminator blotches on a low-poly smooth sphere,
// auto exposure that holds still across an animation, missing or undecodable textures drawn as
// a checker and named, and --animation errors that list the file's animations. Each test writes
// the glTF it needs (generated geometry) into its own temporary folder.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "support/run_command.hpp"
#include "support/temp_dir.hpp"
#include "viewer/png_image.hpp"

namespace {

namespace fs = std::filesystem;
using tangent::testing::TempDir;
using Json = nlohmann::json;

using tangent::testing::Image;
using tangent::testing::readPng;

tangent::testing::CommandResult view(const std::string& arguments) {
  return tangent::testing::runCommand(std::string(TANGENT_VIEW) + " " + arguments);
}

struct Shot {
  Image image;
  std::string output;  // stdout and stderr
};

Shot screenshot(const TempDir& dir, const std::string& name, const std::string& arguments) {
  const fs::path out = dir / (name + ".png");
  const auto result = view(arguments + " --screenshot '" + out.string() + "'");
  EXPECT_EQ(result.exitCode, 0) << arguments << "\n" << result.output;
  EXPECT_EQ(result.output.find("OpenGL errors"), std::string::npos) << result.output;
  return {result.exitCode == 0 ? readPng(out) : Image{}, result.output};
}

// A glTF written piece by piece: one buffer (a .bin beside the .gltf), accessors appended.
struct AssetWriter {
  Json doc = {{"asset", {{"version", "2.0"}}}, {"scene", 0}, {"scenes", {{{"nodes", Json::array()}}}}};
  std::vector<std::uint8_t> bytes;

  int accessor(const std::vector<float>& values, int components, bool bounds = false) {
    const int count = static_cast<int>(values.size()) / components;
    Json a = {{"bufferView", view(values.data(), values.size() * sizeof(float))}, {"componentType", 5126}, {"count", count},
              {"type", components == 1 ? "SCALAR" : components == 2 ? "VEC2" : components == 3 ? "VEC3" : "VEC4"}};
    if (bounds) {
      std::vector<float> lo(components, 1e30f), hi(components, -1e30f);
      for (int i = 0; i < count; ++i)
        for (int c = 0; c < components; ++c) lo[c] = std::min(lo[c], values[i * components + c]), hi[c] = std::max(hi[c], values[i * components + c]);
      a["min"] = lo;
      a["max"] = hi;
    }
    doc["accessors"].push_back(a);
    return static_cast<int>(doc["accessors"].size()) - 1;
  }
  int indices(const std::vector<std::uint32_t>& values) {
    doc["accessors"].push_back({{"bufferView", view(values.data(), values.size() * 4)}, {"componentType", 5125}, {"count", values.size()}, {"type", "SCALAR"}});
    return static_cast<int>(doc["accessors"].size()) - 1;
  }
  int view(const void* data, std::size_t size) {
    while (bytes.size() % 4) bytes.push_back(0);
    const std::size_t offset = bytes.size();
    bytes.insert(bytes.end(), static_cast<const std::uint8_t*>(data), static_cast<const std::uint8_t*>(data) + size);
    doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", size}});
    return static_cast<int>(doc["bufferViews"].size()) - 1;
  }
  // A node at the scene's root; returns its index.
  int node(Json node) {
    doc["nodes"].push_back(std::move(node));
    const int index = static_cast<int>(doc["nodes"].size()) - 1;
    doc["scenes"][0]["nodes"].push_back(index);
    return index;
  }
  int mesh(Json attributes, int indexAccessor, int material) {
    doc["meshes"].push_back({{"primitives", {{{"attributes", attributes}, {"indices", indexAccessor}, {"material", material}}}}});
    return static_cast<int>(doc["meshes"].size()) - 1;
  }
  int material(Json material) {
    doc["materials"].push_back(std::move(material));
    return static_cast<int>(doc["materials"].size()) - 1;
  }
  fs::path write(const TempDir& dir, const std::string& name) {
    doc["buffers"] = {{{"uri", name + ".bin"}, {"byteLength", bytes.size()}}};
    std::ofstream(dir / (name + ".bin"), std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    std::ofstream(dir / (name + ".gltf")) << doc.dump();
    return dir / (name + ".gltf");
  }
};

// A UV sphere of `segments` x `rings` quads with smooth (analytic) normals, centre `centre`.
int lowPolySphere(AssetWriter& asset, int segments, int rings, std::array<float, 3> centre, float radius, int material) {
  std::vector<float> positions, normals;
  std::vector<std::uint32_t> indices;
  const double pi = 3.14159265358979323846;
  for (int r = 0; r <= rings; ++r) {
    for (int s = 0; s <= segments; ++s) {
      const double theta = pi * r / rings, phi = 2 * pi * s / segments;
      const double n[3] = {std::sin(theta) * std::cos(phi), std::cos(theta), -std::sin(theta) * std::sin(phi)};
      for (int c = 0; c < 3; ++c) {
        normals.push_back(static_cast<float>(n[c]));
        positions.push_back(centre[c] + radius * static_cast<float>(n[c]));
      }
    }
  }
  for (int r = 0; r < rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      const std::uint32_t a = r * (segments + 1) + s, b = a + segments + 1;
      indices.insert(indices.end(), {a, b, a + 1, a + 1, b, b + 1});
    }
  }
  return asset.mesh({{"POSITION", asset.accessor(positions, 3, true)}, {"NORMAL", asset.accessor(normals, 3)}}, asset.indices(indices), material);
}

// A square in the plane y = 0 (normal +y) of half-width `half`, UVs over [0, 1]^2.
int groundSquare(AssetWriter& asset, float half, int material) {
  const std::vector<float> positions = {-half, 0, -half, half, 0, -half, half, 0, half, -half, 0, half};
  const std::vector<float> normals = {0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0};
  const std::vector<float> uvs = {0, 0, 1, 0, 1, 1, 0, 1};
  return asset.mesh({{"POSITION", asset.accessor(positions, 3, true)}, {"NORMAL", asset.accessor(normals, 3)}, {"TEXCOORD_0", asset.accessor(uvs, 2)}},
                    asset.indices({0, 2, 1, 0, 3, 2}), material);
}

// A KHR_lights_punctual light on a node of its own: directional, shining along `direction`, or
// a point light at `position`.
void addLight(AssetWriter& asset, const Json& light, std::array<double, 3> directionOrPosition) {
  asset.doc["extensionsUsed"] = {"KHR_lights_punctual"};
  asset.doc["extensions"]["KHR_lights_punctual"]["lights"].push_back(light);
  const int index = static_cast<int>(asset.doc["extensions"]["KHR_lights_punctual"]["lights"].size()) - 1;
  Json node = {{"extensions", {{"KHR_lights_punctual", {{"light", index}}}}}};
  if (light["type"] == "directional") {
    // The rotation that turns the node's -z onto the direction (the half-way quaternion).
    const auto& d = directionOrPosition;
    const double length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    const double x = d[0] / length, y = d[1] / length, z = d[2] / length;
    std::array<double, 4> q = {y, -x, 0.0, 1 - z};  // cross((0, 0, -1), d), 1 + dot
    const double qLength = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    for (double& v : q) v /= qLength;
    node["rotation"] = q;
  } else {
    node["translation"] = directionOrPosition;
  }
  asset.node(node);
}

// --- Shadows ---------------------------------------------------------------------------------

// The low-poly sphere (8 x 6, radius 1, centre (0, 1, 0)) on a ground square, under one
// directional light from the right, front and above: the terminator runs down the front view.
const std::array<double, 3> kToLight = {1.0, 0.5, 0.6};

fs::path shadowScene(const TempDir& dir) {
  AssetWriter asset;
  const int grey = asset.material({{"pbrMetallicRoughness", {{"baseColorFactor", {0.8, 0.8, 0.8, 1}}, {"metallicFactor", 0}, {"roughnessFactor", 0.9}}}});
  asset.node({{"mesh", lowPolySphere(asset, 8, 6, {0, 1, 0}, 1, grey)}});
  asset.node({{"mesh", groundSquare(asset, 3, grey)}});
  addLight(asset, {{"type", "directional"}, {"intensity", 3}}, {-kToLight[0], -kToLight[1], -kToLight[2]});
  return asset.write(dir, "low_poly_sphere");
}

struct LitSideDifference {
  double mean = 0;    // mean absolute luma difference over the lit side
  double blotch = 0;  // the largest mean difference over a 5 x 5 pixel window inside it
  int pixels = 0;
};

// Where the smooth sphere faces the light (N.L > 0.15: lit, away from the terminator), in the
// front orthographic view framed on the sphere's box: the two images' difference.
LitSideDifference litSideDifference(const Image& shadowed, const Image& plain) {
  LitSideDifference result;
  if (shadowed.width == 0 || plain.width != shadowed.width) return result;
  const double length = std::sqrt(kToLight[0] * kToLight[0] + kToLight[1] * kToLight[1] + kToLight[2] * kToLight[2]);
  // The frame box [-1, 1] x [0, 2] x [-1, 1]: its bounding sphere's radius is sqrt 3.
  const double pixelsPerUnit = shadowed.height / (2 * std::sqrt(3.0) * 1.02);
  const int w = shadowed.width, h = shadowed.height;
  std::vector<char> lit(static_cast<std::size_t>(w) * h, 0);
  std::vector<float> difference(static_cast<std::size_t>(w) * h, 0);
  double sum = 0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const double nx = (x + 0.5 - w / 2.0) / pixelsPerUnit, ny = (h / 2.0 - y - 0.5) / pixelsPerUnit;
      const double rr = nx * nx + ny * ny;
      if (rr > 0.9 * 0.9) continue;  // inside the 12-gon's silhouette
      const double nz = std::sqrt(1 - rr);
      if ((nx * kToLight[0] + ny * kToLight[1] + nz * kToLight[2]) / length < 0.15) continue;
      const std::size_t i = static_cast<std::size_t>(y) * w + x;
      lit[i] = 1;
      difference[i] = std::abs(shadowed.luma(x, y) - plain.luma(x, y));
      sum += difference[i];
      ++result.pixels;
    }
  }
  result.mean = result.pixels ? sum / result.pixels : 0;
  for (int y = 2; y + 2 < h; ++y) {
    for (int x = 2; x + 2 < w; ++x) {
      double window = 0;
      bool inside = true;
      for (int dy = -2; dy <= 2 && inside; ++dy)
        for (int dx = -2; dx <= 2; ++dx) {
          const std::size_t i = static_cast<std::size_t>(y + dy) * w + (x + dx);
          inside = inside && lit[i];
          window += difference[i];
        }
      if (inside) result.blotch = std::max(result.blotch, window / 25);
    }
  }
  return result;
}

TEST(Fidelity, LowPolySphereLitSideShadesAsWithoutShadowsAndStillCastsOnTheGround) {
  TempDir dir;
  const fs::path asset = shadowScene(dir);
  const std::string front = "'" + asset.string() + "' --camera front --ortho --size 500x500 --frame-box -1,0,-1,1,2,1";
  // The coarser map and the wider PCF (whose taps reach further over the facets) show most.
  for (const std::string pcf : {"0", "2"}) {
    const std::string options = " --pcf " + pcf + " --shadow-map-size 1024";
    const Image shadowed = screenshot(dir, "front" + pcf, front + options).image;
    const Image plain = screenshot(dir, "front-plain" + pcf, front + options + " --no-shadows").image;
    const LitSideDifference lit = litSideDifference(shadowed, plain);
    std::printf("pcf %s: lit side %d pixels, mean luma difference %.4f, worst 5x5 blotch %.4f\n", pcf.c_str(), lit.pixels, lit.mean, lit.blotch);
    ASSERT_GT(lit.pixels, 20000);
    EXPECT_LT(lit.mean, 0.0005) << "pcf " << pcf;
    EXPECT_LT(lit.blotch, 0.01) << "pcf " << pcf;
  }
  // The sphere's shadow on the ground, seen from the top (the scene's box [-3, 3] x [0, 2] x
  // [-3, 3], framed orthographically): where the sphere's centre falls along the light.
  const std::string top = "'" + asset.string() + "' --camera top --ortho --size 500x500";
  const Image shadowed = screenshot(dir, "top", top).image;
  const Image plain = screenshot(dir, "top-plain", top + " --no-shadows").image;
  ASSERT_EQ(shadowed.width, 500);
  const double pixelsPerUnit = 500 / (2 * std::sqrt(6.0 * 6.0 + 2.0 * 2.0 + 6.0 * 6.0) / 2 * 1.02);
  const double shadowX = -kToLight[0] / kToLight[1], shadowZ = -kToLight[2] / kToLight[1];
  auto mean = [&](const Image& image) {
    double sum = 0;
    const int cx = static_cast<int>(250 + shadowX * pixelsPerUnit), cy = static_cast<int>(250 + shadowZ * pixelsPerUnit);
    for (int y = cy - 4; y <= cy + 4; ++y)
      for (int x = cx - 4; x <= cx + 4; ++x) sum += image.luma(x, y);
    return sum / 81;
  };
  std::printf("ground under the sphere's shadow: luma %.3f with shadows, %.3f without\n", mean(shadowed), mean(plain));
  EXPECT_LT(mean(shadowed), 0.75 * mean(plain));  // the unshadowed environment lights it too
}

// --- Exposure --------------------------------------------------------------------------------

double exposureOf(const std::string& output) {
  std::smatch match;
  const std::regex pattern("exposure ([0-9.eE+-]+)");
  return std::regex_search(output, match, pattern) ? std::stod(match[1]) : -1;
}

// A sphere that an animation carries 8 units away from a point light over one second: the
// scene's bounds (and the light's illuminance at their centre) change with the time.
fs::path travellingSphere(const TempDir& dir) {
  AssetWriter asset;
  const int grey = asset.material({{"pbrMetallicRoughness", {{"baseColorFactor", {0.8, 0.8, 0.8, 1}}, {"metallicFactor", 0}}}});
  const int node = asset.node({{"mesh", lowPolySphere(asset, 12, 8, {0, 0, 0}, 1, grey)}});
  addLight(asset, {{"type", "point"}, {"intensity", 40}}, {0.0, 3.0, 0.0});
  const int times = asset.accessor({0, 1}, 1, true);
  const int places = asset.accessor({0, 0, 0, 8, 0, 0}, 3);
  Json sampler = {{"input", times}, {"output", places}, {"interpolation", "LINEAR"}};
  Json channel = {{"sampler", 0}, {"target", {{"node", node}, {"path", "translation"}}}};
  Json animation = {{"name", "travel"}, {"samplers", Json::array({sampler})}, {"channels", Json::array({channel})}};
  asset.doc["animations"] = Json::array({animation});
  return asset.write(dir, "travelling_sphere");
}

TEST(Fidelity, AutoExposureIsDecidedOncePerAssetAndHoldsAcrossTheAnimation) {
  TempDir dir;
  const fs::path asset = travellingSphere(dir);
  const std::string common = "'" + asset.string() + "' --size 96x96";
  const double rest = exposureOf(screenshot(dir, "rest", common).output);
  const double start = exposureOf(screenshot(dir, "start", common + " --animation travel --time 0").output);
  const double end = exposureOf(screenshot(dir, "end", common + " --animation travel --time 1").output);
  std::printf("auto exposure: rest pose %.4g, time 0 %.4g, time 1 %.4g\n", rest, start, end);
  ASSERT_GT(rest, 0);
  EXPECT_EQ(start, rest);
  EXPECT_EQ(end, rest);
  // --exposure still sets it outright.
  EXPECT_EQ(exposureOf(screenshot(dir, "fixed", common + " --animation travel --time 1 --exposure 0.25").output), 0.25);
}

// Debian's assimp-testmodels, where installed: a skinned strip and a morphing cube, each at two
// times of its animation and at rest, show the same exposure.
TEST(Fidelity, AutoExposureHoldsAcrossTheAnimationsOfSampleAssets) {
  const fs::path models = "/usr/share/assimp/models/glTF2";
  const fs::path assets[] = {models / "simple_skin" / "simple_skin.gltf",
                             models / "glTF-Sample-Models" / "AnimatedMorphCube-glTF" / "AnimatedMorphCube.gltf"};
  TempDir dir;
  int shown = 0;
  for (const fs::path& asset : assets) {
    if (!fs::exists(asset)) continue;
    ++shown;
    const std::string common = "'" + asset.string() + "' --size 96x96";
    const double rest = exposureOf(screenshot(dir, "rest", common).output);
    const double early = exposureOf(screenshot(dir, "early", common + " --animation 0 --time 0.3").output);
    const double late = exposureOf(screenshot(dir, "late", common + " --animation 0 --time 1.7").output);
    std::printf("%s: auto exposure at rest %.4g, time 0.3 %.4g, time 1.7 %.4g\n", asset.filename().string().c_str(), rest, early, late);
    EXPECT_GT(rest, 0);
    EXPECT_EQ(early, rest) << asset;
    EXPECT_EQ(late, rest) << asset;
  }
  if (shown == 0) GTEST_SKIP() << models << " (assimp-testmodels) is absent";
}

// --- Missing textures ------------------------------------------------------------------------

// A ground square seen from the top, its base colour texture `uri` (written by the caller, or
// not at all).
fs::path texturedSquare(const TempDir& dir, const std::string& name, const std::string& uri) {
  AssetWriter asset;
  asset.doc["images"] = {{{"uri", uri}}};
  asset.doc["textures"] = {{{"source", 0}}};
  const int material = asset.material({{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}, {"metallicFactor", 0}}}});
  asset.node({{"mesh", groundSquare(asset, 1, material)}});
  return asset.write(dir, name);
}

// Cells of the checker across the middle row of the square (top view, orthographic: the square
// [-1, 1]^2 fills sqrt 2 / 1.02 of the image's half-width): the number of colour changes
// between magenta-ish and dark, and whether both colours appear.
int checkerChanges(const Image& image) {
  const int y = image.height / 2 + 3;  // off the cells' shared edge
  const double half = image.width / 2.0 / (std::sqrt(2.0) * 1.02);
  int changes = 0, last = -1;
  for (int x = static_cast<int>(image.width / 2.0 - 0.95 * half); x < static_cast<int>(image.width / 2.0 + 0.95 * half); ++x) {
    const auto c = image.at(x, y);
    const int kind = (c[0] > 0.3f && c[2] > 0.3f && c[1] < 0.6f * c[0]) ? 1 : (c[0] < 0.2f && c[1] < 0.2f && c[2] < 0.2f) ? 0 : -1;
    if (kind < 0) continue;
    if (last >= 0 && kind != last) ++changes;
    last = kind;
  }
  return changes;
}

TEST(Fidelity, MissingOrUndecodableTextureIsACheckerAndNamed) {
  TempDir dir;
  for (const std::string name : {"garbage.png", "garbage.dat"})
    std::ofstream(dir / name, std::ios::binary) << "this is not an image file, only some bytes that no decoder reads";
  for (const std::string uri : {"missing.png", "garbage.png", "garbage.dat"}) {
    const fs::path asset = texturedSquare(dir, "square_" + uri.substr(0, uri.size() - 4), uri);
    const Shot shot = screenshot(dir, uri, "'" + asset.string() + "' --camera top --ortho --size 300x300 --no-shadows");
    std::printf("%s: %d colour changes across the square\n", uri.c_str(), checkerChanges(shot.image));
    // 8 cells across the UV square: 7 changes inside it.
    EXPECT_GE(checkerChanges(shot.image), 6) << uri;
    EXPECT_NE(shot.output.find("image 0 '" + uri + "'"), std::string::npos) << shot.output;
    EXPECT_NE(shot.output.find("drawn as a magenta checker"), std::string::npos) << shot.output;
    // No message that ends where its reason should be.
    EXPECT_EQ(std::regex_search(shot.output, std::regex(": *\n")), false) << shot.output;
  }
}

// --- --animation errors ----------------------------------------------------------------------

TEST(Fidelity, UnknownAnimationErrorListsTheFilesAnimations) {
  TempDir dir;
  const fs::path asset = travellingSphere(dir);
  for (const std::string asked : {"walk", "1"}) {
    const auto result = view("'" + asset.string() + "' --size 64x64 --animation " + asked + " --screenshot '" + (dir / "x.png").string() + "'");
    EXPECT_NE(result.exitCode, 0) << result.output;
    EXPECT_NE(result.output.find("no animation '" + asked + "'"), std::string::npos) << result.output;
    EXPECT_NE(result.output.find("it has 1: 0 'travel'"), std::string::npos) << result.output;
  }
  // A file without animations says so.
  const fs::path still = shadowScene(dir);
  const auto result = view("'" + still.string() + "' --size 64x64 --time 1 --screenshot '" + (dir / "y.png").string() + "'");
  EXPECT_NE(result.output.find("it has 0: none"), std::string::npos) << result.output;
}

}  // namespace
