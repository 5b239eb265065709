// SPDX-License-Identifier: MIT
// Parametric surfaces whose exact tangent frame is known in closed form, tessellated at a
// chosen resolution, for measuring error against run time. Exact tangent: dP/du projected onto
// the tangent plane and normalized; exact w: sign(dot(cross(N, T), dP/dv)), in the
// bottom-left (MikkTSpace) UV convention.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "tangent/tangent.hpp"

namespace tangent::bench {

struct AnalyticMesh {
  std::string surface;
  std::vector<float> positions, normals, uvs;  // per vertex
  std::vector<std::uint32_t> indices;
  std::vector<float> exactTangents;            // per vertex: xyz, w
  MeshArrays arrays() const { return {positions, normals, uvs, indices}; }
  std::size_t triangles() const { return indices.size() / 3; }
};

// Names: "sphere" (UV sphere with poles), "torus", "cylinder", "heightfield" (z = f(x, y) with
// u = x, v = y), "sheared" (the same height field with the non-orthogonal mapping u = x,
// v = y + 0.6 x, whose tangent dP/du leans away from the x axis).
const std::vector<std::string>& surfaceNames();

// About `targetTriangles` triangles (a grid of n x n quads, n = sqrt(target / 2)).
AnalyticMesh makeSurface(const std::string& surface, std::size_t targetTriangles);

}  // namespace tangent::bench
