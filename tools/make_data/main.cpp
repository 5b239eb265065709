// SPDX-License-Identifier: MIT
// Generates the bundled demo asset in data/demo/: a UV sphere, two quads with a mirrored UV
// island, and a ground plane without a normal map, plus the bump normal map they use; the
// viewer's demo scene and primitives. On request (not committed): a skinned and a morphing
// asset, animated, for the README's images, a textured sphere for benchmarks, and the material
// scenes whose features read the tangent frame (anisotropy, clearcoat) or COLOR_0.
// Usage: tangent-make-data OUT_DIR | --animated OUT_DIR | --materials OUT_DIR | --sphere N OUT_DIR [--one-primitive]
#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include "tangent/tangent.hpp"
#include <algorithm>
#include <cstdlib>
#include <numbers>
#include <utility>
#include <vector>

namespace {

using Json = nlohmann::ordered_json;

struct MeshData {
  std::vector<float> positions, normals, uvs;
  std::vector<std::uint16_t> indices;
  std::vector<std::uint32_t> indices32;  // used instead of `indices` when not empty (large meshes)
  std::vector<float> tangents;  // TANGENT (4 per vertex) when not empty
};

MeshData uvSphere(int slices, int stacks, float radius) {
  MeshData mesh;
  for (int j = 0; j <= stacks; ++j) {
    const double v = double(j) / stacks, theta = v * std::numbers::pi;
    for (int i = 0; i <= slices; ++i) {
      const double u = double(i) / slices, phi = u * 2 * std::numbers::pi;
      const double n[3] = {std::sin(theta) * std::cos(phi), std::cos(theta), -std::sin(theta) * std::sin(phi)};
      for (int k = 0; k < 3; ++k) {
        mesh.positions.push_back(static_cast<float>(radius * n[k]));
        mesh.normals.push_back(static_cast<float>(n[k]));
      }
      mesh.uvs.push_back(static_cast<float>(u * 2));  // the map tiles twice around
      mesh.uvs.push_back(static_cast<float>(v));
    }
  }
  for (int j = 0; j < stacks; ++j) {
    for (int i = 0; i < slices; ++i) {
      const auto a = static_cast<std::uint16_t>(j * (slices + 1) + i), b = static_cast<std::uint16_t>(a + slices + 1);
      if (j != 0) mesh.indices.insert(mesh.indices.end(), {a, b, static_cast<std::uint16_t>(a + 1)});
      if (j != stacks - 1) mesh.indices.insert(mesh.indices.end(), {static_cast<std::uint16_t>(a + 1), b, static_cast<std::uint16_t>(b + 1)});
    }
  }
  return mesh;
}

// Two unit quads side by side facing +z; the right one's UVs mirror the left one's in u.
MeshData mirroredQuads() {
  MeshData mesh;
  const float xs[3] = {-1, 0, 1};
  const float us[3] = {0, 1, 0};
  for (int row = 0; row < 2; ++row) {
    for (int col = 0; col < 3; ++col) {
      mesh.positions.insert(mesh.positions.end(), {xs[col], static_cast<float>(row) - 0.5f, 0});
      mesh.normals.insert(mesh.normals.end(), {0, 0, 1});
      mesh.uvs.insert(mesh.uvs.end(), {us[col], static_cast<float>(1 - row)});
    }
  }
  mesh.indices = {0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 4};
  return mesh;
}

MeshData plane(float halfSize, float y) {
  MeshData mesh;
  mesh.positions = {-halfSize, y, halfSize, halfSize, y, halfSize, halfSize, y, -halfSize, -halfSize, y, -halfSize};
  mesh.normals = {0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0};
  mesh.uvs = {0, 4, 4, 4, 4, 0, 0, 0};
  mesh.indices = {0, 1, 2, 0, 2, 3};
  return mesh;
}

// Tangent-space normal map of circular raised bumps (OpenGL convention, +y up, as glTF wants).
bool writeBumpNormalMap(const std::filesystem::path& path, int size, int bumpsPerSide) {
  std::vector<unsigned char> pixels(static_cast<std::size_t>(size) * size * 3);
  const double cell = double(size) / bumpsPerSide, radius = cell * 0.35;
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const double cx = std::fmod(x + 0.5, cell) - cell / 2;
      const double cy = -(std::fmod(y + 0.5, cell) - cell / 2);  // image rows go down, +y is up
      const double r = std::hypot(cx, cy);
      double n[3] = {0, 0, 1};
      if (r < radius) {
        // Height h = sqrt(R^2 - r^2) scaled; normal = normalize(-dh/dx, -dh/dy, 1).
        const double h = std::sqrt(radius * radius - r * r) + 1e-6;
        const double slope = 0.6;
        n[0] = slope * cx / h;
        n[1] = slope * cy / h;
        const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + 1);
        for (double& c : n) c /= length;
      }
      for (int k = 0; k < 3; ++k)
        pixels[(static_cast<std::size_t>(y) * size + x) * 3 + k] = static_cast<unsigned char>(std::lround((n[k] * 0.5 + 0.5) * 255));
    }
  }
  auto out = OIIO::ImageOutput::create(path.string());
  if (!out) return false;
  OIIO::ImageSpec spec(size, size, 3, OIIO::TypeDesc::UINT8);
  if (!out->open(path.string(), spec)) return false;
  const bool ok = out->write_image(OIIO::TypeDesc::UINT8, pixels.data());
  return out->close() && ok;
}


MeshData cube(float half) {
  // 24 vertices: 4 per face, u along the face's first edge, outward winding.
  MeshData mesh;
  const int axes[6][3] = {{0, 1, 2}, {0, 1, 2}, {2, 1, 0}, {2, 1, 0}, {0, 2, 1}, {0, 2, 1}};
  const float sides[6] = {1, -1, -1, 1, -1, 1};
  for (int f = 0; f < 6; ++f) {
    const int ua = axes[f][0], va = axes[f][1], na = axes[f][2];
    const float side = sides[f];
    const auto base = static_cast<std::uint16_t>(mesh.positions.size() / 3);
    const float corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (const auto& c : corners) {
      float p[3] = {0, 0, 0}, n[3] = {0, 0, 0};
      p[ua] = c[0] * half * side * (f >= 4 ? -1.0f : 1.0f);
      p[va] = c[1] * half;
      p[na] = half * side;
      n[na] = side;
      mesh.positions.insert(mesh.positions.end(), p, p + 3);
      mesh.normals.insert(mesh.normals.end(), n, n + 3);
      mesh.uvs.insert(mesh.uvs.end(), {(c[0] + 1) / 2, (1 - c[1]) / 2});
    }
    // Wind counter-clockwise as seen from outside: flip when the (u, v, n) basis is left-handed.
    float pu[3] = {0, 0, 0}, pv[3] = {0, 0, 0}, pn[3] = {0, 0, 0};
    pu[ua] = side * (f >= 4 ? -1.0f : 1.0f);
    pv[va] = 1;
    pn[na] = side;
    const float handed = (pu[1] * pv[2] - pu[2] * pv[1]) * pn[0] + (pu[2] * pv[0] - pu[0] * pv[2]) * pn[1] + (pu[0] * pv[1] - pu[1] * pv[0]) * pn[2];
    if (handed > 0) mesh.indices.insert(mesh.indices.end(), {base, static_cast<std::uint16_t>(base + 1), static_cast<std::uint16_t>(base + 2), base, static_cast<std::uint16_t>(base + 2), static_cast<std::uint16_t>(base + 3)});
    else mesh.indices.insert(mesh.indices.end(), {base, static_cast<std::uint16_t>(base + 2), static_cast<std::uint16_t>(base + 1), base, static_cast<std::uint16_t>(base + 3), static_cast<std::uint16_t>(base + 2)});
  }
  return mesh;
}

MeshData torus(int rings, int sides, float major, float minor) {
  MeshData mesh;
  for (int i = 0; i <= rings; ++i) {
    for (int j = 0; j <= sides; ++j) {
      const double a = 2 * std::numbers::pi * i / rings, b = 2 * std::numbers::pi * j / sides;
      const double n[3] = {std::cos(a) * std::cos(b), std::sin(b), -std::sin(a) * std::cos(b)};
      mesh.positions.insert(mesh.positions.end(), {static_cast<float>(major * std::cos(a) + minor * n[0]), static_cast<float>(minor * n[1]),
                                                   static_cast<float>(-major * std::sin(a) + minor * n[2])});
      mesh.normals.insert(mesh.normals.end(), {static_cast<float>(n[0]), static_cast<float>(n[1]), static_cast<float>(n[2])});
      mesh.uvs.insert(mesh.uvs.end(), {static_cast<float>(3.0 * i / rings), static_cast<float>(1.0 * j / sides)});
    }
  }
  for (int i = 0; i < rings; ++i) {
    for (int j = 0; j < sides; ++j) {
      const auto a = static_cast<std::uint16_t>(i * (sides + 1) + j), b = static_cast<std::uint16_t>(a + sides + 1);
      // Counter-clockwise seen from outside, as the normals point (glTF: front faces CCW).
      mesh.indices.insert(mesh.indices.end(), {a, b, static_cast<std::uint16_t>(a + 1), static_cast<std::uint16_t>(a + 1), b, static_cast<std::uint16_t>(b + 1)});
    }
  }
  return mesh;
}

// A cylinder of `radius` along +y from 0 to `height`, rings every `height / (rings - 1)`, open at
// both ends; u goes twice around, v once per unit of height. Rings from the top down, wound
// as uvSphere's (counter-clockwise seen from outside).
MeshData cylinder(int rings, int sides, float radius, float height) {
  MeshData mesh;
  for (int j = 0; j < rings; ++j) {
    const double y = height * (1.0 - double(j) / (rings - 1));
    for (int i = 0; i <= sides; ++i) {
      const double a = 2 * std::numbers::pi * i / sides;
      mesh.positions.insert(mesh.positions.end(), {static_cast<float>(radius * std::cos(a)), static_cast<float>(y), static_cast<float>(-radius * std::sin(a))});
      mesh.normals.insert(mesh.normals.end(), {static_cast<float>(std::cos(a)), 0.0f, static_cast<float>(-std::sin(a))});
      mesh.uvs.insert(mesh.uvs.end(), {static_cast<float>(2.0 * i / sides), static_cast<float>(height - y)});
    }
  }
  for (int j = 0; j + 1 < rings; ++j) {
    for (int i = 0; i < sides; ++i) {
      const auto a = static_cast<std::uint16_t>(j * (sides + 1) + i), b = static_cast<std::uint16_t>(a + sides + 1);
      mesh.indices.insert(mesh.indices.end(), {a, b, static_cast<std::uint16_t>(a + 1), static_cast<std::uint16_t>(a + 1), b, static_cast<std::uint16_t>(b + 1)});
    }
  }
  return mesh;
}

// A grid over [-1, 1]^2 at z = 0 facing +z, `segments` squares a side; the map tiles twice.
MeshData grid(int segments) {
  MeshData mesh;
  for (int j = 0; j <= segments; ++j) {
    for (int i = 0; i <= segments; ++i) {
      const float x = -1.0f + 2.0f * i / segments, y = 1.0f - 2.0f * j / segments;
      mesh.positions.insert(mesh.positions.end(), {x, y, 0.0f});
      mesh.normals.insert(mesh.normals.end(), {0.0f, 0.0f, 1.0f});
      mesh.uvs.insert(mesh.uvs.end(), {x + 1, 1 - y});
    }
  }
  for (int j = 0; j < segments; ++j) {
    for (int i = 0; i < segments; ++i) {
      const auto a = static_cast<std::uint16_t>(j * (segments + 1) + i), b = static_cast<std::uint16_t>(a + segments + 1);
      mesh.indices.insert(mesh.indices.end(), {a, b, static_cast<std::uint16_t>(a + 1), static_cast<std::uint16_t>(a + 1), b, static_cast<std::uint16_t>(b + 1)});
    }
  }
  return mesh;
}

MeshData quad(float half) {
  MeshData mesh;
  mesh.positions = {-half, -half, 0, half, -half, 0, half, half, 0, -half, half, 0};
  mesh.normals = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
  mesh.uvs = {0, 1, 1, 1, 1, 0, 0, 0};
  mesh.indices = {0, 1, 2, 0, 2, 3};
  return mesh;
}

bool writeImage(const std::filesystem::path& path, int width, int height, int channels, const std::vector<unsigned char>& pixels) {
  auto out = OIIO::ImageOutput::create(path.string());
  if (!out) return false;
  OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::UINT8);
  if (!out->open(path.string(), spec)) return false;
  const bool ok = out->write_image(OIIO::TypeDesc::UINT8, pixels.data());
  return out->close() && ok;
}

// Specular map with green, white and black regions (RGB: highlight colour, A: strength).
bool writeSpecularRegions(const std::filesystem::path& path, int size) {
  std::vector<unsigned char> pixels(static_cast<std::size_t>(size) * size * 4);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const int region = (x * 3) / size;  // vertical bands: green, white, black
      const unsigned char colors[3][3] = {{40, 255, 60}, {255, 255, 255}, {0, 0, 0}};
      unsigned char* p = &pixels[(static_cast<std::size_t>(y) * size + x) * 4];
      for (int c = 0; c < 3; ++c) p[c] = colors[region][c];
      p[3] = region == 2 ? 0 : 255;
    }
  }
  return writeImage(path, size, size, 4, pixels);
}

bool writeWhite(const std::filesystem::path& path) { return writeImage(path, 4, 4, 3, std::vector<unsigned char>(4 * 4 * 3, 255)); }

// Sphere map: a sky gradient over a darker ground with a bright sun, as seen in a mirror ball.
bool writeSphereMap(const std::filesystem::path& path, int size) {
  std::vector<unsigned char> pixels(static_cast<std::size_t>(size) * size * 3);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const double sx = (x + 0.5) / size * 2 - 1, sy = 1 - (y + 0.5) / size * 2;
      const double r2 = sx * sx + sy * sy;
      double color[3] = {0.1, 0.1, 0.12};
      if (r2 <= 1) {
        const double up = sy;  // reflection's up component grows with image height
        const double sky = std::clamp(up * 0.5 + 0.5, 0.0, 1.0);
        color[0] = 0.35 + 0.25 * sky;
        color[1] = 0.35 + 0.35 * sky;
        color[2] = 0.40 + 0.55 * sky;
        if (up < 0) color[0] = color[1] = color[2] = 0.25 + 0.1 * (1 + up);
        const double sun = std::exp(-((sx - 0.35) * (sx - 0.35) + (sy - 0.45) * (sy - 0.45)) * 60);
        for (double& c : color) c = std::min(1.0, c + sun);
      }
      for (int c = 0; c < 3; ++c) pixels[(static_cast<std::size_t>(y) * size + x) * 3 + c] = static_cast<unsigned char>(std::lround(color[c] * 255));
    }
  }
  return writeImage(path, size, size, 3, pixels);
}

// Where the demo scene's sun shines: down and across, so that from the default (iso) camera
// the spheres are lit and their shadows fall beside them. The viewer test predicts the shadow.
constexpr double kSunDirection[3] = {0.7, -0.6, -0.3};

// Accumulates meshes, nodes and buffer data of one glTF document, written as .gltf + .bin.
class DocumentWriter {
 public:
  struct Placement {
    std::string name;
    float translation[3] = {0, 0, 0};
  };

  // Adds a mesh with POSITION, NORMAL, TEXCOORD_0 and uint16 (or uint32) indices, and a node for it.
  void addMesh(const MeshData& mesh, const std::string& name, int material, const float (&translation)[3]) {
    const std::size_t n = mesh.positions.size() / 3;
    float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
      lo[i % 3] = std::min(lo[i % 3], mesh.positions[i]);
      hi[i % 3] = std::max(hi[i % 3], mesh.positions[i]);
    }
    const std::size_t first = accessors_.size();
    accessors_.push_back({{"bufferView", addView(mesh.positions.data(), n * 12, 34962)}, {"componentType", 5126}, {"count", n},
                          {"type", "VEC3"}, {"min", {lo[0], lo[1], lo[2]}}, {"max", {hi[0], hi[1], hi[2]}}});
    accessors_.push_back({{"bufferView", addView(mesh.normals.data(), n * 12, 34962)}, {"componentType", 5126}, {"count", n}, {"type", "VEC3"}});
    accessors_.push_back({{"bufferView", addView(mesh.uvs.data(), n * 8, 34962)}, {"componentType", 5126}, {"count", n}, {"type", "VEC2"}});
    if (mesh.indices32.empty())
      accessors_.push_back({{"bufferView", addView(mesh.indices.data(), mesh.indices.size() * 2, 34963)}, {"componentType", 5123},
                            {"count", mesh.indices.size()}, {"type", "SCALAR"}});
    else
      accessors_.push_back({{"bufferView", addView(mesh.indices32.data(), mesh.indices32.size() * 4, 34963)}, {"componentType", 5125},
                            {"count", mesh.indices32.size()}, {"type", "SCALAR"}});
    Json primitive = Json::object();
    primitive["attributes"] = {{"POSITION", first}, {"NORMAL", first + 1}, {"TEXCOORD_0", first + 2}};
    primitive["indices"] = first + 3;
    if (!mesh.tangents.empty())
      primitive["attributes"]["TANGENT"] = addAccessor(mesh.tangents.data(), mesh.tangents.size() / 4, 5126, "VEC4", 34962);
    primitive["material"] = material;
    meshes_.push_back({{"name", name}, {"primitives", Json::array({primitive})}});
    Json node = {{"name", name}, {"mesh", meshes_.size() - 1}};
    if (translation[0] != 0 || translation[1] != 0 || translation[2] != 0) node["translation"] = {translation[0], translation[1], translation[2]};
    nodes_.push_back(node);
  }
  void addNode(Json node) { nodes_.push_back(std::move(node)); }
  Json& node(std::size_t index) { return nodes_[index]; }
  Json& accessor(std::size_t index) { return accessors_[index]; }
  // The primitive of the mesh added last, to give more attributes or morph targets.
  Json& lastPrimitive() { return meshes_.back()["primitives"][0]; }
  Json& lastMesh() { return meshes_.back(); }
  // An accessor over `count` elements of `type` (SCALAR, VEC3, ...) of float (5126), unsigned
  // short (5123) or unsigned byte (5121) components; its index.
  std::size_t addAccessor(const void* data, std::size_t count, int componentType, const std::string& type, int target = 0) {
    const int components = type == "SCALAR" ? 1 : type == "MAT4" ? 16 : type.back() - '0';
    const std::size_t bytes = count * components * (componentType == 5126 ? 4 : componentType == 5121 ? 1 : 2);
    const std::size_t view = target ? addView(data, bytes, target) : addView(data, bytes);
    accessors_.push_back({{"bufferView", view}, {"componentType", componentType}, {"count", count}, {"type", type}});
    if (type == "SCALAR" && componentType == 5126 && count > 0) {  // animation inputs need min and max
      const auto* values = static_cast<const float*>(data);
      accessors_.back()["min"] = {*std::min_element(values, values + count)};
      accessors_.back()["max"] = {*std::max_element(values, values + count)};
    }
    return accessors_.size() - 1;
  }

  // Writes dir/stem.gltf and dir/stem.bin; `extra` holds materials, textures and the rest.
  void write(const std::filesystem::path& dir, const std::string& stem, Json extra) const {
    std::vector<std::uint8_t> bin = bin_;
    while (bin.size() % 4) bin.push_back(0);
    // The scene's roots: every node that is no other node's child.
    std::vector<bool> isChild(nodes_.size(), false);
    for (const Json& node : nodes_)
      if (node.contains("children"))
        for (const Json& child : node["children"]) isChild[child.get<std::size_t>()] = true;
    Json sceneNodes = Json::array();
    for (std::size_t i = 0; i < nodes_.size(); ++i)
      if (!isChild[i]) sceneNodes.push_back(i);
    Json doc = {{"asset", {{"version", "2.0"}, {"generator", "libtangent tangent-make-data"}, {"copyright", "libtangent authors, CC0"}}}};
    if (extra.contains("extensionsUsed")) doc["extensionsUsed"] = extra["extensionsUsed"];
    doc["scene"] = 0;
    doc["scenes"] = {{{"name", stem}, {"nodes", sceneNodes}}};
    doc["nodes"] = nodes_;
    doc["meshes"] = meshes_;
    for (auto& [key, value] : extra.items()) {
      if (key != "extensionsUsed") doc[key] = value;
    }
    doc["accessors"] = accessors_;
    doc["bufferViews"] = views_;
    doc["buffers"] = {{{"uri", stem + ".bin"}, {"byteLength", bin.size()}}};
    std::ofstream(dir / (stem + ".bin"), std::ios::binary).write(reinterpret_cast<const char*>(bin.data()), static_cast<std::streamsize>(bin.size()));
    std::ofstream(dir / (stem + ".gltf")) << doc.dump(2) << "\n";
  }

 private:
  std::size_t addView(const void* data, std::size_t bytes, int target = 0) {
    while (bin_.size() % 4) bin_.push_back(0);
    views_.push_back({{"buffer", 0}, {"byteOffset", bin_.size()}, {"byteLength", bytes}});
    if (target) views_.back()["target"] = target;
    const auto* p = static_cast<const std::uint8_t*>(data);
    bin_.insert(bin_.end(), p, p + bytes);
    return views_.size() - 1;
  }

  std::vector<std::uint8_t> bin_;
  Json accessors_ = Json::array(), views_ = Json::array(), meshes_ = Json::array(), nodes_ = Json::array();
};

// Materials and textures shared by the scene and the primitives; image URIs relative to
// `imagePrefix` ("" or "../").
Json sharedMaterials(const std::string& imagePrefix) {
  Json specular = {{"specularFactor", 1.0}, {"specularTexture", {{"index", 2}}}, {"specularColorTexture", {{"index", 2}}}};
  return {
      {"extensionsUsed", {"KHR_materials_specular", "KHR_lights_punctual"}},
      {"materials",
       {{{"name", "BumpsSpecular"},
         // Mid grey over the white texture: room above the diffuse for the highlights to show.
         {"pbrMetallicRoughness", {{"baseColorFactor", {0.55, 0.55, 0.55, 1.0}}, {"baseColorTexture", {{"index", 1}}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.35}}},
         {"normalTexture", {{"index", 0}}},
         {"extensions", {{"KHR_materials_specular", specular}}}},
        {{"name", "Ground"},
         {"pbrMetallicRoughness", {{"baseColorFactor", {0.85, 0.85, 0.85, 1}}, {"baseColorTexture", {{"index", 1}}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.9}}}}}},
      {"textures", {{{"source", 0}, {"sampler", 0}}, {{"source", 1}, {"sampler", 0}}, {{"source", 2}, {"sampler", 0}}}},
      {"samplers", {{{"magFilter", 9729}, {"minFilter", 9987}, {"wrapS", 10497}, {"wrapT", 10497}}}},
      {"images",
       {{{"uri", imagePrefix + "bumps_normal.png"}, {"mimeType", "image/png"}},
        {{"uri", imagePrefix + "white.png"}, {"mimeType", "image/png"}},
        {{"uri", imagePrefix + "specular_regions.png"}, {"mimeType", "image/png"}}}}};
}

// An animation of one LINEAR sampler driving `path` of `node`.
Json animation(const std::string& name, std::size_t input, std::size_t output, int node, const std::string& path) {
  Json sampler = {{"input", input}, {"output", output}, {"interpolation", "LINEAR"}};
  Json target = {{"node", node}, {"path", path}};
  Json channel = {{"sampler", 0}, {"target", target}};
  return {{"name", name}, {"samplers", Json::array({sampler})}, {"channels", Json::array({channel})}};
}

// The material of the skinned and morphing assets: the bump normal map on a light grey.
Json bumpsOnly() {
  return {{"materials", {{{"name", "Bumps"},
                          {"pbrMetallicRoughness", {{"baseColorFactor", {0.8, 0.8, 0.8, 1}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.5}}},
                          {"normalTexture", {{"index", 0}}}}}},
          {"textures", {{{"source", 0}, {"sampler", 0}}}},
          {"samplers", {{{"magFilter", 9729}, {"minFilter", 9987}, {"wrapS", 10497}, {"wrapT", 10497}}}},
          {"images", {{{"uri", "bumps_normal.png"}, {"mimeType", "image/png"}}}}};
}

// skinned.gltf: a normal-mapped cylinder (radius 0.35, 2 high) skinned to two joints, Root at
// the origin and Bend at y = 1 (its child), blended linearly from y = 0.8 to 1.2; the animation
// "bend" turns Bend 90 degrees about z at 1 s and back at 2 s (LINEAR). No TANGENT: bake adds it.
void writeSkinned(const std::filesystem::path& dir) {
  DocumentWriter writer;
  const MeshData mesh = cylinder(21, 32, 0.35f, 2.0f);
  const float origin[3] = {0, 0, 0};
  writer.addMesh(mesh, "Cylinder", 0, origin);
  const std::size_t vertices = mesh.positions.size() / 3;
  std::vector<std::uint16_t> joints;
  std::vector<float> weights;
  for (std::size_t v = 0; v < vertices; ++v) {
    const float bend = std::clamp((mesh.positions[3 * v + 1] - 0.8f) / 0.4f, 0.0f, 1.0f);
    // A joint of weight 0 is given as 0 (the validator's ACCESSOR_JOINTS_USED_ZERO_WEIGHT).
    joints.insert(joints.end(), {0, static_cast<std::uint16_t>(bend > 0 ? 1 : 0), 0, 0});
    weights.insert(weights.end(), {1 - bend, bend, 0, 0});
  }
  writer.lastPrimitive()["attributes"]["JOINTS_0"] = writer.addAccessor(joints.data(), vertices, 5123, "VEC4", 34962);
  writer.lastPrimitive()["attributes"]["WEIGHTS_0"] = writer.addAccessor(weights.data(), vertices, 5126, "VEC4", 34962);
  writer.node(0)["skin"] = 0;
  writer.addNode({{"name", "Root"}, {"children", {2}}});
  writer.addNode({{"name", "Bend"}, {"translation", {0.0, 1.0, 0.0}}});
  // Inverse bind matrices (column-major): the joints' world transforms at rest undone.
  const float inverseBind[32] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1};
  const std::size_t bindMatrices = writer.addAccessor(inverseBind, 2, 5126, "MAT4");
  const float times[3] = {0, 1, 2};
  const float h = static_cast<float>(std::sqrt(0.5));
  const float rotations[12] = {0, 0, 0, 1, 0, 0, h, h, 0, 0, 0, 1};
  const std::size_t input = writer.addAccessor(times, 3, 5126, "SCALAR"), output = writer.addAccessor(rotations, 3, 5126, "VEC4");
  Json extra = bumpsOnly();
  extra["skins"] = {{{"joints", {1, 2}}, {"skeleton", 1}, {"inverseBindMatrices", bindMatrices}}};
  extra["animations"] = Json::array({animation("bend", input, output, 2, "rotation")});
  writer.write(dir, "skinned", extra);
}

// morphing.gltf: a normal-mapped 2 x 2 grid facing +z with one morph target that bends it about
// the y axis into an arc of 135 degrees (radius 2 / (0.75 pi), its width kept), POSITION and
// NORMAL deltas analytic; the animation "bend" takes the weight from 0 to 1 at 1 s and back at
// 2 s (LINEAR). No TANGENT: bake adds it and its deltas.
void writeMorphing(const std::filesystem::path& dir) {
  DocumentWriter writer;
  const MeshData mesh = grid(24);
  const float origin[3] = {0, 0, 0};
  writer.addMesh(mesh, "Sheet", 0, origin);
  const std::size_t vertices = mesh.positions.size() / 3;
  const double radius = 2.0 / (0.75 * std::numbers::pi);
  std::vector<float> positionDeltas, normalDeltas;
  for (std::size_t v = 0; v < vertices; ++v) {
    const double x = mesh.positions[3 * v], angle = x / radius;
    positionDeltas.insert(positionDeltas.end(), {static_cast<float>(radius * std::sin(angle) - x), 0.0f, static_cast<float>(radius * std::cos(angle) - radius)});
    normalDeltas.insert(normalDeltas.end(), {static_cast<float>(std::sin(angle)), 0.0f, static_cast<float>(std::cos(angle) - 1)});
  }
  const std::size_t positions = writer.addAccessor(positionDeltas.data(), vertices, 5126, "VEC3", 34962);
  // A POSITION morph target needs its bounds (glTF 2.0 3.7.2.2).
  float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
  for (std::size_t i = 0; i < positionDeltas.size(); ++i) lo[i % 3] = std::min(lo[i % 3], positionDeltas[i]), hi[i % 3] = std::max(hi[i % 3], positionDeltas[i]);
  writer.accessor(positions)["min"] = {lo[0], lo[1], lo[2]};
  writer.accessor(positions)["max"] = {hi[0], hi[1], hi[2]};
  writer.lastPrimitive()["targets"] = {{{"POSITION", positions}, {"NORMAL", writer.addAccessor(normalDeltas.data(), vertices, 5126, "VEC3", 34962)}}};
  writer.lastMesh()["weights"] = {0.0};
  const float times[3] = {0, 1, 2}, weights[3] = {0, 1, 0};
  const std::size_t input = writer.addAccessor(times, 3, 5126, "SCALAR"), output = writer.addAccessor(weights, 3, 5126, "SCALAR");
  Json extra = bumpsOnly();
  extra["animations"] = Json::array({animation("bend", input, output, 0, "weights")});
  writer.write(dir, "morphing", extra);
}


// anisotropy_direction.png: KHR_materials_anisotropy's direction texture for a disc whose UVs
// map [-1, 1]^2 onto the image (u = (x + 1) / 2, v = (1 - y) / 2): circular brushing, the
// direction turning around the centre (RG: the direction in (tangent, bitangent) space mapped
// from [-1, 1], B: strength, fading to half towards the centre where the circles are tight).
bool writeCircularDirections(const std::filesystem::path& path, int size) {
  std::vector<unsigned char> pixels(static_cast<std::size_t>(size) * size * 3);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      // Tangent space: T = +u = +x, B = up in the image (-v) = +y.
      const double px = (x + 0.5) / size * 2 - 1, py = 1 - (y + 0.5) / size * 2;
      const double r = std::hypot(px, py);
      const double dx = r > 1e-6 ? -py / r : 1, dy = r > 1e-6 ? px / r : 0;  // counter-clockwise around the centre
      unsigned char* p = &pixels[(static_cast<std::size_t>(y) * size + x) * 3];
      p[0] = static_cast<unsigned char>(std::lround((dx * 0.5 + 0.5) * 255));
      p[1] = static_cast<unsigned char>(std::lround((dy * 0.5 + 0.5) * 255));
      p[2] = static_cast<unsigned char>(std::lround(std::clamp(0.5 + r, 0.5, 1.0) * 255));
    }
  }
  return writeImage(path, size, size, 3, pixels);
}

// A disc of `radius` at z = 0 facing +z, in `rings` rings of `segments` quads around a centre
// fan; UVs map [-radius, radius]^2 to [0, 1]^2 (v down, as glTF's images).
MeshData disc(int rings, int segments, float radius) {
  MeshData mesh;
  auto vertex = [&](double x, double y) {
    mesh.positions.insert(mesh.positions.end(), {static_cast<float>(x), static_cast<float>(y), 0.0f});
    mesh.normals.insert(mesh.normals.end(), {0.0f, 0.0f, 1.0f});
    mesh.uvs.insert(mesh.uvs.end(), {static_cast<float>((x / radius + 1) / 2), static_cast<float>((1 - y / radius) / 2)});
    // T along +u (+x); B = cross(N, T) * w = +y, towards the image's top (-v): w = +1.
    mesh.tangents.insert(mesh.tangents.end(), {1.0f, 0.0f, 0.0f, 1.0f});
  };
  vertex(0, 0);
  for (int ring = 1; ring <= rings; ++ring)
    for (int i = 0; i < segments; ++i) {
      const double a = 2 * std::numbers::pi * i / segments, r = radius * ring / rings;
      vertex(r * std::cos(a), r * std::sin(a));
    }
  auto at = [&](int ring, int i) { return static_cast<std::uint16_t>(ring == 0 ? 0 : 1 + (ring - 1) * segments + (i % segments)); };
  for (int i = 0; i < segments; ++i) mesh.indices.insert(mesh.indices.end(), {at(0, 0), at(1, i), at(1, i + 1)});
  for (int ring = 1; ring < rings; ++ring)
    for (int i = 0; i < segments; ++i)
      mesh.indices.insert(mesh.indices.end(), {at(ring, i), at(ring + 1, i), at(ring + 1, i + 1), at(ring, i), at(ring + 1, i + 1), at(ring, i + 1)});
  return mesh;
}

// A directional light shining along `direction` (KHR_lights_punctual lights shine along their
// node's -z; the rotation turns -z onto it: q = normalize(1 + dot(a, b), cross(a, b))).
Json sunNode(const std::string& name, const double (&direction)[3]) {
  const double length = std::sqrt(direction[0] * direction[0] + direction[1] * direction[1] + direction[2] * direction[2]);
  const double d[3] = {direction[0] / length, direction[1] / length, direction[2] / length};
  double q[4] = {d[1], -d[0], 0.0, 1.0 - d[2]};  // x, y, z, w for a = (0, 0, -1)
  const double qLength = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  for (double& c : q) c /= qLength;
  return {{"name", name}, {"rotation", {q[0], q[1], q[2], q[3]}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}};
}

Json oneSun(double intensity) {
  Json lights = Json::object();
  lights["lights"] = Json::array({Json{{"name", "Sun"}, {"type", "directional"}, {"color", {1.0, 1.0, 1.0}}, {"intensity", intensity}}});
  return lights;
}

// The material scenes (--materials), each lit by one sun from near the front camera so that the
// highlights face the viewer (tangent-view --camera front):
// - anisotropy_disc.gltf: a brushed-metal disc (KHR_materials_anisotropy: strength 0.8, rotation
//   0.5 rad, a circular direction texture), no normal map: anisotropy alone reads the frame.
// - clearcoat_sphere.gltf: a rough red sphere under a smooth clearcoat (KHR_materials_clearcoat)
//   whose clearcoatNormalTexture (the bumps) samples TEXCOORD_1 through a rotated
//   KHR_texture_transform; no normalTexture.
// - vertex_colors.gltf: a grid whose COLOR_0 (normalized unsigned bytes, RGBA) shades from red
//   through green to blue across x, over a white base colour.
// With TANGENT where a consumer of the frame needs it (the validator asks for it): the disc's
// and the sphere's, written analytically; `tangent check` compares them with MikkTSpace's.
int writeMaterialScenes(const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  if (!writeBumpNormalMap(dir / "bumps_normal.png", 256, 4) || !writeCircularDirections(dir / "anisotropy_direction.png", 64)) {
    std::cerr << "tangent-make-data: cannot write the material textures: " << OIIO::geterror() << "\n";
    return 1;
  }
  const float origin[3] = {0, 0, 0};
  const double towardsScene[3] = {-0.2, -0.25, -1.0};  // from above and to the right of the front camera
  const Json sampler = {{"magFilter", 9729}, {"minFilter", 9987}, {"wrapS", 10497}, {"wrapT", 10497}};
  {
    DocumentWriter writer;
    writer.addMesh(disc(12, 96, 1.0f), "BrushedDisc", 0, origin);
    writer.addNode(sunNode("Sun", towardsScene));
    Json anisotropy = {{"anisotropyStrength", 0.8}, {"anisotropyRotation", 0.5}, {"anisotropyTexture", {{"index", 0}}}};
    Json extra = {
        {"extensionsUsed", {"KHR_materials_anisotropy", "KHR_lights_punctual"}},
        {"extensions", {{"KHR_lights_punctual", oneSun(3.0)}}},
        {"materials", {{{"name", "BrushedMetal"},
                        {"pbrMetallicRoughness", {{"baseColorFactor", {0.9, 0.9, 0.9, 1}}, {"metallicFactor", 1.0}, {"roughnessFactor", 0.35}}},
                        {"extensions", {{"KHR_materials_anisotropy", anisotropy}}}}}},
        {"textures", {{{"source", 0}, {"sampler", 0}}}},
        {"samplers", {sampler}},
        {"images", {{{"uri", "anisotropy_direction.png"}, {"mimeType", "image/png"}}}}};
    writer.write(dir, "anisotropy_disc", extra);
  }
  {
    DocumentWriter writer;
    MeshData sphere = uvSphere(64, 32, 1.0f);
    const double rotation = 0.6, scale = 3.0;  // the clearcoat normal texture's transform (uniform scale)
    // TANGENT as the clearcoat normal texture reads it: MikkTSpace (libtangent's default, what
    // `tangent bake` writes) on TEXCOORD_1 through its KHR_texture_transform (u' = c s u + s s v + o,
    // v' = -s s u + c s v, as tangent/primitive.cpp applies it). The sphere's corners of one
    // vertex share every input, so they get one tangent: the vertex's.
    {
      const double c = std::cos(rotation), s = std::sin(rotation);
      std::vector<float> uvs(sphere.uvs.size());
      for (std::size_t i = 0; i < uvs.size(); i += 2) {
        const double u = sphere.uvs[i] / 2, v = sphere.uvs[i + 1];  // TEXCOORD_1 (below)
        uvs[i] = static_cast<float>(scale * (c * u + s * v) + 0.1);
        uvs[i + 1] = static_cast<float>(scale * (-s * u + c * v));
      }
      const std::vector<std::uint32_t> indices(sphere.indices.begin(), sphere.indices.end());
      std::vector<float> corners(indices.size() * 4);
      tangent::computeCornerTangents({sphere.positions, sphere.normals, uvs, indices}, corners);
      // The pole copies no triangle uses keep any unit frame.
      for (std::size_t v = 0; v < sphere.positions.size() / 3; ++v) sphere.tangents.insert(sphere.tangents.end(), {1.0f, 0.0f, 0.0f, 1.0f});
      for (std::size_t corner = 0; corner < indices.size(); ++corner)
        std::copy_n(&corners[4 * corner], 4, &sphere.tangents[4 * indices[corner]]);
    }
    writer.addMesh(sphere, "CoatedSphere", 0, origin);
    // TEXCOORD_1: the sphere's UVs once around (TEXCOORD_0 goes twice), the transform tiles them.
    std::vector<float> uv1(sphere.uvs);
    for (std::size_t i = 0; i < uv1.size(); i += 2) uv1[i] *= 0.5f;
    writer.lastPrimitive()["attributes"]["TEXCOORD_1"] = writer.addAccessor(uv1.data(), uv1.size() / 2, 5126, "VEC2", 34962);
    writer.addNode(sunNode("Sun", towardsScene));
    Json transform = {{"rotation", rotation}, {"scale", {scale, scale}}, {"offset", {0.1, 0.0}}};
    Json clearcoat = {{"clearcoatFactor", 1.0},
                      {"clearcoatRoughnessFactor", 0.08},
                      {"clearcoatNormalTexture", {{"index", 0}, {"texCoord", 1}, {"scale", 0.8}, {"extensions", {{"KHR_texture_transform", transform}}}}}};
    Json extra = {
        {"extensionsUsed", {"KHR_materials_clearcoat", "KHR_texture_transform", "KHR_lights_punctual"}},
        {"extensions", {{"KHR_lights_punctual", oneSun(3.0)}}},
        {"materials", {{{"name", "CoatedPaint"},
                        {"pbrMetallicRoughness", {{"baseColorFactor", {0.7, 0.08, 0.05, 1}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.7}}},
                        {"extensions", {{"KHR_materials_clearcoat", clearcoat}}}}}},
        {"textures", {{{"source", 0}, {"sampler", 0}}}},
        {"samplers", {sampler}},
        {"images", {{{"uri", "bumps_normal.png"}, {"mimeType", "image/png"}}}}};
    writer.write(dir, "clearcoat_sphere", extra);
  }
  {
    DocumentWriter writer;
    const MeshData mesh = grid(16);
    writer.addMesh(mesh, "ColouredGrid", 0, origin);
    std::vector<std::uint8_t> colours;
    for (std::size_t v = 0; v < mesh.positions.size() / 3; ++v) {
      const double s = (mesh.positions[3 * v] + 1) / 2;  // 0 at x = -1, 1 at x = 1
      const double rgb[3] = {std::clamp(1 - 2 * s, 0.0, 1.0), 1 - std::abs(2 * s - 1), std::clamp(2 * s - 1, 0.0, 1.0)};
      for (double c : rgb) colours.push_back(static_cast<std::uint8_t>(std::lround(c * 255)));
      colours.push_back(255);
    }
    const std::size_t colour = writer.addAccessor(colours.data(), colours.size() / 4, 5121, "VEC4", 34962);
    writer.accessor(colour)["normalized"] = true;
    writer.lastPrimitive()["attributes"]["COLOR_0"] = colour;
    writer.addNode(sunNode("Sun", towardsScene));
    Json extra = {
        {"extensionsUsed", {"KHR_lights_punctual"}},
        {"extensions", {{"KHR_lights_punctual", oneSun(3.0)}}},
        {"materials", {{{"name", "VertexColoured"},
                        {"pbrMetallicRoughness", {{"baseColorFactor", {1, 1, 1, 1}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.8}}}}}}};
    writer.write(dir, "vertex_colors", extra);
  }
  std::cout << "wrote " << dir.string() << ": anisotropy_disc.gltf, clearcoat_sphere.gltf, vertex_colors.gltf and their textures\n";
  return 0;
}

}  // namespace

// A textured UV sphere of 2 * segments * (segments - 1) triangles, with its textures, for
// benchmarks (not committed). Split into meshes with uint16 indices, or with onePrimitive a
// single primitive with uint32 indices (what the peer benchmarks compare on).
int writeBenchmarkSphere(int segments, const std::filesystem::path& dir, bool onePrimitive) {
  std::filesystem::create_directories(dir);
  if (!writeBumpNormalMap(dir / "bumps_normal.png", 256, 4) || !writeSpecularRegions(dir / "specular_regions.png", 96) ||
      !writeWhite(dir / "white.png")) {
    std::cerr << "tangent-make-data: cannot write textures: " << OIIO::geterror() << "\n";
    return 1;
  }
  if (segments < 3 || segments > 4000) {
    std::cerr << "tangent-make-data: --sphere needs 3..4000 segments\n";
    return 2;
  }
  // uint16 indices limit a mesh to 65536 vertices: split the sphere into bands that fit.
  DocumentWriter writer;
  const int rowsPerBand = onePrimitive ? segments : std::max(1, 60000 / (segments + 1) - 1);
  for (int first = 0, band = 0; first < segments; first += rowsPerBand, ++band) {
    const int last = std::min(segments, first + rowsPerBand);
    MeshData mesh;
    for (int j = first; j <= last; ++j) {
      const double v = double(j) / segments, theta = v * std::numbers::pi;
      for (int i = 0; i <= segments; ++i) {
        const double u = double(i) / segments, phi = u * 2 * std::numbers::pi;
        const double n[3] = {std::sin(theta) * std::cos(phi), std::cos(theta), -std::sin(theta) * std::sin(phi)};
        for (int k = 0; k < 3; ++k) {
          mesh.positions.push_back(static_cast<float>(n[k]));
          mesh.normals.push_back(static_cast<float>(n[k]));
        }
        mesh.uvs.insert(mesh.uvs.end(), {static_cast<float>(u * 4), static_cast<float>(v * 2)});
      }
    }
    for (int j = first; j < last; ++j) {
      for (int i = 0; i < segments; ++i) {
        const auto a = static_cast<std::uint32_t>((j - first) * (segments + 1) + i), b = a + segments + 1;
        std::vector<std::uint32_t> quad;
        if (j != 0) quad.insert(quad.end(), {a, b, a + 1});
        if (j != segments - 1) quad.insert(quad.end(), {a + 1, b, b + 1});
        for (std::uint32_t index : quad) {
          if (onePrimitive) mesh.indices32.push_back(index);
          else mesh.indices.push_back(static_cast<std::uint16_t>(index));
        }
      }
    }
    const float origin[3] = {0, 0, 0};
    writer.addMesh(mesh, onePrimitive ? std::string("sphere") : "band" + std::to_string(band), 0, origin);
  }
  Json extra = sharedMaterials("");
  extra["extensionsUsed"] = {"KHR_materials_specular"};
  const std::string stem = "sphere-" + std::to_string(segments);
  writer.write(dir, stem, extra);
  std::cout << "wrote " << (dir / (stem + ".gltf")).string() << ": " << 2 * segments * (segments - 1) << " triangles\n";
  return 0;
}

int main(int argc, char** argv) {
  namespace fs = std::filesystem;
  if ((argc == 4 || (argc == 5 && std::string(argv[4]) == "--one-primitive")) && std::string(argv[1]) == "--sphere")
    return writeBenchmarkSphere(std::atoi(argv[2]), argv[3], argc == 5);
  if (argc == 3 && std::string(argv[1]) == "--materials") return writeMaterialScenes(argv[2]);
  if (argc == 3 && std::string(argv[1]) == "--animated") {
    const fs::path dir = argv[2];
    fs::create_directories(dir);
    if (!writeBumpNormalMap(dir / "bumps_normal.png", 256, 4)) {
      std::cerr << "tangent-make-data: cannot write " << (dir / "bumps_normal.png") << ": " << OIIO::geterror() << "\n";
      return 1;
    }
    writeSkinned(dir);
    writeMorphing(dir);
    std::cout << "wrote " << dir.string() << ": skinned.gltf, morphing.gltf and bumps_normal.png\n";
    return 0;
  }
  const char* usage =
      "usage: tangent-make-data OUT_DIR              the bundled demo data\n"
      "       tangent-make-data --animated OUT_DIR   a skinned and a morphing asset with a \"bend\" animation\n"
      "       tangent-make-data --materials OUT_DIR  an anisotropic brushed disc, a clearcoat sphere (its normal map on\n"
      "                                              TEXCOORD_1, rotated) and a vertex-coloured grid\n"
      "       tangent-make-data --sphere N OUT_DIR [--one-primitive]\n"
      "                                              a textured N x N UV sphere for benchmarks (split into\n"
      "                                              uint16-indexed meshes, or one uint32-indexed primitive)\n";
  // An argument that starts with '-' is an option, never the output folder ("--help" was
  // taken for one, and the data written into a folder named --help).
  if (argc == 2 && (std::string(argv[1]) == "-h" || std::string(argv[1]) == "--help")) {
    std::cout << usage;
    return 0;
  }
  if (argc != 2 || argv[1][0] == '-') {
    if (argc == 2)
      std::cerr << "tangent-make-data: unknown option " << argv[1] << " (a folder starting with '-': write ./"
                << argv[1] << ")\n";
    std::cerr << usage;
    return 2;
  }
  const fs::path dir = argv[1];
  fs::create_directories(dir);
  if (!writeBumpNormalMap(dir / "bumps_normal.png", 256, 4)) {
    std::cerr << "tangent-make-data: cannot write " << (dir / "bumps_normal.png") << ": " << OIIO::geterror() << "\n";
    return 1;
  }

  // bake's default input: a sphere and mirrored quads with the bump map, a plain ground.
  {
    DocumentWriter demo;
    const float sphereAt[3] = {0, 0, 0}, quadsAt[3] = {0, 0.5f, 1.5f}, groundAt[3] = {0, 0, 0};
    demo.addMesh(uvSphere(32, 16, 1.0f), "Sphere", 0, sphereAt);
    demo.addMesh(mirroredQuads(), "MirroredQuads", 0, quadsAt);
    demo.addMesh(plane(4.0f, -1.0f), "Ground", 1, groundAt);
    Json extra = {
        {"materials", {{{"name", "Bumps"}, {"pbrMetallicRoughness", {{"baseColorFactor", {1, 1, 1, 1}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.4}}},
                        {"normalTexture", {{"index", 0}}}},
                       {{"name", "PlainGround"}, {"pbrMetallicRoughness", {{"baseColorFactor", {0.8, 0.8, 0.8, 1}}, {"metallicFactor", 0.0}}}}}},
        {"textures", {{{"source", 0}, {"sampler", 0}}}},
        {"samplers", {{{"magFilter", 9729}, {"minFilter", 9987}, {"wrapS", 10497}, {"wrapT", 10497}}}},
        {"images", {{{"uri", "bumps_normal.png"}, {"mimeType", "image/png"}}}}};
    demo.write(dir, "demo", extra);
  }

  // The viewer's demo scene: spheres on a plane under a directional light.
  if (!writeSpecularRegions(dir / "specular_regions.png", 96) || !writeWhite(dir / "white.png") || !writeSphereMap(dir / "spheremap.png", 256)) {
    std::cerr << "tangent-make-data: cannot write the demo textures: " << OIIO::geterror() << "\n";
    return 1;
  }
  {
    DocumentWriter scene;
    const float groundAt[3] = {0, 0, 0};
    MeshData ground = plane(4.0f, 0.0f);
    scene.addMesh(ground, "Ground", 1, groundAt);
    const float positions[3][3] = {{-1.6f, 0.7f, 0.3f}, {0.0f, 0.7f, -0.4f}, {1.6f, 0.7f, 0.3f}};
    const char* sphereNames[3] = {"SphereLeft", "SphereMiddle", "SphereRight"};
    for (int i = 0; i < 3; ++i) scene.addMesh(uvSphere(48, 24, 0.7f), sphereNames[i], 0, positions[i]);
    // Sun: KHR_lights_punctual lights shine along their node's -z; the rotation turns -z to
    // kSunDirection (q = normalize(1 + dot(a, b), cross(a, b)) for unit a, b).
    const double length = std::sqrt(kSunDirection[0] * kSunDirection[0] + kSunDirection[1] * kSunDirection[1] + kSunDirection[2] * kSunDirection[2]);
    const double d[3] = {kSunDirection[0] / length, kSunDirection[1] / length, kSunDirection[2] / length};
    double q[4] = {d[1], -d[0], 0.0, 1.0 - d[2]};  // x, y, z, w for a = (0, 0, -1)
    const double qLength = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    for (double& c : q) c /= qLength;
    scene.addNode({{"name", "Sun"}, {"rotation", {q[0], q[1], q[2], q[3]}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    Json extra = sharedMaterials("");
    Json sun = {{"name", "Sun"}, {"type", "directional"}, {"color", {1.0, 0.97, 0.9}}, {"intensity", 1.0}};
    Json lamp = {{"name", "Lamp"}, {"type", "point"}, {"color", {0.4, 0.5, 0.9}}, {"intensity", 4.0}};
    Json lights = Json::object();
    lights["lights"] = Json::array({sun, lamp});
    extra["extensions"] = Json::object();
    extra["extensions"]["KHR_lights_punctual"] = lights;
    scene.addNode({{"name", "Lamp"}, {"translation", {-2.5, 2.0, 2.5}}, {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
    scene.write(dir, "scene", extra);
  }
  // Primitives to choose in the viewer's panel: beside the textures, so that each file stays
  // inside its own folder (the loader's default asset root).
  const std::pair<const char*, MeshData> primitives[] = {
      {"quad", quad(1.0f)}, {"cube", cube(0.8f)}, {"sphere", uvSphere(48, 24, 1.0f)}, {"torus", torus(64, 24, 0.9f, 0.35f)}};
  for (const auto& [name, mesh] : primitives) {
    DocumentWriter writer;
    const float origin[3] = {0, 0, 0};
    writer.addMesh(mesh, name, 0, origin);
    Json extra = sharedMaterials("");
    extra["extensionsUsed"] = {"KHR_materials_specular"};
    writer.write(dir, name, extra);
  }
  std::cout << "wrote " << dir.string() << ": demo.gltf, scene.gltf, {quad,cube,sphere,torus}.gltf and their textures\n";
  return 0;
}
