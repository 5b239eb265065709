// SPDX-License-Identifier: MIT
// The material features that read the tangent frame, and COLOR_0, as tangent-view renders them
// (under Xvfb with Mesa's llvmpipe): on tangent-make-data --materials' scenes, edited per case.
// - KHR_materials_anisotropy: the highlight of the brushed disc, lit and seen head-on, is
//   stretched along the extension's direction; its principal axis (second moments of the bright
//   pixels) turns with anisotropyRotation, follows the direction texture, and mirrors when
//   TANGENT's w is flipped.
// - KHR_materials_clearcoat: the coat adds a second, sharp highlight over the rough base, and its
//   normal map (TEXCOORD_1 through a rotated KHR_texture_transform) perturbs it.
// - COLOR_0 multiplies the base colour, in each of its accessor forms.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numbers>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "support/run_command.hpp"
#include "support/temp_dir.hpp"
#include "viewer/png_image.hpp"

namespace {

namespace fs = std::filesystem;
using tangent::testing::TempDir;
using Json = nlohmann::ordered_json;

using tangent::testing::Image;

double srgbToLinear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }
double linearLuma(const float* c) {
  return 0.2126 * srgbToLinear(c[0]) + 0.7152 * srgbToLinear(c[1]) + 0.0722 * srgbToLinear(c[2]);
}
bool isBackground(const float* c) {
  return std::abs(c[0] - 0.16f) < 0.01f && std::abs(c[1] - 0.17f) < 0.01f && std::abs(c[2] - 0.19f) < 0.01f;
}

Image screenshot(const TempDir& dir, const fs::path& file, const std::string& name, const std::string& arguments) {
  const fs::path out = dir / (name + ".png");
  const auto result = tangent::testing::runCommand(std::string(TANGENT_VIEW) + " '" + file.string() + "' " + arguments +
                                                   " --screenshot '" + out.string() + "'");
  EXPECT_EQ(result.exitCode, 0) << arguments << "\n" << result.output;
  EXPECT_EQ(result.output.find("OpenGL errors"), std::string::npos) << result.output;
  if (result.exitCode != 0) {
    ADD_FAILURE() << "no screenshot " << out;
    return Image{};
  }
  return tangent::testing::readPng(out);
}

// tangent-make-data --materials into dir/made; the folder.
fs::path makeScenes(const TempDir& dir) {
  const fs::path makeData = fs::path(TANGENT_VIEW).parent_path() / "tangent-make-data";
  const auto made = tangent::testing::runCommand("'" + makeData.string() + "' --materials '" + (dir / "made").string() + "'");
  EXPECT_EQ(made.exitCode, 0) << made.output;
  return dir / "made";
}

Json readJson(const fs::path& file) { return Json::parse(std::ifstream(file)); }
fs::path writeJson(const fs::path& file, const Json& doc) {
  std::ofstream(file) << doc.dump(1);
  return file;
}

void writeRgbPng(const fs::path& path, std::array<unsigned char, 3> texel) {
  std::vector<unsigned char> pixels;
  for (int i = 0; i < 16; ++i) pixels.insert(pixels.end(), texel.begin(), texel.end());
  auto out = OIIO::ImageOutput::create(path.string());
  ASSERT_TRUE(out);
  ASSERT_TRUE(out->open(path.string(), OIIO::ImageSpec(4, 4, 3, OIIO::TypeDesc::UINT8)));
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, pixels.data()));
  out->close();
}

// The principal axis of the bright region: pixels whose linear luminance is above the midpoint
// between the object's median and its peak, weighted by how far above; the angle in degrees from
// the image's +x towards its top (-90..90], and the ratio of the axes' standard deviations.
struct Axis {
  double degrees = 0, elongation = 0;
  std::size_t pixels = 0;
};
Axis brightAxis(const Image& image) {
  std::vector<double> lumas;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      if (!isBackground(image.pixel(x, y))) lumas.push_back(linearLuma(image.pixel(x, y)));
  Axis axis;
  if (lumas.empty()) return axis;
  std::vector<double> sorted = lumas;
  std::sort(sorted.begin(), sorted.end());
  const double threshold = (sorted[sorted.size() / 2] + sorted.back()) / 2;
  double w = 0, mx = 0, my = 0;
  for (int pass = 0; pass < 2; ++pass) {
    double sxx = 0, syy = 0, sxy = 0;
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x) {
        const float* c = image.pixel(x, y);
        if (isBackground(c)) continue;
        const double weight = linearLuma(c) - threshold;
        if (weight <= 0) continue;
        const double px = x + 0.5, py = image.height - (y + 0.5);  // y up
        if (pass == 0) {
          w += weight, mx += weight * px, my += weight * py;
          ++axis.pixels;
        } else {
          sxx += weight * (px - mx) * (px - mx), syy += weight * (py - my) * (py - my), sxy += weight * (px - mx) * (py - my);
        }
      }
    if (pass == 0) {
      if (w <= 0) return axis;
      mx /= w, my /= w;
    } else {
      axis.degrees = 0.5 * std::atan2(2 * sxy, sxx - syy) * 180 / std::numbers::pi;
      const double mean = (sxx + syy) / 2, spread = std::sqrt((sxx - syy) * (sxx - syy) / 4 + sxy * sxy);
      axis.elongation = std::sqrt((mean + spread) / std::max(mean - spread, 1e-12));
    }
  }
  return axis;
}

// The difference of two axis angles, as lines (modulo 180), in (-90, 90].
double axisDifference(double a, double b) {
  double d = std::fmod(a - b, 180.0);
  if (d > 90) d -= 180;
  if (d <= -90) d += 180;
  return d;
}

// The disc lit and seen head-on: its sun along -z (the node's rotation removed), so that the
// highlight sits at the centre; anisotropy as given (the texture dropped unless `texture`).
fs::path discVariant(const fs::path& made, const std::string& name, double rotation, const std::string& texture = "") {
  Json doc = readJson(made / "anisotropy_disc.gltf");
  for (Json& node : doc["nodes"])
    if (node.contains("extensions")) node.erase("rotation");
  Json& anisotropy = doc["materials"][0]["extensions"]["KHR_materials_anisotropy"];
  anisotropy["anisotropyRotation"] = rotation;
  if (texture.empty()) anisotropy.erase("anisotropyTexture");
  else doc["images"][0]["uri"] = texture;
  return writeJson(made / (name + ".gltf"), doc);
}

const std::string kDiscView = "--camera front --size 240x240 --no-shadows --no-ibl --tone-map none --exposure 0.5";

TEST(Materials, AnisotropicHighlightTurnsWithTheRotationAndMirrorsWithW) {
  TempDir dir;
  const fs::path made = makeScenes(dir);
  const double small = 0.3, large = 1.1;  // radians: 17.2 and 63.0 degrees
  const Axis atSmall = brightAxis(screenshot(dir, discVariant(made, "small", small), "small", kDiscView));
  const Axis atLarge = brightAxis(screenshot(dir, discVariant(made, "large", large), "large", kDiscView));
  const Axis flipped = brightAxis(screenshot(dir, discVariant(made, "flipped", small), "flipped", kDiscView + " --negate-w"));
  // Isotropic (strength 0): no preferred axis, as a control of the measure. Its highlight is
  // narrower and far brighter: exposed less, so that it does not clip.
  Json isotropic = readJson(discVariant(made, "isotropic", small));
  isotropic["materials"][0]["extensions"]["KHR_materials_anisotropy"]["anisotropyStrength"] = 0.0;
  const Axis round = brightAxis(screenshot(dir, writeJson(made / "isotropic.gltf", isotropic), "isotropic", kDiscView + " --exposure 0.02"));
  std::printf("highlight axis: rotation %.1f deg -> %.1f deg (elongation %.2f, %zu px); rotation %.1f deg -> %.1f deg (%.2f); "
              "w flipped -> %.1f deg (%.2f); isotropic elongation %.2f (%zu px)\n",
              small * 180 / std::numbers::pi, atSmall.degrees, atSmall.elongation, atSmall.pixels, large * 180 / std::numbers::pi,
              atLarge.degrees, atLarge.elongation, flipped.degrees, flipped.elongation, round.elongation, round.pixels);
  ASSERT_GT(atSmall.pixels, 50u);
  ASSERT_GT(round.pixels, 50u);
  // Stretched, and along the direction the extension defines: rotation counter-clockwise from T
  // (+x, image right) towards B (+y, image up).
  EXPECT_GT(atSmall.elongation, 1.5);
  EXPECT_GT(atLarge.elongation, 1.5);
  EXPECT_LT(round.elongation, 1.3);
  EXPECT_NEAR(axisDifference(atSmall.degrees, small * 180 / std::numbers::pi), 0, 8);
  EXPECT_NEAR(axisDifference(atLarge.degrees, atSmall.degrees), (large - small) * 180 / std::numbers::pi, 8);
  // w flipped: B = -y, the direction mirrored about T.
  EXPECT_NEAR(axisDifference(flipped.degrees, -atSmall.degrees), 0, 8);
  EXPECT_GT(std::abs(axisDifference(flipped.degrees, atSmall.degrees)), 20);
}

TEST(Materials, AnisotropyTextureGivesTheDirectionAndTheRotationTurnsIt) {
  TempDir dir;
  const fs::path made = makeScenes(dir);
  // A texture of one direction, 60 degrees from T ((cos, sin) * 0.5 + 0.5 in RG), full strength.
  const double degrees = 60, radians = degrees * std::numbers::pi / 180;
  writeRgbPng(made / "direction60.png", {static_cast<unsigned char>(std::lround((std::cos(radians) * 0.5 + 0.5) * 255)),
                                         static_cast<unsigned char>(std::lround((std::sin(radians) * 0.5 + 0.5) * 255)), 255});
  const Axis fromTexture = brightAxis(screenshot(dir, discVariant(made, "texture", 0, "direction60.png"), "texture", kDiscView));
  const Axis turned = brightAxis(screenshot(dir, discVariant(made, "texture-turned", -0.5, "direction60.png"), "turned", kDiscView));
  std::printf("texture at 60 deg -> %.1f deg (elongation %.2f); turned by -28.6 deg -> %.1f deg (%.2f)\n", fromTexture.degrees,
              fromTexture.elongation, turned.degrees, turned.elongation);
  EXPECT_GT(fromTexture.elongation, 1.5);
  EXPECT_NEAR(axisDifference(fromTexture.degrees, degrees), 0, 8);
  EXPECT_NEAR(axisDifference(turned.degrees, degrees - 0.5 * 180 / std::numbers::pi), 0, 8);
}

// The anisotropy-direction view: the disc's direction field (the made disc's circular texture
// turned by its rotation) as colour, (x, y, z) * 0.5 + 0.5 in world space, in the xy plane.
TEST(Materials, AnisotropyDirectionViewShowsTheDirectionField) {
  TempDir dir;
  const fs::path made = makeScenes(dir);
  const Image image = screenshot(dir, made / "anisotropy_disc.gltf", "direction", "--camera front --ortho --size 200x200 --view anisotropy-direction");
  ASSERT_EQ(image.width, 200);
  const double rotation = readJson(made / "anisotropy_disc.gltf")["materials"][0]["extensions"]["KHR_materials_anisotropy"]["anisotropyRotation"];
  // At points around the centre: the texture's direction is counter-clockwise tangential
  // (atan2 + 90 deg), turned by the rotation.
  int checked = 0;
  for (int k = 0; k < 8; ++k) {
    const double around = k * std::numbers::pi / 4, r = 0.6 * image.width / 2 / 1.02;  // --ortho frames the disc's sphere
    const int x = static_cast<int>(image.width / 2 + r * std::cos(around)), y = static_cast<int>(image.height / 2 - r * std::sin(around));
    const float* c = image.pixel(x, y);
    const double shown = std::atan2(2.0 * c[1] - 1, 2.0 * c[0] - 1);
    const double expected = around + std::numbers::pi / 2 + rotation;
    double difference = std::remainder(shown - expected, 2 * std::numbers::pi) * 180 / std::numbers::pi;
    EXPECT_NEAR(difference, 0, 10) << "at " << around * 180 / std::numbers::pi << " deg around";
    EXPECT_NEAR(2.0 * c[2] - 1, 0, 0.05);  // in the disc's plane
    ++checked;
  }
  EXPECT_EQ(checked, 8);
}

// The axis of short lines drawn over an image: the pixels where `with` differs from `without`,
// in pieces that touch (8-connected); each piece's principal axis (second moments) as a doubled
// angle, weighted by its pixels and averaged; the axis in degrees from the image's +x towards its
// top (-90..90]. Pieces of fewer than 3 pixels have no axis and are left out.
struct LineAxis {
  double degrees = 0, coherence = 0;  // coherence: the mean vector's length, 1 when all pieces agree
  std::size_t pixels = 0;
};
LineAxis drawnLinesAxis(const Image& with, const Image& without) {
  const int w = with.width, h = with.height;
  std::vector<char> drawn(static_cast<std::size_t>(w) * h, 0);
  LineAxis axis;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float *a = with.pixel(x, y), *b = without.pixel(x, y);
      drawn[static_cast<std::size_t>(y) * w + x] = std::abs(a[0] - b[0]) + std::abs(a[1] - b[1]) + std::abs(a[2] - b[2]) > 0.15f;
      axis.pixels += drawn[static_cast<std::size_t>(y) * w + x];
    }
  double c = 0, s = 0, weight = 0;
  std::vector<std::pair<int, int>> piece, stack;
  for (int start = 0; start < w * h; ++start) {
    if (!drawn[static_cast<std::size_t>(start)]) continue;
    piece.clear();
    stack.assign(1, {start % w, start / w});
    drawn[static_cast<std::size_t>(start)] = 0;
    while (!stack.empty()) {
      const auto [x, y] = stack.back();
      stack.pop_back();
      piece.push_back({x, y});
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = x + dx, ny = y + dy;
          if (nx < 0 || ny < 0 || nx >= w || ny >= h || !drawn[static_cast<std::size_t>(ny) * w + nx]) continue;
          drawn[static_cast<std::size_t>(ny) * w + nx] = 0;
          stack.push_back({nx, ny});
        }
    }
    if (piece.size() < 3) continue;
    double mx = 0, my = 0, sxx = 0, syy = 0, sxy = 0;
    for (const auto& [x, y] : piece) mx += x, my += -y;  // y up
    mx /= piece.size(), my /= piece.size();
    for (const auto& [x, y] : piece) sxx += (x - mx) * (x - mx), syy += (-y - my) * (-y - my), sxy += (x - mx) * (-y - my);
    const double doubled = std::atan2(2 * sxy, sxx - syy), n = static_cast<double>(piece.size());
    c += n * std::cos(doubled), s += n * std::sin(doubled), weight += n;
  }
  if (weight == 0) return axis;
  axis.degrees = 0.5 * std::atan2(s, c) * 180 / std::numbers::pi;
  axis.coherence = std::hypot(c, s) / weight;
  return axis;
}

// The anisotropy-direction view's glyphs: one line at each glyph corner along the direction (a
// disc without texture: the rotation from T, +x; with w flipped, mirrored), and nowhere on a
// material without the extension; in the lit view the glyphs stay the T/B/N frames.
TEST(Materials, AnisotropyGlyphsLieAlongTheDirection) {
  TempDir dir;
  const fs::path made = makeScenes(dir);
  const std::string view = "--camera front --ortho --size 400x400 --view anisotropy-direction";
  auto glyphAxis = [&](const fs::path& file, const std::string& name, const std::string& extra) {
    const Image plain = screenshot(dir, file, name, view + extra);
    const Image glyphs = screenshot(dir, file, name + "-glyphs", view + extra + " --glyphs");
    return drawnLinesAxis(glyphs, plain);
  };
  const double small = 0.3, large = 1.1;  // radians: 17.2 and 63.0 degrees
  const LineAxis atSmall = glyphAxis(discVariant(made, "small", small), "small", "");
  const LineAxis atLarge = glyphAxis(discVariant(made, "large", large), "large", "");
  const LineAxis flipped = glyphAxis(discVariant(made, "flipped", small), "flipped", " --negate-w");
  std::printf("glyph axis: rotation %.1f deg -> %.1f deg (coherence %.2f, %zu px); %.1f deg -> %.1f deg (%.2f); w flipped -> %.1f deg\n",
              small * 180 / std::numbers::pi, atSmall.degrees, atSmall.coherence, atSmall.pixels, large * 180 / std::numbers::pi,
              atLarge.degrees, atLarge.coherence, flipped.degrees);
  ASSERT_GT(atSmall.pixels, 300u) << "the glyphs are not drawn";
  EXPECT_GT(atSmall.coherence, 0.8);
  EXPECT_NEAR(axisDifference(atSmall.degrees, small * 180 / std::numbers::pi), 0, 3);
  EXPECT_NEAR(axisDifference(atLarge.degrees, large * 180 / std::numbers::pi), 0, 3);
  EXPECT_NEAR(axisDifference(flipped.degrees, -small * 180 / std::numbers::pi), 0, 3);
  // Without the extension there is no direction to draw.
  Json plainDisc = readJson(discVariant(made, "none", small));
  plainDisc["materials"][0]["extensions"].erase("KHR_materials_anisotropy");
  EXPECT_EQ(glyphAxis(writeJson(made / "none.gltf", plainDisc), "none", "").pixels, 0u);
}

// Pixels of `a` brighter than `b` by more than `delta` in linear luminance, and pixels that
// differ by more than `delta` either way.
struct Difference {
  std::size_t brighter = 0, differing = 0, object = 0;
};
Difference compareImages(const Image& a, const Image& b, double delta) {
  Difference d;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      if (isBackground(a.pixel(x, y))) continue;
      ++d.object;
      const double change = linearLuma(a.pixel(x, y)) - linearLuma(b.pixel(x, y));
      if (change > delta) ++d.brighter;
      if (std::abs(change) > delta) ++d.differing;
    }
  return d;
}

TEST(Materials, ClearcoatAddsASharpHighlightThatItsNormalMapPerturbs) {
  TempDir dir;
  const fs::path made = makeScenes(dir);
  const std::string view = "--camera front --size 240x240 --no-shadows --no-ibl";
  const Json doc = readJson(made / "clearcoat_sphere.gltf");
  auto variant = [&](const std::string& name, auto edit) {
    Json copy = doc;
    edit(copy["materials"][0]["extensions"]["KHR_materials_clearcoat"]);
    return screenshot(dir, writeJson(made / (name + ".gltf"), copy), name, view);
  };
  const Image coated = screenshot(dir, made / "clearcoat_sphere.gltf", "coated", view);
  const Image bare = variant("bare", [](Json& coat) { coat["clearcoatFactor"] = 0.0; });
  const Image smooth = variant("smooth", [](Json& coat) { coat.erase("clearcoatNormalTexture"); });
  const Image unturned = variant("unturned", [](Json& coat) { coat["clearcoatNormalTexture"]["extensions"]["KHR_texture_transform"]["rotation"] = 0.0; });
  ASSERT_EQ(coated.width, 240);
  // The coat without its normal map against no coat: a small region much brighter (the sharp
  // highlight); elsewhere the coat's reflection of the sky stays faint.
  const Difference highlight = compareImages(smooth, bare, 0.2);
  // Its normal map moves the coat's reflections about across the sphere (the bumps), and it is
  // read on TEXCOORD_1 through the transform: another rotation, another picture.
  const Difference perturbed = compareImages(coated, smooth, 0.02);
  const Difference rotated = compareImages(coated, unturned, 0.02);
  std::printf("clearcoat: %zu of %zu pixels brighter by > 0.2 than without the coat; normal map changes %zu pixels (> 0.02), "
              "its transform's rotation %zu\n",
              highlight.brighter, highlight.object, perturbed.differing, rotated.differing);
  EXPECT_GT(highlight.brighter, 10u);
  EXPECT_LT(highlight.brighter, highlight.object / 20);
  EXPECT_GT(perturbed.differing, highlight.object / 40);
  EXPECT_GT(rotated.differing, highlight.object / 40);
}

// The clearcoat-normal view: the coat's normal in world space as colour, its normal map read
// through the TANGENT frame on its own UV set. Without its map it is the geometry's normal; with
// it the bumps show, and turn over when w is flipped (the map's green along -B); the same in
// every shading mode; grey where the material has no coat.
TEST(Materials, ClearcoatNormalViewShowsTheCoatsNormalMap) {
  TempDir dir;
  const fs::path made = makeScenes(dir);
  const std::string view = "--camera front --size 200x200";
  const Json doc = readJson(made / "clearcoat_sphere.gltf");
  auto variant = [&](const std::string& name, auto edit) {
    Json copy = doc;
    edit(copy["materials"][0]["extensions"]["KHR_materials_clearcoat"]);
    return writeJson(made / (name + ".gltf"), copy);
  };
  const fs::path sphere = made / "clearcoat_sphere.gltf";
  const Image coat = screenshot(dir, sphere, "coat", view + " --view clearcoat-normal");
  const Image coatPhong = screenshot(dir, sphere, "coat-phong", view + " --view clearcoat-normal --shading phong");
  const Image coatFlipped = screenshot(dir, sphere, "coat-flipped", view + " --view clearcoat-normal --negate-w");
  const Image geometry = screenshot(dir, sphere, "geometry", view + " --view geometry-normal");
  const Image smooth =
      screenshot(dir, variant("smooth", [](Json& c) { c.erase("clearcoatNormalTexture"); }), "smooth", view + " --view clearcoat-normal");
  const Image bare = screenshot(dir, variant("bare", [](Json& c) { c["clearcoatFactor"] = 0.0; }), "bare", view + " --view clearcoat-normal");
  ASSERT_EQ(coat.width, 200);
  // Pixels of the object, and how many of them differ by more than `delta` in some channel.
  auto differing = [&](const Image& a, const Image& b, float delta) {
    std::size_t count = 0, object = 0;
    for (int y = 0; y < a.height; ++y)
      for (int x = 0; x < a.width; ++x) {
        if (isBackground(a.pixel(x, y))) continue;
        ++object;
        const float *p = a.pixel(x, y), *q = b.pixel(x, y);
        count += std::max({std::abs(p[0] - q[0]), std::abs(p[1] - q[1]), std::abs(p[2] - q[2])}) > delta;
      }
    return std::pair{count, object};
  };
  const auto [bumps, object] = differing(coat, geometry, 0.05f);
  const auto [flips, object2] = differing(coat, coatFlipped, 0.05f);
  std::printf("clearcoat normal: %zu of %zu pixels off the geometry's normal by > 0.05; %zu change when w is flipped\n", bumps, object,
              flips);
  ASSERT_GT(object, 5000u);
  EXPECT_GT(bumps, object / 5);
  EXPECT_GT(flips, object / 10);
  EXPECT_EQ(differing(smooth, geometry, 0.01f).first, 0u) << "without its map the coat's normal is the geometry's";
  EXPECT_EQ(differing(coatPhong, coat, 0.01f).first, 0u) << "the view depends on the shading mode";
  std::size_t grey = 0, bareObject = 0;
  for (int y = 0; y < bare.height; ++y)
    for (int x = 0; x < bare.width; ++x) {
      const float* c = bare.pixel(x, y);
      if (isBackground(c)) continue;
      ++bareObject;
      grey += std::abs(c[0] - 0.5f) < 0.01f && std::abs(c[1] - 0.5f) < 0.01f && std::abs(c[2] - 0.5f) < 0.01f;
    }
  EXPECT_GT(bareObject, 5000u);
  EXPECT_EQ(grey, bareObject) << "a material without a coat shows grey";
}

// COLOR_0 accessor forms: a uniform colour in float RGB, normalized unsigned short RGBA and
// normalized unsigned byte RGB, each added to the made grid's buffer in place of its own COLOR_0.
struct ColourForm {
  const char* name;
  int componentType;  // 5126 float, 5123 unsigned short, 5121 unsigned byte
  int components;
};

fs::path uniformColourGrid(const fs::path& made, const ColourForm& form, std::array<double, 3> colour) {
  Json doc = readJson(made / "vertex_colors.gltf");
  std::ifstream binIn(made / "vertex_colors.bin", std::ios::binary);
  std::string bin((std::istreambuf_iterator<char>(binIn)), {});
  const std::size_t count = doc["accessors"][doc["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"].get<int>()]["count"];
  const std::size_t offset = bin.size();
  for (std::size_t v = 0; v < count; ++v)
    for (int c = 0; c < form.components; ++c) {
      const double value = c < 3 ? colour[c] : 1.0;
      if (form.componentType == 5126) {
        const float f = static_cast<float>(value);
        bin.append(reinterpret_cast<const char*>(&f), 4);
      } else if (form.componentType == 5123) {
        const auto s = static_cast<std::uint16_t>(std::lround(value * 65535));
        bin.append(reinterpret_cast<const char*>(&s), 2);
      } else {
        bin.push_back(static_cast<char>(static_cast<unsigned char>(std::lround(value * 255))));
      }
    }
  const std::size_t bytes = bin.size() - offset;
  while (bin.size() % 4) bin.push_back('\0');
  const std::size_t stride = ((bytes / count) + 3) / 4 * 4;  // byte RGB needs a stride of 4: repack
  if (stride != bytes / count) {
    std::string packed;
    for (std::size_t v = 0; v < count; ++v) {
      packed.append(bin, offset + v * (bytes / count), bytes / count);
      packed.append(stride - bytes / count, '\0');
    }
    bin.resize(offset);
    bin += packed;
  }
  Json view = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", stride * count}, {"target", 34962}};
  if (stride != bytes / count) view["byteStride"] = stride;
  doc["bufferViews"].push_back(view);
  Json accessor = {{"bufferView", doc["bufferViews"].size() - 1}, {"componentType", form.componentType}, {"count", count},
                   {"type", form.components == 3 ? "VEC3" : "VEC4"}};
  if (form.componentType != 5126) accessor["normalized"] = true;
  doc["accessors"].push_back(accessor);
  doc["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"] = doc["accessors"].size() - 1;
  const std::string stem = std::string("colour_") + form.name;
  doc["buffers"][0] = {{"uri", stem + ".bin"}, {"byteLength", bin.size()}};
  std::ofstream(made / (stem + ".bin"), std::ios::binary) << bin;
  return writeJson(made / (stem + ".gltf"), doc);
}

// Mean linear colour of the object's pixels, in columns [x0, x1) of the width (fractions).
std::array<double, 3> meanColour(const Image& image, double x0 = 0, double x1 = 1) {
  std::array<double, 3> sum{};
  std::size_t n = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = static_cast<int>(x0 * image.width); x < static_cast<int>(x1 * image.width); ++x) {
      const float* c = image.pixel(x, y);
      if (isBackground(c)) continue;
      for (int k = 0; k < 3; ++k) sum[k] += srgbToLinear(c[k]);
      ++n;
    }
  for (double& s : sum) s /= std::max<std::size_t>(n, 1);
  return sum;
}

TEST(Materials, VertexColourTintsTheBaseColourInEveryForm) {
  TempDir dir;
  const fs::path made = makeScenes(dir);
  const std::string view = "--camera front --size 160x160 --no-shadows --no-ibl";
  Json white = readJson(made / "vertex_colors.gltf");
  white["meshes"][0]["primitives"][0]["attributes"].erase("COLOR_0");
  const auto plain = meanColour(screenshot(dir, writeJson(made / "white.gltf", white), "white", view));
  // The made grid: red on the left, blue on the right (normalized unsigned bytes, RGBA).
  const Image gradient = screenshot(dir, made / "vertex_colors.gltf", "gradient", view);
  const auto left = meanColour(gradient, 0.1, 0.25), right = meanColour(gradient, 0.75, 0.9);
  std::printf("no COLOR_0: (%.3f %.3f %.3f); gradient left (%.3f %.3f %.3f), right (%.3f %.3f %.3f)\n", plain[0], plain[1], plain[2],
              left[0], left[1], left[2], right[0], right[1], right[2]);
  EXPECT_GT(left[0], 2 * left[2]);
  EXPECT_GT(right[2], 2 * right[0]);
  const std::array<double, 3> colour{0.15, 0.45, 1.0};
  for (const ColourForm& form : {ColourForm{"float_rgb", 5126, 3}, ColourForm{"ushort_rgba", 5123, 4}, ColourForm{"ubyte_rgb", 5121, 3}}) {
    const auto tinted = meanColour(screenshot(dir, uniformColourGrid(made, form, colour), form.name, view));
    std::array<double, 3> ratio{};
    for (int k = 0; k < 3; ++k) ratio[k] = tinted[k] / plain[k];
    std::printf("%s: mean (%.3f %.3f %.3f), against white x (%.2f %.2f %.2f)\n", form.name, tinted[0], tinted[1], tinted[2], ratio[0],
                ratio[1], ratio[2]);
    // The diffuse part scales by the colour per channel; the highlight, white, lifts each a little.
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(ratio[k], colour[k], 0.1 + 0.15 * (1 - colour[k])) << form.name << " channel " << k;
    EXPECT_LT(ratio[0], ratio[1]);
    EXPECT_LT(ratio[1], ratio[2]);
  }
}

}  // namespace
