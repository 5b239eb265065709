// The plain-array API: builds the half-edge mesh, runs the method, copies one tangent per corner.
#include <algorithm>
#include <bit>
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

  // Extra vertices a caller must create: distinct tangents per input vertex, minus one.
  using Entry = std::tuple<std::uint32_t, std::uint32_t, std::uint32_t, std::uint32_t, std::uint32_t>;
  std::vector<Entry> entries(cornerCount);
  for (std::size_t corner = 0; corner < cornerCount; ++corner) {
    const float* t = &cornerTangents[4 * corner];
    entries[corner] = {arrays.indices[corner], std::bit_cast<std::uint32_t>(t[0]), std::bit_cast<std::uint32_t>(t[1]),
                       std::bit_cast<std::uint32_t>(t[2]), std::bit_cast<std::uint32_t>(t[3])};
  }
  std::sort(entries.begin(), entries.end());
  for (std::size_t i = 1; i < entries.size(); ++i) {
    if (std::get<0>(entries[i]) == std::get<0>(entries[i - 1]) && entries[i] != entries[i - 1]) ++report.splitVertices;
  }
  return report;
}

}  // namespace tangent
