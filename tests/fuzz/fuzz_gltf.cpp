// SPDX-License-Identifier: MIT
// libFuzzer target: a .gltf or .glb file's bytes through the loader (depth limit, document
// validation, URI containment, tinygltf, accessor checks), then every triangle primitive's
// geometry through the core. Input errors are answers; a crash, hang, leak or sanitizer
// report is a finding. The asset's folder holds the base buffer and image of
// tests/malformed, so relative URIs can resolve.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <vector>

#include "read/asset.hpp"
#include "fuzz_support.hpp"
#include "read/primitive.hpp"
#include "tangent/gltf.hpp"
#include "tangent/tangent.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace detail = tangent::gltf::detail;
  static const std::filesystem::path folder = tangent::fuzz::assetFolder();
  try {
    const detail::Asset asset =
        detail::loadAssetBytes(std::vector<std::uint8_t>(data, data + size), folder / "in.gltf", {}, false);
    const auto& doc = asset.json;
    const std::size_t meshCount = doc.contains("meshes") ? doc["meshes"].size() : 0;
    for (std::size_t m = 0; m < meshCount; ++m) {
      const auto& primitives = doc["meshes"][m]["primitives"];
      for (std::size_t p = 0; p < primitives.size(); ++p) {
        const detail::PrimitiveNeeds needs = detail::primitiveNeeds(doc, primitives[p], true);
        if (!needs.triangles || needs.texCoord < 0) continue;
        try {
          const detail::PrimitiveGeometry g = detail::readGeometry(asset, primitives[p], needs, "fuzz");
          tangent::fuzz::computeAndCheck(g.positions, g.normals, g.uvs, g.corners, tangent::Method::mikktspace);
        } catch (const tangent::gltf::InputError&) {
        }
      }
    }
  } catch (const tangent::gltf::InputError&) {
  }
  return 0;
}
