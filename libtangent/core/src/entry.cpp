// SPDX-License-Identifier: MIT
// The array entry point: the arrays checked once, the threads resolved once, one switch on
// the method; every method runs on these arrays and the same workspace.
#include "thread_backend.hpp"
#if defined(TANGENT_ONETBB)
#include <tbb/info.h>
#endif

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>

#include "lengyel.hpp"
#include "parallel.hpp"

namespace tangent {

unsigned threadCount(const Options& options) {
  if (options.threads > 0) return options.threads;
#if defined(TANGENT_SERIAL)
  return 1;  // built without threads
#elif defined(TANGENT_STD_THREADS)
  return detail::poolHardwareThreads();
#else
  return static_cast<unsigned>(std::max(1, tbb::info::default_concurrency()));
#endif
}

void checkMeshArrays(const MeshArrays& mesh) {
  detail::checkArraySizes(mesh);
  detail::WorkspaceData serial;  // one thread: a check outside any call
  detail::checkIndices(serial, mesh);
}

namespace {

// The one switch on the method, inside the call's arena, on checked arrays.
Report runMethod(detail::WorkspaceData& ws, const MeshArrays& mesh, const CornerOutputs& outputs, const Options& options) {
  switch (options.method) {
    case Method::mikktspace: return detail::mikktspaceOnArrays(ws, mesh, outputs, options);
    case Method::lengyel: return detail::lengyelOnArrays(ws, mesh, outputs, options, detail::Grouping::byValue);
    case Method::flat: return detail::lengyelOnArrays(ws, mesh, outputs, options, detail::Grouping::perFace);
    case Method::meshopt: return detail::lengyelOnArrays(ws, mesh, outputs, options, detail::Grouping::byValue);
  }
  throw std::invalid_argument("options.method: not a Method");
}

void checkStrided(const StridedMesh& mesh) {
  auto check = [&](const char* name, const void* data, std::size_t stride, std::size_t size) {
    if (stride < size)
      throw std::invalid_argument(std::string(name) + ": stride " + std::to_string(stride) + " is less than " +
                                  std::to_string(size) + " bytes");
    if (data == nullptr && mesh.vertexCount > 0) throw std::invalid_argument(std::string(name) + ": null");
  };
  check("positions", mesh.positions, mesh.positionStride, 3 * sizeof(float));
  check("normals", mesh.normals, mesh.normalStride, 3 * sizeof(float));
  check("uvs", mesh.uvs, mesh.uvStride, 2 * sizeof(float));
  if (mesh.indices == nullptr && mesh.indexCount > 0) throw std::invalid_argument("indices: null");
}

// `count` vertices of `width` floats, `stride` bytes apart, packed into `out` (in parallel).
void packFloats(const detail::WorkspaceData& ws, const void* data, std::size_t stride, int width, std::size_t count,
                BulkVector<float>& out) {
  detail::ensureSize(out, width * count);
  const auto* bytes = static_cast<const std::byte*>(data);
  float* packed = out.data();
  detail::forRange(ws, count, 1 << 14, [&](std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) std::memcpy(packed + width * v, bytes + v * stride, width * sizeof(float));
  });
}

}  // namespace

Report computeCornerTangents(const MeshArrays& mesh, const CornerOutputs& outputs, const Options& options,
                             TangentWorkspace& workspace) {
  detail::checkArrays(mesh, outputs);
  detail::WorkspaceData& ws = workspace.data();
  ws.threads = threadCount(options);
  Report report;
  detail::onThreads(ws, [&] { report = runMethod(ws, mesh, outputs, options); });
  return report;
}

Report computeCornerTangents(const StridedMesh& mesh, const CornerOutputs& outputs, const Options& options,
                             TangentWorkspace& workspace) {
  checkStrided(mesh);
  const std::size_t vertexCount = mesh.vertexCount, cornerCount = mesh.indexCount;
  detail::WorkspaceData& ws = workspace.data();
  ws.threads = threadCount(options);
  // Read in place where the layout is the packed one and the pointers are aligned for it.
  auto packed = [](const void* data, std::size_t stride, std::size_t size) {
    return stride == size && reinterpret_cast<std::uintptr_t>(data) % alignof(float) == 0;
  };
  const bool floatsInPlace = packed(mesh.positions, mesh.positionStride, 12) && packed(mesh.normals, mesh.normalStride, 12) &&
                             packed(mesh.uvs, mesh.uvStride, 8);
  const bool indicesInPlace =
      mesh.indexType == IndexType::uint32 && reinterpret_cast<std::uintptr_t>(mesh.indices) % alignof(std::uint32_t) == 0;
  Report report;
  detail::onThreads(ws, [&] {
    MeshArrays arrays;
    if (floatsInPlace) {
      arrays.positions = {static_cast<const float*>(mesh.positions), 3 * vertexCount};
      arrays.normals = {static_cast<const float*>(mesh.normals), 3 * vertexCount};
      arrays.uvs = {static_cast<const float*>(mesh.uvs), 2 * vertexCount};
    } else {
      packFloats(ws, mesh.positions, mesh.positionStride, 3, vertexCount, ws.packedPositions);
      packFloats(ws, mesh.normals, mesh.normalStride, 3, vertexCount, ws.packedNormals);
      packFloats(ws, mesh.uvs, mesh.uvStride, 2, vertexCount, ws.packedUvs);
      arrays.positions = {ws.packedPositions.data(), 3 * vertexCount};
      arrays.normals = {ws.packedNormals.data(), 3 * vertexCount};
      arrays.uvs = {ws.packedUvs.data(), 2 * vertexCount};
    }
    if (indicesInPlace) {
      arrays.indices = {static_cast<const std::uint32_t*>(mesh.indices), cornerCount};
    } else {
      detail::ensureSize(ws.packedIndices, cornerCount);
      const auto* bytes = static_cast<const std::byte*>(mesh.indices);
      const bool narrow = mesh.indexType == IndexType::uint16;
      std::uint32_t* wide = ws.packedIndices.data();
      detail::forRange(ws, cornerCount, 1 << 16, [&](std::size_t begin, std::size_t end) {
        for (std::size_t c = begin; c < end; ++c) {
          if (narrow) {
            std::uint16_t index;
            std::memcpy(&index, bytes + 2 * c, sizeof index);
            wide[c] = index;
          } else {
            std::memcpy(&wide[c], bytes + 4 * c, sizeof wide[c]);
          }
        }
      });
      arrays.indices = {wide, cornerCount};
    }
    detail::checkArrays(arrays, outputs);
    report = runMethod(ws, arrays, outputs, options);
  });
  return report;
}

Report computeCornerTangents(const MeshArrays& mesh, std::span<float> cornerTangents, const Options& options,
                             std::span<FrameSource> cornerSources) {
  CachedWorkspace workspace;
  return computeCornerTangents(mesh, CornerOutputs{cornerTangents, cornerSources, {}}, options, workspace.get());
}

}  // namespace tangent
