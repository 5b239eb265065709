// Generates the bundled demo asset in data/demo/: a UV sphere, two quads with a mirrored UV
// island, and a ground plane without a normal map, plus the bump normal map they use.
// Usage: tangent-make-data OUT_DIR
#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <vector>

namespace {

using Json = nlohmann::ordered_json;

struct MeshData {
  std::vector<float> positions, normals, uvs;
  std::vector<std::uint16_t> indices;
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

}  // namespace

int main(int argc, char** argv) {
  namespace fs = std::filesystem;
  if (argc != 2) {
    std::cerr << "usage: tangent-make-data OUT_DIR\n";
    return 2;
  }
  const fs::path dir = argv[1];
  fs::create_directories(dir);
  if (!writeBumpNormalMap(dir / "bumps_normal.png", 256, 4)) {
    std::cerr << "tangent-make-data: cannot write " << (dir / "bumps_normal.png") << ": " << OIIO::geterror() << "\n";
    return 1;
  }

  const MeshData meshes[3] = {uvSphere(32, 16, 1.0f), mirroredQuads(), plane(4.0f, -1.0f)};
  const char* names[3] = {"Sphere", "MirroredQuads", "Ground"};
  const int materials[3] = {0, 0, 1};
  std::vector<std::uint8_t> bin;
  Json accessors = Json::array(), views = Json::array(), meshJson = Json::array(), nodes = Json::array();
  auto addView = [&](const void* data, std::size_t bytes, int target) {
    while (bin.size() % 4) bin.push_back(0);
    views.push_back({{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes}, {"target", target}});
    const auto* p = static_cast<const std::uint8_t*>(data);
    bin.insert(bin.end(), p, p + bytes);
    return views.size() - 1;
  };
  for (int m = 0; m < 3; ++m) {
    const MeshData& mesh = meshes[m];
    const std::size_t n = mesh.positions.size() / 3;
    float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
      lo[i % 3] = std::min(lo[i % 3], mesh.positions[i]);
      hi[i % 3] = std::max(hi[i % 3], mesh.positions[i]);
    }
    const std::size_t first = accessors.size();
    accessors.push_back({{"bufferView", addView(mesh.positions.data(), n * 12, 34962)}, {"componentType", 5126}, {"count", n},
                         {"type", "VEC3"}, {"min", {lo[0], lo[1], lo[2]}}, {"max", {hi[0], hi[1], hi[2]}}});
    accessors.push_back({{"bufferView", addView(mesh.normals.data(), n * 12, 34962)}, {"componentType", 5126}, {"count", n}, {"type", "VEC3"}});
    accessors.push_back({{"bufferView", addView(mesh.uvs.data(), n * 8, 34962)}, {"componentType", 5126}, {"count", n}, {"type", "VEC2"}});
    accessors.push_back({{"bufferView", addView(mesh.indices.data(), mesh.indices.size() * 2, 34963)}, {"componentType", 5123},
                         {"count", mesh.indices.size()}, {"type", "SCALAR"}});
    Json primitive = Json::object();
    primitive["attributes"] = {{"POSITION", first}, {"NORMAL", first + 1}, {"TEXCOORD_0", first + 2}};
    primitive["indices"] = first + 3;
    primitive["material"] = materials[m];
    meshJson.push_back({{"name", names[m]}, {"primitives", Json::array({primitive})}});
  }
  nodes.push_back({{"name", "Sphere"}, {"mesh", 0}, {"translation", {0, 0, 0}}});
  nodes.push_back({{"name", "MirroredQuads"}, {"mesh", 1}, {"translation", {0, 0.5, 1.5}}});
  nodes.push_back({{"name", "Ground"}, {"mesh", 2}});
  while (bin.size() % 4) bin.push_back(0);

  Json doc = {
      {"asset", {{"version", "2.0"}, {"generator", "libtangent tangent-make-data"}, {"copyright", "libtangent authors, CC0"}}},
      {"scene", 0},
      {"scenes", {{{"name", "Demo"}, {"nodes", {0, 1, 2}}}}},
      {"nodes", nodes},
      {"meshes", meshJson},
      {"materials", {{{"name", "Bumps"}, {"pbrMetallicRoughness", {{"baseColorFactor", {1, 1, 1, 1}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.4}}},
                      {"normalTexture", {{"index", 0}}}},
                     {{"name", "PlainGround"}, {"pbrMetallicRoughness", {{"baseColorFactor", {0.8, 0.8, 0.8, 1}}, {"metallicFactor", 0.0}}}}}},
      {"textures", {{{"source", 0}, {"sampler", 0}}}},
      {"samplers", {{{"magFilter", 9729}, {"minFilter", 9987}, {"wrapS", 10497}, {"wrapT", 10497}}}},
      {"images", {{{"uri", "bumps_normal.png"}, {"mimeType", "image/png"}}}},
      {"accessors", accessors},
      {"bufferViews", views},
      {"buffers", {{{"uri", "demo.bin"}, {"byteLength", bin.size()}}}}};
  std::ofstream(dir / "demo.bin", std::ios::binary).write(reinterpret_cast<const char*>(bin.data()), static_cast<std::streamsize>(bin.size()));
  std::ofstream(dir / "demo.gltf") << doc.dump(2) << "\n";
  std::cout << "wrote " << (dir / "demo.gltf").string() << ", demo.bin, bumps_normal.png\n";
  return 0;
}
