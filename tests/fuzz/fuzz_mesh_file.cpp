// SPDX-License-Identifier: MIT
// libFuzzer target: OBJ, PLY and OFF files (the first byte picks the format) through the
// checked OpenMesh importer and on into the core. Input errors are answers; a crash, hang,
// leak or sanitizer report is a finding.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <vector>

#include "read/asset.hpp"
#include "fuzz_support.hpp"
#include "read/primitive.hpp"
#include "tangent/gltf.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace detail = tangent::gltf::detail;
  if (size < 1) return 0;
  static const std::filesystem::path folder = tangent::fuzz::assetFolder();
  static const char* const extensions[] = {".obj", ".ply", ".off"};
  const std::filesystem::path file = folder / (std::string("in") + extensions[data[0] % 3]);
  {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data + 1), static_cast<std::streamsize>(size - 1));
  }
  try {
    const detail::Asset asset = detail::loadAsset(file);
    const auto& primitive = asset.json["meshes"][0]["primitives"][0];
    const detail::PrimitiveNeeds needs = detail::primitiveNeeds(asset.json, primitive, true);
    const detail::PrimitiveGeometry g = detail::readGeometry(asset, primitive, needs, "fuzz");
    tangent::fuzz::computeAndCheck(g.positions, g.normals, g.uvs, g.corners, tangent::Method::mikktspace);
  } catch (const tangent::gltf::InputError&) {
  }
  return 0;
}
