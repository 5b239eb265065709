// SPDX-License-Identifier: MIT
// The workspace, and the checks every call starts with: array sizes, then every index.
#include "parallel.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cstring>
#include <limits>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace tangent {
namespace detail {

std::size_t WorkspaceData::bytes() const {
  auto size = [](const auto& v) { return v.capacity() * sizeof(v[0]); };
  return size(table) + size(weldCounts) + size(vertexId) + size(bucketStart) + size(bucketCorners) + size(bucketNextId) + size(bucketPreviousId) +
         size(orientation) + size(triangleFlags) + size(cornerLink) + size(cornerState) + adapter.bytes() + size(packedPositions) + size(packedNormals) +
         size(packedUvs) + size(packedIndices) +
         size(bucketExtra) + size(bucketUniform) + size(positionRepresentative) + size(positionTable) +
         size(triangleTerms) + size(cornerNormals) + size(cornerWeights) + size(invalidNormal) +
         size(vertexUnitNormals) + size(vertexNormalInvalid) + size(edgeStart) + size(edgeNext) + size(edgeEnds) + size(edges) +
         size(onSharedEdge) + size(edgeCounts) + size(edgeLowInRange);
}

void checkArraySizes(const MeshArrays& mesh) {
  auto fail = [](const std::string& what) { throw std::invalid_argument(what); };
  if (mesh.positions.size() % 3 != 0) fail("positions: size " + std::to_string(mesh.positions.size()) + " is not a multiple of 3");
  const std::size_t vertexCount = mesh.positions.size() / 3;
  if (vertexCount >= kNone) fail("positions: more than 2^32 - 2 vertices");
  if (mesh.normals.size() != vertexCount * 3)
    fail("normals: expected " + std::to_string(vertexCount * 3) + " floats, got " + std::to_string(mesh.normals.size()));
  if (mesh.uvs.size() != vertexCount * 2)
    fail("uvs: expected " + std::to_string(vertexCount * 2) + " floats, got " + std::to_string(mesh.uvs.size()));
  if (mesh.indices.size() % 3 != 0) fail("indices: size " + std::to_string(mesh.indices.size()) + " is not a multiple of 3");
  const std::size_t cornerCount = mesh.indices.size();
  if (cornerCount >= kNone) fail("indices: more than 2^32 - 2 corners");
}

void checkArrays(const MeshArrays& mesh, const CornerOutputs& outputs) {
  auto fail = [](const std::string& what) { throw std::invalid_argument(what); };
  checkArraySizes(mesh);
  const std::size_t cornerCount = mesh.indices.size();
  if (outputs.tangents.size() != cornerCount * 4)
    fail("tangents: expected " + std::to_string(cornerCount * 4) + " floats (4 per corner), got " +
         std::to_string(outputs.tangents.size()));
  if (!outputs.sources.empty() && outputs.sources.size() != cornerCount)
    fail("sources: expected " + std::to_string(cornerCount) + " entries (one per corner), got " +
         std::to_string(outputs.sources.size()));
  if (!outputs.cornerVertex.empty() && outputs.cornerVertex.size() != cornerCount)
    fail("cornerVertex: expected " + std::to_string(cornerCount) + " entries (one per corner), got " +
         std::to_string(outputs.cornerVertex.size()));
}

namespace {

// Whether any of indices[begin, end) is count or more (0 < count < 2^32). Written out in
// SSE2: at -O2, GCC left the plain loop scalar (0.6 ns an index, 2% of the call at 1e5).
bool anyAtLeast(const std::uint32_t* indices, std::size_t begin, std::size_t end, std::uint32_t count) {
  std::size_t i = begin;
  bool any = false;
#if defined(__SSE2__)
  // Unsigned x > count - 1 as a signed compare, both sides with the top bit flipped.
  const __m128i flip = _mm_set1_epi32(INT32_MIN);
  const __m128i last = _mm_set1_epi32(static_cast<std::int32_t>((count - 1) ^ 0x80000000u));
  __m128i over = _mm_setzero_si128();
  for (; i + 16 <= end; i += 16) {
    for (std::size_t k = 0; k < 16; k += 4) {
      const __m128i x = _mm_loadu_si128(reinterpret_cast<const __m128i*>(indices + i + k));
      over = _mm_or_si128(over, _mm_cmpgt_epi32(_mm_xor_si128(x, flip), last));
    }
  }
  any = _mm_movemask_epi8(over) != 0;
#endif
  for (; i < end; ++i) any |= indices[i] >= count;
  return any;
}

}  // namespace

// Whether every index is in range, in parallel (a pass over the whole index array: serial,
// it was 8% of the call's wall time on 16 CPUs); only where one is not, the first such
// index, named.
void checkIndices(const WorkspaceData& ws, const MeshArrays& mesh) {
  const std::uint32_t* indices = mesh.indices.data();
  const std::size_t cornerCount = mesh.indices.size(), vertexCount = mesh.positions.size() / 3;
  if (vertexCount > std::numeric_limits<std::uint32_t>::max()) return;  // every 32-bit index is in range
  std::atomic<bool> outOfRange{vertexCount == 0 && cornerCount > 0};
  if (vertexCount > 0) {
    forRange(ws, cornerCount, 1 << 16, [&](std::size_t begin, std::size_t end) {
      if (anyAtLeast(indices, begin, end, static_cast<std::uint32_t>(vertexCount))) outOfRange.store(true, std::memory_order_relaxed);
    });
  }
  if (!outOfRange.load(std::memory_order_relaxed)) return;
  for (std::size_t i = 0; i < cornerCount; ++i) {
    if (indices[i] >= vertexCount)
      throw std::invalid_argument("indices[" + std::to_string(i) + "] = " + std::to_string(indices[i]) +
                                  " is out of range (vertex count " + std::to_string(vertexCount) + ")");
  }
}

void beginCall(WorkspaceData& ws, const MeshArrays& mesh) {
  ws.vertexCount = mesh.positions.size() / 3;
  ws.cornerCount = mesh.indices.size();
  checkIndices(ws, mesh);
}

}  // namespace detail

TangentWorkspace::TangentWorkspace() : data_(std::make_unique<detail::WorkspaceData>()) {}
TangentWorkspace::~TangentWorkspace() = default;
TangentWorkspace::TangentWorkspace(TangentWorkspace&&) noexcept = default;
TangentWorkspace& TangentWorkspace::operator=(TangentWorkspace&&) noexcept = default;
std::size_t TangentWorkspace::bytesReserved() const { return data_->bytes(); }
void TangentWorkspace::setWeldOnly(std::optional<std::span<const std::uint32_t>> vertices) { data_->weldOnly = vertices; }
void TangentWorkspace::setReleaseAsItGoes(bool release) { data_->releaseAsItGoes = release; }
bool TangentWorkspace::releasesAsItGoes() const { return data_->releaseAsItGoes; }
TangentWorkspace::AdapterBuffers& TangentWorkspace::adapterBuffers() { return data_->adapter; }
std::size_t TangentWorkspace::AdapterBuffers::bytes() const {
  auto size = [](const auto& v) { return v.capacity() * sizeof(v[0]); };
  return size(positions) + size(normals) + size(uvs) + size(tangents) + size(indices) + size(vertexCorner) + size(vertexValues) +
         size(list);
}

namespace {

std::atomic<std::size_t> cacheLimit{kDefaultWorkspaceCacheLimit};

// One thread's cached workspace. Its owner leases it for a call; releaseCachedWorkspaces()
// from any thread frees it when not leased, hence the mutex (never contended in a call).
struct ThreadCache {
  std::mutex mutex;
  std::unique_ptr<TangentWorkspace> workspace;
  bool leased = false;
  ThreadCache();
  ~ThreadCache();
};

// Every live thread's cache (a thread's is listed on its first plain call, removed at its
// end). Never destroyed: worker threads may end after the static objects are gone.
std::mutex& registryMutex() {
  static auto* mutex = new std::mutex;
  return *mutex;
}
std::vector<ThreadCache*>& registry() {
  static auto* caches = new std::vector<ThreadCache*>;
  return *caches;
}
ThreadCache::ThreadCache() {
  std::lock_guard lock(registryMutex());
  registry().push_back(this);
}
ThreadCache::~ThreadCache() {
  std::lock_guard lock(registryMutex());
  std::erase(registry(), this);
}

ThreadCache& threadCache() {
  thread_local ThreadCache cache;
  return cache;
}

}  // namespace

CachedWorkspace::CachedWorkspace() {
  if (cacheLimit.load(std::memory_order_relaxed) > 0) {
    ThreadCache& cache = threadCache();
    std::lock_guard lock(cache.mutex);
    if (!cache.leased) {
      if (!cache.workspace) cache.workspace = std::make_unique<TangentWorkspace>();
      cache.leased = true;
      workspace_ = cache.workspace.get();
      return;
    }
  }
  own_ = std::make_unique<TangentWorkspace>();
  workspace_ = own_.get();
}

CachedWorkspace::~CachedWorkspace() {
  if (own_) return;
  ThreadCache& cache = threadCache();
  std::lock_guard lock(cache.mutex);
  cache.leased = false;
  if (cache.workspace->bytesReserved() > cacheLimit.load(std::memory_order_relaxed)) cache.workspace.reset();
}

std::size_t workspaceCacheLimit() { return cacheLimit.load(std::memory_order_relaxed); }
void setWorkspaceCacheLimit(std::size_t bytes) { cacheLimit.store(bytes, std::memory_order_relaxed); }

void releaseCachedWorkspaces() {
  std::lock_guard lock(registryMutex());
  for (ThreadCache* cache : registry()) {
    std::lock_guard cacheLock(cache->mutex);
    if (!cache->leased) cache->workspace.reset();
  }
}

std::size_t cachedWorkspaceBytes() {
  std::lock_guard lock(registryMutex());
  std::size_t bytes = 0;
  for (ThreadCache* cache : registry()) {
    std::lock_guard cacheLock(cache->mutex);
    if (cache->workspace) bytes += cache->workspace->bytesReserved();
  }
  return bytes;
}

}  // namespace tangent
