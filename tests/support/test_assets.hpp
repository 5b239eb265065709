// SPDX-License-Identifier: MIT
// Generated glTF test assets covering the accessor forms and document features bake must
// handle. Used by the GoogleTest round trip and by the validator run (tangent-test-assets).
#pragma once

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace tangent::testing {

struct TestAsset {
  std::string name;
  nlohmann::ordered_json json;
  std::vector<std::uint8_t> bin;  // buffer 0
};

// Every case, each a complete glTF document.
std::vector<TestAsset> makeTestAssets();

// Writes `name.gltf` + `name.bin` (or `name.glb`) into dir; returns the main file.
std::filesystem::path writeAsset(const TestAsset& asset, const std::filesystem::path& dir, bool glb);

// Plain-array meshes for core tests.
struct GridMesh {
  std::vector<float> positions, normals, uvs;
  std::vector<std::uint32_t> indices;
};
// nx * ny quads on a gently curved sheet; mirrorColumns alternates the u direction per column
// of quads, so every interior column of vertices needs two frames.
GridMesh makeGrid(int nx, int ny, bool mirrorColumns);
// A mirrored 6 x 6 grid whose normals lean up to ~30 deg away from the surface and whose UVs
// are jittered, so that the triangles around a vertex have dP/du with different components
// along its normal and the weightings (and a raw projection onto a non-unit normal) differ.
GridMesh leaningGrid();
// The mesh with its triangles in a random order and each triangle's corners rotated;
// originalCorner[c] is the corner of `mesh` that corner c of the result came from.
struct ShuffledMesh {
  GridMesh mesh;
  std::vector<std::size_t> originalCorner;
};
ShuffledMesh shuffleFacesAndRotateCorners(const GridMesh& mesh, unsigned seed);

// Torus and UV sphere (with poles) with analytic normals, both wound counter-clockwise seen
// from outside (glTF's front faces agree with the normals). exactPoles puts every pole vertex
// at exactly (0, 0, +-1); without it the bottom pole's copies sit sin(pi) ~ 1e-16 apart.
GridMesh makeTorus(int rings, int sides);
GridMesh makeSphere(int slices, int stacks, bool exactPoles = true);
// The inconsistent-winding fixture: the mesh with triangles 0, every, 2 * every, ... turned
// over (two corners swapped), so they are wound against their normals; every = 1 turns all.
GridMesh reverseWinding(GridMesh mesh, int every);

// One normal-mapped primitive of `mesh` (float POSITION, NORMAL unless withNormal is false,
// TEXCOORD_0, uint16 indices) in a complete document.
TestAsset meshAsset(const std::string& name, const GridMesh& mesh, bool withNormal = true);

}  // namespace tangent::testing
