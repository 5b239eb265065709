// SPDX-License-Identifier: MIT
// The meshes tangent-make-data writes: positions, normals, UVs and indices (and TANGENT where a
// scene writes it analytically), each shape a function.
#pragma once

#include <cstdint>
#include <vector>

namespace make_data {

struct MeshData {
  std::vector<float> positions, normals, uvs;
  std::vector<std::uint16_t> indices;
  std::vector<std::uint32_t> indices32;  // used instead of `indices` when not empty (large meshes)
  std::vector<float> tangents;  // TANGENT (4 per vertex) when not empty
};

// A UV sphere of `slices` x `stacks` quads (u twice around, v once pole to pole).
MeshData uvSphere(int slices, int stacks, float radius);
// Two unit quads side by side facing +z; the right one's UVs mirror the left one's in u.
MeshData mirroredQuads();
// A square ground of half-size `halfSize` at height `y`, facing +y.
MeshData plane(float halfSize, float y);
// A cube of half-size `half`: 24 vertices, 4 per face, u along the face's first edge.
MeshData cube(float half);
// A torus around +y: `rings` around the axis, `sides` around the tube.
MeshData torus(int rings, int sides, float major, float minor);
// A cylinder of `radius` along +y from 0 to `height`, rings every `height / (rings - 1)`, open at
// both ends; u goes twice around, v once per unit of height. Rings from the top down, wound
// as uvSphere's (counter-clockwise seen from outside).
MeshData cylinder(int rings, int sides, float radius, float height);
// A grid over [-1, 1]^2 at z = 0 facing +z, `segments` squares a side; the map tiles twice.
MeshData grid(int segments);
// A square of half-size `half` facing +z.
MeshData quad(float half);
// A disc of `radius` at z = 0 facing +z, in `rings` rings of `segments` quads around a centre
// fan; UVs map [-radius, radius]^2 to [0, 1]^2 (v down, as glTF's images).
MeshData disc(int rings, int segments, float radius);

}  // namespace make_data
