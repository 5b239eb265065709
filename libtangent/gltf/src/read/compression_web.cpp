// SPDX-License-Identifier: MIT
// The web build's stand-ins for the glTF layer's two decoders that need native libraries
// (Debian ships Draco and meshoptimizer as native code only): Draco and EXT_meshopt_compression
// decoding (draco_decode.cpp, meshopt_decode.cpp). libtangent/CMakeLists.txt compiles this file
// instead of those two under emscripten; each refuses what it is given with a message naming
// the file and element, as the library's readers do, and README.md lists them as left out of
// the web viewer.
#include "read/asset.hpp"
#include "read/compression.hpp"
#include "tangent/gltf.hpp"

namespace tangent::gltf::detail {

void decodeMeshoptViews(Asset& asset) {
  const auto& doc = asset.json;
  if (!doc.contains("bufferViews")) return;
  for (std::size_t i = 0; i < doc["bufferViews"].size(); ++i) {
    const auto& view = doc["bufferViews"][i];
    if (view.contains("extensions") && view["extensions"].is_object() && view["extensions"].contains(kMeshoptExtension))
      throw InputError(asset.path.string() + ": bufferViews[" + std::to_string(i) + "] uses " + kMeshoptExtension +
                       ", which the web viewer does not decode (meshoptimizer is native code only); open an uncompressed copy");
  }
}

void decodeDracoPrimitives(Asset& asset) {
  const auto& doc = asset.json;
  if (!doc.contains("meshes")) return;
  for (std::size_t m = 0; m < doc["meshes"].size(); ++m) {
    const auto& mesh = doc["meshes"][m];
    if (!mesh.contains("primitives")) continue;
    for (std::size_t p = 0; p < mesh["primitives"].size(); ++p) {
      const auto& primitive = mesh["primitives"][p];
      if (primitive.contains("extensions") && primitive["extensions"].is_object() && primitive["extensions"].contains(kDracoExtension))
        throw InputError(asset.path.string() + ": meshes[" + std::to_string(m) + "].primitives[" + std::to_string(p) + "] uses " +
                         kDracoExtension + ", which the web viewer does not decode (Draco is native code only); open an uncompressed copy");
    }
  }
}

}  // namespace tangent::gltf::detail
