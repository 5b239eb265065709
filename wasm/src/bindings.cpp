// SPDX-License-Identifier: MIT
// The WebAssembly entry points of the npm package (wasm/package): the core's public array call
// (every method) on arrays in the module's memory, built without threads (TANGENT_SERIAL) or
// on the core's pool of standard threads over emscripten's pthreads (TANGENT_STD_THREADS: the
// threaded build, wasm/build.sh), without OpenMesh. Method, weighting and UV origin come as the names the command line takes,
// parsed by the core; the report goes back as the core's JSON (tangent::reportJson). One
// workspace is reused from call to call, so repeated calls allocate nothing new. The per-vertex
// outputs (the vertex split) are made only when asked for: generateTangents returns one tangent
// per corner, and without them a call does less and touches 24 bytes fewer per corner (memory
// the module touches for the first time costs a page fault per 4 KiB: at 4e6 triangles a
// quarter of the first call).
// Every function returns 0 on success; on failure 1 and tangent_error() says why.
#include <emscripten/emscripten.h>

#include <cmath>
#include <cstdint>
#include <exception>
#include <numeric>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "tangent/frame_rules.hpp"
#include "tangent/shared_vertices.hpp"
#include "tangent/tangent.hpp"

namespace {

struct State {
  tangent::TangentWorkspace workspace;
  std::vector<std::uint32_t> sequence;  // 0, 1, 2, ... for de-indexed input with the vertex split
  tangent::SharedVertices shared;  // de-indexed input, indexed (tangent/shared_vertices.hpp)
  tangent::VertexSharer sharer;     // fills `shared` from the staging buffer
  std::vector<float> staging;             // kStageCorners corners: positions, normals, uvs
  std::vector<float> cornerTangents;    // 4 per corner
  std::vector<std::uint32_t> cornerVertex;
  std::vector<float> vertexTangents;    // 4 per output vertex
  std::vector<std::uint32_t> vertexSource;  // output vertex -> input vertex
  std::vector<std::uint8_t> used;  // per output vertex: written from a corner yet (writeVertexOutputs)
  std::string report;  // JSON
  std::string error;
};

State& state() {
  static State s;
  return s;
}

// Corners per staging run: 8 floats each, 512 KiB in all, so that a run is shared while it is
// still in cache (the de-indexed input is never in the module's memory whole: 32 bytes a
// corner, 384 MB at 4e6 triangles, that were written and read back once).
constexpr std::uint32_t kStageCorners = 1 << 14;

// The arrays tangent_run may be given: positions, normals and uvs all, or none of them for
// the corners tangent_share_add has shared (no indices then, and no vertex split). A null
// array is refused here: the core would read the module's memory from address 0 as the mesh.
void requireArrays(const float* positions, const float* normals, const float* uvs, const std::uint32_t* indices,
                   int vertexSplit) {
  const int given = (positions != nullptr) + (normals != nullptr) + (uvs != nullptr);
  if (given == 3) return;
  if (given == 0 && !indices && !vertexSplit) return;
  if (given == 0) {
    throw std::invalid_argument(
        "positions, normals, uvs: null, which only the shared corners of tangent_share_add may be (no indices, no "
        "vertex split)");
  }
  std::string missing;
  auto note = [&](const char* name, const float* array) {
    if (!array) missing += (missing.empty() ? "" : ", ") + std::string(name);
  };
  note("positions", positions);
  note("normals", normals);
  note("uvs", uvs);
  throw std::invalid_argument(missing + ": null; positions, normals and uvs are given together or not at all");
}

}  // namespace

extern "C" {

namespace {

// tangent_run's options from the names the command line takes; std::invalid_argument naming the
// argument otherwise.
tangent::Options runOptions(const char* method, const char* weighting, const char* uvOrigin, std::uint32_t threads) {
  tangent::Options options;
  const auto parsedMethod = tangent::parseMethod(method);
  if (!parsedMethod) throw std::invalid_argument(std::string("method: '") + method + "' is not mikktspace, lengyel, flat or meshopt");
  const auto parsedWeighting = tangent::parseWeighting(weighting);
  if (!parsedWeighting) throw std::invalid_argument(std::string("weighting: '") + weighting + "' is not angle, area or uniform");
  const auto parsedOrigin = tangent::parseUvOrigin(uvOrigin);
  if (!parsedOrigin) throw std::invalid_argument(std::string("uvOrigin: '") + uvOrigin + "' is not top-left or bottom-left");
  options.method = *parsedMethod;
  options.weighting = *parsedWeighting;
  options.uvOrigin = *parsedOrigin;
  // The package's JavaScript passes 1 to the single-threaded build and at most its pool's
  // threads to the threaded one; the same bits for any count.
  options.threads = threads < 1 ? 1 : threads;
  return options;
}

// The arrays tangent_run hands the core.
struct RunArrays {
  const float *positions, *normals, *uvs;
  const std::uint32_t* indices;
  std::uint32_t vertexCount;
};

// Per-corner tangents only, without indices: the corners with the same bits share a vertex
// first (the same output bits, a sixth of the vertices to weld and bucket on a typical mesh),
// from the arrays or, where positions is null, as tangent_share_add has done already.
void useSharedVertices(State& s, RunArrays& a, std::uint32_t cornerCount, unsigned threads) {
  if (a.vertexCount != cornerCount) throw std::invalid_argument("indices: null, but the vertex count is not the corner count");
  if (a.positions) {
    // On the call's threads (the threaded build's JavaScript passes the arrays whole then).
    tangent::shareVertices(a.positions, a.normals, a.uvs, cornerCount, s.shared, threads);
  } else if (s.sharer.added() != cornerCount) {
    throw std::invalid_argument("positions: null, but tangent_share_add gave " + std::to_string(s.sharer.added()) + " of " +
                                std::to_string(cornerCount) + " corners");
  }
  a = RunArrays{s.shared.positions.data(), s.shared.normals.data(), s.shared.uvs.data(), s.shared.indices.data(),
                static_cast<std::uint32_t>(s.shared.vertexCount)};
  // No two shared vertices have the same bits: the core need weld only those with a zero
  // (the others, nearly all on most meshes, were hashed and probed for no merge).
  s.workspace.setWeldOnly(std::span<const std::uint32_t>(s.shared.zeroVertices));
}

// Per output vertex: the tangent of its corners and the input vertex it copies.
void writeVertexOutputs(State& s, const tangent::Report& report, const RunArrays& a, std::uint32_t cornerCount) {
  const std::size_t outputVertices = static_cast<std::size_t>(report.outputVertices);
  s.vertexTangents.assign(outputVertices * 4, 0.0f);
  s.vertexSource.resize(outputVertices);
  // Every corner of an output vertex has its tangent bits and its input vertex (the vertex
  // split), so each output vertex is written once, from its first corner (about a sixth of the
  // corners on a typical mesh; a byte per vertex, kept from call to call, says which are).
  s.used.assign(outputVertices, 0);
  std::uint8_t* used = s.used.data();
  const float* cornerTangents = s.cornerTangents.data();
  float* vertexTangents = s.vertexTangents.data();
  for (std::uint32_t c = 0; c < cornerCount; ++c) {
    const std::uint32_t v = s.cornerVertex[c];
    if (used[v]) continue;
    used[v] = 1;
    std::copy(cornerTangents + 4 * std::size_t(c), cornerTangents + 4 * std::size_t(c) + 4, vertexTangents + 4 * std::size_t(v));
    s.vertexSource[v] = a.indices[c];
  }
  for (std::size_t v = 0; v < outputVertices; ++v) {
    if (used[v]) continue;
    s.vertexSource[v] = static_cast<std::uint32_t>(v);  // unused input vertices keep their place
    tangent::unusedVertexTangent(std::span<const float, 3>(&a.normals[3 * v], 3), std::span<float, 4>(&s.vertexTangents[4 * v], 4));
  }
}

}  // namespace

// Tangents per corner for `cornerCount` corners (a triangle list) of `vertexCount` vertices;
// indices may be null (corner i is vertex i). method, weighting, uvOrigin: names as the
// command line takes them (mikktspace | lengyel | flat | meshopt; angle | area | uniform; top-left, glTF's
// UV origin and w, | bottom-left, MikkTSpace's own fSign, as the npm mikktspace package returns).
// vertexSplit: nonzero to make the per-vertex outputs too (tangent_corner_vertices,
// tangent_vertex_tangents, tangent_vertex_sources); zero for the per-corner tangents only.
// positions, normals and uvs are null only after tangent_share_add (requireArrays). threads:
// the threads the core runs on (1 in the single-threaded build).
EMSCRIPTEN_KEEPALIVE int tangent_run(const float* positions, const float* normals, const float* uvs, const std::uint32_t* indices,
                                     std::uint32_t vertexCount, std::uint32_t cornerCount, const char* method,
                                     const char* weighting, const char* uvOrigin, int vertexSplit, std::uint32_t threads) {
  State& s = state();
  s.error.clear();
  // Set by useSharedVertices for the shared corners only (their vertices are distinct by bits),
  // and reset when the call ends whichever way (so unset when the next one starts): the list
  // lives in `shared`, which the next call refills.
  struct ResetWeldOnly {
    tangent::TangentWorkspace& workspace;
    ~ResetWeldOnly() { workspace.setWeldOnly(std::nullopt); }
  } resetWeldOnly{s.workspace};
  try {
    const tangent::Options options = runOptions(method, weighting, uvOrigin, threads);
    requireArrays(positions, normals, uvs, indices, vertexSplit);
    RunArrays a{positions, normals, uvs, indices, vertexCount};
    if (!indices && vertexSplit) {
      if (s.sequence.size() < cornerCount) {
        s.sequence.resize(cornerCount);
        std::iota(s.sequence.begin(), s.sequence.end(), 0u);
      }
      a.indices = s.sequence.data();
    } else if (!indices) {
      useSharedVertices(s, a, cornerCount, options.threads);
    }
    s.cornerTangents.resize(std::size_t(cornerCount) * 4);
    s.cornerVertex.resize(vertexSplit ? cornerCount : 0);
    const tangent::MeshArrays mesh{{a.positions, std::size_t(a.vertexCount) * 3},
                                   {a.normals, std::size_t(a.vertexCount) * 3},
                                   {a.uvs, std::size_t(a.vertexCount) * 2},
                                   {a.indices, cornerCount}};
    const tangent::CornerOutputs outputs{s.cornerTangents, {}, s.cornerVertex};
    const tangent::Report report = tangent::computeCornerTangents(mesh, outputs, options, s.workspace);
    s.report = tangent::reportJson(report);
    if (vertexSplit) writeVertexOutputs(s, report, a, cornerCount);
    return 0;
  } catch (const std::exception& e) {
    s.error = e.what();
  } catch (...) {
    s.error = "unknown error";
  }
  return 1;
}

// De-indexed input through the staging buffer: tangent_share_begin(cornerCount) returns it
// (null on failure, tangent_error() says why), tangent_stage_corners() corners of positions,
// then as many normals, then UVs; tangent_share_add(count) shares the first `count` corners
// staged; tangent_run with null arrays then runs the core on the shared vertices.
EMSCRIPTEN_KEEPALIVE float* tangent_share_begin(std::uint32_t cornerCount) {
  State& s = state();
  s.error.clear();
  try {
    s.staging.resize(std::size_t(kStageCorners) * 8);
    s.sharer.begin(cornerCount, s.shared);
    return s.staging.data();
  } catch (const std::exception& e) {
    s.error = e.what();
  }
  return nullptr;
}
EMSCRIPTEN_KEEPALIVE std::uint32_t tangent_stage_corners() { return kStageCorners; }
// Whether tangent_run shares `cornerCount` de-indexed corners on several threads when given
// them whole (1), or as well staged (0: one thread's sharing either way).
EMSCRIPTEN_KEEPALIVE int tangent_shares_on_threads(std::uint32_t cornerCount, std::uint32_t threads) {
  return tangent::threadsToShareOn(cornerCount, threads) > 1 ? 1 : 0;
}
EMSCRIPTEN_KEEPALIVE int tangent_share_add(std::uint32_t count) {
  State& s = state();
  const float* staged = s.staging.data();
  if (count <= kStageCorners && s.sharer.add(staged, staged + 3 * kStageCorners, staged + 6 * kStageCorners, count)) return 0;
  s.error = "tangent_share_add: " + std::to_string(count) + " corners past the staging buffer or the call's count";
  return 1;
}

EMSCRIPTEN_KEEPALIVE const char* tangent_error() { return state().error.c_str(); }
EMSCRIPTEN_KEEPALIVE float* tangent_corner_tangents() { return state().cornerTangents.data(); }
EMSCRIPTEN_KEEPALIVE std::uint32_t* tangent_corner_vertices() { return state().cornerVertex.data(); }
EMSCRIPTEN_KEEPALIVE float* tangent_vertex_tangents() { return state().vertexTangents.data(); }
EMSCRIPTEN_KEEPALIVE std::uint32_t* tangent_vertex_sources() { return state().vertexSource.data(); }
EMSCRIPTEN_KEEPALIVE const char* tangent_report() { return state().report.c_str(); }

}  // extern "C"
