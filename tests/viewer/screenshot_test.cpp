// SPDX-License-Identifier: MIT
// tangent-view headless, as the tests of the viewer issue ask: runs under Xvfb with Mesa's
// llvmpipe (the CTest entry wraps it in xvfb-run).
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <numeric>
#include <sstream>

#include <nlohmann/json.hpp>

#include "support/run_command.hpp"
#include "support/skip_or_fail.hpp"
#include "support/temp_dir.hpp"
#include "viewer/png_image.hpp"

namespace {

namespace fs = std::filesystem;
using tangent::testing::TempDir;

using tangent::testing::Image;
using tangent::testing::readPng;

int run(const std::string& arguments, std::string& output) {
  const auto result = tangent::testing::runCommand(std::string(TANGENT_VIEW) + " " + arguments);
  output = result.output;
  return result.exitCode;
}

Image screenshot(const TempDir& dir, const std::string& name, const std::string& arguments) {
  const fs::path out = dir / (name + ".png");
  std::string output;
  const int exit = run(arguments + " --screenshot '" + out.string() + "'", output);
  EXPECT_EQ(exit, 0) << arguments << "\n" << output;
  EXPECT_EQ(output.find("OpenGL errors"), std::string::npos) << output;
  return exit == 0 ? readPng(out) : Image{};
}

// Mean luma of the pixels within `radius` of (cx, cy), split into four quadrants.
std::array<float, 4> quadrantMeans(const Image& image, double cx, double cy, double radius) {
  std::array<double, 4> sum{};
  std::array<int, 4> count{};
  for (int y = static_cast<int>(cy - radius); y <= static_cast<int>(cy + radius); ++y) {
    for (int x = static_cast<int>(cx - radius); x <= static_cast<int>(cx + radius); ++x) {
      const double dx = x - cx, dy = y - cy;
      if (dx * dx + dy * dy > radius * radius || x < 0 || y < 0 || x >= image.width || y >= image.height) continue;
      const int q = (dx < 0 ? 0 : 1) + (dy < 0 ? 0 : 2);
      sum[q] += image.luma(x, y);
      ++count[q];
    }
  }
  std::array<float, 4> means{};
  for (int q = 0; q < 4; ++q) means[q] = count[q] ? static_cast<float>(sum[q] / count[q]) : 0.0f;
  return means;
}

// NormalTangentTest, front, orthographic: 3 x 5 cells; in each, a sphere of real geometry
// (left square) and a flat quad with the same sphere in its normal map (right square).
// Model-space layout of the asset: columns at x = -0.8, 0, 0.8 (squares at -/+0.16), rows at
// y = 0.8 ... -0.8. Returns, per cell, the largest quadrant difference in mean luma.
std::vector<float> cellDifferences(const Image& image) {
  // The camera frames the bounding sphere: centre and radius of the asset's POSITION bounds.
  const double minX = -1.11, maxX = 1.11, minY = -1.2, maxY = 0.95, minZ = -0.00999999, maxZ = 0.0805;
  const double cx = (minX + maxX) / 2, cy = (minY + maxY) / 2;
  const double radius = std::sqrt((maxX - minX) * (maxX - minX) + (maxY - minY) * (maxY - minY) + (maxZ - minZ) * (maxZ - minZ)) / 2;
  const double halfHeight = radius * 1.02;  // OrbitCamera's orthographic framing (square image)
  const double pixelsPerUnit = image.height / (2 * halfHeight);
  auto toPixel = [&](double x, double y) {
    return std::make_pair(image.width / 2.0 + (x - cx) * pixelsPerUnit, image.height / 2.0 - (y - cy) * pixelsPerUnit);
  };
  std::vector<float> differences;
  for (double column : {-0.8, 0.0, 0.8}) {
    for (double row : {0.8, 0.4, 0.0, -0.4, -0.8}) {
      const auto [lx, ly] = toPixel(column - 0.16, row);
      const auto [rx, ry] = toPixel(column + 0.16, row);
      const double r = 0.09 * pixelsPerUnit;  // inside the sphere of each square
      const auto left = quadrantMeans(image, lx, ly, r), right = quadrantMeans(image, rx, ry, r);
      float worst = 0;
      for (int q = 0; q < 4; ++q) worst = std::max(worst, std::abs(left[q] - right[q]));
      differences.push_back(worst);
    }
  }
  return differences;
}

TEST(Viewer, NormalTangentTestHalvesShadeAlikeAndFlipsAreCaught) {
  const fs::path asset = fs::path(TANGENT_SOURCE_DIR) / ".." / "shared" / "assets" / "NormalTangentTest.glb";
  if (!fs::exists(asset)) TANGENT_SKIP_OR_FAIL("../shared/assets is absent: skipping NormalTangentTest");
  TempDir dir;
  const std::string common = "'" + asset.string() + "' --camera front --ortho --size 800x800 --no-shadows";
  const auto good = cellDifferences(screenshot(dir, "good", common));
  const auto flipped = cellDifferences(screenshot(dir, "flip", common + " --flip-green"));
  const auto negated = cellDifferences(screenshot(dir, "negate", common + " --negate-w"));
  ASSERT_EQ(good.size(), 15u);
  int flippedCaught = 0, negatedCaught = 0;
  for (std::size_t cell = 0; cell < good.size(); ++cell) {
    std::printf("cell %2zu: quadrant luma difference good %.3f, green flipped %.3f, w negated %.3f\n", cell, good[cell], flipped[cell],
                negated[cell]);
    EXPECT_LT(good[cell], 0.06f) << "cell " << cell;
    flippedCaught += flipped[cell] > 0.08f;
    negatedCaught += negated[cell] > 0.08f;
  }
  EXPECT_EQ(flippedCaught, 15);
  EXPECT_EQ(negatedCaught, 15);
}

TEST(Viewer, DemoSceneShadowFallsWhereTheSphereOccludesTheSun) {
  TempDir dir;
  // The environment of image-based lighting is not shadowed (as in the Sample Viewer): left out
  // here, so that the shadow map's part is what is measured.
  const std::string common = "--camera top --ortho --size 600x600 --no-ibl";
  const Image shadowed = screenshot(dir, "shadows", common);
  const Image plain = screenshot(dir, "no-shadows", common + " --no-shadows");
  ASSERT_EQ(shadowed.width, 600);
  // data/demo/scene.gltf: plane y = 0 over [-4, 4]^2, middle sphere at (0, 0.7, -0.4) radius 0.7,
  // sun shining along (0.7, -0.6, -0.3) (tools/make_data). The shadow of the sphere's centre:
  const double d[3] = {0.7, -0.6, -0.3};
  const double t = 0.7 / -d[1];
  const double shadowX = 0 + t * d[0], shadowZ = -0.4 + t * d[2];
  // Top view of the scene's bounding sphere (centre (0, 0.7, 0), the plane's corners dominate).
  const double radius = std::sqrt(8.0 * 8.0 + 8.0 * 8.0 + 1.4 * 1.4) / 2, halfHeight = radius * 1.02;
  const double pixelsPerUnit = 600 / (2 * halfHeight);
  auto pixel = [&](double x, double z) { return std::make_pair(300 + x * pixelsPerUnit, 300 + z * pixelsPerUnit); };
  auto meanLuma = [](const Image& image, std::pair<double, double> at) {
    const auto q = quadrantMeans(image, at.first, at.second, 6);
    return (q[0] + q[1] + q[2] + q[3]) / 4;
  };
  const auto inShadow = pixel(shadowX, shadowZ);
  const auto litPlane = pixel(-2.5, 2.5);  // far from every sphere and shadow
  const float shadowOn = meanLuma(shadowed, inShadow), shadowOff = meanLuma(plain, inShadow);
  const float litOn = meanLuma(shadowed, litPlane), litOff = meanLuma(plain, litPlane);
  std::printf("shadow spot: %.3f with shadows, %.3f without; lit plane: %.3f / %.3f\n", shadowOn, shadowOff, litOn, litOff);
  EXPECT_LT(shadowOn, 0.6f * shadowOff);            // a clear shadow where the sphere blocks the sun
  EXPECT_NEAR(litOn, litOff, 0.02f);                // the lit plane is untouched
  // Without shadows the spot is as bright as plane nearby (1 unit across the light's path; the
  // blue point lamp brightens the far corner, so that is no reference here).
  const float besideOff = meanLuma(plain, pixel(shadowX - 0.36, shadowZ - 0.84));
  EXPECT_GT(shadowOff, 0.85f * besideOff);
}

// PCF widens the shadow's edge: on a coarse shadow map (256 texels over the scene, about 2.3
// pixels a texel here), PCF 5x5 shades many more pixels around the sphere's shadow between the
// shadowed and the lit level than a single bilinear comparison does. PCF is a shader variant
// (SHADOW_PCF), so a variant that left its taps out would show the hard edge at every radius.
TEST(Viewer, PcfSoftensTheShadowEdge) {
  TempDir dir;
  const std::string common = "--camera top --ortho --size 600x600 --no-ibl --shadow-map-size 256";
  const Image hard = screenshot(dir, "pcf0", common + " --pcf 0");
  const Image soft = screenshot(dir, "pcf2", common + " --pcf 2");
  const Image plain = screenshot(dir, "no-shadows", common + " --no-shadows");
  ASSERT_EQ(hard.width, 600);
  // Pixels within 130 of the image centre (the middle sphere's shadow falls there, as in
  // DemoSceneShadowFallsWhereTheSphereOccludesTheSun) that the shadow darkens by 20-80% of its
  // full depth (the darkest pixel's).
  auto partlyShadowed = [&](const Image& shadowed) {
    float deepest = 0;
    for (int y = 170; y < 430; ++y)
      for (int x = 170; x < 430; ++x) deepest = std::max(deepest, plain.luma(x, y) - shadowed.luma(x, y));
    int count = 0;
    for (int y = 170; y < 430; ++y)
      for (int x = 170; x < 430; ++x) {
        const float darkening = plain.luma(x, y) - shadowed.luma(x, y);
        if (darkening > 0.2f * deepest && darkening < 0.8f * deepest) ++count;
      }
    return count;
  };
  const int hardEdge = partlyShadowed(hard), softEdge = partlyShadowed(soft);
  std::printf("partly shadowed pixels: %d with PCF off, %d with PCF 5x5\n", hardEdge, softEdge);
  EXPECT_GT(hardEdge, 0);
  EXPECT_GT(softEdge, 2 * hardEdge);
}

// The demo material's specular map has green, white and black bands (RGB colour, A strength):
// in the specular-map mode, the highlight the specular term adds must come in white and in green.
TEST(Viewer, SpecularMapColoursTheHighlights) {
  TempDir dir;
  const std::string common = "'" + (fs::path(TANGENT_SOURCE_DIR) / "data" / "demo" / "sphere.gltf").string() +
                             "' --camera front --size 400x400 --no-shadows";
  const Image on = screenshot(dir, "specular", common + " --shading blinn-phong"),
              off = screenshot(dir, "no-specular", common + " --shading blinn-phong --no-specular");
  ASSERT_EQ(on.rgb.size(), off.rgb.size());
  int white = 0, green = 0;
  for (int y = 0; y < on.height; ++y) {
    for (int x = 0; x < on.width; ++x) {
      const auto a = on.at(x, y), b = off.at(x, y);
      const float r = a[0] - b[0], g = a[1] - b[1], bl = a[2] - b[2];
      if (g > 0.08f && std::abs(r - g) < 0.03f && std::abs(bl - g) < 0.03f) ++white;
      if (g > 0.04f && g > 2 * r && g > 2 * bl) ++green;  // the green band lies off the key light's highlight
    }
  }
  std::printf("highlight pixels: %d white, %d green\n", white, green);
  EXPECT_GT(white, 50);
  EXPECT_GT(green, 20);
}

TEST(Viewer, EveryDebugViewRendersAndDiffersFromLit) {
  TempDir dir;
  const std::string common = "--size 320x180";
  const Image lit = screenshot(dir, "lit", common);
  ASSERT_EQ(lit.width, 320);
  for (const char* view : {"geometry-normal", "tangent", "bitangent", "shading-normal", "uv", "handedness", "error", "face-orientation"}) {
    const Image image = screenshot(dir, view, common + " --view " + view);
    ASSERT_EQ(image.rgb.size(), lit.rgb.size()) << view;
    double difference = 0;
    for (std::size_t i = 0; i < image.rgb.size(); ++i) difference += std::abs(image.rgb[i] - lit.rgb[i]);
    difference /= static_cast<double>(image.rgb.size());
    EXPECT_GT(difference, 0.02) << view;
  }
  const Image glyphs = screenshot(dir, "glyphs", common + " --glyphs");
  double difference = 0;
  for (std::size_t i = 0; i < glyphs.rgb.size(); ++i) difference += std::abs(glyphs.rgb[i] - lit.rgb[i]);
  EXPECT_GT(difference, 0.0);
}

// A copy of a demo asset (with its .bin and textures) whose scene is wrapped in a node with
// the given extra JSON (a transform), and whose material is given `doubleSided`.
fs::path demoCopy(const TempDir& dir, const std::string& name, const nlohmann::json& wrapper, bool doubleSided) {
  const fs::path demo = fs::path(TANGENT_SOURCE_DIR) / "data" / "demo";
  const fs::path folder = dir / (name + (wrapper.empty() ? "" : "-wrapped") + (doubleSided ? "-double" : ""));
  fs::create_directories(folder);
  for (const auto& entry : fs::directory_iterator(demo)) {
    if (entry.path().extension() != ".gltf") fs::copy_file(entry.path(), folder / entry.path().filename());
  }
  nlohmann::json doc = nlohmann::json::parse(std::ifstream(demo / (name + ".gltf")));
  if (!wrapper.empty()) {
    nlohmann::json node = wrapper;
    node["children"] = doc["scenes"][0]["nodes"];
    doc["nodes"].push_back(node);
    doc["scenes"][0]["nodes"] = nlohmann::json::array({doc["nodes"].size() - 1});
  }
  for (auto& material : doc["materials"]) material["doubleSided"] = doubleSided;
  std::ofstream(folder / (name + ".gltf")) << doc.dump();
  return folder / (name + ".gltf");
}

float backgroundShare(const Image& image) {
  int background = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const auto c = image.at(x, y);
      background += std::abs(c[0] - 0.16f) < 0.02f && std::abs(c[1] - 0.17f) < 0.02f && std::abs(c[2] - 0.19f) < 0.02f;
    }
  }
  return static_cast<float>(background) / static_cast<float>(image.width * image.height);
}

// The demo sphere's specularTexture and specularColorTexture are one texture, which the viewer
// reads once (strength from A, colour from RGB); a copy whose colour texture names a second image
// of the same file takes the two-fetch path. Both render alike, and the specular map shows.
TEST(Viewer, OneFetchForTheSharedSpecularTextureRendersAsTwo) {
  TempDir dir;
  const fs::path shared = demoCopy(dir, "sphere", {}, false);
  const fs::path folder = dir / "separate";
  fs::create_directories(folder);
  for (const auto& entry : fs::directory_iterator(shared.parent_path())) fs::copy_file(entry.path(), folder / entry.path().filename());
  nlohmann::json doc = nlohmann::json::parse(std::ifstream(shared));
  auto& extension = doc["materials"][0]["extensions"]["KHR_materials_specular"];
  ASSERT_EQ(extension["specularTexture"]["index"], extension["specularColorTexture"]["index"]);
  const int texture = extension["specularTexture"]["index"];
  nlohmann::json image = doc["images"][doc["textures"][texture]["source"].get<int>()];
  doc["images"].push_back(image);
  doc["textures"].push_back({{"source", doc["images"].size() - 1}, {"sampler", doc["textures"][texture]["sampler"]}});
  extension["specularColorTexture"]["index"] = doc["textures"].size() - 1;
  std::ofstream(folder / "sphere.gltf") << doc.dump();
  const std::string common = " --camera front --size 300x300";
  const Image one = screenshot(dir, "one-fetch", "'" + shared.string() + "'" + common),
              two = screenshot(dir, "two-fetches", "'" + (folder / "sphere.gltf").string() + "'" + common),
              none = screenshot(dir, "no-specular", "'" + shared.string() + "'" + common + " --no-specular");
  ASSERT_EQ(one.rgb.size(), two.rgb.size());
  ASSERT_EQ(one.rgb.size(), none.rgb.size());
  float largest = 0, specular = 0;
  for (std::size_t i = 0; i < one.rgb.size(); ++i) {
    largest = std::max(largest, std::abs(one.rgb[i] - two.rgb[i]));
    specular = std::max(specular, std::abs(two.rgb[i] - none.rgb[i]));
  }
  std::printf("largest difference one fetch against two: %.4f; specular's largest contribution: %.4f\n", largest, specular);
  EXPECT_LE(largest, 2.5f / 255);
  EXPECT_GT(specular, 0.1f);
}

// Every demo primitive, and the same under a mirroring node, is wound counter-clockwise seen
// from outside: the face-orientation view shows no back face (red) anywhere.
TEST(Viewer, DemoPrimitivesShowOnlyFrontFaces) {
  TempDir dir;
  for (const char* name : {"cube", "sphere", "torus", "scene"}) {
    for (const bool mirror : {false, true}) {
      const fs::path file = mirror ? demoCopy(dir, name, {{"scale", {-1, 1, 1}}}, false)
                                   : fs::path(TANGENT_SOURCE_DIR) / "data" / "demo" / (std::string(name) + ".gltf");
      const Image image = screenshot(dir, std::string(name) + (mirror ? "-mirrored" : ""),
                                     "'" + file.string() + "' --view face-orientation --size 240x180");
      int front = 0, back = 0;
      for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) {
          const auto c = image.at(x, y);
          front += c[2] > 0.8f && c[0] < 0.3f;
          back += c[0] > 0.8f && c[2] < 0.3f;
        }
      }
      EXPECT_GT(front, 1000) << name << (mirror ? " mirrored" : "");
      EXPECT_EQ(back, 0) << name << (mirror ? " mirrored" : "");
    }
  }
}

// Mirroring a normal-mapped sphere with a node's negative scale mirrors its shading normals:
// pixel (x, y) of the copy shows the normal of pixel (w - 1 - x, y) of the original with x
// negated (shading-normal view: red = x * 0.5 + 0.5). This needs the node's winding handled
// and the bitangent's sign turned with the transform's determinant.
TEST(Viewer, MirroredNodeMirrorsTheShadingNormals) {
  TempDir dir;
  const fs::path original = fs::path(TANGENT_SOURCE_DIR) / "data" / "demo" / "sphere.gltf";
  const fs::path mirrored = demoCopy(dir, "sphere", {{"scale", {-1, 1, 1}}}, false);
  const std::string common = " --view shading-normal --camera front --ortho --size 300x300";
  const Image a = screenshot(dir, "sphere", "'" + original.string() + "'" + common);
  const Image b = screenshot(dir, "sphere-mirrored", "'" + mirrored.string() + "'" + common);
  ASSERT_EQ(a.rgb.size(), b.rgb.size());
  double error = 0, flatError = 0;
  int samples = 0;
  for (int y = 0; y < a.height; ++y) {
    for (int x = 0; x < a.width; ++x) {
      const auto p = a.at(a.width - 1 - x, y), q = b.at(x, y);
      if (backgroundShare(Image{1, 1, {p[0], p[1], p[2]}}) > 0 || backgroundShare(Image{1, 1, {q[0], q[1], q[2]}}) > 0) continue;
      error += std::abs(q[0] - (1 - p[0])) + std::abs(q[1] - p[1]) + std::abs(q[2] - p[2]);
      flatError += std::abs(q[0] - p[0]) + std::abs(q[1] - p[1]) + std::abs(q[2] - p[2]);
      ++samples;
    }
  }
  ASSERT_GT(samples, 20000);
  std::printf("mirrored shading normals: mean error %.4f (unmirrored comparison %.4f) over %d pixels\n", error / samples,
              flatError / samples, samples);
  EXPECT_LT(error / samples, 0.02);
}

// Seen from behind, a single-sided quad is culled and a double-sided one is drawn.
TEST(Viewer, OnlyDoubleSidedMaterialsShowTheirBackFaces) {
  TempDir dir;
  const std::string common = " --camera back --size 240x180 --no-shadows";
  const Image single = screenshot(dir, "single", "'" + demoCopy(dir, "quad", {}, false).string() + "'" + common);
  const Image both = screenshot(dir, "double", "'" + demoCopy(dir, "quad", {}, true).string() + "'" + common);
  EXPECT_GT(backgroundShare(single), 0.999f);
  EXPECT_LT(backgroundShare(both), 0.7f);
}

// Every generated test asset (every accessor form: strides, quantized and normalized
// integers, sparse, no bufferView, strips and fans, morph targets, a second UV set, materials
// without pbrMetallicRoughness), as written and as baked, opens and renders without error.
TEST(Viewer, OpensEveryGeneratedTestAsset) {
  TempDir dir;
  const auto written = tangent::testing::runCommand(std::string(TANGENT_TEST_ASSETS) + " '" + dir.path().string() + "'");
  ASSERT_EQ(written.exitCode, 0) << written.output;
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(dir.path())) {
    if (entry.path().extension() == ".gltf") files.push_back(entry.path());  // the .glb twins hold the same
  }
  std::sort(files.begin(), files.end());
  ASSERT_GE(files.size(), 8u);
  fs::create_directories(dir / "baked");
  for (const fs::path& file : files) {
    const fs::path baked = dir / "baked" / (file.stem().string() + ".glb");
    const auto bake = tangent::testing::runCommand(std::string(TANGENT_CLI) + " bake '" + file.string() + "' -o '" + baked.string() + "' --all -q");
    ASSERT_EQ(bake.exitCode, 0) << file << "\n" << bake.output;
    for (const fs::path& input : {file, baked}) {
      const Image image = screenshot(dir, input.stem().string() + (input == baked ? "-baked" : ""),
                                     "'" + input.string() + "' --size 160x120 --no-shadows");
      EXPECT_EQ(image.width, 160) << input;
      EXPECT_LT(backgroundShare(image), 0.995f) << input << " shows nothing";
    }
  }
}

// ---- Linear pipeline, PBR, texCoord and KHR_texture_transform, alpha, MSAA, shadow cache ----

// Writes an RGBA8 PNG of width x height whose pixel (x, y) (y from the top) is colour(x, y).
template <class Colour>
void writeRgbaPng(const fs::path& path, int width, int height, Colour colour) {
  std::vector<unsigned char> pixels(static_cast<std::size_t>(width) * height * 4);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const std::array<unsigned char, 4> c = colour(x, y);
      std::copy(c.begin(), c.end(), &pixels[(static_cast<std::size_t>(y) * width + x) * 4]);
    }
  auto out = OIIO::ImageOutput::create(path.string());
  OIIO::ImageSpec spec(width, height, 4, OIIO::TypeDesc::UINT8);
  spec.attribute("oiio:UnassociatedAlpha", 1);  // written as given: straight alpha, as glTF's
  ASSERT_TRUE(out && out->open(path.string(), spec));
  out->write_image(OIIO::TypeDesc::UINT8, pixels.data());
  out->close();
}

// A quad over [-1, 1]^2 at z = 0 facing +z with TEXCOORD_0 = ((x + 1) / 2, (1 - y) / 2) (the
// image upright seen from the front) and TEXCOORD_1 the same mirrored in u, with `material` and
// texture 0 = image 0 = `image`.
fs::path quadAsset(const TempDir& dir, const std::string& name, const nlohmann::json& material, const std::string& image,
                   const nlohmann::json& patch = nlohmann::json::object()) {
  const float positions[] = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
  const float normals[] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
  const float uv0[] = {0, 1, 1, 1, 1, 0, 0, 0};
  const float uv1[] = {1, 1, 0, 1, 0, 0, 1, 0};
  const std::uint16_t indices[] = {0, 1, 2, 0, 2, 3};
  std::string bin;
  auto append = [&](const void* data, std::size_t bytes) { bin.append(static_cast<const char*>(data), bytes); };
  append(positions, sizeof positions);
  append(normals, sizeof normals);
  append(uv0, sizeof uv0);
  append(uv1, sizeof uv1);
  append(indices, sizeof indices);
  std::ofstream(dir / (name + ".bin"), std::ios::binary) << bin;
  nlohmann::json doc = {
      {"asset", {{"version", "2.0"}}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}, {"TEXCOORD_1", 3}}}, {"indices", 4}, {"material", 0}}}}}}},
      {"materials", {material}},
      {"textures", {{{"source", 0}}}},
      {"images", {{{"uri", image}}}},
      {"buffers", {{{"uri", name + ".bin"}, {"byteLength", bin.size()}}}},
      {"bufferViews", {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 48}},
                       {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 48}},
                       {{"buffer", 0}, {"byteOffset", 96}, {"byteLength", 32}},
                       {{"buffer", 0}, {"byteOffset", 128}, {"byteLength", 32}},
                       {{"buffer", 0}, {"byteOffset", 160}, {"byteLength", 12}}}},
      {"accessors", {{{"bufferView", 0}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}, {"min", {-1, -1, 0}}, {"max", {1, 1, 0}}},
                     {{"bufferView", 1}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}},
                     {{"bufferView", 2}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}},
                     {{"bufferView", 3}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}},
                     {{"bufferView", 4}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}}}},
  };
  if (material.contains("extensions")) {
    for (const auto& [extension, value] : material["extensions"].items()) doc["extensionsUsed"].push_back(extension);
  }
  doc.merge_patch(patch);
  const fs::path file = dir / (name + ".gltf");
  std::ofstream(file) << doc.dump(1);
  return file;
}

// The pixel of a front orthographic 200x200 view of quadAsset at model point (x, y): the
// camera frames the quad's bounding sphere (radius sqrt 2) with OrbitCamera's 1.02 margin.
std::array<float, 3> quadPixel(const Image& image, double x, double y) {
  const double pixelsPerUnit = image.height / (2 * std::sqrt(2.0) * 1.02);
  return image.at(static_cast<int>(image.width / 2.0 + x * pixelsPerUnit), static_cast<int>(image.height / 2.0 - y * pixelsPerUnit));
}

double srgbToLinear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }
double linearToSrgb(double c) { return c <= 0.0031308 ? c * 12.92 : 1.055 * std::pow(c, 1 / 2.4) - 0.055; }

const char* const kQuadView = " --camera front --ortho --size 200x200 --no-shadows";

// An unlit quad with a flat sRGB mid-grey texture reads back as that grey (decoded to linear by
// the sampler, encoded again at the output); with baseColorFactor 0.5 it reads back as half the
// linear value, sRGB-encoded (92/255), not as half the stored value (64/255) that lighting in
// gamma space gives.
TEST(Viewer, SrgbTextureDecodedLitLinearAndEncoded) {
  TempDir dir;
  writeRgbaPng(dir / "grey.png", 8, 8, [](int, int) { return std::array<unsigned char, 4>{128, 128, 128, 255}; });
  for (const double factor : {1.0, 0.5}) {
    const nlohmann::json material = {
        {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}, {"baseColorFactor", {factor, factor, factor, 1.0}}}},
        {"extensions", {{"KHR_materials_unlit", nlohmann::json::object()}}}};
    const std::string name = "grey-" + std::to_string(static_cast<int>(factor * 100));
    const Image image = screenshot(dir, name, "'" + quadAsset(dir, name, material, "grey.png").string() + "'" + kQuadView);
    ASSERT_EQ(image.width, 200);
    const double expected = linearToSrgb(factor * srgbToLinear(128 / 255.0));
    const auto centre = quadPixel(image, 0, 0);
    std::printf("factor %.1f: centre %.4f (%.1f/255), expected %.4f (%.1f/255)\n", factor, centre[0], centre[0] * 255, expected, expected * 255);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(centre[c], expected, 1.5 / 255) << "factor " << factor;
  }
}

// Four flat quadrants: top left red, top right green, bottom left blue, bottom right white.
std::array<unsigned char, 4> quadrantColour(int x, int y) {
  const bool right = x >= 32, bottom = y >= 32;
  if (!right && !bottom) return {255, 0, 0, 255};
  if (right && !bottom) return {0, 255, 0, 255};
  if (!right && bottom) return {0, 0, 255, 255};
  return {255, 255, 255, 255};
}

char colourName(std::array<float, 3> c) {
  if (c[0] > 0.8f && c[1] > 0.8f && c[2] > 0.8f) return 'W';
  if (c[0] > 0.8f && c[1] < 0.2f && c[2] < 0.2f) return 'R';
  if (c[1] > 0.8f && c[0] < 0.2f && c[2] < 0.2f) return 'G';
  if (c[2] > 0.8f && c[0] < 0.2f && c[1] < 0.2f) return 'B';
  return '?';
}

// Each texture samples the UV set its texCoord names, through its KHR_texture_transform (the
// extension's texCoord overriding), rotation as textureTransformMatrix documents it.
TEST(Viewer, TexCoordAndTextureTransformChooseTheTexels) {
  TempDir dir;
  writeRgbaPng(dir / "quadrants.png", 64, 64, quadrantColour);
  struct Case {
    const char* name;
    const char* textureInfo;  // JSON
    const char* expected;     // colours at the quad's top left and top right quarter points
  };
  const Case cases[] = {
      {"texcoord0", R"({"index": 0})", "RG"},
      {"texcoord1", R"({"index": 0, "texCoord": 1})", "GR"},
      {"offset", R"({"index": 0, "extensions": {"KHR_texture_transform": {"offset": [0.5, 0.0]}}})", "GR"},
      {"scale", R"({"index": 0, "extensions": {"KHR_texture_transform": {"scale": [1.0, 3.0]}}})", "BW"},
      // A quarter turn: uv' = (cos u + sin v, -sin u + cos v): (0.25, 0.25) -> (0.25, -0.25),
      // blue (repeat); the GLSL listing's matrix would give (-0.25, 0.25), green.
      {"rotation", R"({"index": 0, "extensions": {"KHR_texture_transform": {"rotation": 1.5707963267948966}}})", "BR"},
      {"override", R"({"index": 0, "extensions": {"KHR_texture_transform": {"texCoord": 1}}})", "GR"},
  };
  for (const Case& c : cases) {
    const nlohmann::json material = {{"pbrMetallicRoughness", {{"baseColorTexture", nlohmann::json::parse(c.textureInfo)}}},
                                     {"extensions", {{"KHR_materials_unlit", nlohmann::json::object()}}}};
    const Image image = screenshot(dir, c.name, "'" + quadAsset(dir, c.name, material, "quadrants.png").string() + "'" + kQuadView);
    ASSERT_EQ(image.width, 200) << c.name;
    const std::string seen{colourName(quadPixel(image, -0.5, 0.5)), colourName(quadPixel(image, 0.5, 0.5))};
    EXPECT_EQ(seen, c.expected) << c.name;
  }
}

// alphaMode: MASK discards below alphaCutoff, BLEND mixes over what is behind, OPAQUE ignores alpha.
TEST(Viewer, AlphaMaskCutsOutAndBlendMixes) {
  TempDir dir;
  // Left half alpha 0, right half alpha 1, all white.
  writeRgbaPng(dir / "half.png", 64, 64, [](int x, int) { return std::array<unsigned char, 4>{255, 255, 255, static_cast<unsigned char>(x < 32 ? 0 : 255)}; });
  const std::array<float, 3> background{0.16f, 0.17f, 0.19f};
  auto render = [&](const std::string& mode, double factorAlpha) {
    nlohmann::json material = {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}, {"baseColorFactor", {1.0, 1.0, 1.0, factorAlpha}}}},
                               {"alphaMode", mode},
                               {"extensions", {{"KHR_materials_unlit", nlohmann::json::object()}}}};
    return screenshot(dir, mode, "'" + quadAsset(dir, mode, material, "half.png").string() + "'" + kQuadView);
  };
  const Image mask = render("MASK", 1.0), blend = render("BLEND", 0.5), opaque = render("OPAQUE", 1.0);
  ASSERT_EQ(mask.width, 200);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(quadPixel(mask, -0.5, 0)[c], background[c], 0.01f) << "masked-out half shows the background";
    EXPECT_NEAR(quadPixel(mask, 0.5, 0)[c], 1.0f, 0.01f) << "kept half is white";
    EXPECT_NEAR(quadPixel(blend, -0.5, 0)[c], background[c], 0.01f) << "alpha 0 adds nothing";
    EXPECT_NEAR(quadPixel(blend, 0.5, 0)[c], 0.5f * (1.0f + background[c]), 0.01f) << "alpha 0.5 mixes half and half";
    EXPECT_NEAR(quadPixel(opaque, -0.5, 0)[c], 1.0f, 0.01f) << "opaque ignores alpha";
  }
}

// occlusionTexture darkens the environment (ambient) term where its R channel is low, as much
// as its strength says; direct light is untouched.
TEST(Viewer, OcclusionMapDarkensTheAmbientTerm) {
  TempDir dir;
  writeRgbaPng(dir / "occlusion.png", 64, 64, [](int x, int) {
    const auto r = static_cast<unsigned char>(x < 32 ? 0 : 255);
    return std::array<unsigned char, 4>{r, r, r, 255};
  });
  auto render = [&](const std::string& name, double strength) {
    const nlohmann::json material = {{"pbrMetallicRoughness", {{"metallicFactor", 0.0}, {"roughnessFactor", 1.0}}},
                                     {"occlusionTexture", {{"index", 0}, {"strength", strength}}}};
    return screenshot(dir, name, "'" + quadAsset(dir, name, material, "occlusion.png").string() + "'" + kQuadView + " --shading pbr");
  };
  const Image full = render("strength1", 1.0), none = render("strength0", 0.0);
  ASSERT_EQ(full.width, 200);
  auto luma = [](std::array<float, 3> c) { return 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2]; };
  const float occludedHalf = luma(quadPixel(full, -0.5, 0)), openHalf = luma(quadPixel(full, 0.5, 0));
  const float noneLeft = luma(quadPixel(none, -0.5, 0)), noneRight = luma(quadPixel(none, 0.5, 0));
  std::printf("strength 1: occluded %.3f, open %.3f; strength 0: %.3f, %.3f\n", occludedHalf, openHalf, noneLeft, noneRight);
  EXPECT_LT(occludedHalf, openHalf - 0.03f);
  EXPECT_NEAR(openHalf, noneRight, 0.01f);     // occlusion 1 changes nothing
  EXPECT_GT(noneLeft, occludedHalf + 0.03f);   // strength 0 turns it off
}

// glTF's occlusion-roughness-metallic packing: occlusionTexture and metallicRoughnessTexture
// are one texture, which the viewer reads once (occlusion from R); a copy whose occlusionTexture
// names a second image of the same file takes the two-fetch path. Both render alike, and the
// occlusion (R: dark on the left) and the metallic (B: metal at the bottom) both show.
TEST(Viewer, OneFetchForThePackedOcclusionTextureRendersAsTwo) {
  TempDir dir;
  writeRgbaPng(dir / "orm.png", 64, 64, [](int x, int y) {
    return std::array<unsigned char, 4>{static_cast<unsigned char>(x < 32 ? 30 : 255), 150, static_cast<unsigned char>(y < 32 ? 0 : 255), 255};
  });
  auto render = [&](const std::string& name, int occlusionTexture, double strength) {
    const nlohmann::json material = {
        {"pbrMetallicRoughness", {{"baseColorFactor", {0.8, 0.7, 0.6, 1.0}}, {"metallicRoughnessTexture", {{"index", 0}}}}},
        {"occlusionTexture", {{"index", occlusionTexture}, {"strength", strength}}}};
    const nlohmann::json patch = {{"textures", {{{"source", 0}}, {{"source", 1}}}}, {"images", {{{"uri", "orm.png"}}, {{"uri", "orm.png"}}}}};
    return screenshot(dir, name, "'" + quadAsset(dir, name, material, "orm.png", patch).string() + "'" + kQuadView + " --shading pbr");
  };
  const Image one = render("one-fetch", 0, 1.0), two = render("two-fetches", 1, 1.0), off = render("strength0", 0, 0.0);
  ASSERT_EQ(one.rgb.size(), two.rgb.size());
  float largest = 0;
  for (std::size_t i = 0; i < one.rgb.size(); ++i) largest = std::max(largest, std::abs(one.rgb[i] - two.rgb[i]));
  auto luma = [](std::array<float, 3> c) { return 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2]; };
  const float occluded = luma(quadPixel(one, -0.5, 0.5)), open = luma(quadPixel(one, 0.5, 0.5));
  const float dielectric = luma(quadPixel(off, 0.5, 0.5)), metal = luma(quadPixel(off, 0.5, -0.5));
  std::printf("largest difference one fetch against two: %.4f; occluded %.3f, open %.3f; strength 0: dielectric %.3f, metal %.3f\n",
              largest, occluded, open, dielectric, metal);
  EXPECT_LE(largest, 1.0f / 255);
  EXPECT_LT(occluded, open - 0.03f);
  EXPECT_NEAR(open, dielectric, 0.01f);  // occlusion 1 (R = 255) changes nothing
  EXPECT_GT(std::abs(metal - dielectric), 0.03f);
}

// A node of quadAsset's scene that places light `light` (its index in the file's
// KHR_lights_punctual array) with `transform` (JSON: translation, rotation, matrix).
struct LightNode {
  nlohmann::json transform;
  int light;
};

// quadAsset's patch adding the KHR_lights_punctual `lights` (a JSON array) to the file and
// `lightNodes`, in their order, to the scene after the quad's node.
nlohmann::json lightsPatch(const nlohmann::json& lights, const std::vector<LightNode>& lightNodes) {
  nlohmann::json nodes = {{{"mesh", 0}}}, sceneNodes = {0};
  for (const LightNode& lightNode : lightNodes) {
    nlohmann::json node = lightNode.transform;
    node["extensions"] = {{"KHR_lights_punctual", {{"light", lightNode.light}}}};
    sceneNodes.push_back(static_cast<int>(nodes.size()));
    nodes.push_back(node);
  }
  return {{"extensionsUsed", {"KHR_lights_punctual"}},
          {"extensions", {{"KHR_lights_punctual", {{"lights", lights}}}}},
          {"nodes", nodes},
          {"scenes", {{{"nodes", sceneNodes}}}}};
}

// lightsPatch with the one light `light` (JSON) on a node with `transform`.
nlohmann::json lightPatch(const nlohmann::json& light, const nlohmann::json& transform) {
  return lightsPatch(nlohmann::json::array({light}), {{transform, 0}});
}

// Each mesh program is compiled for the number of lights it shades with (LIGHT_COUNT): one to
// four equal directional lights from the same direction light the quad more with each one added
// (no tone mapping, no environment), so a program that ran fewer trips than the file has lights
// would show it.
TEST(Viewer, EveryLightOfTheFileLightsTheMesh) {
  TempDir dir;
  writeRgbaPng(dir / "white.png", 4, 4, [](int, int) { return std::array<unsigned char, 4>{255, 255, 255, 255}; });
  auto render = [&](int count) {
    nlohmann::json lights = nlohmann::json::array();
    std::vector<LightNode> lightNodes;
    for (int i = 0; i < count; ++i) {
      lights.push_back({{"type", "directional"}, {"intensity", 0.4}});
      lightNodes.push_back({{{"rotation", {std::sin(0.25), 0.0, 0.0, std::cos(0.25)}}}, i});
    }
    const nlohmann::json patch = lightsPatch(lights, lightNodes);
    const nlohmann::json material = {{"pbrMetallicRoughness", {{"baseColorFactor", {0.8, 0.8, 0.8, 1.0}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.6}}}};
    const std::string name = "lights-" + std::to_string(count);
    return screenshot(dir, name, "'" + quadAsset(dir, name, material, "white.png", patch).string() + "'" + kQuadView +
                                     " --exposure 1 --tone-map none --no-ibl --no-shadows");
  };
  auto luma = [](std::array<float, 3> c) { return 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2]; };
  float previous = 0;
  for (int count = 1; count <= 4; ++count) {
    const float now = luma(quadPixel(render(count), 0, 0));
    std::printf("%d light(s): luma %.3f\n", count, now);
    EXPECT_GT(now, previous + 0.03f) << count << " lights";
    previous = now;
  }
}

// A file with more lights than a program shades with (four): the four brightest at the scene's
// centre are kept whatever their place in the file or their intensity alone, and the viewer
// names the others by their index in the file's light array (here the reverse of the node
// order). Two faint point lights near the quad, three point lights of the largest intensity
// but far away (each gives the quad 1e-5 lux), then two directional lights, render as the two
// directional lights alone. The old cap kept the first four nodes' lights (luma 0); a ranking
// by intensity alone would keep one directional light.
TEST(Viewer, MoreLightsThanFourKeepTheBrightestAndSaySo) {
  TempDir dir;
  writeRgbaPng(dir / "white.png", 4, 4, [](int, int) { return std::array<unsigned char, 4>{255, 255, 255, 255}; });
  auto render = [&](const std::string& name, bool withPoints, std::string& output) {
    std::vector<std::pair<nlohmann::json, nlohmann::json>> placed;  // light, its node
    if (withPoints) {
      for (int i = 0; i < 2; ++i)
        placed.push_back({{{"type", "point"}, {"intensity", 1e-6}, {"name", "faint" + std::to_string(i)}}, {{"translation", {0.0, 0.0, 2.0}}}});
      for (int i = 0; i < 3; ++i)
        placed.push_back({{{"type", "point"}, {"intensity", 1e3}, {"name", "far" + std::to_string(i)}}, {{"translation", {0.0, 0.0, 1e4}}}});
    }
    for (int i = 0; i < 2; ++i)
      placed.push_back({{{"type", "directional"}, {"intensity", 0.4}}, {{"rotation", {std::sin(0.25), 0.0, 0.0, std::cos(0.25)}}}});
    // Light k of the file is placed by node 1 + (n - 1 - k): the nodes list them in reverse.
    const int n = static_cast<int>(placed.size());
    nlohmann::json lights = nlohmann::json::array();
    std::vector<LightNode> lightNodes;
    for (int k = 0; k < n; ++k) lights.push_back(placed[n - 1 - k].first);
    for (int j = 0; j < n; ++j) lightNodes.push_back({placed[j].second, n - 1 - j});
    const nlohmann::json patch = lightsPatch(lights, lightNodes);
    const nlohmann::json material = {{"pbrMetallicRoughness", {{"baseColorFactor", {0.8, 0.8, 0.8, 1.0}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.6}}}};
    const fs::path out = dir / (name + ".png");
    const int exit = run("'" + quadAsset(dir, name, material, "white.png", patch).string() + "'" + kQuadView +
                             " --exposure 1 --tone-map none --no-ibl --screenshot '" + out.string() + "'",
                         output);
    EXPECT_EQ(exit, 0) << output;
    return exit == 0 ? readPng(out) : Image{};
  };
  auto luma = [](std::array<float, 3> c) { return 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2]; };
  std::string sevenOutput, twoOutput;
  const Image seven = render("seven", true, sevenOutput), two = render("two", false, twoOutput);
  ASSERT_FALSE(seven.rgb.empty());
  ASSERT_EQ(seven.rgb.size(), two.rgb.size());
  const float withSeven = luma(quadPixel(seven, 0, 0)), withTwo = luma(quadPixel(two, 0, 0));
  std::printf("seven lights: luma %.3f; the two directional alone: %.3f\n%s", withSeven, withTwo, sevenOutput.c_str());
  EXPECT_NEAR(withSeven, withTwo, 1.5f / 255);
  EXPECT_GT(withTwo, 0.1f);
  // Nodes 1-2 place the faint lights (file lights 6, 5), nodes 3-5 the far ones (4, 3, 2): kept
  // are two far ones (1e-5 lux beats 2.5e-7), in node order the first two, so far2 (node 5) and
  // both faint lights are left out.
  EXPECT_NE(sevenOutput.find("7 punctual lights in the scene"), std::string::npos) << sevenOutput;
  EXPECT_NE(sevenOutput.find("left out: light 2 'far2' (node 5), 5 'faint1' (node 2), 6 'faint0' (node 1)"), std::string::npos) << sevenOutput;
  EXPECT_EQ(twoOutput.find("punctual lights"), std::string::npos) << twoOutput;
}

// With every light directional (the default rig), lighting.glsl is compiled without its
// positional code; the same directional light beside a point light too faint to show takes the
// general code. Both render alike, and the directional light's angle shows (a light from the
// side shades the quad darker than one from the front).
TEST(Viewer, DirectionalOnlyLightingRendersAsTheGeneralPath) {
  TempDir dir;
  writeRgbaPng(dir / "white.png", 4, 4, [](int, int) { return std::array<unsigned char, 4>{255, 255, 255, 255}; });
  auto render = [&](const std::string& name, bool withPoint, double tilt) {
    nlohmann::json lights = {{{"type", "directional"}, {"intensity", 3.0}, {"color", {1.0, 0.9, 0.8}}}};
    const nlohmann::json tilted = {{"rotation", {std::sin(tilt / 2), 0.0, 0.0, std::cos(tilt / 2)}}};
    std::vector<LightNode> lightNodes = {{tilted, 0}};
    if (withPoint) {
      lights.push_back({{"type", "point"}, {"intensity", 1e-6}});
      lightNodes.push_back({{{"translation", {0.0, 0.0, 2.0}}}, 1});
    }
    const nlohmann::json patch = lightsPatch(lights, lightNodes);
    const nlohmann::json material = {{"pbrMetallicRoughness", {{"baseColorFactor", {0.8, 0.8, 0.8, 1.0}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.4}}}};
    return screenshot(dir, name, "'" + quadAsset(dir, name, material, "white.png", patch).string() + "'" + kQuadView + " --exposure 1");
  };
  const Image directional = render("directional", false, 0.5), general = render("general", true, 0.5), side = render("side", false, 1.2);
  ASSERT_EQ(directional.rgb.size(), general.rgb.size());
  float largest = 0;
  for (std::size_t i = 0; i < directional.rgb.size(); ++i) largest = std::max(largest, std::abs(directional.rgb[i] - general.rgb[i]));
  auto luma = [](std::array<float, 3> c) { return 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2]; };
  const float front = luma(quadPixel(directional, 0, 0)), fromSide = luma(quadPixel(side, 0, 0));
  std::printf("largest difference directional-only against general: %.4f; centre lit from 29 deg %.3f, from 69 deg %.3f\n", largest, front, fromSide);
  EXPECT_LE(largest, 1.0f / 255);
  EXPECT_GT(front, fromSide + 0.05f);
}

// The sRGB encoding of the output (colour.glsl's linearToSrgb, a sum of square roots standing in
// for pow, within 0.25/255 of IEC 61966-2-1 over [0, 1]) undoes the texture's sRGB decoding: an
// unlit quad whose base colour texture holds each of the 256 byte values, sampled nearest, shows
// each value as stored, to within one level where the decoding rounds.
TEST(Viewer, OutputEncodingReturnsEveryTextureByte) {
  TempDir dir;
  writeRgbaPng(dir / "ramp.png", 16, 16, [](int x, int y) {
    const auto value = static_cast<unsigned char>(16 * y + x);
    return std::array<unsigned char, 4>{value, static_cast<unsigned char>(255 - value), value, 255};
  });
  const nlohmann::json material = {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}, {"extensions", {{"KHR_materials_unlit", nlohmann::json::object()}}}};
  const nlohmann::json patch = {{"samplers", {{{"magFilter", 9728}, {"minFilter", 9728}}}}, {"textures", {{{"source", 0}, {"sampler", 0}}}}};
  const Image image = screenshot(dir, "ramp", "'" + quadAsset(dir, "ramp", material, "ramp.png", patch).string() + "' --camera front --ortho --size 400x400 --no-shadows");
  int largest = 0, differing = 0;
  for (int value = 0; value < 256; ++value) {
    const double u = (value % 16 + 0.5) / 16, v = (value / 16 + 0.5) / 16;
    const auto c = quadPixel(image, 2 * u - 1, 1 - 2 * v);
    const int expected[3] = {value, 255 - value, value};
    for (int channel = 0; channel < 3; ++channel) {
      const int difference = std::abs(static_cast<int>(std::lround(c[channel] * 255)) - expected[channel]);
      largest = std::max(largest, difference);
      differing += difference > 0;
    }
  }
  std::printf("output bytes against the texture's: largest difference %d levels, %d of 768 differ\n", largest, differing);
  EXPECT_LE(largest, 1);
  EXPECT_LE(differing, 768 / 20);
}

// Copy of data/demo/sphere.gltf with one untextured metallic-roughness material.
fs::path plainSphere(const TempDir& dir, const std::string& name, double metallic, double roughness) {
  const fs::path demo = fs::path(TANGENT_SOURCE_DIR) / "data" / "demo";
  const fs::path folder = dir / name;
  fs::create_directories(folder);
  fs::copy_file(demo / "sphere.bin", folder / "sphere.bin");
  nlohmann::json doc = nlohmann::json::parse(std::ifstream(demo / "sphere.gltf"));
  doc.erase("textures");
  doc.erase("images");
  doc.erase("samplers");
  doc.erase("extensionsUsed");
  doc["materials"] = {{{"pbrMetallicRoughness", {{"baseColorFactor", {0.9, 0.9, 0.9, 1.0}}, {"metallicFactor", metallic}, {"roughnessFactor", roughness}}}}};
  std::ofstream(folder / "sphere.gltf") << doc.dump();
  return folder / "sphere.gltf";
}

// Linear luminance (sRGB decoded) of every pixel that is not background, sorted.
std::vector<float> objectLuminances(const Image& image) {
  std::vector<float> lumas;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const auto c = image.at(x, y);
      if (std::abs(c[0] - 0.16f) < 0.01f && std::abs(c[1] - 0.17f) < 0.01f && std::abs(c[2] - 0.19f) < 0.01f) continue;
      lumas.push_back(static_cast<float>(0.2126 * srgbToLinear(c[0]) + 0.7152 * srgbToLinear(c[1]) + 0.0722 * srgbToLinear(c[2])));
    }
  std::sort(lumas.begin(), lumas.end());
  return lumas;
}

// PBR mode (glTF appendix B): a metal has no diffuse term, so away from its highlight a metal
// sphere is far darker (in linear luminance) than a dielectric one of the same base colour; a
// smoother metal has a brighter, smaller highlight.
TEST(Viewer, PbrMetalHasNoDiffuseAndSmootherMeansSharperHighlights) {
  TempDir dir;
  // The lights' BRDF only: with image-based lighting a metal shows its environment instead
  // (ImageBasedLightingShowsSharperReflectionsOnSmootherMetal).
  const std::string common = " --camera front --size 300x300 --no-shadows --shading pbr --no-ibl";
  auto lumas = [&](const std::string& name, double metallic, double roughness) {
    return objectLuminances(screenshot(dir, name, "'" + plainSphere(dir, name, metallic, roughness).string() + "'" + common));
  };
  const auto dielectric = lumas("dielectric", 0, 0.5), metal = lumas("metal", 1, 0.5);
  const auto smoothMetal = lumas("smooth-metal", 1, 0.2), roughMetal = lumas("rough-metal", 1, 0.8);
  ASSERT_GT(dielectric.size(), 10000u);
  ASSERT_GT(metal.size(), 10000u);
  auto median = [](const std::vector<float>& v) { return v[v.size() / 2]; };
  auto peak = [](const std::vector<float>& v) { return v[v.size() - 1 - v.size() / 1000]; };  // 99.9th percentile
  auto brightShare = [](const std::vector<float>& v, float threshold) {
    return static_cast<float>(v.end() - std::upper_bound(v.begin(), v.end(), threshold)) / static_cast<float>(v.size());
  };
  std::printf("median luminance: dielectric %.3f, metal %.3f; peak: smooth metal %.3f, rough metal %.3f; share > 0.6: smooth %.4f, rough %.4f\n",
              median(dielectric), median(metal), peak(smoothMetal), peak(roughMetal), brightShare(smoothMetal, 0.6f),
              brightShare(roughMetal, 0.6f));
  EXPECT_LT(median(metal), 0.6f * median(dielectric));
  EXPECT_GT(peak(smoothMetal), peak(roughMetal));
  EXPECT_GT(peak(smoothMetal), 0.9f);
}

// MSAA: the silhouette of a sphere in the flat face-orientation view is two colours without
// it, and gets intermediate (coverage-weighted) pixels with it.
TEST(Viewer, MsaaBlendsSilhouettePixels) {
  TempDir dir;
  const std::string common = "'" + (fs::path(TANGENT_SOURCE_DIR) / "data" / "demo" / "sphere.gltf").string() +
                             "' --view face-orientation --camera front --size 200x200";
  auto mixedPixels = [](const Image& image) {
    int mixed = 0;
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x) {
        const auto c = image.at(x, y);
        const bool background = std::abs(c[0] - 0.16f) < 0.01f && std::abs(c[2] - 0.19f) < 0.01f;
        const bool front = std::abs(c[0] - 0.15f) < 0.01f && std::abs(c[2] - 0.95f) < 0.01f;
        mixed += !background && !front;
      }
    return mixed;
  };
  const int aliased = mixedPixels(screenshot(dir, "msaa0", common + " --msaa 0"));
  const int smoothed = mixedPixels(screenshot(dir, "msaa4", common + " --msaa 4"));
  std::printf("silhouette pixels between background and surface: %d without MSAA, %d with 4x\n", aliased, smoothed);
  EXPECT_EQ(aliased, 0);
  EXPECT_GT(smoothed, 150);
}

// A static scene draws its shadow map once, however many frames it renders.
TEST(Viewer, ShadowMapDrawnOnceForAStaticScene) {
  TempDir dir;
  std::string output;
  ASSERT_EQ(run("--size 160x90 --frames 6 --screenshot '" + (dir / "a.png").string() + "'", output), 0) << output;
  EXPECT_NE(output.find("1 shadow pass(es)"), std::string::npos) << output;
  ASSERT_EQ(run("--size 160x90 --frames 6 --no-shadows --screenshot '" + (dir / "b.png").string() + "'", output), 0) << output;
  EXPECT_NE(output.find("0 shadow pass(es)"), std::string::npos) << output;
}

// A static scene's meshes are packed and uploaded once, at load (fresh compare tangents are what
// the load uploaded: uploading them again cost a 10^7-triangle scan 8 s and 1 GB); a compare set
// from the file uploads them again, with that set.
TEST(Viewer, StaticMeshesAreUploadedOnce) {
  TempDir dir;
  const std::string scene = "'" + (fs::path(TANGENT_SOURCE_DIR) / "data" / "demo" / "scene.gltf").string() + "'";
  std::string output;
  ASSERT_EQ(run(scene + " --size 160x90 --frames 3 --screenshot '" + (dir / "a.png").string() + "'", output), 0) << output;
  EXPECT_NE(output.find(" 4 mesh upload(s)"), std::string::npos) << output;  // scene.gltf's four primitives
  ASSERT_EQ(run(scene + " --size 160x90 --compare file --view error --screenshot '" + (dir / "b.png").string() + "'", output), 0) << output;
  EXPECT_NE(output.find(" 8 mesh upload(s)"), std::string::npos) << output;
}

// One primitive is one draw call of the view, in the frame that also draws the shadow map and in
// the frames after it; the shadow map's draw is counted apart (it was added to the first frame's).
TEST(Viewer, DrawCallsOfTheViewAndOfTheShadowMapAreCountedApart) {
  TempDir dir;
  const std::string sphere = "'" + (fs::path(TANGENT_SOURCE_DIR) / "data" / "demo" / "sphere.gltf").string() + "'";
  std::string output;
  for (const char* frames : {"1", "3"}) {
    ASSERT_EQ(run(sphere + " --size 160x90 --frames " + frames + " --screenshot '" + (dir / "a.png").string() + "'", output), 0) << output;
    EXPECT_NE(output.find(" 1 draw calls, "), std::string::npos) << output;
    EXPECT_NE(output.find("1 shadow pass(es) of 1 draw call(s)"), std::string::npos) << output;
  }
  ASSERT_EQ(run(sphere + " --size 160x90 --no-shadows --screenshot '" + (dir / "b.png").string() + "'", output), 0) << output;
  EXPECT_NE(output.find(" 1 draw calls, "), std::string::npos) << output;
  EXPECT_NE(output.find("0 shadow pass(es) of 0 draw call(s)"), std::string::npos) << output;
}

// The perspective camera frames the bounding box to the view: the demo sphere seen from the
// front spans about 72% of the frame's height (the bounding box's front face fills it; framing the
// box's bounding sphere gave 52%).
TEST(Viewer, PerspectiveFramingFillsTheView) {
  TempDir dir;
  const Image image = screenshot(dir, "sphere", "'" + (fs::path(TANGENT_SOURCE_DIR) / "data" / "demo" / "sphere.gltf").string() +
                                                    "' --camera front --size 320x180 --view face-orientation");
  ASSERT_EQ(image.width, 320);
  int top = image.height, bottom = -1;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      if (image.at(x, y)[2] > 0.8f) top = std::min(top, y), bottom = std::max(bottom, y);
  const float share = static_cast<float>(bottom - top + 1) / static_cast<float>(image.height);
  std::printf("sphere spans %.0f%% of the frame's height\n", 100 * share);
  EXPECT_GT(share, 0.65f);
  EXPECT_LT(share, 1.0f);  // and is not cut off
}

// ---- Tone mapping, lights in physical units, alpha-tested shadows ----

const nlohmann::json kWhiteRough = {{"pbrMetallicRoughness", {{"baseColorFactor", {1.0, 1.0, 1.0, 1.0}}, {"metallicFactor", 0.0}, {"roughnessFactor", 1.0}}}};

// Mean linear (sRGB-decoded) red of the pixels within 5 of the quad's point (x, y).
double meanLinear(const Image& image, double x, double y) {
  const double pixelsPerUnit = image.height / (2 * std::sqrt(2.0) * 1.02);
  const int cx = static_cast<int>(image.width / 2.0 + x * pixelsPerUnit), cy = static_cast<int>(image.height / 2.0 - y * pixelsPerUnit);
  double sum = 0;
  int count = 0;
  for (int py = cy - 5; py <= cy + 5; ++py)
    for (int px = cx - 5; px <= cx + 5; ++px) sum += srgbToLinear(image.at(px, py)[0]), ++count;
  return sum / count;
}

// A directional light (pi lux, shining along -z) on a white quad exposed to about 1.3 and 2.6:
// without tone mapping the lower already clips to 255; with Khronos PBR Neutral (the default) and ACES both
// stay below white and the brighter one reads brighter.
TEST(Viewer, ToneMappingRollsOffBrightValuesInsteadOfClipping) {
  TempDir dir;
  writeRgbaPng(dir / "white.png", 4, 4, [](int, int) { return std::array<unsigned char, 4>{255, 255, 255, 255}; });
  const fs::path file = quadAsset(dir, "lit", kWhiteRough, "white.png",
                                  lightPatch({{"type", "directional"}, {"intensity", 3.14159265}}, {{"translation", {0, 0, 3}}}));
  std::map<std::string, std::array<float, 2>> centre;
  for (const std::string toneMap : {"none", "khr-pbr-neutral", "aces"}) {
    for (int e = 0; e < 2; ++e) {
      if (toneMap == "none" && e == 1) {  // clipped at the lower exposure already
        centre[toneMap][e] = centre[toneMap][0];
        continue;
      }
      const std::string name = toneMap + std::to_string(e);
      const Image image = screenshot(dir, name, "'" + file.string() + "'" + kQuadView + " --tone-map " + toneMap + " --exposure " + (e ? "2.5" : "1.25"));
      ASSERT_EQ(image.width, 200) << name;
      centre[toneMap][e] = quadPixel(image, 0, 0)[0];
    }
    std::printf("%-16s exposure 1.25: %.1f/255, exposure 2.5: %.1f/255\n", toneMap.c_str(), centre[toneMap][0] * 255, centre[toneMap][1] * 255);
  }
  EXPECT_EQ(centre["none"][0], 1.0f);
  for (const char* toneMap : {"khr-pbr-neutral", "aces"}) {
    EXPECT_LT(centre[toneMap][1], 254 / 255.0f) << toneMap;
    EXPECT_GT(centre[toneMap][1], centre[toneMap][0] + 2 / 255.0f) << toneMap;
    EXPECT_GT(centre[toneMap][0], 200 / 255.0f) << toneMap;
  }
}

// KHR_lights_punctual in PBR mode, in its units: a point light 2 above a white quad; doubling
// its intensity (candela) doubles the linear radiance (fixed exposure, no tone mapping); a
// range shorter than the distance cuts it off; a range of 4 scales it by the window
// 1 - (2/4)^4 at the centre.
TEST(Viewer, PointLightIntensityIsLinearAndRangeCutsItOff) {
  TempDir dir;
  writeRgbaPng(dir / "white.png", 4, 4, [](int, int) { return std::array<unsigned char, 4>{255, 255, 255, 255}; });
  auto radiance = [&](const std::string& name, double intensity, double range) {
    nlohmann::json light = {{"type", "point"}, {"intensity", intensity}};
    if (range > 0) light["range"] = range;
    const fs::path file = quadAsset(dir, name, kWhiteRough, "white.png", lightPatch(light, {{"translation", {0, 0, 2}}}));
    const Image image = screenshot(dir, name, "'" + file.string() + "'" + kQuadView + " --tone-map none --exposure 2");
    return image.width == 200 ? meanLinear(image, 0, 0) : -1.0;
  };
  const double one = radiance("one", 1.0, 0), two = radiance("two", 2.0, 0);
  const double cut = radiance("cut", 2.0, 1.5), windowed = radiance("windowed", 2.0, 4.0);
  std::printf("linear radiance at the centre: 1 cd %.4f, 2 cd %.4f (ratio %.4f), range 1.5 %.4f, range 4 %.4f (ratio %.4f, window %.4f)\n",
              one, two, two / one, cut, windowed, windowed / two, 1 - std::pow(0.5, 4));
  EXPECT_GT(one, 0.1);
  EXPECT_NEAR(two / one, 2.0, 0.03);
  EXPECT_EQ(cut, 0.0);
  EXPECT_NEAR(windowed / two, 1 - std::pow(0.5, 4), 0.02);
}

// A ground quad (6 x 6 at y = 0) under a MASK quad (2 x 2 at y = 1) with a square hole in its
// texture's alpha (the middle half in u and v), a sun shining along (1, -1, 0): the hole's
// shadow-free spot lands on the ground at x 0.5..1.5, the rim's shadow at 1.5..2, seen from the
// top beside the quad at x 1..2.
fs::path maskShadowAsset(const TempDir& dir) {
  writeRgbaPng(dir / "hole.png", 64, 64, [](int x, int y) {
    const bool hole = x >= 16 && x < 48 && y >= 16 && y < 48;
    return std::array<unsigned char, 4>{255, 255, 255, static_cast<unsigned char>(hole ? 0 : 255)};
  });
  std::vector<float> positions, normals, uvs;
  for (const auto& [half, height] : {std::pair{3.0f, 0.0f}, std::pair{1.0f, 1.0f}}) {
    for (const auto& [x, z] : {std::pair{-1, 1}, std::pair{1, 1}, std::pair{1, -1}, std::pair{-1, -1}}) {
      positions.insert(positions.end(), {x * half, height, z * half});
      normals.insert(normals.end(), {0, 1, 0});
      uvs.insert(uvs.end(), {(x + 1) * 0.5f, (z + 1) * 0.5f});
    }
  }
  const std::uint16_t indices[] = {0, 1, 2, 0, 2, 3};
  std::string bin;
  auto append = [&](const void* data, std::size_t bytes) { bin.append(static_cast<const char*>(data), bytes); };
  append(positions.data(), positions.size() * 4);
  append(normals.data(), normals.size() * 4);
  append(uvs.data(), uvs.size() * 4);
  append(indices, sizeof indices);
  std::ofstream(dir / "mask-shadow.bin", std::ios::binary) << bin;
  const double s = std::sqrt(0.5);
  nlohmann::json doc = nlohmann::json::parse(R"({
    "asset": {"version": "2.0"},
    "extensionsUsed": ["KHR_lights_punctual"],
    "extensions": {"KHR_lights_punctual": {"lights": [{"type": "directional", "intensity": 2.0}]}},
    "scene": 0,
    "scenes": [{"nodes": [0, 1, 2]}],
    "nodes": [{"mesh": 0}, {"mesh": 1}, {"extensions": {"KHR_lights_punctual": {"light": 0}}}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 2, "TEXCOORD_0": 4}, "indices": 6, "material": 0}]},
               {"primitives": [{"attributes": {"POSITION": 1, "NORMAL": 3, "TEXCOORD_0": 5}, "indices": 6, "material": 1}]}],
    "materials": [{"pbrMetallicRoughness": {"metallicFactor": 0.0, "roughnessFactor": 1.0}, "doubleSided": true},
                  {"pbrMetallicRoughness": {"metallicFactor": 0.0, "baseColorTexture": {"index": 0}}, "alphaMode": "MASK", "doubleSided": true}],
    "textures": [{"source": 0}],
    "images": [{"uri": "hole.png"}],
    "buffers": [{"uri": "mask-shadow.bin", "byteLength": 268}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 48},
                    {"buffer": 0, "byteOffset": 96, "byteLength": 48}, {"buffer": 0, "byteOffset": 144, "byteLength": 48},
                    {"buffer": 0, "byteOffset": 192, "byteLength": 32}, {"buffer": 0, "byteOffset": 224, "byteLength": 32},
                    {"buffer": 0, "byteOffset": 256, "byteLength": 12}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-3, 0, -3], "max": [3, 0, 3]},
                  {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-1, 1, -1], "max": [1, 1, 1]},
                  {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC3"},
                  {"bufferView": 3, "componentType": 5126, "count": 4, "type": "VEC3"},
                  {"bufferView": 4, "componentType": 5126, "count": 4, "type": "VEC2"},
                  {"bufferView": 5, "componentType": 5126, "count": 4, "type": "VEC2"},
                  {"bufferView": 6, "componentType": 5123, "count": 6, "type": "SCALAR"}]
  })");
  EXPECT_EQ(bin.size(), 268u);
  // The light's -z is (1, -1, 0) / sqrt 2: columns x (s, s, 0), y (0, 0, -1), z (-s, s, 0).
  doc["nodes"][2]["matrix"] = {s, s, 0, 0, 0, 0, -1, 0, -s, s, 0, 0, 0, 0, 0, 1};
  std::ofstream(dir / "mask-shadow.gltf") << doc.dump(1);
  return dir / "mask-shadow.gltf";
}

TEST(Viewer, MaskedQuadCastsACutOutShadow) {
  TempDir dir;
  const fs::path file = maskShadowAsset(dir);
  const std::string common = "'" + file.string() + "' --camera top --ortho --size 256x256 --no-ibl";  // the shadow map's part only
  const Image shadowed = screenshot(dir, "shadows", common), plain = screenshot(dir, "no-shadows", common + " --no-shadows");
  ASSERT_EQ(shadowed.width, 256);
  // Top view: x to the right, z down; the bounds' sphere (centre (0, 0.5, 0)) framed with 1.02.
  const double pixelsPerUnit = 256 / (2 * 1.02 * std::sqrt(36.0 + 36.0 + 1.0) / 2);
  auto meanLuma = [&](const Image& image, double x, double z) {
    const auto q = quadrantMeans(image, 128 + x * pixelsPerUnit, 128 + z * pixelsPerUnit, 3);
    return (q[0] + q[1] + q[2] + q[3]) / 4;
  };
  const float holeOn = meanLuma(shadowed, 1.25, 0), holeOff = meanLuma(plain, 1.25, 0);
  const float rimOn = meanLuma(shadowed, 1.75, 0), rimOff = meanLuma(plain, 1.75, 0);
  std::printf("ground under the hole: %.3f with shadows, %.3f without; under the rim: %.3f / %.3f\n", holeOn, holeOff, rimOn, rimOff);
  EXPECT_NEAR(holeOn, holeOff, 0.02f);   // light through the hole
  EXPECT_LT(rimOn, 0.6f * rimOff);       // the rim's shadow
}

// The vertex layout tables and the linked programs agree: every active input of the mesh
// program (in a spread of variants), the shadow and the line programs is in its table, at the
// table's location, with its component count, and every table entry is read somewhere.
TEST(Viewer, LinkedProgramsMatchTheVertexLayoutTables) {
  std::string output;
  EXPECT_EQ(run("--check-shaders", output), 0) << output;
  EXPECT_NE(output.find("agree with the layout tables"), std::string::npos) << output;
}

TEST(Viewer, BadInputIsAnErrorNotACrash) {
  TempDir dir;
  std::string output;
  EXPECT_EQ(run("'" + (dir / "missing.glb").string() + "' --screenshot '" + (dir / "x.png").string() + "'", output), 1);
  EXPECT_NE(output.find("missing.glb"), std::string::npos) << output;
  EXPECT_EQ(run("--view nonsense --screenshot x.png", output), 2);
  EXPECT_FALSE(fs::exists(dir / "x.png"));
}

// ---- Bounded by the input's size ----

// Indices without a bufferView (zeros by the spec) implying 10^6 and 10^9 triangles in a file of
// a few hundred bytes: refused by name before anything is decoded, as bake, check and info refuse
// them (the viewer died of std::bad_alloc). Under an address-space limit where the build has no
// AddressSanitizer (which reserves terabytes of address space by design).
TEST(Viewer, AccessorsWithoutDataAreRefusedByTheWorkTheyImply) {
  TempDir dir;
  writeRgbaPng(dir / "white.png", 4, 4, [](int, int) { return std::array<unsigned char, 4>{255, 255, 255, 255}; });
  for (const long long triangles : {1000000LL, 1000000000LL}) {
    nlohmann::json accessors = {
        {{"bufferView", 0}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}, {"min", {-1, -1, 0}}, {"max", {1, 1, 0}}},
        {{"bufferView", 1}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}},
        {{"bufferView", 2}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}},
        {{"bufferView", 3}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}},
        {{"componentType", 5125}, {"count", 3 * triangles}, {"type", "SCALAR"}}};
    const fs::path file = quadAsset(dir, "zeros" + std::to_string(triangles), nlohmann::json::object(), "white.png",
                                    {{"accessors", accessors}});
#if defined(__SANITIZE_ADDRESS__)
    const std::string limit;
#else
    const std::string limit = "prlimit --as=2000000000 ";
#endif
    const auto result = tangent::testing::runCommand(limit + TANGENT_VIEW + " '" + file.string() + "' --stats");
    EXPECT_EQ(result.exitCode, 1) << result.output;
    EXPECT_NE(result.output.find(file.filename().string() + ": /accessors/4: has no bufferView"), std::string::npos) << result.output;
    EXPECT_EQ(result.output.find("bad_alloc"), std::string::npos) << result.output;
  }
}

// quadAsset's quad, drawn by `nodes` (the glTF nodes array) from the scene's `roots`.
fs::path nodesAsset(const TempDir& dir, const std::string& name, nlohmann::json nodes, nlohmann::json roots) {
  writeRgbaPng(dir / "white.png", 4, 4, [](int, int) { return std::array<unsigned char, 4>{255, 255, 255, 255}; });
  return quadAsset(dir, name, nlohmann::json::object(), "white.png",
                   {{"nodes", std::move(nodes)}, {"scenes", {{{"nodes", std::move(roots)}}}}});
}

// 100,000 nodes showing one mesh: its corners are read, its tangents computed and its vertices
// uploaded once, and each node draws them (it used to take all three per node: 100 KB of
// vertices a node for a small sphere, past 300 s and out of memory at 10^5 to 10^6 nodes).
TEST(Viewer, HundredThousandInstancesShareOnePrimitive) {
  TempDir dir;
  constexpr int kNodes = 100000, kColumns = 400;
  nlohmann::json nodes = nlohmann::json::array(), roots = nlohmann::json::array();
  for (int n = 0; n < kNodes; ++n) {
    nodes.push_back({{"mesh", 0}, {"translation", {2.2 * (n % kColumns), -2.2 * (n / kColumns), 0.0}}});
    roots.push_back(n);
  }
  const fs::path file = nodesAsset(dir, "instances", std::move(nodes), std::move(roots));
  const auto start = std::chrono::steady_clock::now();
  std::string output;
  const int exit = run("'" + file.string() + "' --stats --camera front --ortho --size 400x250 --no-shadows --screenshot '" +
                           (dir / "instances.png").string() + "'",
                       output);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("%d instances: %.1f s\n%s", kNodes, seconds, output.c_str());
  ASSERT_EQ(exit, 0) << output;
  EXPECT_NE(output.find(": 1 primitive(s), 100000 instance(s), 200000 triangle(s) drawn"), std::string::npos) << output;
  EXPECT_NE(output.find("200000 triangles, 100000 draw calls"), std::string::npos) << output;
  EXPECT_LT(seconds, 120);
  // The grid of quads (83% of it quad) covers the frame's middle: few background pixels there.
  const Image image = readPng(dir / "instances.png");
  ASSERT_EQ(image.width, 400);
  int background = 0, samples = 0;
  for (int y = 100; y < 150; ++y) {
    for (int x = 150; x < 250; ++x, ++samples) {
      const auto c = image.at(x, y);
      background += std::abs(c[0] - 0.16f) < 0.02f && std::abs(c[1] - 0.17f) < 0.02f && std::abs(c[2] - 0.19f) < 0.02f;
    }
  }
  std::printf("background in the frame's middle: %d of %d pixels\n", background, samples);
  EXPECT_LT(background, samples / 2);
}

// The scene loader walks a chain of 150,001 nodes, deeper than the 100,000 node visits it used to
// call a cycle, without a call stack of that depth; a real cycle is still refused (by the
// validation every load runs). --stats loads without GL, so this also runs under the sanitizers.
TEST(Viewer, LongAcyclicChainLoadsAndACycleDoesNot) {
  TempDir dir;
  constexpr int kNodes = 150001;
  nlohmann::json nodes = nlohmann::json::array();
  for (int n = 0; n < kNodes; ++n) {
    nlohmann::json node = {{"mesh", 0}, {"translation", {0.0, 0.0, -1e-4}}};
    if (n + 1 < kNodes) node["children"] = {n + 1};
    nodes.push_back(std::move(node));
  }
  std::string output;
  const fs::path chain = nodesAsset(dir, "chain", std::move(nodes), {0});
  ASSERT_EQ(run("'" + chain.string() + "' --stats", output), 0) << output;
  EXPECT_NE(output.find(": 1 primitive(s), 150001 instance(s)"), std::string::npos) << output;
  // Nodes 1 and 2 are each other's child: one parent each, and no root reaches them.
  const fs::path cycle = nodesAsset(dir, "cycle", {{{"mesh", 0}}, {{"children", {2}}}, {{"children", {1}}}}, {0});
  EXPECT_EQ(run("'" + cycle.string() + "' --stats", output), 1) << output;
  EXPECT_NE(output.find("cycle"), std::string::npos) << output;
}

// A PNG of a few bytes whose header claims width x height RGBA pixels, with an IDAT too short
// for them: decoding would allocate width x height x 4 bytes before finding that out.
void writePngHeader(const fs::path& path, std::uint32_t width, std::uint32_t height) {
  auto crc32 = [](const std::string& bytes) {
    std::uint32_t crc = 0xffffffffu;
    for (const unsigned char byte : bytes) {
      crc ^= byte;
      for (int bit = 0; bit < 8; ++bit) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
    }
    return ~crc;
  };
  auto bigEndian = [](std::uint32_t value) {
    return std::string{static_cast<char>(value >> 24), static_cast<char>(value >> 16), static_cast<char>(value >> 8), static_cast<char>(value)};
  };
  auto chunk = [&](const std::string& type, const std::string& data) { return bigEndian(static_cast<std::uint32_t>(data.size())) + type + data + bigEndian(crc32(type + data)); };
  const std::string ihdr = bigEndian(width) + bigEndian(height) + std::string{8, 6, 0, 0, 0};  // 8 bits, RGBA
  const std::string idat{0x78, 0x01, 0x01, 0x01, 0x00, static_cast<char>(0xfe), static_cast<char>(0xff), 0x00, 0x00, 0x01, 0x00, 0x01};  // zlib: one zero byte
  std::ofstream(path, std::ios::binary) << std::string("\x89PNG\r\n\x1a\n", 8) << chunk("IHDR", ihdr) << chunk("IDAT", idat) << chunk("IEND", "");
}

// An image whose header claims 60000 x 60000 pixels (14.4 GB as RGBA8) is refused from its
// header, with a note naming the file and the image; the quad is drawn without it. It used to be
// decoded into a 14.4 GB buffer (std::bad_alloc where memory is short, naming nothing).
TEST(Viewer, HugeImageHeaderIsRefusedBeforeDecoding) {
  TempDir dir;
  writePngHeader(dir / "huge.png", 60000, 60000);
  ASSERT_LT(fs::file_size(dir / "huge.png"), 100u);
  const nlohmann::json material = {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}},
                                   {"extensions", {{"KHR_materials_unlit", nlohmann::json::object()}}}};
  const fs::path file = quadAsset(dir, "huge", material, "huge.png");
  std::string output;
  const int exit = run("'" + file.string() + "'" + kQuadView + " --screenshot '" + (dir / "huge-shot.png").string() + "'", output);
  std::printf("%s", output.c_str());
  EXPECT_EQ(exit, 0) << output;
  EXPECT_NE(output.find("huge.gltf: image 0 'huge.png': its header claims 60000 x 60000 pixels"), std::string::npos) << output;
  EXPECT_NE(output.find("not decoded"), std::string::npos) << output;
  EXPECT_EQ(output.find("bad_alloc"), std::string::npos) << output;
}

// A valid 20000 x 1 texture, wider than llvmpipe's largest (16384), is downscaled to fit with a
// note; it used to fail the screenshot with GL_INVALID_VALUE (0x501). Left half red, right half
// green, as the texels say.
TEST(Viewer, TextureWiderThanTheGlLimitIsDownscaled) {
  TempDir dir;
  writeRgbaPng(dir / "wide.png", 20000, 1, [](int x, int) {
    return x < 10000 ? std::array<unsigned char, 4>{255, 0, 0, 255} : std::array<unsigned char, 4>{0, 255, 0, 255};
  });
  const nlohmann::json material = {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}},
                                   {"extensions", {{"KHR_materials_unlit", nlohmann::json::object()}}}};
  const fs::path file = quadAsset(dir, "wide", material, "wide.png");
  std::string output;
  const int exit = run("'" + file.string() + "'" + kQuadView + " --screenshot '" + (dir / "wide-shot.png").string() + "'", output);
  std::printf("%s", output.c_str());
  ASSERT_EQ(exit, 0) << output;
  EXPECT_EQ(output.find("OpenGL errors"), std::string::npos) << output;
  EXPECT_NE(output.find("wide.gltf: image 0 'wide.png': 20000 x 1 pixels"), std::string::npos) << output;
  const Image image = readPng(dir / "wide-shot.png");
  ASSERT_EQ(image.width, 200);
  EXPECT_EQ(colourName(quadPixel(image, -0.5, 0)), 'R');
  EXPECT_EQ(colourName(quadPixel(image, 0.5, 0)), 'G');
}

}  // namespace

// ---- Transparency, debug views, morph targets, skinning, animation (issue 38) ----

// A copy of a demo mesh (data/demo/NAME.gltf and its .bin) with one untextured material.
fs::path demoWithMaterial(const TempDir& dir, const std::string& demo, const std::string& name, const nlohmann::json& material) {
  const fs::path source = fs::path(TANGENT_SOURCE_DIR) / "data" / "demo";
  const fs::path folder = dir / name;
  fs::create_directories(folder);
  fs::copy_file(source / (demo + ".bin"), folder / (demo + ".bin"));
  nlohmann::json doc = nlohmann::json::parse(std::ifstream(source / (demo + ".gltf")));
  doc.erase("textures");
  doc.erase("images");
  doc.erase("samplers");
  doc.erase("extensionsUsed");
  doc["materials"] = {material};
  for (auto& mesh : doc["meshes"])
    for (auto& primitive : mesh["primitives"]) primitive["material"] = 0;
  std::ofstream(folder / (demo + ".gltf")) << doc.dump();
  return folder / (demo + ".gltf");
}

// Pixels whose colour differs by more than `tolerance` in some channel.
int differingPixels(const Image& a, const Image& b, float tolerance) {
  int count = 0;
  for (std::size_t i = 0; i + 2 < std::min(a.rgb.size(), b.rgb.size()); i += 3) {
    count += std::abs(a.rgb[i] - b.rgb[i]) > tolerance || std::abs(a.rgb[i + 1] - b.rgb[i + 1]) > tolerance ||
             std::abs(a.rgb[i + 2] - b.rgb[i + 2]) > tolerance;
  }
  return count;
}

// A closed BLEND mesh whose alpha is 1 renders as its OPAQUE copy: blended primitives keep depth
// test and depth writes (as the Khronos Sample Viewer draws them), so the far side of a
// double-sided sphere, or of a torus, does not paint over the near side.
TEST(Viewer, BlendClosedMeshWithAlphaOneLooksOpaque) {
  TempDir dir;
  for (const auto& [demo, doubleSided] : {std::pair{"sphere", true}, std::pair{"torus", false}}) {
    auto render = [&](const std::string& mode) {
      const nlohmann::json material = {{"pbrMetallicRoughness", {{"baseColorFactor", {0.8, 0.5, 0.3, 1.0}}, {"metallicFactor", 0.0}}},
                                       {"alphaMode", mode},
                                       {"doubleSided", doubleSided}};
      const std::string name = std::string(demo) + "-" + mode;
      return screenshot(dir, name, "'" + demoWithMaterial(dir, demo, name, material).string() + "' --size 300x300 --no-shadows");
    };
    const Image opaque = render("OPAQUE"), blend = render("BLEND");
    ASSERT_EQ(opaque.rgb.size(), blend.rgb.size());
    ASSERT_LT(backgroundShare(opaque), 0.9f) << demo;
    const int differing = differingPixels(opaque, blend, 2.5f / 255);
    std::printf("%s: %d of %d pixels differ between BLEND (alpha 1) and OPAQUE\n", demo, differing, opaque.width * opaque.height);
    EXPECT_EQ(differing, 0) << demo;
  }
}

// 'T' teal (w = +1), 'O' orange (w = -1), '.' anything else (background, edges).
char handednessName(std::array<float, 3> c) {
  if (std::abs(c[0] - 0.10f) < 0.03f && std::abs(c[1] - 0.70f) < 0.03f && std::abs(c[2] - 0.75f) < 0.03f) return 'T';
  if (std::abs(c[0] - 0.95f) < 0.03f && std::abs(c[1] - 0.55f) < 0.03f && std::abs(c[2] - 0.10f) < 0.03f) return 'O';
  return '.';
}

// The handedness view shows the file's w: a mirrored copy of the sphere (node scale -1, 1, 1)
// shows the colour of the original at the mirrored pixel. The handedness-world view shows w
// after the mirroring, so there the copy swaps teal and orange.
TEST(Viewer, HandednessViewShowsTheFilesWUnderAMirroringNode) {
  TempDir dir;
  const fs::path original = fs::path(TANGENT_SOURCE_DIR) / "data" / "demo" / "sphere.gltf";
  const fs::path mirrored = demoCopy(dir, "sphere", {{"scale", {-1, 1, 1}}}, false);
  for (const std::string view : {"handedness", "handedness-world"}) {
    const std::string common = " --view " + view + " --camera front --ortho --size 200x200";
    const Image a = screenshot(dir, "sphere-" + view, "'" + original.string() + "'" + common);
    const Image b = screenshot(dir, "mirrored-" + view, "'" + mirrored.string() + "'" + common);
    ASSERT_EQ(a.rgb.size(), b.rgb.size());
    int same = 0, swapped = 0, coloured = 0;
    for (int y = 0; y < a.height; ++y) {
      for (int x = 0; x < a.width; ++x) {
        const char p = handednessName(a.at(a.width - 1 - x, y)), q = handednessName(b.at(x, y));
        if (p == '.' || q == '.') continue;
        ++coloured;
        same += p == q;
        swapped += p != q;
      }
    }
    std::printf("%s: %d coloured pixels, %d the same colour mirrored, %d swapped\n", view.c_str(), coloured, same, swapped);
    ASSERT_GT(coloured, 8000) << view;
    if (view == "handedness") EXPECT_GT(same, coloured * 99 / 100);
    else EXPECT_GT(swapped, coloured * 99 / 100);
  }
}

// The geometry-normal view shows the interpolated NORMAL attribute: on the demo's smooth unit
// sphere (48 x 24 segments, facets 7.5 degrees apart) the colour follows the analytic normal,
// without the facets that screen-space face normals show.
TEST(Viewer, GeometryNormalViewShowsTheInterpolatedNormal) {
  TempDir dir;
  const fs::path sphere = fs::path(TANGENT_SOURCE_DIR) / "data" / "demo" / "sphere.gltf";
  const Image image = screenshot(dir, "normals", "'" + sphere.string() + "' --view geometry-normal --camera front --ortho --size 300x300");
  ASSERT_EQ(image.width, 300);
  // Orthographic framing of the bounding box [-1, 1]^3: half height sqrt(3) * 1.02.
  const double pixelsPerUnit = 150 / (std::sqrt(3.0) * 1.02);
  double error = 0, worst = 0;
  int samples = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const double nx = (x + 0.5 - 150) / pixelsPerUnit, ny = (150 - y - 0.5) / pixelsPerUnit;
      if (nx * nx + ny * ny > 0.8) continue;  // inside, away from the silhouette
      const double normal[3] = {nx, ny, std::sqrt(1 - nx * nx - ny * ny)};
      const auto c = image.at(x, y);
      for (int i = 0; i < 3; ++i) {
        const double e = std::abs(c[i] - (normal[i] * 0.5 + 0.5));
        error += e;
        worst = std::max(worst, e);
      }
      ++samples;
    }
  }
  ASSERT_GT(samples, 15000);
  std::printf("geometry-normal view vs the analytic normal: mean %.4f, worst %.4f per channel over %d pixels\n", error / (3 * samples), worst, samples);
  EXPECT_LT(error / (3 * samples), 0.006);
  EXPECT_LT(worst, 0.02);
}

std::string base64(const std::string& bytes) {
  std::string text;
  static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::uint32_t n = (std::uint32_t(std::uint8_t(bytes[i])) << 16) |
                            (i + 1 < bytes.size() ? std::uint32_t(std::uint8_t(bytes[i + 1])) << 8 : 0) |
                            (i + 2 < bytes.size() ? std::uint32_t(std::uint8_t(bytes[i + 2])) : 0);
    text += kAlphabet[(n >> 18) & 63];
    text += kAlphabet[(n >> 12) & 63];
    text += i + 1 < bytes.size() ? kAlphabet[(n >> 6) & 63] : '=';
    text += i + 2 < bytes.size() ? kAlphabet[n & 63] : '=';
  }
  return text;
}

// Writes a .gltf with one embedded buffer: accessors added one by one (floats or 16-bit
// integers), the document completed by the caller.
struct GltfWriter {
  std::string bin;
  nlohmann::json accessors = nlohmann::json::array(), bufferViews = nlohmann::json::array();
  int add(const void* data, std::size_t bytes, int componentType, std::size_t count, const char* type, bool indices = false) {
    while (bin.size() % 4 != 0) bin.push_back('\0');
    nlohmann::json view = {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes}};
    if (indices) view["target"] = 34963;
    bufferViews.push_back(view);
    bin.append(static_cast<const char*>(data), bytes);
    accessors.push_back({{"bufferView", bufferViews.size() - 1}, {"componentType", componentType}, {"count", count}, {"type", type}});
    return static_cast<int>(accessors.size() - 1);
  }
  int floats(const std::vector<float>& values, const char* type, int components) {
    const int index = add(values.data(), values.size() * sizeof(float), 5126, values.size() / components, type);
    if (std::string(type) == "VEC3" && values.size() >= 3) {  // POSITION needs min and max
      std::array<float, 3> lo{values[0], values[1], values[2]}, hi = lo;
      for (std::size_t i = 0; i < values.size(); ++i) lo[i % 3] = std::min(lo[i % 3], values[i]), hi[i % 3] = std::max(hi[i % 3], values[i]);
      accessors[index]["min"] = lo;
      accessors[index]["max"] = hi;
    }
    if (std::string(type) == "SCALAR" && !values.empty()) {  // an animation sampler's input needs them too
      accessors[index]["min"] = {*std::min_element(values.begin(), values.end())};
      accessors[index]["max"] = {*std::max_element(values.begin(), values.end())};
    }
    return index;
  }
  int shorts(const std::vector<std::uint16_t>& values, const char* type, int components, bool indices = false) {
    return add(values.data(), values.size() * 2, 5123, values.size() / components, type, indices);
  }
  fs::path write(const fs::path& file, nlohmann::json doc) {
    doc["asset"] = {{"version", "2.0"}};
    doc["buffers"] = {{{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + base64(bin)}}};
    doc["bufferViews"] = bufferViews;
    doc["accessors"] = accessors;
    std::ofstream(file) << doc.dump(1);
    return file;
  }
};

// The tangent a tangent-view pixel shows (signedColor: t * 0.5 + 0.5), in the xy plane, as an
// angle in degrees from +x.
double tangentAngleDegrees(std::array<float, 3> c) { return std::atan2(2.0 * c[1] - 1, 2.0 * c[0] - 1) * 180 / 3.14159265358979; }

// A quad over [-1, 1]^2 facing +z whose TANGENT is +x (UVs as quadAsset's), with one morph
// target: `positionDeltas` (12 floats, or empty) and the same TANGENT delta at every vertex;
// mesh.weights 0, node.weights `nodeWeights` when not null; `extend` may add to the document
// (animations) before it is written.
fs::path morphQuad(const TempDir& dir, const std::string& name, const std::vector<float>& positionDeltas, std::array<float, 3> tangentDelta,
                   const nlohmann::json& nodeWeights, const std::function<void(GltfWriter&, nlohmann::json&)>& extend = {}) {
  GltfWriter gltf;
  const int position = gltf.floats({-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0}, "VEC3", 3);
  const int normal = gltf.floats({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3", 3);
  const int tangent = gltf.floats({1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1}, "VEC4", 4);
  const int uv = gltf.floats({0, 1, 1, 1, 1, 0, 0, 0}, "VEC2", 2);
  const auto [dx, dy, dz] = tangentDelta;
  const int tangentDeltas = gltf.floats({dx, dy, dz, dx, dy, dz, dx, dy, dz, dx, dy, dz}, "VEC3", 3);
  nlohmann::json target = {{"TANGENT", tangentDeltas}};
  target["POSITION"] = gltf.floats(positionDeltas.empty() ? std::vector<float>(12, 0.0f) : positionDeltas, "VEC3", 3);
  const int indices = gltf.shorts({0, 1, 2, 0, 2, 3}, "SCALAR", 1, true);
  nlohmann::json node = {{"mesh", 0}};
  if (!nodeWeights.is_null()) node["weights"] = nodeWeights;
  const nlohmann::json attributes = {{"POSITION", position}, {"NORMAL", normal}, {"TANGENT", tangent}, {"TEXCOORD_0", uv}};
  const nlohmann::json primitive = {{"attributes", attributes}, {"indices", indices}, {"targets", nlohmann::json::array({target})}};
  nlohmann::json doc = {{"scene", 0},
                        {"scenes", {{{"nodes", {0}}}}},
                        {"nodes", {node}},
                        {"meshes", {{{"weights", {0.0}}, {"primitives", nlohmann::json::array({primitive})}}}}};
  if (extend) extend(gltf, doc);
  return gltf.write(dir / (name + ".gltf"), doc);
}

// TANGENT deltas that turn the quad's tangent 45 degrees towards +y: the tangent view shows 0
// degrees at weight 0, 45 at weight 1 (node.weights over mesh.weights) and 22.5 at weight 0.5
// (the mean of the two, normalized).
TEST(Viewer, MorphTargetTangentDeltasTurnTheTangent) {
  TempDir dir;
  const float c45 = static_cast<float>(std::sqrt(0.5));
  const std::pair<const char*, nlohmann::json> cases[] = {{"weight0", nullptr}, {"weight1", {1.0}}, {"weight-half", {0.5}}};
  const double expected[] = {0, 45, 22.5};
  for (int i = 0; i < 3; ++i) {
    const fs::path file = morphQuad(dir, cases[i].first, {}, {c45 - 1, c45, 0}, cases[i].second);
    const Image image = screenshot(dir, cases[i].first, "'" + file.string() + "' --view tangent" + kQuadView);
    ASSERT_EQ(image.width, 200);
    for (const auto& [x, y] : {std::pair{0.0, 0.0}, std::pair{-0.5, 0.5}, std::pair{0.5, -0.5}}) {
      const auto colour = quadPixel(image, x, y);
      std::printf("%s at (%.1f, %.1f): tangent at %.2f degrees (expected %.1f), z colour %.3f\n", cases[i].first, x, y, tangentAngleDegrees(colour),
                  expected[i], colour[2]);
      EXPECT_NEAR(tangentAngleDegrees(colour), expected[i], 1.0) << cases[i].first;
      EXPECT_NEAR(colour[2], 0.5f, 0.01f) << cases[i].first;
    }
  }
}

// The error view on a morphed mesh compares its morphed tangents with tangents computed afresh
// on the morphed corners. A target turning the quad 45 degrees in its plane (UVs unchanged)
// with TANGENT deltas turning the tangent along shows no error (blue) at weight 1; the same
// target without TANGENT deltas, a wrong morph tangent, shows 45 degrees (red); at weight 0
// both are blue.
TEST(Viewer, ErrorViewJudgesMorphTangentDeltas) {
  TempDir dir;
  const float c45 = static_cast<float>(std::sqrt(0.5));
  std::vector<float> turn;  // R(45 deg) p - p for the quad's corners
  for (const auto& [x, y] : {std::pair{-1.0f, -1.0f}, std::pair{1.0f, -1.0f}, std::pair{1.0f, 1.0f}, std::pair{-1.0f, 1.0f}})
    turn.insert(turn.end(), {c45 * x - c45 * y - x, c45 * x + c45 * y - y, 0.0f});
  const std::array<float, 3> blue{0.10f, 0.25f, 0.90f}, red{0.90f, 0.10f, 0.10f};
  struct Case {
    const char* name;
    std::array<float, 3> tangentDelta;
    double weight;
    std::array<float, 3> expected;
  };
  const Case cases[] = {{"right-0", {c45 - 1, c45, 0}, 0, blue},
                        {"right-1", {c45 - 1, c45, 0}, 1, blue},
                        {"wrong-0", {0, 0, 0}, 0, blue},
                        {"wrong-1", {0, 0, 0}, 1, red}};
  for (const Case& c : cases) {
    const Image image = screenshot(dir, c.name, "'" + morphQuad(dir, c.name, turn, c.tangentDelta, {c.weight}).string() + "' --view error" + kQuadView);
    ASSERT_EQ(image.width, 200);
    for (const auto& [dx, dy] : {std::pair{0, 0}, std::pair{-20, 10}, std::pair{15, -20}}) {
      const auto colour = image.at(100 + dx, 100 + dy);
      std::printf("%s at +(%d, %d): %.3f %.3f %.3f\n", c.name, dx, dy, colour[0], colour[1], colour[2]);
      for (int i = 0; i < 3; ++i) EXPECT_NEAR(colour[i], c.expected[i], 0.02f) << c.name;
    }
  }
}

// A cylinder of radius 0.25 along +y from 0 to 2 (rings every 0.1, 16 sides), its TANGENT +y
// everywhere, skinned to two joints: joint 0 at the origin holds y <= 0.8, joint 1 at y = 1
// (bound unrotated) holds y >= 1.2, linearly blended between; joint 0's influence in
// JOINTS_0/WEIGHTS_0, joint 1's in JOINTS_1/WEIGHTS_1. Joint 1's own rotation about z is
// `restDegrees`; with `animated`, animation 'bend' turns it from 0 to 90 degrees over 1 s.
fs::path bentCylinder(const TempDir& dir, const std::string& name, double restDegrees, bool animated) {
  const int rings = 21, sides = 16;
  const float radius = 0.25f;
  std::vector<float> positions, normals, tangents, uvs, weights0, weights1;
  std::vector<std::uint16_t> joints0, joints1, indices;
  for (int r = 0; r < rings; ++r) {
    const float y = 0.1f * static_cast<float>(r);
    const float w1 = std::clamp((y - 0.8f) / 0.4f, 0.0f, 1.0f);
    for (int s = 0; s <= sides; ++s) {
      const double theta = 2 * 3.14159265358979 * s / sides;
      const auto sx = static_cast<float>(std::sin(theta)), cz = static_cast<float>(std::cos(theta));
      positions.insert(positions.end(), {radius * sx, y, radius * cz});
      normals.insert(normals.end(), {sx, 0, cz});
      tangents.insert(tangents.end(), {0, 1, 0, 1});
      uvs.insert(uvs.end(), {y / 2, static_cast<float>(s) / sides});
      joints0.insert(joints0.end(), {0, 0, 0, 0});
      joints1.insert(joints1.end(), {1, 0, 0, 0});
      weights0.insert(weights0.end(), {1 - w1, 0, 0, 0});
      weights1.insert(weights1.end(), {w1, 0, 0, 0});
    }
  }
  for (int r = 0; r + 1 < rings; ++r) {
    for (int s = 0; s < sides; ++s) {
      const auto a = static_cast<std::uint16_t>(r * (sides + 1) + s), b = static_cast<std::uint16_t>(a + 1),
                 c = static_cast<std::uint16_t>(a + sides + 2), d = static_cast<std::uint16_t>(a + sides + 1);
      indices.insert(indices.end(), {a, b, c, a, c, d});  // counter-clockwise seen from outside
    }
  }
  GltfWriter gltf;
  const int position = gltf.floats(positions, "VEC3", 3), normal = gltf.floats(normals, "VEC3", 3), tangent = gltf.floats(tangents, "VEC4", 4),
            uv = gltf.floats(uvs, "VEC2", 2), j0 = gltf.shorts(joints0, "VEC4", 4), j1 = gltf.shorts(joints1, "VEC4", 4),
            w0 = gltf.floats(weights0, "VEC4", 4), w1 = gltf.floats(weights1, "VEC4", 4), index = gltf.shorts(indices, "SCALAR", 1, true);
  const int inverseBind = gltf.floats({1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1}, "MAT4", 16);
  const double half = restDegrees * 3.14159265358979 / 360;
  nlohmann::json doc = {
      {"scene", 0},
      {"scenes", {{{"nodes", {0, 1}}}}},
      {"nodes", {{{"mesh", 0}, {"skin", 0}}, {{"children", {2}}}, {{"translation", {0, 1, 0}}, {"rotation", {0, 0, std::sin(half), std::cos(half)}}}}},
      {"skins", {{{"joints", {1, 2}}, {"inverseBindMatrices", inverseBind}}}},
      {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", position}, {"NORMAL", normal}, {"TANGENT", tangent}, {"TEXCOORD_0", uv},
                                                     {"JOINTS_0", j0}, {"WEIGHTS_0", w0}, {"JOINTS_1", j1}, {"WEIGHTS_1", w1}}},
                                      {"indices", index}}}}}}},
  };
  if (animated) {
    const int times = gltf.floats({0, 1}, "SCALAR", 1);
    const int rotations = gltf.floats({0, 0, 0, 1, 0, 0, static_cast<float>(std::sqrt(0.5)), static_cast<float>(std::sqrt(0.5))}, "VEC4", 4);
    const nlohmann::json sampler = {{"input", times}, {"output", rotations}, {"interpolation", "LINEAR"}};
    const nlohmann::json channel = {{"sampler", 0}, {"target", {{"node", 2}, {"path", "rotation"}}}};
    doc["animations"] = nlohmann::json::array({{{"name", "bend"}, {"samplers", nlohmann::json::array({sampler})},
                                                 {"channels", nlohmann::json::array({channel})}}});
  }
  return gltf.write(dir / (name + ".gltf"), doc);
}

// The front orthographic view (300 x 300) of bentCylinder with joint 1 turned `degrees`: the
// tangent view's angle (from +x, in the xy plane) at the front surface of the lower part (y =
// 0.4, held by joint 0: 90 degrees), the blend's middle (y = 1: 90 + degrees / 2, the mean of
// the two joints' tangents) and the upper part (y = 1.7, held by joint 1: 90 + degrees).
std::array<double, 3> cylinderTangentAngles(const Image& image, double degrees) {
  const double a = degrees * 3.14159265358979 / 180;
  // Where the corners go (linear blend skinning, as the viewer should do it), for the framing.
  std::array<double, 3> lo{1e9, 1e9, 1e9}, hi{-1e9, -1e9, -1e9};
  for (int r = 0; r < 21; ++r) {
    const double y = 0.1 * r, w1 = std::clamp((y - 0.8) / 0.4, 0.0, 1.0);
    for (int s = 0; s < 16; ++s) {
      const double theta = 2 * 3.14159265358979 * s / 16, x = 0.25 * std::sin(theta), z = 0.25 * std::cos(theta);
      const double bentX = -(y - 1) * std::sin(a) + x * std::cos(a), bentY = 1 + (y - 1) * std::cos(a) + x * std::sin(a);
      const std::array<double, 3> p{(1 - w1) * x + w1 * bentX, (1 - w1) * y + w1 * bentY, z};
      for (int i = 0; i < 3; ++i) lo[i] = std::min(lo[i], p[i]), hi[i] = std::max(hi[i], p[i]);
    }
  }
  const double radius = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2])) / 2;
  const double pixelsPerUnit = image.height / (2 * radius * 1.02), cx = (lo[0] + hi[0]) / 2, cy = (lo[1] + hi[1]) / 2;
  auto angleAt = [&](double x, double y) {
    return tangentAngleDegrees(image.at(static_cast<int>(image.width / 2.0 + (x - cx) * pixelsPerUnit), static_cast<int>(image.height / 2.0 - (y - cy) * pixelsPerUnit)));
  };
  return {angleAt(0, 0.4), angleAt(0, 1), angleAt(-0.7 * std::sin(a), 1 + 0.7 * std::cos(a))};
}

// Two joints bend a skinned cylinder 90 degrees in its rest pose (joint 1's node rotation; the
// inverse bind matrices are of the straight cylinder): the tangent view shows the skinned
// tangents, transformed by the joints' matrices as the positions are.
TEST(Viewer, SkinnedCylinderBentNinetyDegreesShowsSkinnedTangents) {
  TempDir dir;
  const Image image = screenshot(dir, "bent", "'" + bentCylinder(dir, "bent", 90, false).string() + "' --view tangent --camera front --ortho --size 300x300");
  ASSERT_EQ(image.width, 300);
  const auto angles = cylinderTangentAngles(image, 90);
  const double expected[] = {90, 135, 180};
  for (int i = 0; i < 3; ++i) {
    std::printf("bent cylinder, %s: tangent at %.2f degrees, expected %.1f\n", i == 0 ? "lower part" : i == 1 ? "blend" : "upper part",
                angles[i] < 0 ? angles[i] + 360 : angles[i], expected[i]);
    EXPECT_NEAR(angles[i] < 0 ? angles[i] + 360 : angles[i], expected[i], 3.0) << i;
  }
}

// An animated node at several times: animation 'bend' turns joint 1 of the skinned cylinder
// from 0 to 90 degrees over 1 s (LINEAR, so slerp: 45 degrees at 0.5 s; held after the last
// key). Without --animation the scene shows its rest pose, joint 1's own 30 degrees.
TEST(Viewer, AnimationPosesTheNodeAtTheTimeAsked) {
  TempDir dir;
  const fs::path file = bentCylinder(dir, "animated", 30, true);
  const std::string common = " --view tangent --camera front --ortho --size 300x300";
  struct Case {
    const char* name;
    const char* options;
    double degrees;
  };
  const Case cases[] = {{"rest", "", 30},
                        {"start", " --animation bend --time 0", 0},
                        {"middle", " --animation bend --time 0.5", 45},
                        {"end", " --animation 0 --time 1", 90},
                        {"after", " --time 2.5", 90}};
  for (const Case& c : cases) {
    const Image image = screenshot(dir, c.name, "'" + file.string() + "'" + common + c.options);
    ASSERT_EQ(image.width, 300) << c.name;
    const auto angles = cylinderTangentAngles(image, c.degrees);
    const double expected[] = {90, 90 + c.degrees / 2, 90 + c.degrees};
    for (int i = 0; i < 3; ++i) {
      const double seen = angles[i] < 0 ? angles[i] + 360 : angles[i];
      std::printf("%s: tangent at %.2f degrees, expected %.1f\n", c.name, seen, expected[i]);
      EXPECT_NEAR(seen, expected[i], 3.0) << c.name << " " << i;
    }
  }
  std::string output;
  EXPECT_NE(run("'" + file.string() + "' --animation walk --screenshot '" + (dir / "none.png").string() + "'", output), 0);
  EXPECT_NE(output.find("no animation 'walk'"), std::string::npos) << output;
}

// A weights channel on morphQuad's target (TANGENT deltas turning the tangent 45 degrees) from
// weight 0 at 0 s to 1 at 1 s, in each interpolation: at 0.25 s STEP holds 0, LINEAR gives
// 0.25, CUBICSPLINE with zero tangents the Hermite 3u^2 - 2u^3 = 0.15625.
TEST(Viewer, AnimationSamplersInterpolateAsTheSpecSays) {
  TempDir dir;
  const float c45 = static_cast<float>(std::sqrt(0.5));
  const fs::path file = morphQuad(dir, "animated", {}, {c45 - 1, c45, 0}, nullptr, [](GltfWriter& gltf, nlohmann::json& doc) {
    const int times = gltf.floats({0, 1}, "SCALAR", 1);
    const int values = gltf.floats({0, 1}, "SCALAR", 1);
    const int cubicValues = gltf.floats({0, 0, 0, 0, 1, 0}, "SCALAR", 1);  // (in-tangent, value, out-tangent) per key
    for (const auto& [name, output] : {std::pair{"STEP", values}, std::pair{"LINEAR", values}, std::pair{"CUBICSPLINE", cubicValues}}) {
      const nlohmann::json sampler = {{"input", times}, {"output", output}, {"interpolation", name}};
      const nlohmann::json channel = {{"sampler", 0}, {"target", {{"node", 0}, {"path", "weights"}}}};
      doc["animations"].push_back({{"name", name}, {"samplers", nlohmann::json::array({sampler})}, {"channels", nlohmann::json::array({channel})}});
    }
  });
  const std::pair<const char*, double> cases[] = {{"STEP", 0}, {"LINEAR", 0.25}, {"CUBICSPLINE", 0.15625}};
  for (const auto& [name, weight] : cases) {
    const Image image = screenshot(dir, name, "'" + file.string() + "' --view tangent --animation " + name + " --time 0.25" + kQuadView);
    ASSERT_EQ(image.width, 200) << name;
    const double expected = std::atan2(weight * c45, 1 + weight * (c45 - 1)) * 180 / 3.14159265358979;
    const double seen = tangentAngleDegrees(quadPixel(image, 0, 0));
    std::printf("%s at 0.25 s: tangent at %.2f degrees, expected %.2f (weight %.5f)\n", name, seen, expected, weight);
    EXPECT_NEAR(seen, expected, 0.8) << name;
  }
}

// Debian's assimp-testmodels, which the viewer tests open as a user would.
const fs::path kAssimpGltf = "/usr/share/assimp/models/glTF2";

// The share of the image's non-background pixels that are the views' "no tangent" grey (0.5,
// viewer/debug_colours.hpp), and how much of the image is not background.
std::pair<double, double> noTangentShare(const Image& image) {
  int covered = 0, grey = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const auto c = image.at(x, y);
      if (std::abs(c[0] - 0.16f) < 0.02f && std::abs(c[1] - 0.17f) < 0.02f && std::abs(c[2] - 0.19f) < 0.02f) continue;
      ++covered;
      grey += std::abs(c[0] - 0.5f) < 0.01f && std::abs(c[1] - 0.5f) < 0.01f && std::abs(c[2] - 0.5f) < 0.01f;
    }
  }
  return {covered ? static_cast<double>(grey) / covered : 0.0, static_cast<double>(covered) / (image.width * image.height)};
}

// assimp's simple_skin (simple_skin/simple_skin.gltf: a strip of 8 triangles over x 0..1, y 0..2
// at z = 0, skinned to two joints, the upper one turned by its animation) has no NORMAL and no
// TEXCOORD_0: nothing defines a tangent frame on it, and the loader says "tangents undefined".
// The views of the frame must then show the legend's "no tangent" grey over the whole strip, at
// rest and bent. They used to show the core's fallback for such corners (FrameSource::fixed: the
// axis least aligned with the normal, +x), skinned along with the strip: uniform red at rest
// and a red-to-green gradient once bent, which reads as a real, skinned frame. The same strip
// given TEXCOORD_0 = (x, y / 2) has a frame: no grey there, in the same views.
TEST(Viewer, PrimitiveWithoutUvsShowsNoTangentInTheFrameViews) {
  const fs::path asset = kAssimpGltf / "simple_skin" / "simple_skin.gltf";
  if (!fs::exists(asset)) TANGENT_SKIP_OR_FAIL(asset.string() + " is absent (Debian's assimp-testmodels)");
  TempDir dir;
  // The copy with UVs: a buffer of its own, embedded, for TEXCOORD_0.
  nlohmann::json doc = nlohmann::json::parse(std::ifstream(asset));
  const nlohmann::json& positions = doc["accessors"][doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"].get<int>()];
  const std::size_t vertices = positions["count"].get<std::size_t>();
  ASSERT_EQ(vertices, 10u);
  std::vector<float> uvs;
  for (std::size_t v = 0; v < vertices; ++v) uvs.insert(uvs.end(), {static_cast<float>(v % 2), static_cast<float>(v / 2) * 0.25f});  // (x, y / 2)
  const std::string uvBytes(reinterpret_cast<const char*>(uvs.data()), uvs.size() * sizeof(float));
  doc["buffers"].push_back({{"byteLength", uvBytes.size()}, {"uri", "data:application/octet-stream;base64," + base64(uvBytes)}});
  doc["bufferViews"].push_back({{"buffer", doc["buffers"].size() - 1}, {"byteLength", uvBytes.size()}});
  doc["accessors"].push_back({{"bufferView", doc["bufferViews"].size() - 1}, {"componentType", 5126}, {"count", vertices}, {"type", "VEC2"}});
  doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = doc["accessors"].size() - 1;
  const fs::path withUvs = dir / "simple_skin_uv.gltf";
  std::ofstream(withUvs) << doc.dump(1);

  const std::string common = " --camera front --size 200x200 --no-shadows";
  // Bent (the upper joint turned about 50 degrees at 1 s) in every view of the frame, and at rest.
  const std::pair<const char*, const char*> cases[] = {{"tangent", "0"},    {"tangent", "1"},          {"bitangent", "1"},
                                                       {"handedness", "1"}, {"handedness-world", "1"}, {"error", "1"},
                                                       {"compare-angle", "1"}};
  for (const auto& [view, time] : cases) {
    {
      const std::string name = std::string(view) + "-" + time;
      const std::string options = std::string(" --view ") + view + " --time " + time + common;
      const auto [grey, covered] = noTangentShare(screenshot(dir, name, "'" + asset.string() + "'" + options));
      const auto [greyWithUvs, coveredWithUvs] = noTangentShare(screenshot(dir, name + "-uv", "'" + withUvs.string() + "'" + options));
      std::printf("%-16s at %s s: %.1f %% of the strip grey (%.0f %% of the image), with UVs %.1f %%\n", view, time, 100 * grey,
                  100 * covered, 100 * greyWithUvs);
      EXPECT_GT(covered, 0.05) << name;
      EXPECT_GT(grey, 0.99) << name << ": the undefined frame shows as something else than 'no tangent'";
      EXPECT_GT(coveredWithUvs, 0.05) << name;
      EXPECT_LT(greyWithUvs, 0.01) << name << ": a defined frame shows as 'no tangent'";
    }
  }
}

// Every animated asset the tests generate (tangent-make-data --animated's skinned and morphing
// assets, raw and baked; the skinned cylinder and the morphing quad with STEP, LINEAR and
// CUBICSPLINE weights above) and assimp's simple_skin and AnimatedMorphCube, raw and baked, open
// and render at several times of every animation they have: at the start, within it, and long
// after its last key (held there). Each frame shows the asset, and the times do not all give the
// same frame (the animation poses it).
TEST(Viewer, OpensEveryAnimatedAssetAtSeveralTimes) {
  const fs::path simpleSkin = kAssimpGltf / "simple_skin" / "simple_skin.gltf";
  const fs::path morphCube = kAssimpGltf / "glTF-Sample-Models" / "AnimatedMorphCube-glTF" / "AnimatedMorphCube.gltf";
  if (!fs::exists(simpleSkin) || !fs::exists(morphCube)) TANGENT_SKIP_OR_FAIL("Debian's assimp-testmodels are absent");
  TempDir dir;
  const fs::path makeData = fs::path(TANGENT_VIEW).parent_path() / "tangent-make-data";
  const auto made = tangent::testing::runCommand("'" + makeData.string() + "' --animated '" + (dir / "made").string() + "'");
  ASSERT_EQ(made.exitCode, 0) << made.output;
  const float c45 = static_cast<float>(std::sqrt(0.5));
  const fs::path morphing = morphQuad(dir, "morph_quad_animated", {}, {c45 - 1, c45, 0}, nullptr, [](GltfWriter& gltf, nlohmann::json& doc) {
    const int times = gltf.floats({0, 1}, "SCALAR", 1);
    const int values = gltf.floats({0, 1}, "SCALAR", 1);
    const int cubicValues = gltf.floats({0, 0, 0, 0, 1, 0}, "SCALAR", 1);
    for (const auto& [name, output] : {std::pair{"STEP", values}, std::pair{"LINEAR", values}, std::pair{"CUBICSPLINE", cubicValues}}) {
      const nlohmann::json sampler = {{"input", times}, {"output", output}, {"interpolation", name}};
      const nlohmann::json channel = {{"sampler", 0}, {"target", {{"node", 0}, {"path", "weights"}}}};
      doc["animations"].push_back({{"name", name}, {"samplers", nlohmann::json::array({sampler})}, {"channels", nlohmann::json::array({channel})}});
    }
  });
  // Each file, the .gltf its animations are counted in, and whether it is baked too.
  const std::vector<std::pair<fs::path, bool>> sources = {
      {dir / "made" / "skinned.gltf", true}, {dir / "made" / "morphing.gltf", true}, {bentCylinder(dir, "bent_animated", 30, true), false},
      {morphing, false},                     {simpleSkin, true},                      {morphCube, true}};
  int files = 0;
  for (const auto& [source, bakeToo] : sources) {
    ASSERT_TRUE(fs::exists(source)) << source;
    const std::size_t animations = nlohmann::json::parse(std::ifstream(source)).value("animations", nlohmann::json::array()).size();
    ASSERT_GE(animations, 1u) << source;
    std::vector<fs::path> inputs{source};
    if (bakeToo) {
      const fs::path baked = dir / (source.stem().string() + ".baked.glb");
      const auto bake = tangent::testing::runCommand(std::string(TANGENT_CLI) + " bake '" + source.string() + "' -o '" + baked.string() + "' --all -q");
      ASSERT_EQ(bake.exitCode, 0) << source << "\n" << bake.output;
      inputs.push_back(baked);
    }
    for (const fs::path& input : inputs) {
      ++files;
      for (std::size_t animation = 0; animation < animations; ++animation) {
        std::vector<Image> frames;
        for (const char* time : {"0", "0.5", "100"}) {
          const std::string name = input.filename().string() + "-" + std::to_string(animation) + "-" + time;
          frames.push_back(screenshot(dir, name, "'" + input.string() + "' --view tangent --size 160x120 --no-shadows --animation " +
                                                     std::to_string(animation) + " --time " + time));
          ASSERT_EQ(frames.back().width, 160) << name;
          EXPECT_LT(backgroundShare(frames.back()), 0.995f) << name << " shows nothing";
        }
        const bool posed = frames[0].rgb != frames[1].rgb || frames[0].rgb != frames[2].rgb;
        std::printf("%s, animation %zu: drawn at 0, 0.5 and 100 s, %s\n", input.filename().string().c_str(), animation,
                    posed ? "posed differently" : "THE SAME FRAME");
        EXPECT_TRUE(posed) << input << " animation " << animation << ": the same frame at 0, 0.5 and 100 s";
      }
    }
  }
  EXPECT_EQ(files, 10);
}

// ---- Back faces of double-sided materials (issue 42, last class) ----

// glTF 2.0 3.9.6: a double-sided material's back face "MUST have its normals reversed before
// the lighting equation is evaluated". The rule derived from it for the tangent frame: the back
// face is the same bumpy surface seen from its other side, so its shading normal at a point must
// be the front's negated, whatever the normal map holds: T' x + B' y + N' z = -(T x + B y + N z)
// for every texel (x, y, z) needs N' = -N, T' = -T and B' = -B. With B' = cross(N', T') * w' =
// cross(N, T) * w' that means w' = -w (the Khronos Sample Viewer negates t, b and n alike).
//
// The quad: [-1, 1]^2 at z = 0, NORMAL +z, TEXCOORD_0 mirrored in u, u = (1 - x) / 2,
// v = (1 - y) / 2. Its tangent follows increasing u: T = -x. The normal map's +green points to
// the image's top, decreasing v (glTF's v points down): B = +y, and cross(N, T) = cross(z, -x) =
// -y, so w = -1. The file stores TANGENT (-1, 0, 0, -1). Seen from the back: N' = -z, T' = +x,
// B' = -y.
fs::path mirroredDoubleSidedQuad(const TempDir& dir, const std::array<unsigned char, 3>& normalTexel) {
  writeRgbaPng(dir / "normal.png", 4, 4, [&](int, int) { return std::array<unsigned char, 4>{normalTexel[0], normalTexel[1], normalTexel[2], 255}; });
  GltfWriter gltf;
  const int position = gltf.floats({-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0}, "VEC3", 3);
  const int normal = gltf.floats({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3", 3);
  const int tangent = gltf.floats({-1, 0, 0, -1, -1, 0, 0, -1, -1, 0, 0, -1, -1, 0, 0, -1}, "VEC4", 4);
  const int uv = gltf.floats({1, 1, 0, 1, 0, 0, 1, 0}, "VEC2", 2);
  const int indices = gltf.shorts({0, 1, 2, 0, 2, 3}, "SCALAR", 1, true);
  const nlohmann::json attributes = {{"POSITION", position}, {"NORMAL", normal}, {"TANGENT", tangent}, {"TEXCOORD_0", uv}};
  // Two directional lights in the quad's plane: red shining down (towards -y, so it lights
  // normals leaning to +y), green shining up (lighting normals leaning to -y), intensity 1.
  const float h = static_cast<float>(std::sqrt(0.5));
  const nlohmann::json lights = {{{"type", "directional"}, {"color", {1, 0, 0}}, {"intensity", 1}},
                                 {{"type", "directional"}, {"color", {0, 1, 0}}, {"intensity", 1}}};
  nlohmann::json doc = {
      {"scene", 0},
      {"scenes", {{{"nodes", {0, 1, 2}}}}},
      // The light nodes' -z: rotated -90 deg about x it becomes -y, +90 deg +y.
      {"nodes", {{{"mesh", 0}},
                 {{"rotation", {-h, 0, 0, h}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}},
                 {{"rotation", {h, 0, 0, h}}, {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}}}},
      {"meshes", {{{"primitives", {{{"attributes", attributes}, {"indices", indices}, {"material", 0}}}}}}},
      {"materials", {{{"doubleSided", true},
                      {"normalTexture", {{"index", 0}}},
                      {"pbrMetallicRoughness", {{"baseColorFactor", {1, 1, 1, 1}}, {"metallicFactor", 0.0}, {"roughnessFactor", 1.0}}}}}},
      {"textures", {{{"source", 0}}}},
      {"images", {{{"uri", "normal.png"}}}},
      {"extensionsUsed", {"KHR_lights_punctual"}},
      {"extensions", {{"KHR_lights_punctual", {{"lights", lights}}}}},
  };
  return gltf.write(dir / "mirrored-double-sided.gltf", doc);
}

// The mirrored double-sided quad from the front and from the back, in the tangent, bitangent
// and lit views, against colours worked out by hand from the rule above (the back face's
// frame reversed, w included), the bitangent view with either bitangent mode. Turning the back face's T and N around but keeping w (B not
// reversed) turns the back's bitangent view from (0.5, 0, 0.5) to (0.5, 1, 0.5) and its lit
// colour from green to red.
TEST(Viewer, DoubleSidedMirroredQuadBackFaceReversesTheWholeFrame) {
  TempDir dir;
  // Normal map texel: tangent-space (x, y, z) = texel / 255 * 2 - 1, leaning towards +B.
  const std::array<unsigned char, 3> texel{128, 204, 230};
  const fs::path file = mirroredDoubleSidedQuad(dir, texel);
  double m[3];
  for (int i = 0; i < 3; ++i) m[i] = texel[i] / 255.0 * 2 - 1;
  const double length = std::sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
  // Shading normal, front: T m.x + B m.y + N m.z = (-m.x, m.y, m.z) / length; back: its negation.
  // Its y is what the lights (along -y and +y) see: red gets max(n.y, 0), green max(-n.y, 0).
  const double frontY = m[1] / length;
  struct Side {
    const char* camera;
    std::array<float, 3> tangent, bitangent;
    double red, green;  // lambert of the red and green lights
  };
  const Side sides[] = {{"front", {0.0f, 0.5f, 0.5f}, {0.5f, 1.0f, 0.5f}, frontY, 0.0},
                        {"back", {1.0f, 0.5f, 0.5f}, {0.5f, 0.0f, 0.5f}, 0.0, frontY}};
  for (const Side& side : sides) {
    const std::string common = "'" + file.string() + "' --camera " + side.camera + " --ortho --size 200x200 --no-shadows";
    for (const char* mode : {"per-fragment", "per-vertex"}) {
      const std::string name = std::string(side.camera) + "-" + mode;
      const Image tangentView = screenshot(dir, name + "-tangent", common + " --view tangent --bitangent " + mode);
      const Image bitangentView = screenshot(dir, name + "-bitangent", common + " --view bitangent --bitangent " + mode);
      ASSERT_EQ(tangentView.width, 200);
      ASSERT_EQ(bitangentView.width, 200);
      for (const auto& [x, y] : {std::pair{100, 100}, std::pair{70, 130}, std::pair{130, 75}}) {
        const auto t = tangentView.at(x, y), b = bitangentView.at(x, y);
        std::printf("%s at (%d, %d): tangent %.3f %.3f %.3f, bitangent %.3f %.3f %.3f\n", name.c_str(), x, y, t[0], t[1], t[2], b[0], b[1], b[2]);
        for (int i = 0; i < 3; ++i) {
          EXPECT_NEAR(t[i], side.tangent[i], 0.01f) << name;
          EXPECT_NEAR(b[i], side.bitangent[i], 0.01f) << name;
        }
      }
    }
    // Lit, specular-map mode without specular: base colour (white) times the lights' ambient
    // (6% of each light's diffuse colour, tangent-view's rule for file lights) plus diffuse
    // colour times lambert; no tone mapping, exposure 1, sRGB-encoded.
    const Image lit = screenshot(dir, std::string(side.camera) + "-lit",
                                 common + " --shading blinn-phong --no-specular --tone-map none --exposure 1");
    ASSERT_EQ(lit.width, 200);
    const double expected[3] = {linearToSrgb(0.06 + side.red), linearToSrgb(0.06 + side.green), linearToSrgb(0.0)};
    for (const auto& [x, y] : {std::pair{100, 100}, std::pair{70, 130}, std::pair{130, 75}}) {
      const auto c = lit.at(x, y);
      std::printf("%s lit at (%d, %d): %.3f %.3f %.3f, expected %.3f %.3f %.3f\n", side.camera, x, y, c[0], c[1], c[2], expected[0], expected[1],
                  expected[2]);
      for (int i = 0; i < 3; ++i) EXPECT_NEAR(c[i], expected[i], 0.01) << side.camera << " lit channel " << i;
    }
  }
}

// ---- Comparing two tangent sets (issue 38, item 4) ----

// A quad over [-1, 1]^2 at z = 0 with quadAsset's UVs (u = (x + 1) / 2, v = (1 - y) / 2), a
// plain material, and per vertex (corners at (-1, -1), (1, -1), (1, 1), (-1, 1)) the given
// NORMAL (3 each) and TANGENT (4 each). For those UVs MikkTSpace's tangent follows increasing
// u, +x, and the bitangent the image's top (decreasing v), +y = cross(+z, +x): w = +1.
fs::path framedQuad(const TempDir& dir, const std::string& name, const std::vector<float>& normals, const std::vector<float>& tangents) {
  GltfWriter gltf;
  const int position = gltf.floats({-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0}, "VEC3", 3);
  const int normal = gltf.floats(normals, "VEC3", 3);
  const int tangent = gltf.floats(tangents, "VEC4", 4);
  const int uv = gltf.floats({0, 1, 1, 1, 1, 0, 0, 0}, "VEC2", 2);
  const int indices = gltf.shorts({0, 1, 2, 0, 2, 3}, "SCALAR", 1, true);
  const nlohmann::json attributes = {{"POSITION", position}, {"NORMAL", normal}, {"TANGENT", tangent}, {"TEXCOORD_0", uv}};
  nlohmann::json doc = {{"scene", 0},
                        {"scenes", {{{"nodes", {0}}}}},
                        {"nodes", {{{"mesh", 0}}}},
                        {"meshes", {{{"primitives", {{{"attributes", attributes}, {"indices", indices}, {"material", 0}}}}}}},
                        {"materials", {{{"pbrMetallicRoughness", {{"metallicFactor", 0.0}}}}}}};
  return gltf.write(dir / (name + ".gltf"), doc);
}

// framedQuad facing +z with the same tangent (x, y, 0, w) at every vertex.
fs::path flatQuad(const TempDir& dir, const std::string& name, float x, float y, float w) {
  return framedQuad(dir, name, {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, {x, y, 0, w, x, y, 0, w, x, y, 0, w, x, y, 0, w});
}

// The angle the compare-angle view's heatmap (debug_views.glsl: blue 0, green 1, yellow 5, red 20
// degrees and more, linear between) gives a colour, read from its green channel; -1 where the
// colour is off the scale.
double heatmapDegrees(std::array<float, 3> c) {
  const std::array<float, 3> blue{0.10f, 0.25f, 0.90f}, green{0.10f, 0.80f, 0.20f}, yellow{0.95f, 0.90f, 0.10f}, red{0.90f, 0.10f, 0.10f};
  const std::array<std::pair<std::array<float, 3>, std::array<float, 3>>, 3> segments{{{blue, green}, {green, yellow}, {yellow, red}}};
  const double from[] = {0, 1, 5}, to[] = {1, 5, 20};
  for (int s = 0; s < 3; ++s) {
    const auto& [a, b] = segments[s];
    // The segment's parameter from its channel that changes most, then the others must agree.
    int channel = 0;
    for (int i = 1; i < 3; ++i)
      if (std::abs(b[i] - a[i]) > std::abs(b[channel] - a[channel])) channel = i;
    const double u = (c[channel] - a[channel]) / (b[channel] - a[channel]);
    if (u < -0.01 || u > 1.01) continue;
    bool fits = true;
    for (int i = 0; i < 3; ++i) fits = fits && std::abs(c[i] - (a[i] + u * (b[i] - a[i]))) < 0.01;
    if (fits) return from[s] + std::clamp(u, 0.0, 1.0) * (to[s] - from[s]);
  }
  return -1;
}

// The compare-angle view: a set against itself shows 0 degrees; the quad's hand-derived
// MikkTSpace tangent (+x, w = +1) against freshly computed ones shows 0; the tangent turned 10
// degrees about the normal (cos 10, sin 10, 0), against either, shows 10 degrees (read back within
// 0.3 degrees, about four steps of the 8-bit green channel), in both bitangent modes; w = -1
// against +1, opposite bitangents, shows red (20 degrees and more).
TEST(Viewer, CompareAngleViewShowsTheAngleBetweenTwoTangentSets) {
  TempDir dir;
  const float c10 = static_cast<float>(std::cos(10 * 3.14159265358979 / 180)), s10 = static_cast<float>(std::sin(10 * 3.14159265358979 / 180));
  const fs::path mikk = flatQuad(dir, "mikk", 1, 0, 1);
  const fs::path turned = flatQuad(dir, "turned", c10, s10, 1);
  const fs::path flipped = flatQuad(dir, "flipped", 1, 0, -1);
  struct Case {
    const char* name;
    fs::path file;
    std::string options;
    double degrees;
  };
  const Case cases[] = {{"itself", mikk, "--compare file", 0},
                        {"fresh", mikk, "", 0},
                        {"turned-vs-fresh", turned, "--compare fresh", 10},
                        {"turned-vs-file", mikk, "--compare '" + turned.string() + "'", 10},
                        {"turned-per-vertex", mikk, "--compare '" + turned.string() + "' --bitangent per-vertex", 10},
                        {"flipped", mikk, "--compare '" + flipped.string() + "'", 20}};
  for (const Case& c : cases) {
    const Image image = screenshot(dir, c.name, "'" + c.file.string() + "' --view compare-angle " + c.options + kQuadView);
    ASSERT_EQ(image.width, 200) << c.name;
    for (const auto& [x, y] : {std::pair{0.0, 0.0}, std::pair{-0.6, 0.5}, std::pair{0.7, -0.6}}) {
      const auto colour = quadPixel(image, x, y);
      const double seen = heatmapDegrees(colour);
      std::printf("%s at (%.1f, %.1f): %.3f %.3f %.3f = %.2f degrees, expected %.0f\n", c.name, x, y, colour[0], colour[1], colour[2], seen, c.degrees);
      EXPECT_NEAR(seen, c.degrees, 0.3) << c.name;
    }
  }
  // A second file of other triangles is refused, naming it.
  std::string output;
  const fs::path sphere = fs::path(TANGENT_SOURCE_DIR) / "data" / "demo" / "sphere.gltf";
  EXPECT_EQ(run("'" + mikk.string() + "' --compare '" + sphere.string() + "' --screenshot '" + (dir / "refused.png").string() + "'", output), 1);
  EXPECT_NE(output.find("--compare " + sphere.string() + ": "), std::string::npos) << output;
}

// The split view: left of the divider the file's TANGENT, right of it the compare set, with a
// light divider between (at --split's fraction of the width). The tangent view of the turned quad
// against fresh tangents shows 10 degrees on the left and 0 on the right; the unturned quad
// against the turned file the other way round.
TEST(Viewer, SplitViewShowsEachTangentSetOnItsSide) {
  TempDir dir;
  const float c10 = static_cast<float>(std::cos(10 * 3.14159265358979 / 180)), s10 = static_cast<float>(std::sin(10 * 3.14159265358979 / 180));
  const fs::path mikk = flatQuad(dir, "mikk", 1, 0, 1);
  const fs::path turned = flatQuad(dir, "turned", c10, s10, 1);
  struct Case {
    const char* name;
    std::string arguments;
    int divider;  // pixel column
    double left, right;
  };
  const Case cases[] = {{"turned-fresh", "'" + turned.string() + "' --compare fresh", 100, 10, 0},
                        {"mikk-turned", "'" + mikk.string() + "' --compare '" + turned.string() + "'", 100, 0, 10},
                        {"quarter", "'" + turned.string() + "' --compare fresh --split 0.25", 50, 10, 0}};
  for (const Case& c : cases) {
    const Image image = screenshot(dir, c.name, c.arguments + " --view tangent" + kQuadView);
    ASSERT_EQ(image.width, 200) << c.name;
    for (const int y : {60, 100, 140}) {
      const double left = tangentAngleDegrees(image.at(c.divider - 12, y)), right = tangentAngleDegrees(image.at(c.divider + 12, y));
      const auto line = image.at(c.divider, y);
      std::printf("%s, row %d: left %.2f degrees, right %.2f, divider %.3f %.3f %.3f\n", c.name, y, left, right, line[0], line[1], line[2]);
      EXPECT_NEAR(left, c.left, 0.5) << c.name;
      EXPECT_NEAR(right, c.right, 0.5) << c.name;
      for (int i = 0; i < 3; ++i) EXPECT_NEAR(line[i], 0.85f, 0.01f) << c.name;
    }
  }
}

// Per-vertex and per-fragment bitangents, on a quad whose frame twists across it: the left
// vertices have N = +z, T = +x (B = cross(N, T) = +y), the right ones N = +x, T = +y (B = +z).
// At a point a fraction r of the way from left to right, the bitangent view shows, per fragment,
// cross(N, T) of the interpolated N = (1 - r) z + r x and T = (1 - r) x + r y (T made orthogonal
// to N first does not turn it); per vertex, the interpolated B = (1 - r) y + r z. Midway these
// are (-1, 1, 1) / sqrt 3 and (0, 1, 1) / sqrt 2, 35 degrees apart.
TEST(Viewer, BitangentModesMatchTheirDefinitions) {
  TempDir dir;
  const fs::path file = framedQuad(dir, "twisted", {0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 0, 1}, {1, 0, 0, 1, 0, 1, 0, 1, 0, 1, 0, 1, 1, 0, 0, 1});
  for (const char* mode : {"per-fragment", "per-vertex"}) {
    const Image image = screenshot(dir, mode, "'" + file.string() + "' --view bitangent --bitangent " + std::string(mode) + kQuadView);
    ASSERT_EQ(image.width, 200) << mode;
    const double pixelsPerUnit = image.height / (2 * std::sqrt(2.0) * 1.02);
    for (const int px : {60, 100, 130, 150}) {
      const double x = (px + 0.5 - image.width / 2.0) / pixelsPerUnit, r = (x + 1) / 2;
      double b[3];
      if (std::string(mode) == "per-fragment") {
        const double n[3] = {r, 0, 1 - r}, t[3] = {1 - r, r, 0};
        b[0] = n[1] * t[2] - n[2] * t[1], b[1] = n[2] * t[0] - n[0] * t[2], b[2] = n[0] * t[1] - n[1] * t[0];
      } else {
        b[0] = 0, b[1] = 1 - r, b[2] = r;
      }
      const double length = std::sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
      const auto c = image.at(px, 100);
      std::printf("%s at x = %.3f: %.3f %.3f %.3f, expected %.3f %.3f %.3f\n", mode, x, c[0], c[1], c[2], b[0] / length * 0.5 + 0.5,
                  b[1] / length * 0.5 + 0.5, b[2] / length * 0.5 + 0.5);
      for (int i = 0; i < 3; ++i) EXPECT_NEAR(c[i], b[i] / length * 0.5 + 0.5, 0.012) << mode << " x " << x << " channel " << i;
    }
  }
}

// The compare set deforms as the file's tangents do: with the divider at the left edge
// (--split 0) the whole tangent view shows the compare set, here the file's own TANGENT again,
// and it must show the skinned cylinder's bent tangents (90, 135, 180 degrees, as the file's
// side does) and the morphed quad's tangent turned 45 degrees at weight 1, not the rest pose's.
TEST(Viewer, CompareSetIsSkinnedAndMorphedAlong) {
  TempDir dir;
  const Image bent = screenshot(dir, "bent", "'" + bentCylinder(dir, "bent", 90, false).string() +
                                                 "' --view tangent --compare file --split 0 --camera front --ortho --size 300x300");
  ASSERT_EQ(bent.width, 300);
  const auto angles = cylinderTangentAngles(bent, 90);
  const double expected[] = {90, 135, 180};
  for (int i = 0; i < 3; ++i) {
    const double seen = angles[i] < 0 ? angles[i] + 360 : angles[i];
    std::printf("compare set on the bent cylinder, part %d: tangent at %.2f degrees, expected %.1f\n", i, seen, expected[i]);
    EXPECT_NEAR(seen, expected[i], 3.0) << i;
  }
  const float c45 = static_cast<float>(std::sqrt(0.5));
  const Image morphed = screenshot(dir, "morphed", "'" + morphQuad(dir, "morphed", {}, {c45 - 1, c45, 0}, {1.0}).string() +
                                                       "' --view tangent --compare file --split 0" + kQuadView);
  ASSERT_EQ(morphed.width, 200);
  const double seen = tangentAngleDegrees(quadPixel(morphed, 0.3, 0.2));
  std::printf("compare set on the morphed quad: tangent at %.2f degrees, expected 45\n", seen);
  EXPECT_NEAR(seen, 45, 1.0);
}

// The fresh compare set of a morphing mesh is MikkTSpace on the morphed corners, not the rest
// pose's fresh set plus the file's TANGENT deltas: a target turning the quad 45 degrees in its
// plane (UVs unchanged) whose file has no TANGENT deltas shows, with the whole view on the
// compare side (--split 0), the tangent turned 45 degrees at weight 1 (fresh tangents follow
// increasing u, which the turn carries along) and 0 degrees at weight 0.
TEST(Viewer, FreshCompareSetIsRecomputedOnTheMorphedMesh) {
  TempDir dir;
  const float c45 = static_cast<float>(std::sqrt(0.5));
  std::vector<float> turn;  // R(45 deg) p - p for the quad's corners
  for (const auto& [x, y] : {std::pair{-1.0f, -1.0f}, std::pair{1.0f, -1.0f}, std::pair{1.0f, 1.0f}, std::pair{-1.0f, 1.0f}})
    turn.insert(turn.end(), {c45 * x - c45 * y - x, c45 * x + c45 * y - y, 0.0f});
  for (const double weight : {0.0, 1.0}) {
    const std::string name = "turned-" + std::to_string(static_cast<int>(weight));
    const Image image = screenshot(dir, name, "'" + morphQuad(dir, name, turn, {0, 0, 0}, {weight}).string() +
                                                  "' --view tangent --compare fresh --split 0 --camera front --ortho --size 200x200");
    ASSERT_EQ(image.width, 200);
    const double seen = tangentAngleDegrees(image.at(100, 100));
    std::printf("fresh compare set at weight %.0f: tangent at %.2f degrees, expected %.0f\n", weight, seen, 45 * weight);
    EXPECT_NEAR(seen, 45 * weight, 1.0) << name;
  }
}

// Without UVs (and without TANGENT) nothing defines a tangent frame: the fresh compare set has
// none there (shown as "no tangent", as the load marks it), also when a morph target moves the
// mesh and the set is computed again on the morphed corners, where MikkTSpace's fixed fallback
// axis must not stand in for it.
TEST(Viewer, FreshCompareSetWithoutUvsStaysUndefinedWhenMorphed) {
  TempDir dir;
  // Neither UVs nor TANGENT: the drawn frames are the fresh ones, undefined everywhere.
  const auto dropUvs = [](GltfWriter&, nlohmann::json& doc) {
    nlohmann::json& primitive = doc["meshes"][0]["primitives"][0];
    primitive["attributes"].erase("TEXCOORD_0");
    primitive["attributes"].erase("TANGENT");
    primitive["targets"][0].erase("TANGENT");
  };
  std::vector<float> lift(12, 0.0f);
  lift[2] = lift[5] = 0.2f;  // the bottom edge moves towards the viewer
  for (const double weight : {0.0, 1.0}) {
    const std::string name = "no-uvs-" + std::to_string(static_cast<int>(weight));
    const Image image = screenshot(dir, name, "'" + morphQuad(dir, name, lift, {0, 0, 0}, {weight}, dropUvs).string() +
                                                  "' --view tangent --compare fresh --split 0 --camera front --ortho --size 200x200");
    ASSERT_EQ(image.width, 200);
    const auto colour = image.at(100, 100);
    std::printf("compare set without UVs at weight %.0f: %.3f %.3f %.3f\n", weight, colour[0], colour[1], colour[2]);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(colour[i], 0.5f, 0.01f) << name;  // "no tangent" grey (viewer/debug_colours.hpp)
  }
}

// The file keeps its TANGENT but has no UVs: the file's frames are drawn as written, and the
// fresh set beside them is undefined ("no tangent" grey) at every weight, as it is without
// TANGENT; MikkTSpace's fixed fallback axis is not a frame to compare with.
TEST(Viewer, FreshCompareSetWithoutUvsStaysUndefinedBesideTheFilesTangents) {
  TempDir dir;
  const auto dropUvs = [](GltfWriter&, nlohmann::json& doc) { doc["meshes"][0]["primitives"][0]["attributes"].erase("TEXCOORD_0"); };
  std::vector<float> lift(12, 0.0f);
  lift[2] = lift[5] = 0.2f;
  for (const double weight : {0.0, 1.0}) {
    const std::string name = "file-tangent-no-uvs-" + std::to_string(static_cast<int>(weight));
    const fs::path file = morphQuad(dir, name, lift, {0, 0, 0}, {weight}, dropUvs);
    const Image fresh = screenshot(dir, name + "-fresh", "'" + file.string() + "' --view tangent --compare fresh --split 0 --camera front --ortho --size 200x200");
    const Image own = screenshot(dir, name + "-file", "'" + file.string() + "' --view tangent --camera front --ortho --size 200x200");
    ASSERT_EQ(fresh.width, 200);
    ASSERT_EQ(own.width, 200);
    const auto colour = fresh.at(100, 100), fileColour = own.at(100, 100);
    std::printf("beside the file's TANGENT, without UVs, at weight %.0f: fresh %.3f %.3f %.3f, file %.3f %.3f %.3f\n", weight, colour[0],
                colour[1], colour[2], fileColour[0], fileColour[1], fileColour[2]);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(colour[i], 0.5f, 0.01f) << name;  // "no tangent" grey
    // The file's frame (+x, the quad's tangent) is still drawn: not grey.
    EXPECT_GT(std::abs(fileColour[0] - 0.5f) + std::abs(fileColour[1] - 0.5f) + std::abs(fileColour[2] - 0.5f), 0.2f) << name;
  }
}

// ---- Default material, glTF samplers, grey images (issue 38, smaller defects) ----

// A primitive without a material is drawn with glTF's default material (glTF 2.0 3.9.1, the
// spec's defaults of pbrMetallicRoughness: base colour 1, metallic 1, roughness 1): exactly as
// the same sphere with that material written out, and not as the old white dielectric of
// roughness 0.5: a metal has no diffuse term (appendix B), so away from the lights' highlights
// it is far darker than the dielectric, as in PbrMetalHasNoDiffuseAndSmootherMeansSharperHighlights.
TEST(Viewer, PrimitiveWithoutMaterialGetsTheSpecDefault) {
  TempDir dir;
  const fs::path bare = demoWithMaterial(dir, "sphere", "bare", nlohmann::json::object());
  {
    nlohmann::json doc = nlohmann::json::parse(std::ifstream(bare));
    doc.erase("materials");
    for (auto& primitive : doc["meshes"][0]["primitives"]) primitive.erase("material");
    std::ofstream(bare) << doc.dump();
  }
  const std::string common = " --camera front --size 300x300 --no-shadows --shading pbr";
  const Image none = screenshot(dir, "none", "'" + bare.string() + "'" + common);
  const Image specDefault = screenshot(
      dir, "spec",
      "'" + demoWithMaterial(dir, "sphere", "spec", {{"pbrMetallicRoughness", {{"metallicFactor", 1.0}, {"roughnessFactor", 1.0}}}}).string() + "'" +
          common);
  const Image old = screenshot(
      dir, "old",
      "'" + demoWithMaterial(dir, "sphere", "old", {{"pbrMetallicRoughness", {{"metallicFactor", 0.0}, {"roughnessFactor", 0.5}}}}).string() + "'" +
          common);
  ASSERT_EQ(none.rgb.size(), specDefault.rgb.size());
  ASSERT_LT(backgroundShare(none), 0.9f);
  EXPECT_EQ(differingPixels(none, specDefault, 1.5f / 255), 0);
  auto median = [](const Image& image) {
    const auto v = objectLuminances(image);
    return v.empty() ? 0.0f : v[v.size() / 2];
  };
  const float defaultMedian = median(none), oldMedian = median(old);
  const int differing = differingPixels(none, old, 4.0f / 255);
  std::printf("median linear luminance: no material %.3f, old metallic 0 roughness 0.5 %.3f; %d pixels differ from the old look\n",
              defaultMedian, oldMedian, differing);
  EXPECT_GT(differing, 5000);
  EXPECT_LT(defaultMedian, 0.6f * oldMedian);
}

// quadAsset's base colour texture sampled through a glTF sampler; quadPixel's colour name.
TEST(Viewer, SamplerWrapModesChooseTheTexels) {
  TempDir dir;
  writeRgbaPng(dir / "quadrants.png", 64, 64, quadrantColour);
  // The texture transform scales UVs by 2: the quad's point (x, y) samples u = x + 1, v = 1 - y.
  // At y = 0.75 (v = 0.25, the top row: red | green), x = 0.25 and 0.75 give u = 1.25 and 1.75:
  // REPEAT 0.25 and 0.75 (red, green), CLAMP_TO_EDGE 1 (green, green), MIRRORED_REPEAT 0.75 and
  // 0.25 (green, red). At x = -0.75 (u = 0.25, the left column: red over blue), y = -0.25 and
  // -0.75 give v = 1.25 and 1.75: REPEAT red, blue; CLAMP blue, blue; MIRRORED blue, red.
  struct Case {
    const char* name;
    int wrapS, wrapT;
    const char* expected;  // two colours along S, then two along T
  };
  const Case cases[] = {
      {"repeat", 10497, 10497, "RGRB"},
      {"clamp", 33071, 33071, "GGBB"},
      {"mirrored", 33648, 33648, "GRBR"},
      {"clamp-s-mirrored-t", 33071, 33648, "GGBR"},
  };
  for (const Case& c : cases) {
    const nlohmann::json material = {
        {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}, {"extensions", {{"KHR_texture_transform", {{"scale", {2.0, 2.0}}}}}}}}}},
        {"extensions", {{"KHR_materials_unlit", nlohmann::json::object()}}}};
    const nlohmann::json patch = {{"samplers", {{{"wrapS", c.wrapS}, {"wrapT", c.wrapT}, {"magFilter", 9728}}}},
                                  {"textures", {{{"source", 0}, {"sampler", 0}}}}};
    const Image image = screenshot(dir, c.name, "'" + quadAsset(dir, c.name, material, "quadrants.png", patch).string() + "'" + kQuadView);
    ASSERT_EQ(image.width, 200) << c.name;
    const std::string seen{colourName(quadPixel(image, 0.25, 0.75)), colourName(quadPixel(image, 0.75, 0.75)),
                           colourName(quadPixel(image, -0.75, -0.25)), colourName(quadPixel(image, -0.75, -0.75))};
    EXPECT_EQ(seen, c.expected) << c.name;
  }
}

// magFilter: a 2 x 1 texture, black | white, stretched over the quad. At u = 0.45 NEAREST takes
// the black texel (u < 0.5); LINEAR blends the texel centres at u = 0.25 and 0.75 with weight
// (0.45 - 0.25) / 0.5 = 0.4 of white, in linear light (an sRGB texture), encoded at the output.
// minFilter: a one-texel checkerboard repeated 16 times shrinks below a texel per pixel: NEAREST
// shows black and white pixels, LINEAR_MIPMAP_LINEAR (also what no filter means) their mean grey.
TEST(Viewer, SamplerFiltersMagnifyAndMinifyAsAsked) {
  TempDir dir;
  writeRgbaPng(dir / "two.png", 2, 1, [](int x, int) { return x == 0 ? std::array<unsigned char, 4>{0, 0, 0, 255} : std::array<unsigned char, 4>{255, 255, 255, 255}; });
  writeRgbaPng(dir / "checker.png", 64, 64, [](int x, int y) {
    const auto v = static_cast<unsigned char>((x + y) % 2 ? 255 : 0);
    return std::array<unsigned char, 4>{v, v, v, 255};
  });
  auto render = [&](const std::string& name, const std::string& image, const nlohmann::json& sampler, double scale) {
    const nlohmann::json material = {
        {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}, {"extensions", {{"KHR_texture_transform", {{"scale", {scale, scale}}}}}}}}}},
        {"extensions", {{"KHR_materials_unlit", nlohmann::json::object()}}}};
    nlohmann::json patch = {{"textures", {{{"source", 0}}}}};
    if (!sampler.is_null()) patch = {{"samplers", {sampler}}, {"textures", {{{"source", 0}, {"sampler", 0}}}}};
    return screenshot(dir, name, "'" + quadAsset(dir, name, material, image, patch).string() + "'" + kQuadView);
  };
  const double x = 2 * 0.45 - 1;  // u = (x + 1) / 2
  const Image nearest = render("nearest", "two.png", {{"magFilter", 9728}, {"wrapS", 33071}}, 1.0);
  const Image linear = render("linear", "two.png", {{"magFilter", 9729}, {"wrapS", 33071}}, 1.0);
  ASSERT_EQ(nearest.width, 200);
  const float expectedLinear = static_cast<float>(linearToSrgb(0.4));
  std::printf("u = 0.45: NEAREST %.3f, LINEAR %.3f (expected %.3f)\n", quadPixel(nearest, x, 0)[0], quadPixel(linear, x, 0)[0], expectedLinear);
  EXPECT_LT(quadPixel(nearest, x, 0)[0], 1.5f / 255);
  EXPECT_NEAR(quadPixel(linear, x, 0)[0], expectedLinear, 3.0f / 255);
  // Spread of the pixels over the middle of the quad.
  auto spread = [](const Image& image) {
    std::vector<float> values;
    for (double y = -0.5; y <= 0.5; y += 0.05)
      for (double px = -0.5; px <= 0.5; px += 0.05) values.push_back(quadPixel(image, px, y)[0]);
    const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
    return std::make_pair(*lo, *hi);
  };
  const auto point = spread(render("min-nearest", "checker.png", {{"minFilter", 9728}}, 16.0));
  const auto trilinear = spread(render("min-trilinear", "checker.png", {{"minFilter", 9987}}, 16.0));
  const auto automatic = spread(render("min-auto", "checker.png", nullptr, 16.0));
  const float grey = static_cast<float>(linearToSrgb(0.5));
  std::printf("minified checkerboard: NEAREST %.3f..%.3f, LINEAR_MIPMAP_LINEAR %.3f..%.3f, no sampler %.3f..%.3f (mean grey %.3f)\n",
              point.first, point.second, trilinear.first, trilinear.second, automatic.first, automatic.second, grey);
  EXPECT_LT(point.first, 0.05f);
  EXPECT_GT(point.second, 0.95f);
  for (const auto& [lo, hi] : {trilinear, automatic}) {
    EXPECT_NEAR(lo, grey, 0.04f);
    EXPECT_NEAR(hi, grey, 0.04f);
  }
}

// Writes a PNG of `channels` 8-bit channels (1 grey, 2 grey + alpha), every pixel `values`.
void writeGreyPng(const fs::path& path, int channels, std::array<unsigned char, 2> values) {
  std::vector<unsigned char> pixels;
  for (int p = 0; p < 16; ++p) pixels.insert(pixels.end(), values.begin(), values.begin() + channels);
  auto out = OIIO::ImageOutput::create(path.string());
  OIIO::ImageSpec spec(4, 4, channels, OIIO::TypeDesc::UINT8);
  if (channels == 2) spec.alpha_channel = 1;
  spec.attribute("oiio:UnassociatedAlpha", 1);
  ASSERT_TRUE(out && out->open(path.string(), spec));
  out->write_image(OIIO::TypeDesc::UINT8, pixels.data());
  out->close();
  // PNG's IHDR colour type (byte 25): 0 grey, 4 grey + alpha.
  std::ifstream in(path, std::ios::binary);
  char header[26] = {};
  in.read(header, sizeof header);
  ASSERT_EQ(header[25], channels == 2 ? 4 : 0) << path;
}

// A grey + alpha PNG (grey 200, alpha 100) on an unlit quad: OPAQUE shows grey 200 in R, G and B
// (an sRGB texel reads back as itself); BLEND mixes it over the background with alpha 100/255,
// blending the encoded values as AlphaMaskCutsOutAndBlendMixes does. A one-channel grey PNG (90)
// shows 90 in R, G and B.
TEST(Viewer, GreyAndGreyAlphaPngsDecodeToGreyAndAlpha) {
  TempDir dir;
  writeGreyPng(dir / "grey-alpha.png", 2, {200, 100});
  writeGreyPng(dir / "grey.png", 1, {90, 0});
  const std::array<float, 3> background{0.16f, 0.17f, 0.19f};
  auto render = [&](const std::string& name, const std::string& image, const std::string& mode) {
    const nlohmann::json material = {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}},
                                     {"alphaMode", mode},
                                     {"extensions", {{"KHR_materials_unlit", nlohmann::json::object()}}}};
    return screenshot(dir, name, "'" + quadAsset(dir, name, material, image).string() + "'" + kQuadView);
  };
  const Image opaque = render("ga-opaque", "grey-alpha.png", "OPAQUE"), blend = render("ga-blend", "grey-alpha.png", "BLEND");
  const Image grey = render("grey", "grey.png", "OPAQUE");
  ASSERT_EQ(opaque.width, 200);
  const auto o = quadPixel(opaque, 0, 0), b = quadPixel(blend, 0, 0), g = quadPixel(grey, 0, 0);
  std::printf("grey+alpha opaque (%.1f %.1f %.1f)/255, blended (%.1f %.1f %.1f)/255; grey (%.1f %.1f %.1f)/255\n", o[0] * 255, o[1] * 255, o[2] * 255,
              b[0] * 255, b[1] * 255, b[2] * 255, g[0] * 255, g[1] * 255, g[2] * 255);
  const float alpha = 100 / 255.0f;
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(o[c], 200 / 255.0f, 1.5f / 255) << c;
    EXPECT_NEAR(b[c], alpha * 200 / 255.0f + (1 - alpha) * background[c], 2.0f / 255) << c;
    EXPECT_NEAR(g[c], 90 / 255.0f, 1.5f / 255) << c;
  }
}

// ---- Image-based lighting (issue 38 item 5) ----

// Image-based lighting on a smooth (roughness 0.05) and a rough (0.6) metal sphere, base colour
// 0.9, seen from the front: the environment's part of the picture is the render with IBL minus
// the render with the environment at intensity 0 (linear, no tone mapping, fixed exposure). The built-in environment is a
// bright sky over a dark ground, so a mirror-like sphere seen from the front shows the horizon
// where its reflection vector is horizontal: R.y = 2 (N.V) N.y = 0 at N.y = 0, the sphere's
// middle row; above it the sky, below it the ground. Prefiltering for roughness is a low-pass
// filter: the rough sphere shows the same sky-over-ground in the same direction, with a smaller
// step across the horizon and a smaller spread over the sphere, while the mean, the reflected
// energy, stays about the same (both metals reflect a fraction of it near their base colour).
TEST(Viewer, ImageBasedLightingShowsSharperReflectionsOnSmootherMetal) {
  TempDir dir;
  const std::string common = " --camera front --size 300x300 --no-shadows --shading pbr --tone-map none --exposure 1";
  struct Environment {
    float stepAcrossHorizon;  // mean linear luminance just above the middle row minus just below
    float spread;             // standard deviation over the middle of the sphere
    float mean;
  };
  auto environmentPart = [&](const std::string& name, double roughness) {
    const fs::path file = plainSphere(dir, name, 1.0, roughness);
    const Image on = screenshot(dir, name + "-ibl", "'" + file.string() + "'" + common);
    const Image off = screenshot(dir, name + "-no-environment", "'" + file.string() + "'" + common + " --ibl-intensity 0");
    EXPECT_EQ(on.rgb.size(), off.rgb.size());
    auto part = [&](int x, int y) {
      const auto a = on.at(x, y), b = off.at(x, y);
      double sum = 0;
      const double weights[3] = {0.2126, 0.7152, 0.0722};
      for (int c = 0; c < 3; ++c) sum += weights[c] * (srgbToLinear(a[c]) - srgbToLinear(b[c]));
      return static_cast<float>(sum);
    };
    // The sphere's centre and radius from its silhouette.
    int top = on.height, bottom = -1, left = on.width, right = -1;
    for (int y = 0; y < on.height; ++y)
      for (int x = 0; x < on.width; ++x) {
        const auto c = on.at(x, y);
        if (std::abs(c[0] - 0.16f) < 0.01f && std::abs(c[1] - 0.17f) < 0.01f && std::abs(c[2] - 0.19f) < 0.01f) continue;
        top = std::min(top, y), bottom = std::max(bottom, y), left = std::min(left, x), right = std::max(right, x);
      }
    const int cx = (left + right) / 2, cy = (top + bottom) / 2, radius = (bottom - top) / 2;
    Environment result{};
    double above = 0, below = 0;
    int count = 0;
    for (int dy = 3; dy <= 8; ++dy)
      for (int dx = -radius / 4; dx <= radius / 4; ++dx) above += part(cx + dx, cy - dy), below += part(cx + dx, cy + dy), ++count;
    result.stepAcrossHorizon = static_cast<float>((above - below) / count);
    std::vector<float> values;
    for (int y = cy - radius / 2; y <= cy + radius / 2; ++y)
      for (int x = cx - radius / 2; x <= cx + radius / 2; ++x) values.push_back(part(x, y));
    const double mean = std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());
    double variance = 0;
    for (const float v : values) variance += (v - mean) * (v - mean);
    result.spread = static_cast<float>(std::sqrt(variance / static_cast<double>(values.size())));
    result.mean = static_cast<float>(mean);
    return result;
  };
  const Environment smooth = environmentPart("smooth", 0.05), rough = environmentPart("rough", 0.6);
  std::printf("environment's part: step across the horizon smooth %.3f, rough %.3f; spread smooth %.3f, rough %.3f; mean smooth %.3f, rough %.3f\n",
              smooth.stepAcrossHorizon, rough.stepAcrossHorizon, smooth.spread, rough.spread, smooth.mean, rough.mean);
  EXPECT_GT(smooth.stepAcrossHorizon, 0.1f);  // sky above, ground below
  EXPECT_GT(rough.stepAcrossHorizon, 0.0f);
  EXPECT_GT(smooth.stepAcrossHorizon, 2 * rough.stepAcrossHorizon);
  EXPECT_GT(smooth.spread, 1.5f * rough.spread);
  EXPECT_NEAR(rough.mean / smooth.mean, 1.0f, 0.35f);
}

// --ibl-intensity scales the environment's part linearly: a rough dielectric sphere's environment
// part (minus the render at intensity 0) doubles from intensity 1 to 2.
TEST(Viewer, IblIntensityScalesTheEnvironmentLinearly) {
  TempDir dir;
  const fs::path file = plainSphere(dir, "sphere", 0.0, 0.8);
  const std::string common = "'" + file.string() + "' --camera front --size 200x200 --no-shadows --shading pbr --tone-map none --exposure 0.5";
  const Image off = screenshot(dir, "off", common + " --ibl-intensity 0"), one = screenshot(dir, "one", common),
              two = screenshot(dir, "two", common + " --ibl-intensity 2");
  ASSERT_EQ(off.width, 200);
  double partOne = 0, partTwo = 0;
  for (int y = 80; y < 120; ++y)
    for (int x = 80; x < 120; ++x) partOne += srgbToLinear(one.at(x, y)[1]) - srgbToLinear(off.at(x, y)[1]), partTwo += srgbToLinear(two.at(x, y)[1]) - srgbToLinear(off.at(x, y)[1]);
  std::printf("environment's part at the centre: intensity 1 %.4f, 2 %.4f (ratio %.3f)\n", partOne / 1600, partTwo / 1600, partTwo / partOne);
  EXPECT_GT(partOne, 0);
  EXPECT_NEAR(partTwo / partOne, 2.0, 0.1);
}

// ---- Shadows from point and spot lights (issue 38 item 5) ----

// maskShadowAsset's ground (6 x 6 at y = 0) and holed occluder (2 x 2 at y = 1, a see-through
// hole over |x|, |z| < 0.5) lit by a point light, or a spot light pointing down, at (0, 3, 0)
// and nothing else. Rays from the light spread: an occluder point at x reaches the ground at
// 1.5 x (distances 2 and 3 from the light). So, seen from the top along z = 0, the ground at
// x = 1.25 (occluder x = 0.83, the rim) is in shadow, though a light straight overhead at
// infinity would light it; at x = 1.75 (occluder x = 1.17, past its edge) it is lit; at x = 0.3
// (occluder x = 0.2, in the hole, seen through it) it is lit.
TEST(Viewer, PointAndSpotLightsCastShadows) {
  TempDir dir;
  const fs::path base = maskShadowAsset(dir);
  const double pixelsPerUnit = 256 / (2 * 1.02 * std::sqrt(36.0 + 36.0 + 1.0) / 2);  // as MaskedQuadCastsACutOutShadow
  auto meanLuma = [&](const Image& image, double x, double z) {
    const auto q = quadrantMeans(image, 128 + x * pixelsPerUnit, 128 + z * pixelsPerUnit, 3);
    return (q[0] + q[1] + q[2] + q[3]) / 4;
  };
  const double s = std::sqrt(0.5);
  const std::pair<nlohmann::json, nlohmann::json> lights[] = {
      {{{"type", "point"}, {"intensity", 20.0}}, {{"translation", {0, 3, 0}}}},
      // The spot shines along its node's -z, turned by -90 degrees about x to point down.
      {{{"type", "spot"}, {"intensity", 20.0}, {"spot", {{"innerConeAngle", 0.5}, {"outerConeAngle", 0.9}}}},
       {{"translation", {0, 3, 0}}, {"rotation", {-s, 0, 0, s}}}},
  };
  for (const auto& [light, node] : lights) {
    const std::string type = light["type"];
    nlohmann::json doc = nlohmann::json::parse(std::ifstream(base));
    doc["extensions"]["KHR_lights_punctual"]["lights"] = {light};
    nlohmann::json lightNode = node;
    lightNode["extensions"] = {{"KHR_lights_punctual", {{"light", 0}}}};
    doc["nodes"][2] = lightNode;
    const fs::path file = dir / (type + "-shadow.gltf");
    std::ofstream(file) << doc.dump(1);
    const std::string common = "'" + file.string() + "' --camera top --ortho --size 256x256 --no-ibl";  // the shadow map's part only
    const Image shadowed = screenshot(dir, type + "-shadows", common), plain = screenshot(dir, type + "-no-shadows", common + " --no-shadows");
    ASSERT_EQ(shadowed.width, 256) << type;
    const float rimOn = meanLuma(shadowed, 1.25, 0), rimOff = meanLuma(plain, 1.25, 0);
    const float pastOn = meanLuma(shadowed, 1.75, 0), pastOff = meanLuma(plain, 1.75, 0);
    const float holeOn = meanLuma(shadowed, 0.3, 0), holeOff = meanLuma(plain, 0.3, 0);
    std::printf("%s light: ground under the rim %.3f with shadows, %.3f without; past the edge %.3f / %.3f; through the hole %.3f / %.3f\n",
                type.c_str(), rimOn, rimOff, pastOn, pastOff, holeOn, holeOff);
    EXPECT_GT(rimOff, 0.2f) << type;              // lit without shadows
    EXPECT_LT(rimOn, 0.5f * rimOff) << type;      // the rim's shadow, spread by the light's position
    EXPECT_NEAR(pastOn, pastOff, 0.02f) << type;  // past the occluder's shadow
    EXPECT_NEAR(holeOn, holeOff, 0.02f) << type;  // light through the hole
  }
}

// A point light inside the scene shadows sideways too (a cube map, not one view towards the
// scene's centre): quadAsset's quad as a 6 x 6 ground (y = 0) and two occluders 0.3 x 0.6 at
// height 0.125 over x in [1.0, 1.3] and [-1.3, -1.0]; the light at (0, 0.25, 0), halfway up
// from the occluders: each occluder point at x reaches the ground at 2 x, so the ground over
// |x| in [2.0, 2.6] is in shadow, 84 degrees from straight down, and |x| = 1.7 and 2.9 are lit.
// At x = 2.3 the light arrives at 84 degrees from the normal: E = 20 cd cos / d^2 = 0.404 lux,
// radiance about E / pi = 0.129, while the plain sky term (--no-ibl; 6% of the light's
// intensity over pi, times 1 / d^2 and the sky's 1.8 straight up) adds 0.128 that no shadow
// removes: in linear light the shadow leaves about half (0.50), no shadow all of it.
TEST(Viewer, PointLightInsideTheSceneShadowsSideways) {
  TempDir dir;
  writeRgbaPng(dir / "white.png", 4, 4, [](int, int) { return std::array<unsigned char, 4>{255, 255, 255, 255}; });
  const double s = std::sqrt(0.5);
  const nlohmann::json faceUp = {-s, 0, 0, s};  // turns the quad's +z normal to +y
  nlohmann::json nodes = {{{"mesh", 0}, {"rotation", faceUp}, {"scale", {3, 3, 1}}}};
  for (const double x : {1.15, -1.15}) nodes.push_back({{"mesh", 0}, {"rotation", faceUp}, {"scale", {0.15, 0.3, 1}}, {"translation", {x, 0.125, 0}}});
  nodes.push_back({{"translation", {0, 0.25, 0}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  const nlohmann::json patch = {{"extensionsUsed", {"KHR_lights_punctual"}},
                                {"extensions", {{"KHR_lights_punctual", {{"lights", {{{"type", "point"}, {"intensity", 20.0}}}}}}}},
                                {"nodes", nodes},
                                {"scenes", {{{"nodes", {0, 1, 2, 3}}}}}};
  const fs::path file = quadAsset(dir, "sideways", kWhiteRough, "white.png", patch);
  const std::string common = "'" + file.string() + "' --camera top --ortho --size 256x256 --no-ibl --tone-map none --exposure 2";
  const Image shadowed = screenshot(dir, "shadows", common), plain = screenshot(dir, "no-shadows", common + " --no-shadows");
  ASSERT_EQ(shadowed.width, 256);
  const double pixelsPerUnit = 256 / (2 * 1.02 * std::sqrt(36.0 + 36.0 + 0.125 * 0.125) / 2);
  auto meanLuma = [&](const Image& image, double x) {  // linear, of the grey's red channel
    const int cx = static_cast<int>(128 + x * pixelsPerUnit);
    double sum = 0;
    for (int py = 126; py <= 130; ++py)
      for (int px = cx - 2; px <= cx + 2; ++px) sum += srgbToLinear(image.at(px, py)[0]);
    return static_cast<float>(sum / 25);
  };
  for (const double side : {1.0, -1.0}) {
    const float shadowOn = meanLuma(shadowed, 2.3 * side), shadowOff = meanLuma(plain, 2.3 * side);
    const float nearOn = meanLuma(shadowed, 1.7 * side), nearOff = meanLuma(plain, 1.7 * side);
    const float farOn = meanLuma(shadowed, 2.9 * side), farOff = meanLuma(plain, 2.9 * side);
    std::printf("x %+.1f: %.3f with shadows, %.3f without; x %+.1f: %.3f / %.3f; x %+.1f: %.3f / %.3f\n", 2.3 * side, shadowOn, shadowOff,
                1.7 * side, nearOn, nearOff, 2.9 * side, farOn, farOff);
    EXPECT_GT(shadowOff, 0.3f);
    EXPECT_NEAR(shadowOn / shadowOff, 0.50f, 0.08f);
    EXPECT_NEAR(nearOn, nearOff, 0.03f);
    EXPECT_NEAR(farOn, farOff, 0.03f);
  }
}

// ---- Exposure keeps a light surface's bumps (issue 38, smaller defects) ----

// A white, rough, ridged plane over [-1, 1]^2 (x, z) seen from the top: 8 flat facets across z,
// tilted +20 and -20 degrees about x in turn (heights 0 and 0.25 tan 20), each with its own
// NORMAL, so that the default rig's key light (from above, 24 degrees towards +z in the y-z
// plane) meets one set at N.L 0.95 and the other at N.L 0.69 (its fill light too leans to +z).
fs::path ridgedWhitePlane(const TempDir& dir) {
  GltfWriter gltf;
  std::vector<float> positions, normals;
  std::vector<std::uint16_t> indices;
  const float width = 0.25f, rise = width * std::tan(20.0f * 3.14159265f / 180);
  for (int facet = 0; facet < 8; ++facet) {
    const float z0 = -1 + width * facet, z1 = z0 + width;
    const float y0 = facet % 2 ? rise : 0, y1 = facet % 2 ? 0 : rise;
    const float length = std::hypot(y1 - y0, width);
    const auto base = static_cast<std::uint16_t>(positions.size() / 3);
    for (const auto& [x, y, z] : {std::array<float, 3>{-1, y0, z0}, {1, y0, z0}, {1, y1, z1}, {-1, y1, z1}}) {
      positions.insert(positions.end(), {x, y, z});
      normals.insert(normals.end(), {0, width / length, -(y1 - y0) / length});
    }
    // Counter-clockwise seen from above.
    indices.insert(indices.end(), {base, static_cast<std::uint16_t>(base + 2), static_cast<std::uint16_t>(base + 1), base,
                                   static_cast<std::uint16_t>(base + 3), static_cast<std::uint16_t>(base + 2)});
  }
  const nlohmann::json attributes = {{"POSITION", gltf.floats(positions, "VEC3", 3)}, {"NORMAL", gltf.floats(normals, "VEC3", 3)}};
  nlohmann::json doc = {
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"meshes", {{{"primitives", {{{"attributes", attributes}, {"indices", gltf.shorts(indices, "SCALAR", 1, true)}, {"material", 0}}}}}}},
      {"materials", {{{"pbrMetallicRoughness", {{"baseColorFactor", {1.0, 1.0, 1.0, 1.0}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.9}}}}}}};
  return gltf.write(dir / "ridged.gltf", doc);
}

// The linear luminance of the lit plane's dim and bright facets: the means of the 10-40th and
// 60-90th percentiles of the pixels in the middle third of the image (all plane; half of them
// on each set of facets).
std::pair<double, double> facetLuminances(const Image& image) {
  std::vector<double> lumas;
  for (int y = image.height / 3; y < 2 * image.height / 3; ++y)
    for (int x = image.width / 3; x < 2 * image.width / 3; ++x) {
      const auto c = image.at(x, y);
      lumas.push_back(0.2126 * srgbToLinear(c[0]) + 0.7152 * srgbToLinear(c[1]) + 0.0722 * srgbToLinear(c[2]));
    }
  std::sort(lumas.begin(), lumas.end());
  auto mean = [&](double from, double to) {
    const auto a = static_cast<std::size_t>(from * static_cast<double>(lumas.size())), b = static_cast<std::size_t>(to * static_cast<double>(lumas.size()));
    return std::accumulate(lumas.begin() + static_cast<std::ptrdiff_t>(a), lumas.begin() + static_cast<std::ptrdiff_t>(b), 0.0) / static_cast<double>(b - a);
  };
  return {mean(0.1, 0.4), mean(0.6, 0.9)};
}

// Under the default rig and auto exposure a white surface facing the key light must not sit in
// the tone curve's shoulder, where its bumps flatten: the ridges' contrast (bright over dim
// facets, linear) in the default lit view keeps at least 80% of their contrast in a linear render
// (no tone mapping, exposure low enough that nothing clips), and the bright facets still read
// light (above 0.6 sRGB-encoded, 0.32 linear).
TEST(Viewer, AutoExposureKeepsTheBumpsOfALightSurface) {
  TempDir dir;
  const fs::path file = ridgedWhitePlane(dir);
  const std::string common = "'" + file.string() + "' --camera top --ortho --size 240x240 --no-shadows";
  const Image lit = screenshot(dir, "lit", common);
  const Image linear = screenshot(dir, "linear", common + " --tone-map none --exposure 0.3");
  ASSERT_EQ(lit.width, 240);
  ASSERT_EQ(linear.width, 240);
  const auto [litDim, litBright] = facetLuminances(lit);
  const auto [linearDim, linearBright] = facetLuminances(linear);
  std::printf("lit: dim %.4f bright %.4f (contrast %.3f); linear: dim %.4f bright %.4f (contrast %.3f)\n", litDim, litBright,
              litBright / litDim, linearDim, linearBright, linearBright / linearDim);
  ASSERT_GT(linearBright / linearDim, 1.1) << "the ridges should differ by their angle to the key light";
  EXPECT_GE(litBright / litDim - 1, 0.8 * (linearBright / linearDim - 1));
  EXPECT_GT(litBright, srgbToLinear(0.6));
  EXPECT_LT(litBright, 0.9);
}

// ---- Trust: untrusted data is noted by element and drawn without it; files under one rule ----

// A quad over [-1, 1]^2 facing +z (node 0), skinned to joint node 1 with one weight per
// vertex, with one morph target (POSITION deltas) and a directional light on node 2. A case
// spoils one part of it: the arrays before they are written, the document after.
struct TrustQuad {
  std::vector<float> weights{1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
  std::vector<std::uint16_t> joints = std::vector<std::uint16_t>(16, 0);
  std::vector<float> inverseBind{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  std::vector<float> morphPositions = std::vector<float>(12, 0.0f);
  std::function<void(nlohmann::json&)> patch;

  fs::path write(const TempDir& dir, const std::string& name) const {
    GltfWriter gltf;
    const int position = gltf.floats({-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0}, "VEC3", 3);
    const int normal = gltf.floats({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3", 3);
    const int uv = gltf.floats({0, 1, 1, 1, 1, 0, 0, 0}, "VEC2", 2);
    const int joint = gltf.shorts(joints, "VEC4", 4), weight = gltf.floats(weights, "VEC4", 4);
    const int morph = gltf.add(morphPositions.data(), morphPositions.size() * sizeof(float), 5126, 4, "VEC3");
    const int indices = gltf.shorts({0, 1, 2, 0, 2, 3}, "SCALAR", 1, true);
    const int inverse = gltf.add(inverseBind.data(), inverseBind.size() * sizeof(float), 5126, 1, "MAT4");
    const nlohmann::json attributes = {{"POSITION", position}, {"NORMAL", normal}, {"TEXCOORD_0", uv}, {"JOINTS_0", joint}, {"WEIGHTS_0", weight}};
    const nlohmann::json primitive = {{"attributes", attributes}, {"indices", indices}, {"targets", {{{"POSITION", morph}}}}};
    nlohmann::json doc = {
        {"scene", 0},
        {"scenes", {{{"nodes", {0, 1, 2}}}}},
        {"nodes", {{{"mesh", 0}, {"skin", 0}, {"weights", {1.0}}}, nlohmann::json::object(),
                   {{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}, {"rotation", {-0.3826834, 0, 0, 0.9238795}}}}},
        {"skins", {{{"joints", {1}}, {"inverseBindMatrices", inverse}}}},
        {"meshes", {{{"name", "trust quad"}, {"primitives", {primitive}}}}},
        {"extensionsUsed", {"KHR_lights_punctual"}},
        {"extensions", {{"KHR_lights_punctual", {{"lights", {{{"type", "directional"}, {"intensity", 3.0}}}}}}}},
    };
    if (patch) patch(doc);
    return gltf.write(dir / (name + ".gltf"), doc);
  }
};

// Each kind of non-finite or out-of-range skin, morph, node and light data: the screenshot run
// names the element in a note and draws the quad without it (unskinned, unmorphed, the node at
// the identity, the light left out), exit 0 with a frame that is not empty. They used to give an
// empty frame (NaN corners) or pass without a word (a joint or light index past its array).
TEST(Viewer, NonFiniteOrOutOfRangeSceneDataIsNotedAndTheRestDrawn) {
  TempDir dir;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  struct Case {
    const char* name;
    std::function<void(TrustQuad&)> spoil;
    const char* note;
  };
  const Case cases[] = {
      {"intact", [](TrustQuad&) {}, nullptr},
      {"weights-nan", [&](TrustQuad& q) { q.weights[8] = nan; }, "mesh 0 'trust quad' primitive 0: WEIGHTS_0 element 2 is not finite; skin not applied"},
      {"inverse-bind-nan", [&](TrustQuad& q) { q.inverseBind[12] = nan; },
       "skin 0: inverseBindMatrices element 0 is not finite; meshes with this skin shown unskinned"},
      {"node-matrix-1e39", [](TrustQuad& q) {
         q.patch = [](nlohmann::json& doc) { doc["nodes"][0]["matrix"] = {1e39, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}; };
       }, "node 0: matrix not finite; treated as identity"},
      {"joint-past-skin", [](TrustQuad& q) { q.joints[4] = 5; },
       "node 0: mesh 0 'trust quad' primitive 0: JOINTS_0 at corner 1 names joint 5, past the 1 joint(s) of skin 0; the node drawn unskinned"},
      {"light-past-lights", [](TrustQuad& q) {
         q.patch = [](nlohmann::json& doc) { doc["nodes"][2]["extensions"]["KHR_lights_punctual"]["light"] = 7; };
       }, "node 2: KHR_lights_punctual light 7 is not one of the file's 1 light(s); left out"},
      {"light-intensity-1e39", [](TrustQuad& q) {
         q.patch = [](nlohmann::json& doc) { doc["extensions"]["KHR_lights_punctual"]["lights"][0]["intensity"] = 1e39; };
       }, "node 2: KHR_lights_punctual light 0: intensity not finite; left out"},
      {"morph-delta-nan", [&](TrustQuad& q) { q.morphPositions[4] = nan; },
       "mesh 0 'trust quad' primitive 0: morph target 0 POSITION element 1 is not finite; morph targets not applied"},
      {"morph-weight-1e39", [](TrustQuad& q) {
         q.patch = [](nlohmann::json& doc) { doc["nodes"][0]["weights"] = {1e39}; };
       }, "node 0: morph weight 0 is not finite; treated as 0"},
  };
  for (const Case& c : cases) {
    TrustQuad quad;
    c.spoil(quad);
    const fs::path file = quad.write(dir, c.name);
    const fs::path shot = dir / (std::string(c.name) + ".png");
    std::string output;
    const int exit = run("'" + file.string() + "' --camera front --ortho --size 64x64 --msaa 0 --screenshot '" + shot.string() + "'", output);
    ASSERT_EQ(exit, 0) << c.name << "\n" << output;
    if (c.note) EXPECT_NE(output.find(std::string("note: ") + file.string() + ": " + c.note), std::string::npos) << c.name << "\n" << output;
    else EXPECT_EQ(output.find("note:"), std::string::npos) << c.name << "\n" << output;
    // The quad covers the middle of the front view (44 x 44 of its 64 x 64 pixels, the camera
    // framing the quad's bounding sphere); an empty frame is all background.
    const Image image = readPng(shot);
    ASSERT_EQ(image.width, 64) << c.name;
    int drawn = 0;
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x) drawn += backgroundShare(Image{1, 1, {image.at(x, y)[0], image.at(x, y)[1], image.at(x, y)[2]}}) == 0;
    std::printf("%s: %d of %d pixels drawn\n", c.name, drawn, image.width * image.height);
    EXPECT_GT(drawn, image.width * image.height / 3) << c.name << ": the frame is (nearly) empty\n" << output;
  }
}

// --sphere-map, --compare and the input under the input rule of every reader: a folder, an
// empty file, a FIFO and a character device are a clean error naming the option, the file and
// why, at once (the time limit fails a run that blocks or reads forever). /dev/zero used to be
// read forever, a FIFO to block, a folder and an empty file to be ignored.
TEST(Viewer, CommandLineFilesMustBeRegularFilesOfBoundedSize) {
  TempDir dir;
  fs::create_directories(dir / "folder.png");
  std::ofstream(dir / "empty.png").close();
  ASSERT_EQ(::mkfifo((dir / "fifo.png").c_str(), 0600), 0);
  ASSERT_EQ(::mkfifo((dir / "fifo.gltf").c_str(), 0600), 0);
  const std::string demo = "'" + (fs::path(TANGENT_SOURCE_DIR) / "data" / "demo" / "quad.gltf").string() + "'";
  const std::string shot = " --size 64x64 --screenshot '" + (dir / "x.png").string() + "'";
  struct Case {
    std::string arguments;
    std::string error;
  };
  const Case cases[] = {
      {demo + " --sphere-map '" + (dir / "folder.png").string() + "'", "--sphere-map: " + (dir / "folder.png").string() + ": is a directory, not an image"},
      {demo + " --sphere-map '" + (dir / "empty.png").string() + "'", "--sphere-map: " + (dir / "empty.png").string() + ": is empty (0 bytes), not an image"},
      {demo + " --sphere-map '" + (dir / "fifo.png").string() + "'", "--sphere-map: " + (dir / "fifo.png").string() + ": is not a regular file"},
      {demo + " --sphere-map /dev/zero", "--sphere-map: /dev/zero: is not a regular file"},
      {demo + " --compare '" + (dir / "fifo.gltf").string() + "'", "--compare: " + (dir / "fifo.gltf").string() + ": is not a regular file"},
      {"'" + (dir / "fifo.gltf").string() + "'", "input: " + (dir / "fifo.gltf").string() + ": is not a regular file"},
      {"'" + dir.path().string() + "'", "input: " + dir.path().string() + ": is a directory, not a glTF file"},
  };
  for (const Case& c : cases) {
    std::string output;
    const auto result = tangent::testing::runCommand("timeout 30 " + std::string(TANGENT_VIEW) + " " + c.arguments + shot);
    EXPECT_EQ(result.exitCode, 1) << c.arguments << " (124: it hung)\n" << result.output;
    EXPECT_NE(result.output.find("error: " + c.error), std::string::npos) << c.arguments << "\n" << result.output;
    EXPECT_FALSE(fs::exists(dir / "x.png")) << c.arguments;
  }
  // A sphere map that is a regular file but no image: also an error, now that --sphere-map names it.
  std::ofstream(dir / "text.png") << "not an image";
  const auto result = tangent::testing::runCommand("timeout 60 " + std::string(TANGENT_VIEW) + " " + demo + " --sphere-map '" +
                                                   (dir / "text.png").string() + "'" + shot);
  EXPECT_EQ(result.exitCode, 1) << result.output;
  EXPECT_NE(result.output.find("error: --sphere-map: " + (dir / "text.png").string() + ": cannot be decoded"), std::string::npos) << result.output;
}

// A mesh name with ESC, CR, LF and NUL reaches the terminal escaped as the CLI escapes it
// (\xHH): no control byte in the output, and no line of the name's own (it would forge an "ok"
// line in a CI log). Both print paths: --stats (no window) and the screenshot run.
TEST(Viewer, FileTextIsPrintedEscaped) {
  TempDir dir;
  TrustQuad quad;
  quad.patch = [](nlohmann::json& doc) {
    doc["meshes"][0]["name"] = std::string("a\x1b[31mred\r\nok all passed\0end", 28);
    doc["meshes"][0]["primitives"][0]["attributes"].erase("NORMAL");  // a note that names the mesh
  };
  const fs::path file = quad.write(dir, "names");
  for (const std::string& mode : {std::string(" --stats"), " --size 64x64 --screenshot '" + (dir / "x.png").string() + "'"}) {
    std::string output;
    ASSERT_EQ(run("'" + file.string() + "'" + mode, output), 0) << output;
    EXPECT_NE(output.find("mesh 0 'a\\x1B[31mred\\x0D\\x0Aok all passed\\x00end' primitive 0: no NORMAL"), std::string::npos) << mode << "\n" << output;
    EXPECT_EQ(output.find('\x1b'), std::string::npos) << mode;
    EXPECT_EQ(output.find('\r'), std::string::npos) << mode;
    EXPECT_EQ(output.find('\0'), std::string::npos) << mode;
    EXPECT_EQ(output.find("\nok"), std::string::npos) << mode << "\n" << output;
  }
}

// libpng's own messages ("libpng error: IDAT: CRC error", which it writes to stderr itself) come
// through the note channel, escaped and naming the glTF and its image; nothing of the decoder's
// reaches the terminal raw. The quad is still drawn (without its texture), exit 0.
TEST(Viewer, ImageDecoderMessagesGoThroughTheNoteChannel) {
  TempDir dir;
  writeRgbaPng(dir / "broken.png", 8, 8, [](int, int) { return std::array<unsigned char, 4>{200, 40, 40, 255}; });
  {
    // The IDAT chunk's CRC, the 4 bytes before IEND's 12, spoiled.
    std::fstream png(dir / "broken.png", std::ios::in | std::ios::out | std::ios::binary);
    png.seekg(-13, std::ios::end);
    const char byte = static_cast<char>(png.get());
    png.seekp(-13, std::ios::end);
    png.put(static_cast<char>(byte ^ 0x5a));
  }
  const nlohmann::json material = {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}},
                                   {"extensions", {{"KHR_materials_unlit", nlohmann::json::object()}}}};
  const fs::path file = quadAsset(dir, "broken", material, "broken.png");
  std::string output;
  ASSERT_EQ(run("'" + file.string() + "' --size 64x64 --screenshot '" + (dir / "x.png").string() + "'", output), 0) << output;
  EXPECT_NE(output.find("note: " + file.string() + ": image 0 'broken.png': decoder says: libpng error: IDAT: CRC error"), std::string::npos)
      << output;
  EXPECT_NE(output.find("note: " + file.string() + ": image 0 'broken.png': cannot be read"), std::string::npos) << output;
  std::istringstream lines(output);
  for (std::string line; std::getline(lines, line);)
    EXPECT_TRUE(line.rfind("note: ", 0) == 0 || line.rfind("wrote ", 0) == 0 || line.rfind("image-based", 0) == 0) << "a raw line: " << line;
}
