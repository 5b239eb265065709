// SPDX-License-Identifier: MIT
#include "test_assets.hpp"

#include <cmath>
#include <cstring>
#include <fstream>
#include <numbers>
#include <numeric>
#include <random>

namespace tangent::testing {
namespace {

using Json = nlohmann::ordered_json;
constexpr double kPi = std::numbers::pi;

// A 1x1 PNG, so textures reference a real image.
const std::uint8_t kTinyPng[] = {
    0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44, 0x52, 0x00, 0x00,
    0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x08, 0x02, 0x00, 0x00, 0x00, 0x90, 0x77, 0x53, 0xde, 0x00, 0x00, 0x00,
    0x0c, 0x49, 0x44, 0x41, 0x54, 0x78, 0x9c, 0x63, 0x68, 0x68, 0xf8, 0x0f, 0x00, 0x03, 0x83, 0x02, 0x00, 0x00,
    0xa5, 0xfb, 0x89, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};

class Builder {
 public:
  explicit Builder(std::string name) {
    asset_.name = std::move(name);
    Json& doc = asset_.json;
    doc["asset"] = {{"version", "2.0"}, {"generator", "libtangent tests"}, {"copyright", "test asset"}};
    doc["scene"] = 0;
    doc["scenes"] = Json::array({{{"nodes", Json::array()}}});
    doc["nodes"] = Json::array();
    doc["meshes"] = Json::array();
    doc["accessors"] = Json::array();
    doc["bufferViews"] = Json::array();
    const int view = addView(kTinyPng, sizeof kTinyPng, 0);
    doc["images"] = Json::array({{{"bufferView", view}, {"mimeType", "image/png"}}});
    doc["samplers"] = Json::array({Json::object()});
    doc["textures"] = Json::array({{{"source", 0}, {"sampler", 0}}});
    doc["materials"] = Json::array({{{"name", "normalMapped"}, {"normalTexture", {{"index", 0}}}},
                                    {{"name", "plain"}, {"extras", {{"note", "no normal map"}}}}});
  }

  int addView(const void* data, std::size_t bytes, int target, int stride = 0) {
    while (asset_.bin.size() % 4) asset_.bin.push_back(0);
    Json view = {{"buffer", 0}, {"byteOffset", asset_.bin.size()}, {"byteLength", bytes}};
    if (stride) view["byteStride"] = stride;
    if (target) view["target"] = target;
    const auto* p = static_cast<const std::uint8_t*>(data);
    asset_.bin.insert(asset_.bin.end(), p, p + bytes);
    asset_.json["bufferViews"].push_back(view);
    return static_cast<int>(asset_.json["bufferViews"].size()) - 1;
  }

  int addAccessor(Json accessor) {
    asset_.json["accessors"].push_back(std::move(accessor));
    return static_cast<int>(asset_.json["accessors"].size()) - 1;
  }

  int floats(const std::vector<float>& values, const char* type, int components, bool minMax = false, int target = 34962) {
    const int view = addView(values.data(), values.size() * 4, target);
    Json accessor = {{"bufferView", view}, {"componentType", 5126}, {"count", values.size() / components}, {"type", type}};
    if (minMax) addMinMax(accessor, values, components);
    return addAccessor(accessor);
  }

  template <typename T>
  int indices(const std::vector<std::uint32_t>& values, int componentType) {
    std::vector<T> narrow(values.begin(), values.end());
    const int view = addView(narrow.data(), narrow.size() * sizeof(T), 34963);
    return addAccessor({{"bufferView", view}, {"componentType", componentType}, {"count", values.size()}, {"type", "SCALAR"}});
  }

  static void addMinMax(Json& accessor, const std::vector<float>& values, int components) {
    std::vector<float> lo(values.begin(), values.begin() + components), hi = lo;
    for (std::size_t i = 0; i < values.size(); ++i) {
      lo[i % components] = std::min(lo[i % components], values[i]);
      hi[i % components] = std::max(hi[i % components], values[i]);
    }
    accessor["min"] = lo;
    accessor["max"] = hi;
  }

  int addMesh(Json primitives, const std::string& name) {
    asset_.json["meshes"].push_back({{"name", name}, {"primitives", std::move(primitives)}});
    const int mesh = static_cast<int>(asset_.json["meshes"].size()) - 1;
    asset_.json["nodes"].push_back({{"mesh", mesh}, {"name", name + "Node"}});
    asset_.json["scenes"][0]["nodes"].push_back(asset_.json["nodes"].size() - 1);
    return mesh;
  }

  // Standard float POSITION/NORMAL/TEXCOORD_0 + uint16 indices primitive.
  Json basicPrimitive(const GridMesh& mesh, int material = 0) {
    Json attributes = {{"POSITION", floats(mesh.positions, "VEC3", 3, true)},
                       {"NORMAL", floats(mesh.normals, "VEC3", 3)},
                       {"TEXCOORD_0", floats(mesh.uvs, "VEC2", 2)}};
    return {{"attributes", attributes}, {"indices", indices<std::uint16_t>(mesh.indices, 5123)}, {"material", material}};
  }

  Json& json() { return asset_.json; }
  TestAsset take() {
    while (asset_.bin.size() % 4) asset_.bin.push_back(0);
    asset_.json["buffers"] = Json::array({{{"byteLength", asset_.bin.size()}}});
    return std::move(asset_);
  }

 private:
  TestAsset asset_;
};

TestAsset interleaved() {
  Builder b("interleaved_ubyte");
  const GridMesh grid = makeGrid(6, 6, true);  // 49 vertices: ubyte indices
  const std::size_t n = grid.positions.size() / 3;
  std::vector<float> interleavedData;
  for (std::size_t v = 0; v < n; ++v) {
    interleavedData.insert(interleavedData.end(), &grid.positions[3 * v], &grid.positions[3 * v + 3]);
    interleavedData.insert(interleavedData.end(), &grid.normals[3 * v], &grid.normals[3 * v + 3]);
    interleavedData.insert(interleavedData.end(), &grid.uvs[2 * v], &grid.uvs[2 * v + 2]);
  }
  const int view = b.addView(interleavedData.data(), interleavedData.size() * 4, 34962, 32);
  std::vector<float> positions = grid.positions;
  Json position = {{"bufferView", view}, {"componentType", 5126}, {"count", n}, {"type", "VEC3"}};
  Builder::addMinMax(position, positions, 3);
  std::vector<std::uint8_t> colors;
  std::vector<float> temperature;
  for (std::size_t v = 0; v < n; ++v) {
    colors.insert(colors.end(), {static_cast<std::uint8_t>(v * 5), static_cast<std::uint8_t>(255 - v), 7, 255});
    temperature.push_back(20.0f + static_cast<float>(v));
  }
  const int colorView = b.addView(colors.data(), colors.size(), 34962);
  Json attributes = {{"POSITION", b.addAccessor(position)},
                     {"NORMAL", b.addAccessor({{"bufferView", view}, {"byteOffset", 12}, {"componentType", 5126}, {"count", n}, {"type", "VEC3"}})},
                     {"TEXCOORD_0", b.addAccessor({{"bufferView", view}, {"byteOffset", 24}, {"componentType", 5126}, {"count", n}, {"type", "VEC2"}})},
                     {"COLOR_0", b.addAccessor({{"bufferView", colorView}, {"componentType", 5121}, {"normalized", true}, {"count", n}, {"type", "VEC4"}})},
                     {"_TEMPERATURE", b.floats(temperature, "SCALAR", 1)}};
  b.addMesh(Json::array({{{"attributes", attributes}, {"indices", b.indices<std::uint8_t>(grid.indices, 5121)}, {"material", 0}}}), "Interleaved");
  return b.take();
}

TestAsset quantized() {
  Builder b("quantized");
  const GridMesh grid = makeGrid(5, 4, true);
  const std::size_t n = grid.positions.size() / 3;
  std::vector<std::int16_t> positions;  // VEC3 SHORT, padded to 8 bytes per element
  std::vector<std::int8_t> normals;     // VEC3 BYTE normalized, padded to 4
  std::vector<std::uint16_t> uvs;       // VEC2 UNSIGNED_SHORT normalized
  std::vector<float> decodedPositions;
  for (std::size_t v = 0; v < n; ++v) {
    for (int k = 0; k < 3; ++k) {
      positions.push_back(static_cast<std::int16_t>(std::lround(grid.positions[3 * v + k] * 100)));
      decodedPositions.push_back(positions.back());
      normals.push_back(static_cast<std::int8_t>(std::lround(grid.normals[3 * v + k] * 127)));
    }
    positions.push_back(0);
    normals.push_back(0);
    for (int k = 0; k < 2; ++k) uvs.push_back(static_cast<std::uint16_t>(std::lround(grid.uvs[2 * v + k] * 65535)));
  }
  Json position = {{"bufferView", b.addView(positions.data(), positions.size() * 2, 34962, 8)}, {"componentType", 5122}, {"count", n}, {"type", "VEC3"}};
  Builder::addMinMax(position, decodedPositions, 3);
  Json attributes = {
      {"POSITION", b.addAccessor(position)},
      {"NORMAL", b.addAccessor({{"bufferView", b.addView(normals.data(), normals.size(), 34962, 4)}, {"componentType", 5120}, {"normalized", true}, {"count", n}, {"type", "VEC3"}})},
      {"TEXCOORD_0", b.addAccessor({{"bufferView", b.addView(uvs.data(), uvs.size() * 2, 34962)}, {"componentType", 5123}, {"normalized", true}, {"count", n}, {"type", "VEC2"}})}};
  b.addMesh(Json::array({{{"attributes", attributes}, {"indices", b.indices<std::uint16_t>(grid.indices, 5123)}, {"material", 0}}}), "Quantized");
  b.json()["extensionsUsed"] = Json::array({"KHR_mesh_quantization"});
  b.json()["extensionsRequired"] = Json::array({"KHR_mesh_quantization"});
  b.json()["nodes"][0]["scale"] = {0.01, 0.01, 0.01};
  return b.take();
}

TestAsset sparse() {
  Builder b("sparse");
  const GridMesh grid = makeGrid(4, 4, false);
  const std::size_t n = grid.positions.size() / 3;
  // POSITION: base data with three vertices lifted by sparse substitution.
  std::vector<float> substituted = grid.positions;
  const std::vector<std::uint16_t> sparseIndices = {3, 7, 12};
  std::vector<float> sparseValues;
  for (auto v : sparseIndices) {
    substituted[3 * v + 2] += 0.25f;
    sparseValues.insert(sparseValues.end(), &substituted[3 * v], &substituted[3 * v + 3]);
  }
  Json position = {{"bufferView", b.addView(grid.positions.data(), grid.positions.size() * 4, 34962)}, {"componentType", 5126}, {"count", n}, {"type", "VEC3"}};
  Builder::addMinMax(position, substituted, 3);
  position["sparse"] = {{"count", sparseIndices.size()},
                        {"indices", {{"bufferView", b.addView(sparseIndices.data(), sparseIndices.size() * 2, 0)}, {"componentType", 5123}}},
                        {"values", {{"bufferView", b.addView(sparseValues.data(), sparseValues.size() * 4, 0)}}}};
  // TEXCOORD_1: no bufferView (zeros) plus sparse values.
  const std::vector<std::uint8_t> uvIndices = {0, 5};
  const std::vector<float> uvValues = {0.5f, 0.25f, 0.75f, 1.0f};
  Json uv1 = {{"componentType", 5126}, {"count", n}, {"type", "VEC2"},
              {"sparse", {{"count", 2}, {"indices", {{"bufferView", b.addView(uvIndices.data(), uvIndices.size(), 0)}, {"componentType", 5121}}},
                          {"values", {{"bufferView", b.addView(uvValues.data(), uvValues.size() * 4, 0)}}}}}};
  Json attributes = {{"POSITION", b.addAccessor(position)}, {"NORMAL", b.floats(grid.normals, "VEC3", 3)},
                     {"TEXCOORD_0", b.floats(grid.uvs, "VEC2", 2)}, {"TEXCOORD_1", b.addAccessor(uv1)}};
  b.addMesh(Json::array({{{"attributes", attributes}, {"indices", b.indices<std::uint32_t>(grid.indices, 5125)}, {"material", 0}}}), "Sparse");
  return b.take();
}

TestAsset stripsAndFans() {
  Builder b("strips_and_fans");
  // Strip: a ribbon of 10 vertices along x, non-indexed.
  std::vector<float> positions, normals, uvs;
  for (int i = 0; i < 10; ++i) {
    const float x = static_cast<float>(i / 2), y = static_cast<float>(i % 2);
    positions.insert(positions.end(), {x, y, 0.1f * x * x});
    const float nx = -0.2f * x, length = std::sqrt(nx * nx + 1);
    normals.insert(normals.end(), {nx / length, 0, 1 / length});
    uvs.insert(uvs.end(), {x / 4, 1 - y});
  }
  Json strip = {{"attributes", {{"POSITION", b.floats(positions, "VEC3", 3, true)}, {"NORMAL", b.floats(normals, "VEC3", 3)}, {"TEXCOORD_0", b.floats(uvs, "VEC2", 2)}}},
                {"mode", 5}, {"material", 0}};
  // Fan: a disk, indexed, centre first.
  std::vector<float> fp = {0, 0, 0}, fn = {0, 0, 1}, fuv = {0.5f, 0.5f};
  std::vector<std::uint32_t> fanIndices = {0};
  for (int i = 0; i <= 12; ++i) {
    const double a = 2 * kPi * (i % 12) / 12;
    if (i < 12) {
      fp.insert(fp.end(), {static_cast<float>(std::cos(a)), static_cast<float>(std::sin(a)), 0});
      fn.insert(fn.end(), {0, 0, 1});
      fuv.insert(fuv.end(), {static_cast<float>(0.5 + 0.5 * std::cos(a)), static_cast<float>(0.5 - 0.5 * std::sin(a))});
    }
    fanIndices.push_back(1 + i % 12);
  }
  Json fan = {{"attributes", {{"POSITION", b.floats(fp, "VEC3", 3, true)}, {"NORMAL", b.floats(fn, "VEC3", 3)}, {"TEXCOORD_0", b.floats(fuv, "VEC2", 2)}}},
              {"indices", b.indices<std::uint16_t>(fanIndices, 5123)}, {"mode", 6}, {"material", 0}};
  b.addMesh(Json::array({strip, fan}), "StripAndFan");
  return b.take();
}

TestAsset morphTargets() {
  Builder b("morph_targets");
  const GridMesh grid = makeGrid(4, 3, true);
  const std::size_t n = grid.positions.size() / 3;
  Json primitive = b.basicPrimitive(grid);
  Json targets = Json::array();
  for (int t = 0; t < 2; ++t) {
    std::vector<float> dp(n * 3, 0.0f), dn(n * 3, 0.0f);
    for (std::size_t v = 0; v < n; ++v) {
      dp[3 * v + 2] = 0.2f * static_cast<float>(t + 1) * grid.positions[3 * v];
      dn[3 * v] = -0.1f * static_cast<float>(t + 1);
    }
    targets.push_back({{"POSITION", b.floats(dp, "VEC3", 3, true)}, {"NORMAL", b.floats(dn, "VEC3", 3)}});
  }
  primitive["targets"] = targets;
  b.addMesh(Json::array({primitive}), "Morph");
  b.json()["meshes"][0]["weights"] = {0.5, 0.0};
  b.json()["meshes"][0]["extras"] = {{"targetNames", {"bend", "twist"}}};
  return b.take();
}

// A normal-mapped torus without NORMAL: bake generates flat normals (glTF 2.0 3.7.2.1).
TestAsset noNormals() {
  Builder b("no_normals");
  Json primitive = b.basicPrimitive(makeTorus(12, 6));
  primitive["attributes"].erase("NORMAL");
  b.addMesh(Json::array({primitive}), "NoNormals");
  return b.take();
}

TestAsset secondUvSet() {
  Builder b("second_uv_set");
  // Flat (z = 0, normals +z), so that the frames the UV sets and the texture transform give
  // are exact directions in the plane.
  GridMesh grid = makeGrid(4, 4, false);
  for (std::size_t v = 0; v < grid.positions.size() / 3; ++v) {
    grid.positions[3 * v + 2] = 0;
    grid.normals[3 * v] = grid.normals[3 * v + 1] = 0;
    grid.normals[3 * v + 2] = 1;
  }
  std::vector<float> rotated;  // TEXCOORD_0 rotated 90 degrees: wrong for the normal map
  for (std::size_t i = 0; i < grid.uvs.size(); i += 2) rotated.insert(rotated.end(), {grid.uvs[i + 1], 1 - grid.uvs[i]});
  Json attributes = {{"POSITION", b.floats(grid.positions, "VEC3", 3, true)}, {"NORMAL", b.floats(grid.normals, "VEC3", 3)},
                     {"TEXCOORD_0", b.floats(rotated, "VEC2", 2)}, {"TEXCOORD_1", b.floats(grid.uvs, "VEC2", 2)}};
  const int indices = b.indices<std::uint16_t>(grid.indices, 5123);
  Json& materials = b.json()["materials"];
  materials.push_back({{"name", "normalOnUv1"}, {"normalTexture", {{"index", 0}, {"texCoord", 1}}}});
  materials.push_back({{"name", "transformOverride"},
                       {"normalTexture", {{"index", 0}, {"texCoord", 0}, {"extensions", {{"KHR_texture_transform", {{"texCoord", 1}, {"rotation", 0.5}, {"scale", {2.0, 2.0}}}}}}}}});
  b.addMesh(Json::array({{{"attributes", attributes}, {"indices", indices}, {"material", 2}},
                         {{"attributes", attributes}, {"indices", indices}, {"material", 3}}}),
            "TwoUvSets");
  b.json()["extensionsUsed"] = Json::array({"KHR_texture_transform"});
  return b.take();
}

TestAsset documentFeatures() {
  Builder b("document_features");
  const GridMesh grid = makeGrid(3, 3, true);
  Json baked = b.basicPrimitive(grid);
  baked["extras"] = {{"primitiveNote", "keep me"}};
  Json plain = b.basicPrimitive(grid, 1);  // no normal map: left alone
  Json points = {{"attributes", {{"POSITION", baked["attributes"]["POSITION"]}}}, {"mode", 0}, {"material", 1}};
  Json noNormals = {{"attributes", {{"POSITION", baked["attributes"]["POSITION"]}, {"TEXCOORD_0", baked["attributes"]["TEXCOORD_0"]}}},
                    {"indices", baked["indices"]}, {"material", 0}};
  // A primitive that already has a valid TANGENT: kept.
  std::vector<float> tangents;
  for (std::size_t v = 0; v < grid.positions.size() / 3; ++v) tangents.insert(tangents.end(), {1, 0, 0, 1});
  Json withTangent = b.basicPrimitive(makeGrid(2, 2, false));
  withTangent["attributes"]["TANGENT"] = b.floats(std::vector<float>(tangents.begin(), tangents.begin() + 9 * 4), "VEC4", 4);
  b.addMesh(Json::array({baked, plain, points, noNormals, withTangent}), "Features");
  // Animation whose accessors come after the mesh's: they must be renumbered correctly.
  const std::vector<float> times = {0, 1, 2};
  const std::vector<float> translations = {0, 0, 0, 0, 1, 0, 0, 0, 0};
  b.json()["animations"] = Json::array({{{"name", "bounce"},
                                         {"channels", {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "translation"}}}}}},
                                         {"samplers", {{{"input", b.floats(times, "SCALAR", 1, true, 0)}, {"output", b.floats(translations, "VEC3", 3, false, 0)}}}}}});
  b.json()["cameras"] = Json::array({{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}, {"extras", {{"k", 1}}}}});
  b.json()["nodes"].push_back({{"camera", 0}, {"name", "Camera"}, {"translation", {0, 0, 5}}, {"extras", {{"owner", "tests"}}}});
  b.json()["scenes"][0]["nodes"].push_back(1);
  b.json()["scenes"][0]["extras"] = {{"exposure", 1.5}};
  b.json()["extras"] = {{"pipeline", {{"stage", 3}, {"tags", {"a", "b"}}}}};
  b.json()["asset"]["extras"] = {{"source", "generated"}};
  return b.take();
}

TestAsset manySplits() {
  Builder b("many_splits");
  // 200 x 300 quads = 60501 vertices, under 65535; mirrored columns push it past: UNSIGNED_INT.
  const GridMesh grid = makeGrid(200, 300, true);
  b.addMesh(Json::array({b.basicPrimitive(grid)}), "ManySplits");
  return b.take();
}

}  // namespace

GridMesh makeGrid(int nx, int ny, bool mirrorColumns) {
  GridMesh mesh;
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) {
      const double x = double(i) / nx, y = double(j) / ny;
      const double z = 0.1 * std::sin(3 * x) * std::cos(2 * y);
      const double dzdx = 0.3 * std::cos(3 * x) * std::cos(2 * y), dzdy = -0.2 * std::sin(3 * x) * std::sin(2 * y);
      const double length = std::sqrt(dzdx * dzdx + dzdy * dzdy + 1);
      mesh.positions.insert(mesh.positions.end(), {static_cast<float>(x), static_cast<float>(y), static_cast<float>(z)});
      mesh.normals.insert(mesh.normals.end(), {static_cast<float>(-dzdx / length), static_cast<float>(-dzdy / length), static_cast<float>(1 / length)});
      // With mirrored columns u runs 0,1,0,1... across vertex columns: neighbours mirror.
      const double u = mirrorColumns ? (i % 2) : x;
      mesh.uvs.insert(mesh.uvs.end(), {static_cast<float>(u), static_cast<float>(1 - y)});
    }
  }
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const std::uint32_t a = j * (nx + 1) + i, b = a + 1, c = a + nx + 1, d = c + 1;
      mesh.indices.insert(mesh.indices.end(), {a, b, d, a, d, c});
    }
  }
  return mesh;
}

GridMesh leaningGrid() {
  GridMesh mesh = makeGrid(6, 6, true);
  for (std::size_t v = 0; v < mesh.normals.size() / 3; ++v) {
    const double lean[3] = {mesh.normals[3 * v] + 0.5 * std::sin(1.3 * v), mesh.normals[3 * v + 1] + 0.5 * std::cos(0.7 * v),
                            double(mesh.normals[3 * v + 2])};
    const double length = std::sqrt(lean[0] * lean[0] + lean[1] * lean[1] + lean[2] * lean[2]);
    for (int k = 0; k < 3; ++k) mesh.normals[3 * v + k] = static_cast<float>(lean[k] / length);
    mesh.uvs[2 * v] += static_cast<float>(0.02 * std::sin(2.1 * v));
    mesh.uvs[2 * v + 1] += static_cast<float>(0.02 * std::cos(1.1 * v));
  }
  return mesh;
}

GridMesh makeTorus(int rings, int sides) {
  GridMesh mesh;
  const double R = 1.0, r = 0.35;
  for (int i = 0; i <= rings; ++i) {
    for (int j = 0; j <= sides; ++j) {
      const double u = double(i) / rings, v = double(j) / sides;
      const double a = 2 * kPi * u, b = 2 * kPi * v;
      const double n[3] = {std::cos(a) * std::cos(b), std::sin(a) * std::cos(b), std::sin(b)};
      mesh.positions.insert(mesh.positions.end(), {static_cast<float>(R * std::cos(a) + r * n[0]), static_cast<float>(R * std::sin(a) + r * n[1]),
                                                   static_cast<float>(r * n[2])});
      mesh.normals.insert(mesh.normals.end(), {static_cast<float>(n[0]), static_cast<float>(n[1]), static_cast<float>(n[2])});
      mesh.uvs.insert(mesh.uvs.end(), {static_cast<float>(u), static_cast<float>(v)});
    }
  }
  for (int i = 0; i < rings; ++i) {
    for (int j = 0; j < sides; ++j) {
      const std::uint32_t a = i * (sides + 1) + j, b = a + sides + 1;
      mesh.indices.insert(mesh.indices.end(), {a, b, b + 1, a, b + 1, a + 1});
    }
  }
  return mesh;
}

GridMesh makeSphere(int slices, int stacks, bool exactPoles) {
  GridMesh mesh;
  for (int j = 0; j <= stacks; ++j) {
    const double v = double(j) / stacks, theta = v * kPi;
    const bool pole = j == 0 || j == stacks;
    const double sinTheta = pole && exactPoles ? 0.0 : std::sin(theta);
    for (int i = 0; i <= slices; ++i) {
      const double u = double(i) / slices, phi = u * 2 * kPi;
      const double n[3] = {sinTheta * std::cos(phi), sinTheta * std::sin(phi), std::cos(theta)};
      for (int k = 0; k < 3; ++k) {
        mesh.positions.push_back(static_cast<float>(n[k]));
        mesh.normals.push_back(static_cast<float>(n[k]));
      }
      mesh.uvs.insert(mesh.uvs.end(), {static_cast<float>(u), static_cast<float>(v)});
    }
  }
  for (int j = 0; j < stacks; ++j) {
    for (int i = 0; i < slices; ++i) {
      const std::uint32_t a = j * (slices + 1) + i, b = a + slices + 1;
      // Counter-clockwise seen from outside (j runs from the north pole down, i eastward: a,
      // b below it, a + 1 east of it), so glTF's front faces agree with the normals. Pole rows
      // keep their zero-area triangles on purpose: they are the stiff case.
      mesh.indices.insert(mesh.indices.end(), {a, b, a + 1, a + 1, b, b + 1});
    }
  }
  return mesh;
}

GridMesh reverseWinding(GridMesh mesh, int every) {
  for (std::size_t t = 0; t < mesh.indices.size() / 3; t += static_cast<std::size_t>(every))
    std::swap(mesh.indices[3 * t + 1], mesh.indices[3 * t + 2]);
  return mesh;
}

ShuffledMesh shuffleFacesAndRotateCorners(const GridMesh& mesh, unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<std::size_t> order(mesh.indices.size() / 3);
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::shuffle(order.begin(), order.end(), rng);
  ShuffledMesh shuffled{mesh, std::vector<std::size_t>(mesh.indices.size())};
  for (std::size_t i = 0; i < order.size(); ++i) {
    const int rotation = static_cast<int>(rng() % 3);
    for (int k = 0; k < 3; ++k) {
      const std::size_t original = 3 * order[i] + (k + rotation) % 3;
      shuffled.mesh.indices[3 * i + k] = mesh.indices[original];
      shuffled.originalCorner[3 * i + k] = original;
    }
  }
  return shuffled;
}

std::vector<TestAsset> makeTestAssets() {
  return {interleaved(), quantized(), sparse(), stripsAndFans(), morphTargets(), secondUvSet(), documentFeatures(), manySplits(),
          noNormals()};
}

TestAsset meshAsset(const std::string& name, const GridMesh& mesh, bool withNormal) {
  Builder b(name);
  Json primitive = b.basicPrimitive(mesh);
  if (!withNormal) primitive["attributes"].erase("NORMAL");
  b.addMesh(Json::array({primitive}), name);
  return b.take();
}

std::filesystem::path writeAsset(const TestAsset& asset, const std::filesystem::path& dir, bool glb) {
  std::filesystem::create_directories(dir);
  nlohmann::ordered_json doc = asset.json;
  if (glb) {
    const std::string json = doc.dump();
    const std::size_t jsonPadded = (json.size() + 3) & ~std::size_t(3);
    const std::size_t binPadded = (asset.bin.size() + 3) & ~std::size_t(3);
    const std::uint32_t header[5] = {0x46546C67, 2, static_cast<std::uint32_t>(12 + 8 + jsonPadded + 8 + binPadded),
                                     static_cast<std::uint32_t>(jsonPadded), 0x4E4F534A};
    const auto path = dir / (asset.name + ".glb");
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(header), sizeof header);
    out << json << std::string(jsonPadded - json.size(), ' ');
    const std::uint32_t binHeader[2] = {static_cast<std::uint32_t>(binPadded), 0x004E4942};
    out.write(reinterpret_cast<const char*>(binHeader), sizeof binHeader);
    out.write(reinterpret_cast<const char*>(asset.bin.data()), static_cast<std::streamsize>(asset.bin.size()));
    out << std::string(binPadded - asset.bin.size(), '\0');
    return path;
  }
  doc["buffers"][0]["uri"] = asset.name + ".bin";
  std::ofstream(dir / (asset.name + ".bin"), std::ios::binary)
      .write(reinterpret_cast<const char*>(asset.bin.data()), static_cast<std::streamsize>(asset.bin.size()));
  const auto path = dir / (asset.name + ".gltf");
  std::ofstream(path) << doc.dump(2) << "\n";
  return path;
}

}  // namespace tangent::testing
