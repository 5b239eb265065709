// SPDX-License-Identifier: MIT
// For the Python tests: the C++ library on raw arrays read from files, so that the module's
// results can be compared bit for bit with a call that does not go through Python.
//   tangent-arrays-tool DIR METHOD UV_ORIGIN [WEIGHTING]
// reads DIR/{positions,normals,uvs}.f32 and DIR/indices.u32, writes DIR/tangents.f32 and
// DIR/corner_vertex.u32.
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "tangent/tangent.hpp"

namespace {

template <typename T>
std::vector<T> readRaw(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  const std::vector<char> bytes{std::istreambuf_iterator<char>(in), {}};
  std::vector<T> values(bytes.size() / sizeof(T));
  std::copy(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(values.size() * sizeof(T)),
            reinterpret_cast<char*>(values.data()));
  return values;
}

template <typename T>
void writeRaw(const std::filesystem::path& file, const std::vector<T>& values) {
  std::ofstream(file, std::ios::binary).write(reinterpret_cast<const char*>(values.data()),
                                              static_cast<std::streamsize>(values.size() * sizeof(T)));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4 && argc != 5) {
    std::fprintf(stderr, "usage: tangent-arrays-tool DIR METHOD top-left|bottom-left [WEIGHTING]\n");
    return 2;
  }
  const std::filesystem::path dir = argv[1];
  tangent::Options options;
  const std::optional<tangent::Method> method = tangent::parseMethod(argv[2]);
  if (!method) return 2;
  options.method = *method;
  const std::optional<tangent::UvOrigin> origin = tangent::parseUvOrigin(argv[3]);
  const std::optional<tangent::Weighting> weighting = tangent::parseWeighting(argc == 5 ? argv[4] : "angle");
  if (!origin || !weighting) return 2;
  options.uvOrigin = *origin;
  options.weighting = *weighting;
  const auto positions = readRaw<float>(dir / "positions.f32"), normals = readRaw<float>(dir / "normals.f32"),
             uvs = readRaw<float>(dir / "uvs.f32");
  const auto indices = readRaw<std::uint32_t>(dir / "indices.u32");
  std::vector<float> tangents(indices.size() * 4);
  std::vector<std::uint32_t> cornerVertex(indices.size());
  tangent::TangentWorkspace workspace;
  tangent::computeCornerTangents({positions, normals, uvs, indices}, tangent::CornerOutputs{tangents, {}, cornerVertex}, options,
                                 workspace);
  writeRaw(dir / "tangents.f32", tangents);
  writeRaw(dir / "corner_vertex.u32", cornerVertex);
  return 0;
}
