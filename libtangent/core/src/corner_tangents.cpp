// The entry points: the plain-array call (every method) and the OpenMesh call.
#include <tbb/task_arena.h>

#include <algorithm>
#include <stdexcept>
#include <string>

#include "methods.hpp"
#include "tangent/halfedge_mesh.hpp"
#include "workspace.hpp"

namespace tangent {
namespace {

unsigned threadCount(const Options& options) {
  if (options.threads > 0) return options.threads;
  return static_cast<unsigned>(std::max(1, tbb::this_task_arena::max_concurrency()));
}

// Methods `lengyel` and `flat` run on the half-edge mesh; their frames come back per corner
// in the bottom-left convention with their sources, for finishOutputs.
void lengyelOnArrays(detail::WorkspaceData& ws, const MeshArrays& mesh, const CornerOutputs& outputs, const Options& options,
                     Report& report) {
  CornerMesh cornerMesh = buildCornerMesh(mesh);
  Options native = options;
  native.uvOrigin = UvOrigin::bottomLeft;
  std::vector<FrameSource> sources(ws.cornerCount);
  report = detail::lengyelTangents(cornerMesh, native, sources);
  detail::ensureSize(ws.cornerState, ws.cornerCount);
  detail::ensureSize(ws.cornerLink, ws.cornerCount);
  for (std::size_t c = 0; c < ws.cornerCount; ++c) {
    const TangentVec& t = cornerMesh.mesh.property(cornerMesh.tangent, cornerMesh.cornerHalfedge[c]);
    for (int i = 0; i < 4; ++i) outputs.tangents[4 * c + i] = static_cast<float>(t[i]);
    ws.cornerState[c] = static_cast<std::uint8_t>(sources[c]);
    ws.cornerLink[c] = detail::kNone;
  }
  const std::uint64_t invalidNormals = report.invalidNormals;
  detail::finishOutputs(ws, mesh, outputs, options, report);
  report.invalidNormals = invalidNormals;
}

}  // namespace

Report computeCornerTangents(const MeshArrays& mesh, const CornerOutputs& outputs, const Options& options,
                             TangentWorkspace& workspace) {
  detail::checkArrays(mesh, outputs);
  detail::WorkspaceData& ws = workspace.data();
  ws.threads = threadCount(options);
  Report report;
  auto body = [&] {
    if (options.method == Method::mikktspace) {
      report = detail::mikktspaceOnArrays(ws, mesh, outputs, options);
    } else {
      detail::weldAndBucket(ws, mesh);
      lengyelOnArrays(ws, mesh, outputs, options, report);
    }
  };
  detail::onThreads(ws, body);
  return report;
}

Report computeCornerTangents(const MeshArrays& mesh, std::span<float> cornerTangents, const Options& options,
                             std::span<FrameSource> cornerSources) {
  TangentWorkspace workspace;
  return computeCornerTangents(mesh, CornerOutputs{cornerTangents, cornerSources, {}}, options, workspace);
}

Report computeTangents(CornerMesh& cornerMesh, const Options& options, std::span<FrameSource> cornerSources) {
  TangentWorkspace workspace;
  return computeTangents(cornerMesh, options, workspace, cornerSources);
}

Report computeTangents(CornerMesh& cornerMesh, const Options& options, TangentWorkspace& workspace,
                       std::span<FrameSource> cornerSources) {
  const std::size_t cornerCount = cornerMesh.cornerHalfedge.size();
  if (!cornerSources.empty() && cornerSources.size() != cornerCount)
    throw std::invalid_argument("cornerSources: expected one per corner");
  if (options.method != Method::mikktspace) return detail::lengyelTangents(cornerMesh, options, cornerSources);
  // The same kernel as the array call, on the corners' values: the same bits.
  const TriMesh& mesh = cornerMesh.mesh;
  detail::WorkspaceData& ws = workspace.data();
  detail::ensureSize(ws.meshPositions, 3 * cornerCount);
  detail::ensureSize(ws.meshNormals, 3 * cornerCount);
  detail::ensureSize(ws.meshUvs, 2 * cornerCount);
  detail::ensureSize(ws.meshTangents, 4 * cornerCount);
  detail::ensureSize(ws.meshIndices, cornerCount);
  float* positions = ws.meshPositions.data();
  float* normals = ws.meshNormals.data();
  float* uvs = ws.meshUvs.data();
  float* tangents = ws.meshTangents.data();
  std::uint32_t* indices = ws.meshIndices.data();
  ws.threads = threadCount(options);
  auto inArena = [&](const auto& body) { detail::onThreads(ws, [&] { detail::forRange(ws, cornerCount, 1 << 14, body); }); };
  inArena([&](std::size_t begin, std::size_t end) {
    for (std::size_t c = begin; c < end; ++c) {
      const auto halfedge = cornerMesh.cornerHalfedge[c];
      const auto& p = mesh.point(mesh.to_vertex_handle(halfedge));
      const auto& n = mesh.normal(halfedge);
      const auto& uv = mesh.texcoord2D(halfedge);
      for (int i = 0; i < 3; ++i) {
        positions[3 * c + i] = static_cast<float>(p[i]);
        normals[3 * c + i] = static_cast<float>(n[i]);
      }
      uvs[2 * c] = static_cast<float>(uv[0]);
      uvs[2 * c + 1] = static_cast<float>(uv[1]);
      indices[c] = static_cast<std::uint32_t>(c);
    }
  });
  const MeshArrays arrays{std::span<const float>(positions, 3 * cornerCount), std::span<const float>(normals, 3 * cornerCount),
                          std::span<const float>(uvs, 2 * cornerCount), std::span<const std::uint32_t>(indices, cornerCount)};
  Report report = computeCornerTangents(arrays, CornerOutputs{std::span<float>(tangents, 4 * cornerCount), cornerSources, {}},
                                        options, workspace);
  report.nonManifoldFaces = std::max(report.nonManifoldFaces, cornerMesh.nonManifoldFaces);
  report.splitVertices = 0;  // corners of the half-edge mesh are its vertices here
  report.outputVertices = cornerCount;
  inArena([&](std::size_t begin, std::size_t end) {
    for (std::size_t c = begin; c < end; ++c) {
      const float* t = &tangents[4 * c];
      cornerMesh.mesh.property(cornerMesh.tangent, cornerMesh.cornerHalfedge[c]) = TangentVec(t[0], t[1], t[2], t[3]);
    }
  });
  return report;
}

}  // namespace tangent
