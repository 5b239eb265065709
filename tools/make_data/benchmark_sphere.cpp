// SPDX-License-Identifier: MIT
// --sphere N: a textured UV sphere for benchmarks.

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numbers>

#include "document_writer.hpp"
#include "families.hpp"
#include "textures.hpp"

namespace make_data {

namespace {

// Rows `first` to `last` (of `segments`) of a unit UV sphere of `segments` x `segments` quads
// (the map tiles four times around, twice pole to pole); uint32 indices with onePrimitive, else
// uint16.
MeshData sphereBand(int segments, int first, int last, bool onePrimitive) {
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
  return mesh;
}

}  // namespace

// A textured UV sphere of 2 * segments * (segments - 1) triangles, with its textures, for
// benchmarks (not committed). Split into meshes with uint16 indices, or with onePrimitive a
// single primitive with uint32 indices (what the peer benchmarks compare on).
int writeBenchmarkSphere(int segments, const std::filesystem::path& dir, bool onePrimitive) {
  std::filesystem::create_directories(dir);
  if (!writeBumpNormalMap(dir / "bumps_normal.png", 256, 4) || !writeSpecularRegions(dir / "specular_regions.png", 96) ||
      !writeWhite(dir / "white.png")) {
    return 1;  // writeImage said which file and why
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
    const MeshData mesh = sphereBand(segments, first, last, onePrimitive);
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

}  // namespace make_data
