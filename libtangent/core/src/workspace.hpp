// SPDX-License-Identifier: MIT
// Scratch memory of one call, kept between calls (TangentWorkspace), and the phases that every
// method shares: checking the arrays, welding corners by value, bucketing corners by welded
// vertex, and the vertex split of the output. The parallel helpers on the workspace's threads
// are in parallel.hpp.
#pragma once

#include "thread_backend.hpp"
#if defined(TANGENT_ONETBB)
#include <tbb/combinable.h>
#include <tbb/cache_aligned_allocator.h>
#include <tbb/enumerable_thread_specific.h>
#elif defined(TANGENT_STD_THREADS)
#include "thread_pool.hpp"
#endif

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <type_traits>
#include <optional>
#include <span>
#include <vector>

#include "tangent/bulk_buffer.hpp"
#include "state_bits.hpp"
#include "triangle_tangent.hpp"
#include "tangent/tangent.hpp"

namespace tangent::detail {

constexpr std::uint32_t kNone = ~std::uint32_t(0);
constexpr std::size_t kBucketIdPadding = 16;

#if defined(TANGENT_SERIAL)
// Built without threads (TANGENT_SERIAL: the WebAssembly package): one of each, in the
// shape of the oneTBB types used below.
template <typename T>
struct Combinable {
  T value{};
  T& local() { return value; }
  template <typename F>
  void combine_each(F f) const {
    f(value);
  }
  template <typename F>
  T combine(F) const {
    return value;
  }
};
template <typename T>
using PerThread = Combinable<T>;
template <typename T>
using ScratchAllocator = std::allocator<T>;
// The operations of std::atomic_ref used by the weld, on a plain reference (one thread).
template <typename T>
class AtomicRef {
 public:
  explicit AtomicRef(T& value) : value_(value) {}
  T load(std::memory_order) const { return value_; }
  bool compare_exchange_weak(T& expected, T desired, std::memory_order) {
    if (value_ != expected) {
      expected = value_;
      return false;
    }
    value_ = desired;
    return true;
  }
  void store(T desired, std::memory_order) { value_ = desired; }
  T fetch_add(T add, std::memory_order) {
    const T old = value_;
    value_ += add;
    return old;
  }

 private:
  T& value_;
};
#elif defined(TANGENT_STD_THREADS)
// Built with the standard library's threads (thread_pool.hpp): its types in oneTBB's place.
template <typename T>
using AtomicRef = BuiltinAtomicRef<T>;
template <typename T>
using PerThread = Combinable<T>;
template <typename T>
using ScratchAllocator = CacheAlignedAllocator<T>;
#else
template <typename T>
using AtomicRef = std::atomic_ref<T>;
template <typename T>
using Combinable = tbb::combinable<T>;
template <typename T>
using PerThread = tbb::enumerable_thread_specific<T>;
template <typename T>
using ScratchAllocator = tbb::cache_aligned_allocator<T>;
#endif

// Scratch of one worker thread: small arrays reused bucket after bucket. They are written
// for every bucket, so no cache line of one thread's scratch may hold another thread's: with
// the heap's small blocks side by side, the two-thread group pass ran at 60% of the speed of
// one thread per thread (false sharing); hence a cache-aligned allocator.
template <typename T>
using ScratchVector = std::vector<T, ScratchAllocator<T>>;
struct BucketScratch {
  ScratchVector<std::uint64_t> keys;
  ScratchVector<std::uint32_t> items;
  ScratchVector<std::uint32_t> parent;
  ScratchVector<double> values;
  // The bucketing from four threads (weld.cpp, bucketByRanges): one range's ids set aside.
  ScratchVector<std::uint32_t> rangeIds;
  // The non-manifold count from four threads (lengyel.cpp): one range's edges set aside.
  ScratchVector<std::uint64_t> rangeEdges;
  ScratchVector<std::uint16_t> rangeLows;
};


// BulkAllocator for arrays of small value classes (Vec3, TriangleTerms) that every pass writes
// before it reads: resize() leaves new elements unwritten, as BulkVector leaves numbers. Their
// member initializers (zeros) would write every byte of a resized array, which in a new
// process costs a page fault per page, and makes resident the whole of an array written in a
// few places (the invalid normals' replacements: 72 bytes a triangle, for lengyel, meshopt
// and flat). Only for types whose objects need no construction (trivially copyable and
// destructible: the allocation itself creates them).
template <typename T>
struct UnwrittenAllocator : BulkAllocator<T> {
  static_assert(std::is_trivially_copyable_v<T> && std::is_trivially_destructible_v<T>);
  UnwrittenAllocator() noexcept = default;
  template <typename U>
  UnwrittenAllocator(const UnwrittenAllocator<U>&) noexcept {}
  using BulkAllocator<T>::construct;  // copies and other constructions as BulkAllocator does them
  template <typename U>
  void construct(U*) noexcept {}  // hides BulkAllocator's default construction
};
template <typename T>
using UnwrittenVector = std::vector<T, UnwrittenAllocator<T>>;

struct WorkspaceData {
  unsigned threads = 1;
  // The mikktspace kernel's shortcut for a plain fan (fastBucket); off, every bucket takes the
  // full grouping. Only tests turn it off, to check that both agree (to the last bits of a
  // frame: the shortcut's sums are rounded to a grid, the full grouping's are not).
  bool fastBuckets = true;
  // TangentWorkspace::setReleaseAsItGoes: each large array freed once the call is done with it.
  bool releaseAsItGoes = false;
  std::size_t vertexCount = 0, cornerCount = 0;
  BulkVector<std::uint32_t> table;          // open-addressing weld table(s) (vertex + 1, 0 empty)
  BulkVector<std::uint32_t> weldCounts;     // threaded weld: per-chunk counts, partition starts
  BulkVector<std::uint32_t> vertexId;       // welded id of each input vertex: the smallest
                                             // vertex index with the same values
  bool weldMergedNone = false;              // set by the weld: every vertex is its own welded id
                                             // (vertexId[v] == v), so a corner's id is its index
  // TangentWorkspace::setWeldOnly: the only vertices the weld compares; unset, every vertex.
  std::optional<std::span<const std::uint32_t>> weldOnly;
  BulkVector<std::uint32_t> bucketStart;    // vertexCount + 1: corners of welded id v are
  BulkVector<std::uint32_t> bucketCorners;  // bucketCorners[bucketStart[v] .. bucketStart[v+1])
  // With the buckets where the kernel asks for them (weldAndBucket's `edges`): each bucketed
  // corner's next and previous identities (welded ids), at its bucketCorners slot; then
  // kBucketIdPadding slots that may be read (never used), so that a vector load of a bucket's
  // ids need not stop at the end.
  BulkVector<std::uint32_t> bucketNextId, bucketPreviousId;
  BulkVector<std::int8_t> orientation;      // per triangle: sign of the UV area (resolved)
  BulkVector<std::uint8_t> triangleFlags;   // per triangle: TriangleFlag bits
  BulkVector<std::uint32_t> cornerLink;     // per corner: neighbour, then group weight bits
                                             // (state_bits.hpp says which when)
  BulkVector<std::uint8_t> cornerState;     // per corner: CornerState bits (state_bits.hpp)
  BulkVector<std::uint32_t> bucketExtra;    // per welded id: extra output vertices, then offsets
  BulkVector<std::uint8_t> bucketUniform;   // per welded id: BucketChain, then BucketUniform
                                             // bits (state_bits.hpp)
  // lengyel, meshopt and flat: the triangle pass's results (TriangleData, lengyel.hpp) ...
  UnwrittenVector<TriangleTerms> triangleTerms;
  UnwrittenVector<Vec3> cornerNormals;  // written where a normal is invalid only: mostly never touched
  BulkVector<double> cornerWeights;
  BulkVector<std::uint8_t> invalidNormal;
  UnwrittenVector<Vec3> vertexUnitNormals;    // per vertex, read by each of its corners
  BulkVector<std::uint8_t> vertexNormalInvalid;
  // ... and each vertex's position representative (the smallest vertex
  // with the same position bits) and the open-addressing table that finds it (lengyel.cpp).
  BulkVector<std::uint32_t> positionRepresentative, positionTable;
  // ... and the non-manifold count's edges, by their smaller end (lengyel.cpp): on one or two
  // threads each edge's other end (edgeEnds), from four each edge's other end and triangle.
  BulkVector<std::uint32_t> edgeStart, edgeNext, edgeEnds;
  BulkVector<std::uint64_t> edges;
  BulkVector<std::uint8_t> onSharedEdge;
  // ... from four threads, first by ranges of smaller ends: per-chunk counters then the
  // ranges' starts, and each edge's smaller end within its range.
  BulkVector<std::uint32_t> edgeCounts;
  BulkVector<std::uint16_t> edgeLowInRange;
  PerThread<BucketScratch> scratch;
  // Strided or 16-bit-indexed input, packed (entry.cpp).
  BulkVector<float> packedPositions, packedNormals, packedUvs;
  BulkVector<std::uint32_t> packedIndices;
  // The OpenMesh call's corners as arrays (openmesh/src/compute_tangents.cpp).
  TangentWorkspace::AdapterBuffers adapter;

  std::size_t bytes() const;
};

// std::bit_cast for the few trivially copyable types used here (the WebAssembly toolchain's
// standard library lacks it).
template <typename To, typename From>
inline To bitCast(const From& from) {
  static_assert(sizeof(To) == sizeof(From));
  To to;
  std::memcpy(&to, &from, sizeof to);
  return to;
}

// A hint that *address will be read soon (no effect where the compiler has no such builtin).
inline void prefetch(const void* address) {
#if defined(__GNUC__) || defined(__clang__)
  __builtin_prefetch(address);
#else
  (void)address;
#endif
}

// The bits of a float with -0 taken as +0: the order and hash of values that compare equal.
// (Integer only: x == 0 exactly where the bits without the sign are 0.)
inline std::uint32_t canonicalBits(float x) {
  const auto bits = bitCast<std::uint32_t>(x);
  return (bits << 1) == 0 ? 0u : bits;
}

// A fixed unit vector perpendicular to the unit normal n, for a corner with no frame to
// borrow: the axis least aligned with n, made orthogonal to it.
inline void axisPerpendicular(const double n[3], double out[3]) {
  const double a[3] = {std::abs(n[0]), std::abs(n[1]), std::abs(n[2])};
  const int axis = a[0] <= a[1] && a[0] <= a[2] ? 0 : (a[1] <= a[2] ? 1 : 2);
  double t[3] = {0, 0, 0};
  t[axis] = 1;
  const double along = n[0] * t[0] + n[1] * t[1] + n[2] * t[2];
  for (int i = 0; i < 3; ++i) t[i] = t[i] - n[i] * along;
  const double scale = 1.0 / std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
  for (int i = 0; i < 3; ++i) out[i] = t[i] * scale;
}

// Sorts the few keys of one bucket: insertion sort up to two dozen, std::sort beyond.
template <typename T>
void sortSmall(T* begin, T* end) {
  if (end - begin < 2) return;  // also an empty range at a null pointer
  if (end - begin > 24) {
    std::sort(begin, end);
    return;
  }
  for (T* i = begin + 1; i < end; ++i) {
    const T value = *i;
    T* j = i;
    for (; j > begin && *(j - 1) > value; --j) *j = *(j - 1);
    *j = value;
  }
}

// Grows v to at least n elements (never shrinks, so a reused workspace allocates nothing).
template <typename Vector>
void ensureSize(Vector& v, std::size_t n) {
  if (v.size() < n) v.resize(n);
}

// Frees each of `arrays` where the workspace gives memory back as the call goes
// (releaseAsItGoes) and the array is a large one (2 MiB and more: mapped on its own, so freeing
// it lowers the process's resident memory at once). Called where a phase has read them for the
// last time in this call; a later phase or call allocates them again (ensureSize).
template <typename... Vectors>
void releaseWhenDone(WorkspaceData& ws, Vectors&... arrays) {
  if (!ws.releaseAsItGoes) return;
  auto release = [](auto& v) {
    using Vector = std::remove_reference_t<decltype(v)>;
    if (v.capacity() * sizeof(typename Vector::value_type) >= kHugePage) Vector().swap(v);
  };
  (release(arrays), ...);
}

// Checks the input arrays' sizes; throws std::invalid_argument naming the array (the one
// statement of these checks and their messages: every entry point and buildCornerMesh).
void checkArraySizes(const MeshArrays& mesh);
// The same, and the outputs' sizes.
void checkArrays(const MeshArrays& mesh, const CornerOutputs& outputs);
// Checks every index against the vertex count on ws's threads; std::invalid_argument naming
// the first one out of range.
void checkIndices(const WorkspaceData& ws, const MeshArrays& mesh);

// Starts a call on checked arrays: records the counts in ws, resets its per-call state and
// checks every index (in parallel, inside the call's arena; std::invalid_argument naming the
// first one out of range). Every path calls it before anything reads through the indices.
void beginCall(WorkspaceData& ws, const MeshArrays& mesh);

// Welds vertices by exact (position, normal, UV) value as the reference does (+0 and -0
// equal), then buckets the corners by welded id, each bucket in corner order (after
// beginCall). `threads` picks the way, with the same bits for any: one table and one slice
// of counters for one thread, the least work; at most ws.threads, fewer where other work
// runs beside it. Writes only the weld's and the buckets' arrays (table, weldCounts,
// vertexId, bucketStart, bucketCorners, bucketExtra; cornerLink from four threads, which the
// caller sizes first; bucketNextId and bucketPreviousId with `edges`), so that passes on other
// arrays may run beside it.
void weldAndBucket(WorkspaceData& ws, const MeshArrays& mesh, unsigned threads, bool edges = false);

// The method `mikktspace` on checked arrays: beginCall, then the weld and buckets beside the
// triangle pass, groups, output pass (finishOutputs), on the calling thread's arena.
Report mikktspaceOnArrays(WorkspaceData& ws, const MeshArrays& mesh, const CornerOutputs& outputs, const Options& options);

// The vector width of the triangle passes: mikktspace's floats scalar, four lanes (SSE2 on x86,
// SIMD128 in WebAssembly; never both in one build) or eight (AVX2); lengyel's, meshopt's and
// flat's doubles scalar, two lanes or four (AVX2). Every width gives the same bits.
enum class VectorIsa : std::uint8_t { scalar, sse2, simd128, avx2 };
// The widest this build and this processor have, capped by the environment variable
// TANGENT_MAX_CPU_ISA where it names one of them (scalar, sse2, simd128, avx2). Read at each
// call.
VectorIsa activeVectorIsa();

// What mikktspace's kernel hands the output pass, so that it can skip work; lengyel and flat
// hand nothing (the defaults).
struct KernelOutcome {
  // The kernel wrote w with the UV origin applied and counted the corners with w < 0 (copies
  // of duplicate triangles aside): the output pass need not read every tangent.
  bool wInOutputConvention = false;
  std::uint64_t mirroredCorners = 0;
  bool anyCopy = true;  // a corner may be kCopy: the copy pass must run
  // Per welded id, BucketUniform bits (state_bits.hpp), or null where not known.
  const std::uint8_t* bucketUniform = nullptr;
  // The kernel wrote outputs.cornerVertex (the input vertex) for every corner of each bucket
  // it marked kUniformVertex: the vertex split need not visit their corners again.
  bool uniformVerticesWritten = false;
};

// Copies duplicate corners, applies the UV origin to w (unless kernel.wInOutputConvention),
// counts sources and mirrored corners, and works out the vertex split (outputs.cornerVertex
// when asked for).
void finishOutputs(WorkspaceData& ws, const MeshArrays& mesh, const CornerOutputs& outputs, const Options& options,
                   Report& report, const KernelOutcome& kernel = {});

}  // namespace tangent::detail
