// The plain-array API: builds the half-edge mesh, runs the method, copies one tangent per corner.
#include <algorithm>
#include <bit>
#include <cstring>
#include <stdexcept>
#include <string>
#include <tuple>

#include "methods.hpp"
#include "tangent/halfedge_mesh.hpp"

namespace tangent {

Report computeTangents(CornerMesh& mesh, const Options& options, std::span<FrameSource> cornerSources) {
  if (!cornerSources.empty() && cornerSources.size() != mesh.cornerHalfedge.size())
    throw std::invalid_argument("cornerSources: expected one per corner");
  if (options.method == Method::mikktspace) return detail::mikktspaceTangents(mesh, options, cornerSources);
  return detail::lengyelTangents(mesh, options, cornerSources);
}

Report computeCornerTangents(const MeshArrays& arrays, std::span<float> cornerTangents, const Options& options,
                             std::span<FrameSource> cornerSources) {
  if (cornerTangents.size() != arrays.indices.size() * 4)
    throw std::invalid_argument("cornerTangents: expected " + std::to_string(arrays.indices.size() * 4) +
                                " floats (4 per corner), got " + std::to_string(cornerTangents.size()));
  CornerMesh cornerMesh = buildCornerMesh(arrays);
  if (!cornerSources.empty() && cornerSources.size() != arrays.indices.size())
    throw std::invalid_argument("cornerSources: expected " + std::to_string(arrays.indices.size()) + " entries (one per corner)");
  Report report = computeTangents(cornerMesh, options, cornerSources);
  const std::size_t cornerCount = arrays.indices.size();
  for (std::size_t corner = 0; corner < cornerCount; ++corner) {
    const TangentVec& t = cornerMesh.mesh.property(cornerMesh.tangent, cornerMesh.cornerHalfedge[corner]);
    for (int i = 0; i < 4; ++i) cornerTangents[4 * corner + i] = static_cast<float>(t[i]);
  }

  // Extra vertices a caller must create: distinct tangents per input vertex, minus one. Most
  // vertices have one tangent: compare with the vertex's first corner and sort only the rest.
  const std::size_t vertexCount = arrays.positions.size() / 3;
  std::vector<std::int64_t> firstCorner(vertexCount, -1);
  std::vector<std::tuple<std::uint32_t, std::uint32_t, std::uint32_t, std::uint32_t, std::uint32_t>> others;
  auto bits = [&](std::size_t corner, int i) { return std::bit_cast<std::uint32_t>(cornerTangents[4 * corner + i]); };
  for (std::size_t corner = 0; corner < cornerCount; ++corner) {
    const std::uint32_t v = arrays.indices[corner];
    if (firstCorner[v] < 0) {
      firstCorner[v] = static_cast<std::int64_t>(corner);
    } else if (std::memcmp(&cornerTangents[4 * corner], &cornerTangents[4 * firstCorner[v]], 16) != 0) {
      others.emplace_back(v, bits(corner, 0), bits(corner, 1), bits(corner, 2), bits(corner, 3));
    }
  }
  std::sort(others.begin(), others.end());
  report.splitVertices = static_cast<std::uint64_t>(std::unique(others.begin(), others.end()) - others.begin());
  return report;
}

}  // namespace tangent
