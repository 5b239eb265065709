// SPDX-License-Identifier: MIT
// libtangent core API: tangent frames for triangle meshes.
//
// The core computes and opens no files, and needs no OpenMesh. One entry point,
// computeCornerTangents(), over plain arrays (positions, normals, UVs, indices in; one tangent
// per corner and a Report out), for every method. OpenMesh users have tangent/openmesh.hpp
// (target tangent::openmesh), which calls this one.
#pragma once

#include <array>
#include <concepts>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "tangent/bulk_buffer.hpp"

namespace tangent {

// Which algorithm computes the frames.
enum class Method : std::uint8_t {
  // MikkTSpace (M. Mikkelsen, "Simulation of Wrinkled Surfaces Revisited", 2008, and the
  // reference implementation's rules): per-triangle tangents projected onto each corner's
  // normal, averaged with angle weights over the corners of a vertex that are connected
  // through shared edges with identical position, normal and UV and the same UV orientation.
  // What nearly every normal-map baker uses and what glTF asks for. Default.
  mikktspace,
  // Lengyel, "Computing Tangent Space Basis Vectors for an Arbitrary Mesh" (2001):
  // per-triangle tangent/bitangent from edge and UV deltas, accumulated over the corners of
  // a vertex that share position, normal, UV and UV orientation, then Gram-Schmidt
  // orthogonalized against the normal. Weighting is selectable (see Weighting).
  lengyel,
  // One frame per face (no smoothing): the triangle's tangent orthogonalized against each
  // corner's normal. Requires nothing beyond the triangle itself.
  flat,
  // meshoptimizer's default weighting (meshopt_generateTangents without
  // meshopt_TangentCompatible, meshoptimizer 1.x; what Godot's importer and gltfpack -gt use):
  // lengyel's groups and sums, each corner's term weighted by the angle between its two edges
  // projected onto the normal's plane times the product of those projected edge lengths (so
  // slivers count less than by angle alone), w from the UV orientation. For matching an engine
  // that computes tangents this way; a normal map baked with MikkTSpace wants `mikktspace`.
  meshopt,
};

// How the triangles around a vertex are weighted when their tangents are accumulated.
enum class Weighting : std::uint8_t {
  angle,    // corner angle (default; independent of tessellation)
  area,     // triangle area in 3D
  uniform,  // every triangle counts once
};

// Where the texture's v = 0 lies. It decides the sign of w, never the tangent direction.
enum class UvOrigin : std::uint8_t {
  topLeft,     // glTF, DirectX: w is negated relative to the frame on the stored UVs
  bottomLeft,  // OpenGL, OBJ, MikkTSpace's native convention
};

// glTF's UV origin: what bake and check compute and expect TANGENT in.
inline constexpr UvOrigin kGltfUvOrigin = UvOrigin::topLeft;

// The one rule for handedness: the w of a frame whose UVs, as stored, turn with
// `uvOrientation` (the sign of the signed UV area, +1 counter-clockwise, -1 clockwise; 0 where
// undefined stays 0), in the convention of `origin`. bottomLeft keeps the orientation
// (MikkTSpace's own sign); topLeft negates it, so in glTF w = -sign(UV area) (README, "glTF's
// w convention"). The core, tangent check and the viewer's shaders all take it from here.
template <std::floating_point T>
constexpr T handedness(T uvOrientation, UvOrigin origin) {
  return uvOrientation * (origin == UvOrigin::topLeft ? T(-1) : T(1));
}

struct Options {
  Method method = Method::mikktspace;
  Weighting weighting = Weighting::angle;  // lengyel only; mikktspace and meshopt have their own
  UvOrigin uvOrigin = UvOrigin::topLeft;
  unsigned threads = 0;                    // worker threads, 0: all hardware threads; the output
                                           // never depends on it
};

// The worker threads a call with these options runs on, whatever the method: options.threads,
// or where that is 0 every hardware thread this process may use (oneTBB's default
// concurrency, which follows the process's CPU affinity). One pool (oneTBB) runs them all.
unsigned threadCount(const Options& options);

// Where a corner's frame came from.
enum class FrameSource : std::uint8_t {
  computed,   // from the triangles of its group
  inherited,  // a degenerate triangle's corner copied the frame of a corner with the same
              // position, normal and UV (MikkTSpace's rule for degenerate triangles)
  neighbour,  // no usable triangle: borrowed from another corner of its vertex or its 1-ring
  fixed,      // nothing to borrow: a fixed unit vector perpendicular to the normal
};

// What a call did. Every count is of input triangles or corners; nothing is silent.
struct Report {
  Method method = Method::mikktspace;  // method actually used
  std::optional<Weighting> weighting;  // weighting actually used (none for flat and meshopt)
  std::uint64_t triangles = 0;
  std::uint64_t corners = 0;
  std::uint64_t degenerateTriangles = 0;    // zero or non-finite 3D area
  std::uint64_t zeroUvAreaTriangles = 0;    // zero UV area or collinear UVs
  std::uint64_t nonFiniteTriangles = 0;     // NaN/Inf in a position or UV of the triangle
  std::uint64_t mirroredCorners = 0;        // corners whose output w is -1
  std::uint64_t splitVertices = 0;          // extra vertices needed: corners of one input
                                            // vertex that got different frames
  // Faces on an edge that more than two faces share, with "edge" as each method sees one.
  // mikktspace, as the reference pairs edges: ends welded by position, normal and UV; an edge
  // counts where it runs more than once one way and at least once the other, an exact duplicate
  // triangle being a copy that does not count (so two same-wound faces on an edge with none
  // opposite are not counted). lengyel, flat and meshopt: ends welded by position alone; an
  // edge of three or more triangles whose corners are at three distinct positions. The two can
  // differ on one mesh: triangles (0,2,1), (0,2,4), (2,1,0), (2,4,1) give 0 and 4.
  std::uint64_t nonManifoldFaces = 0;
  std::uint64_t invalidNormals = 0;         // corners with zero/non-finite normal (replaced)
  std::uint64_t inheritedCorners = 0;       // FrameSource::inherited
  std::uint64_t fallbackFromNeighbours = 0; // FrameSource::neighbour
  std::uint64_t fallbackFixed = 0;          // FrameSource::fixed
  std::uint64_t outputVertices = 0;         // input vertices + splitVertices (see CornerOutputs)
};

// The vector instructions mikktspace's triangle pass uses on this machine: "avx2", "sse2",
// "simd128" (WebAssembly) or "scalar". The widest the build and the processor have, capped by
// the environment variable TANGENT_MAX_CPU_ISA where it names one of these ("sse2" and
// "simd128" both name four lanes; read at each call; other values are ignored). Every choice gives the same bits: the variable is for testing and comparing them.
std::string_view vectorIsa();

std::string_view toString(Method method);
std::string_view toString(Weighting weighting);
// Parse a name as accepted on the command line (the names toString gives); none if unknown.
std::optional<Method> parseMethod(std::string_view name);
std::optional<Weighting> parseWeighting(std::string_view name);

// UV origins by the names the command line, Python and the npm package use: "top-left",
// "bottom-left".
std::string_view toString(UvOrigin origin);
std::optional<UvOrigin> parseUvOrigin(std::string_view name);

// The report's counts by name, the one list of its field names: bake's JSON, Python and the
// npm package all give these, in this order.
struct ReportCount {
  std::string_view name;
  std::uint64_t value;
};
std::array<ReportCount, 13> reportCounts(const Report& report);
// The report as one JSON object: "method", "weighting" ("" for flat and meshopt), then reportCounts.
std::string reportJson(const Report& report);

// Plain-array input. Corners are the entries of `indices`, three per triangle.
struct MeshArrays {
  std::span<const float> positions;       // 3 per vertex
  std::span<const float> normals;         // 3 per vertex
  std::span<const float> uvs;             // 2 per vertex
  std::span<const std::uint32_t> indices; // 3 per triangle
};

// Input in the layout a vertex buffer has, as meshoptimizer's meshopt_generateTangents takes
// it: each attribute a pointer and a byte stride (attributes may interleave in one buffer;
// any alignment), indices 16- or 32-bit. The call gives the bits computeCornerTangents gives
// on the same values packed. Packed floats (strides 12, 12, 8) with 32-bit indices are read
// in place; any other layout is gathered into the workspace once (no copy by the caller).
enum class IndexType : std::uint8_t { uint16, uint32 };
struct StridedMesh {
  std::size_t vertexCount = 0;
  const void* positions = nullptr;  // 3 floats per vertex
  std::size_t positionStride = 3 * sizeof(float);  // bytes from one vertex's to the next's
  const void* normals = nullptr;    // 3 floats per vertex
  std::size_t normalStride = 3 * sizeof(float);
  const void* uvs = nullptr;        // 2 floats per vertex
  std::size_t uvStride = 2 * sizeof(float);
  const void* indices = nullptr;    // indexCount entries of indexType, 3 per triangle
  std::size_t indexCount = 0;
  IndexType indexType = IndexType::uint32;
};

// Checks the arrays as every call does (sizes, then every index), with the same messages:
// throws std::invalid_argument naming the array, or the first index out of range.
void checkMeshArrays(const MeshArrays& mesh);

namespace detail {
struct WorkspaceData;
}

// Scratch memory reused across calls: a caller that computes many meshes keeps one per thread
// and repeated mikktspace calls of the same or smaller size allocate nothing (lengyel, flat and
// meshopt allocate their per-call arrays apart from it and free them on return). Not for
// concurrent calls.
class TangentWorkspace {
 public:
  TangentWorkspace();
  ~TangentWorkspace();
  TangentWorkspace(TangentWorkspace&&) noexcept;
  TangentWorkspace& operator=(TangentWorkspace&&) noexcept;
  TangentWorkspace(const TangentWorkspace&) = delete;
  TangentWorkspace& operator=(const TangentWorkspace&) = delete;
  std::size_t bytesReserved() const;  // scratch memory held now
  // For a caller whose vertices are distinct by bits (no two with the same bits in all eight
  // values, as shareVertices makes them; tangent/shared_vertices.hpp): the vertices that may
  // still weld with another, in increasing order. Such vertices are equal as floats only where
  // they differ in the signs of zeros, so only one with a value of +0 or -0 can weld: the weld
  // then compares the listed vertices only. It holds for the calls on this workspace until
  // reset with std::nullopt (the default: every vertex is welded); a list out of range or out
  // of order is refused by the call (std::invalid_argument). The same bits as without it.
  void setWeldOnly(std::optional<std::span<const std::uint32_t>> vertices);
  // Off (the default), the calls on this workspace keep every scratch array for the next call,
  // which then touches no fresh memory. On, each call frees every large array (2 MiB and
  // more) as soon as it has read it for the last time, and takes it fresh when a later phase
  // or call needs it again: a lower peak for a one-off call on a huge mesh, for a page fault
  // per 2 MiB on the next call (tangent bake turns it on for primitives of a million triangles
  // and more: at 4e6 triangles its peak fell 628 -> 547 MB, lengyel's 1030 -> 821 MB). The same
  // bits either way.
  void setReleaseAsItGoes(bool release);
  bool releasesAsItGoes() const;

  // Scratch arrays kept here for an adapter that gathers its mesh into the array call's inputs
  // (the OpenMesh computeTangents): grown as needed, never zero-filled, counted in
  // bytesReserved(), and reused by the next call on this workspace as the core reuses its own.
  struct AdapterBuffers {
    BulkVector<float> positions, normals, uvs;  // 3, 3, 2 per array vertex
    BulkVector<float> tangents;                 // 4 per corner
    BulkVector<std::uint32_t> indices;          // per corner
    BulkVector<std::uint32_t> vertexCorner;     // per vertex of the adapter's mesh
    BulkVector<float> vertexValues;             // 8 per vertex of the adapter's mesh
    BulkVector<std::uint32_t> list;             // per array vertex
    std::size_t bytes() const;
  };
  AdapterBuffers& adapterBuffers();
  detail::WorkspaceData& data() { return *data_; }

 private:
  std::unique_ptr<detail::WorkspaceData> data_;
};

// The calls without a TangentWorkspace argument (the plain computeCornerTangents below, the
// OpenMesh computeTangents) and the glTF layer's bake and check keep their scratch memory
// between calls: one workspace per calling thread, kept after a call while it holds at most
// workspaceCacheLimit() bytes (mikktspace: about 70 bytes a triangle). So a pipeline that
// calls once per mesh, with other work in between, touches no fresh memory from its second
// call on; fresh memory costs a page fault per page and the kernel's zeroing of it, a third of
// a plain call's time at 1e5 triangles before this cache (docs/benchmarks.md, "Fresh
// memory"). The memory stays with the thread until releaseCachedWorkspaces(), a call that
// leaves the workspace over the limit, or the thread's end. A call made while its thread's
// cached workspace is in use (a call nested in another on the same thread) takes a workspace
// of its own. Every call gives the same bits with or without the cache.
class CachedWorkspace {  // the calling thread's cached workspace, leased for one call
 public:
  CachedWorkspace();
  ~CachedWorkspace();  // back to the cache, or freed when over the limit
  CachedWorkspace(const CachedWorkspace&) = delete;
  CachedWorkspace& operator=(const CachedWorkspace&) = delete;
  TangentWorkspace& get() { return *workspace_; }

 private:
  TangentWorkspace* workspace_ = nullptr;
  std::unique_ptr<TangentWorkspace> own_;  // set where the cache was in use or is off
};
inline constexpr std::size_t kDefaultWorkspaceCacheLimit = std::size_t(512) << 20;
std::size_t workspaceCacheLimit();
// For every thread from its next call on; 0 keeps nothing (each call allocates and frees).
void setWorkspaceCacheLimit(std::size_t bytes);
// Frees every thread's cached workspace that no call is using now (safe from any thread).
void releaseCachedWorkspaces();
// What the cached workspaces of all threads hold now.
std::size_t cachedWorkspaceBytes();

// What a call writes; the caller owns every array.
struct CornerOutputs {
  std::span<float> tangents;                   // required: x, y, z, w per corner (4 floats)
  std::span<FrameSource> sources = {};         // optional: where each corner's frame came from
  // Optional, one per corner: the output vertex of each corner (the vertex split). Corners of
  // input vertex v that got the same tangent bits as v's first corner (in corner order) keep
  // vertex v; every other distinct tangent of v becomes a new vertex, numbered from the input
  // vertex count up (in order of first corner). So an output vertex buffer is the input
  // vertices followed by Report::splitVertices copies, copy o of input vertex indices[c] for
  // the first corner c with cornerVertex[c] == o.
  std::span<std::uint32_t> cornerVertex = {};
};

// The main entry point. Writes one tangent (x, y, z, w) per corner: xyz unit length and
// orthogonal to the corner's normal, w exactly +1 or -1, every value finite, whatever the
// input; the same bits for any thread count and any order of the triangles. Throws
// std::invalid_argument when the array sizes disagree or an index is out of range.
Report computeCornerTangents(const MeshArrays& mesh, const CornerOutputs& outputs, const Options& options,
                             TangentWorkspace& workspace);

// The same on strided or 16-bit-indexed input (see StridedMesh). Throws std::invalid_argument
// also when a stride is smaller than its attribute or a pointer is null where data is needed.
Report computeCornerTangents(const StridedMesh& mesh, const CornerOutputs& outputs, const Options& options,
                             TangentWorkspace& workspace);

// The same with the calling thread's cached workspace (CachedWorkspace). Computes one tangent (x, y, z, w) per corner into cornerTangents (4 floats per corner).
// xyz is unit length and orthogonal to the corner's normal, w is exactly +1 or -1, and every
// value is finite, whatever the input. When cornerSources is not empty (one per corner) it
// receives where each frame came from. Throws std::invalid_argument when the array sizes
// disagree or an index is out of range.
Report computeCornerTangents(const MeshArrays& mesh, std::span<float> cornerTangents,
                             const Options& options = {}, std::span<FrameSource> cornerSources = {});

}  // namespace tangent
