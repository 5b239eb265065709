// SPDX-License-Identifier: MIT
// Built against the installed package: writes a one-quad glTF (external .bin, no material),
// bakes it through tangent::gltf::bakeFile with `all` (every triangle primitive), and reads the
// TANGENT accessor of the output back. Exits 1 when anything differs from the value worked out
// by hand. Usage: consumer_gltf WORK_DIR
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include <nlohmann/json.hpp>
#include <tangent/gltf.hpp>

namespace {

template <class T>
void append(std::vector<char>& bytes, const std::vector<T>& values) {
  const auto* begin = reinterpret_cast<const char*>(values.data());
  bytes.insert(bytes.end(), begin, begin + values.size() * sizeof(T));
}

// The README's quad (u = x, v = y, facing +z): glTF's tangent is (1, 0, 0, -1) at every vertex.
void writeQuad(const std::filesystem::path& gltfPath) {
  const std::vector<float> positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const std::vector<float> normals = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
  const std::vector<float> uvs = {0, 0, 1, 0, 1, 1, 0, 1};
  const std::vector<std::uint16_t> indices = {0, 1, 2, 0, 2, 3};
  std::vector<char> bytes;
  append(bytes, positions);
  append(bytes, normals);
  append(bytes, uvs);
  append(bytes, indices);
  std::ofstream(gltfPath.parent_path() / "quad.bin", std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  using Json = nlohmann::json;
  const Json document = {
      {"asset", {{"version", "2.0"}}},
      {"buffers", {{{"uri", "quad.bin"}, {"byteLength", bytes.size()}}}},
      {"bufferViews", {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 48}},
                       {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 48}},
                       {{"buffer", 0}, {"byteOffset", 96}, {"byteLength", 32}},
                       {{"buffer", 0}, {"byteOffset", 128}, {"byteLength", 12}}}},
      {"accessors", {{{"bufferView", 0}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"},
                      {"min", {0, 0, 0}}, {"max", {1, 1, 0}}},
                     {{"bufferView", 1}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}},
                     {{"bufferView", 2}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}},
                     {{"bufferView", 3}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}}}},
      {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}}}, {"indices", 3}}}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"scenes", {{{"nodes", {0}}}}},
      {"scene", 0}};
  std::ofstream(gltfPath) << document.dump(1);
}

// The VEC4 float TANGENT of the first primitive of the baked .gltf, read from its buffer.
std::vector<float> readTangents(const std::filesystem::path& gltfPath) {
  const auto document = nlohmann::json::parse(std::ifstream(gltfPath));
  const auto& accessor = document.at("accessors").at(document.at("meshes")[0].at("primitives")[0].at("attributes").at("TANGENT").get<int>());
  const auto& view = document.at("bufferViews").at(accessor.at("bufferView").get<int>());
  const auto& buffer = document.at("buffers").at(view.at("buffer").get<int>());
  if (accessor.at("componentType") != 5126 || accessor.at("type") != "VEC4") return {};
  std::ifstream file(gltfPath.parent_path() / buffer.at("uri").get<std::string>(), std::ios::binary);
  const std::vector<char> bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  const std::size_t stride = view.value("byteStride", std::size_t{16});
  const std::size_t start = view.value("byteOffset", std::size_t{0}) + accessor.value("byteOffset", std::size_t{0});
  std::vector<float> tangents(accessor.at("count").get<std::size_t>() * 4);
  for (std::size_t vertex = 0; vertex * 4 < tangents.size(); ++vertex) {
    if (start + vertex * stride + 16 > bytes.size()) return {};
    std::memcpy(&tangents[vertex * 4], bytes.data() + start + vertex * stride, 16);
  }
  return tangents;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: consumer_gltf WORK_DIR\n");
    return 2;
  }
  const std::filesystem::path folder = argv[1];
  std::filesystem::create_directories(folder);
  writeQuad(folder / "quad.gltf");
  tangent::gltf::BakeOptions options;
  options.all = true;
  const tangent::gltf::BakeResult result = tangent::gltf::bakeFile(folder / "quad.gltf", folder / "quad-baked.gltf", options);
  int failures = 0;
  if (result.primitives.size() != 1 || result.primitives[0].action != tangent::gltf::PrimitiveAction::baked || result.primitives[0].tangents.corners != 6) {
    std::printf("bake: %zu primitives, first %s (%s)\n", result.primitives.size(),
                result.primitives.empty() ? "-" : tangent::gltf::toString(result.primitives[0].action),
                result.primitives.empty() ? "-" : result.primitives[0].reason.c_str());
    ++failures;
  }
  const std::vector<float> tangents = readTangents(folder / "quad-baked.gltf");
  if (tangents.size() != 16) {
    std::printf("baked TANGENT: %zu values, expected 16 float (4 vertices)\n", tangents.size());
    ++failures;
  }
  for (std::size_t vertex = 0; vertex * 4 < tangents.size(); ++vertex) {
    const float* t = &tangents[4 * vertex];
    if (std::abs(t[0] - 1) > 1e-6f || std::abs(t[1]) > 1e-6f || std::abs(t[2]) > 1e-6f || t[3] != -1.0f) {
      std::printf("vertex %zu: tangent %g %g %g %g, expected 1 0 0 -1\n", vertex, t[0], t[1], t[2], t[3]);
      ++failures;
    }
  }
  std::printf("consumer_gltf: %s\n", failures == 0 ? "baked tangents as expected" : "WRONG baked tangents");
  return failures == 0 ? 0 : 1;
}
