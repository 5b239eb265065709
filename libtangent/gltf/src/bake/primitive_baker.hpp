// SPDX-License-Identifier: MIT
// PrimitiveBaker: bake's pipeline per primitive, in phases that each have a file: plan
// (plan.cpp), compute (compute.cpp), emit and refer (emit.cpp), and primitives that share one
// vertex buffer (vertex_group.cpp); bakeAll, which runs them, and bakeFile are in bake.cpp.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "bake/vertex_split.hpp"
#include "read/accessors.hpp"
#include "read/asset.hpp"
#include "read/compression.hpp"
#include "read/primitive.hpp"
#include "tangent/gltf.hpp"
#include "write/document.hpp"

namespace tangent::gltf::detail {

// What plan() decided for one primitive: where it is, what it needs and, when it is to be
// baked, why. When `bake` is false the result is final (skipped, or kept).
struct PrimitivePlan {
  int mesh = 0;
  int primitive = 0;
  std::string where;  // "<file>: mesh M 'name' primitive P", for messages
  PrimitiveNeeds needs;
  std::string why;    // why the primitive gets tangents
  bool bake = false;
  bool hasTangent = false;       // an existing TANGENT, kept or recomputed as decideExisting says
  bool replacesTangent = false;  // an existing TANGENT is recomputed
  bool generatesNormals = false; // no NORMAL: bake writes one (BakeOptions::normals) and computes from it
  PrimitiveResult result;
};

// What compute() produced, per output vertex: the vertex split with its tangents, and the
// morph targets' TANGENT deltas.
struct ComputedTangents {
  std::size_t vertexCount = 0;  // input vertices
  int indexComponentType = 0;   // of the input's indices (0 when it has none)
  VertexSplit split;
  std::vector<std::vector<float>> targetTangentDeltas;
  PrimitiveCompression compression;
  bool rebuild = false;  // every vertex accessor and the indices are written anew
  std::vector<float> generatedNormals;  // 3 per output vertex where bake writes a NORMAL, else empty
  // The split's vertices are a part of a shared vertex buffer (VertexGroup): rebuilt accessors
  // get the min/max of the part (the spec requires them for POSITION, the validator compares).
  bool partOfBuffer = false;
};

// An accessor's elements as rebuilt attributes gather them: where they lie in the loaded
// buffer (denseElements), else decoded (sparse values, no bufferView; Draco's, whose bounds
// are recomputed from them). `data` has the header, and the bytes where decoded.
struct CarriedElements {
  AccessorData data;
  const std::uint8_t* first = nullptr;
  std::size_t stride = 0;
};

// A morph target's deltas as the tangents are computed from them: empty where absent.
struct TargetDeltas {
  std::vector<float> positions, normals;
};

// Primitives that share their vertex attributes (detail::sameVertexKey) and draw with
// different indices: one vertex buffer of a CAD model, one indices accessor per part. Each
// part gets its frames from the vertices it uses (time in its corners, not in the buffer).
struct VertexGroup {
  std::vector<std::size_t> firstOfInput;  // the first plan of each input key (sameInputKey), in document order
};

// The accessors emit() wrote for a primitive, by name: every later primitive with the same
// inputs (detail::sameInputKey) refers to these instead of computing and writing its own.
struct EmittedAccessors {
  std::vector<std::pair<std::string, int>> attributes;                // TANGENT and, when rebuilt, the others
  std::vector<std::vector<std::pair<std::string, int>>> targets;      // per morph target, likewise
  int indices = -1;                                                   // rebuilt indices, -1 when kept
  bool dropDraco = false;                                             // the Draco extension goes
};

// What baking one set of inputs gave: the accessors and the result's fields that depend on
// the inputs only (the reason names the material, so it stays per primitive).
struct SharedBake {
  bool baked = false;
  std::string notBaked;              // why not, when not baked (no triangles)
  EmittedAccessors emitted;
  Report tangents;
  std::uint64_t verticesIn = 0;
  std::uint64_t verticesOut = 0;
  std::string compressionNote;       // "; written uncompressed (was ...)", or ""
  std::optional<NormalsMode> normalsGenerated;
};

// Which plans bake together: each baked plan's input key (detail::sameInputKey, and the
// normals mode where bake generates normals) and the VertexGroup it belongs to.
struct PlanGroups {
  std::vector<std::string> inputKeys;   // per plan; empty where the plan is not baked
  std::vector<std::size_t> groupOfPlan;  // per plan, an index into `groups`
  std::vector<VertexGroup> groups;
};

// Bakes every primitive in four steps: plan (does it need tangents, is it valid), compute
// (tangents, vertex split, morph deltas; reads the document only), emit (new accessors) and
// refer (the primitive's references to them). Compute and emit run once per set of inputs;
// a primitive with the inputs of an earlier one only refers. Primitives that share a vertex
// buffer with different indices are computed and emitted together (bakeVertexGroup). Nothing
// holds a reference into the document across an insertion: refer looks the primitive up after
// emit has appended.
class PrimitiveBaker {
 public:
  PrimitiveBaker(Asset& asset, OutputDocument& output, const BakeOptions& options)
      : asset_(asset), output_(output), options_(options) {}

  // Every primitive's result, in mesh and primitive order.
  std::vector<PrimitiveResult> bakeAll();

 private:
  nlohmann::ordered_json& primitiveJson(const PrimitivePlan& plan) {
    return output_.json()["meshes"][plan.mesh]["primitives"][plan.primitive];
  }
  // plan (plan.cpp)
  std::vector<PrimitivePlan> planAll();
  PrimitivePlan planPrimitive(int meshIndex, int primitiveIndex);
  void decideExisting(std::vector<PrimitivePlan>& plans);
  PlanGroups groupPlans(const std::vector<PrimitivePlan>& plans);
  // bake.cpp: compute and emit once per input key
  const SharedBake& bakedFor(std::size_t planIndex, const PlanGroups& groups, std::vector<PrimitivePlan>& plans);
  SharedBake bakeInputs(PrimitivePlan& plan);
  // vertex_group.cpp
  void bakeVertexGroup(const VertexGroup& group, std::vector<PrimitivePlan>& plans);
  // compute (compute.cpp): reads the document only
  std::optional<ComputedTangents> compute(PrimitivePlan& plan);
  std::optional<ComputedTangents> computeWithGeneratedNormals(PrimitivePlan& plan, const PrimitiveGeometry& geometry);
  std::vector<TargetDeltas> readTargetDeltas(const PrimitivePlan& plan, std::size_t vertexCount);
  std::optional<ComputedTangents> computeFrames(PrimitivePlan& plan, const PrimitiveGeometry& geometry,
                                                const std::vector<TargetDeltas>& targets);
  std::optional<StridedMesh> inPlaceMesh(const PrimitivePlan& plan, int& indexComponentType);
  ComputedTangents computeSplit(PrimitivePlan& plan, const StridedMesh& mesh, int indexComponentType);
  Options coreOptions(std::size_t corners);
  Arena* arenaFor(const Options& options);
  // emit and refer (emit.cpp): append accessors, then point the primitive at them
  const CarriedElements& carriedData(int index, const std::string& what, bool decoded);
  SharedBake emit(const PrimitivePlan& plan, ComputedTangents& computed);
  EmittedAccessors emitBufferTangents(std::vector<float> tangents, std::vector<std::vector<float>>& targetDeltas,
                                      std::size_t vertexCount);
  void refer(PrimitivePlan& plan, const SharedBake& shared);
  void rebuildAttributes(const PrimitivePlan& plan, const ComputedTangents& computed, EmittedAccessors& emitted);
  int addGathered(int index, const CarriedElements& carried, const ComputedTangents& computed);
  void rebuildTargets(const PrimitivePlan& plan, const ComputedTangents& computed, EmittedAccessors& emitted);
  void writeIndices(const PrimitivePlan& plan, ComputedTangents& computed, EmittedAccessors& emitted);
  void writeTangents(const PrimitivePlan& plan, ComputedTangents& computed, EmittedAccessors& emitted);

  Asset& asset_;
  OutputDocument& output_;
  const BakeOptions& options_;
  CachedWorkspace workspace_;  // the thread's cached workspace (tangent.hpp), for every compute
  std::optional<Arena> arena_;                              // bake's own passes over a primitive's corners
  [[maybe_unused]] unsigned arenaThreads_ = 0;              // arena_'s (none without threads)
  std::unordered_map<std::string, SharedBake> baked_;       // by detail::sameInputKey
  std::unordered_map<int, CarriedElements> carried_;        // by accessor (and decoded: + 1 << 30), while one group is emitted
  std::unordered_map<std::size_t, SharedBake> groupBakes_;  // bakeVertexGroup's, by the plan of each input key
};

}  // namespace tangent::gltf::detail
