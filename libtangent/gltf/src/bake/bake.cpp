// SPDX-License-Identifier: MIT
// `bake`: TANGENT for the primitives that need it (glTF 2.0 spec 3.7.2.1), vertices split where
// the corners of one glTF vertex got different frames, every other attribute carried along.
#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstring>
#include <numeric>
#include <optional>
#include <unordered_map>
#include <utility>

#include "bake/vertex_split.hpp"
#include "read/accessors.hpp"
#include "read/asset.hpp"
#include "check/check_primitive.hpp"
#include "read/compression.hpp"
#include "write/document.hpp"
#include "entry_point.hpp"
#include "read/primitive.hpp"
#include "tangent/bulk_buffer.hpp"
#include "tangent/frame_rules.hpp"
#include "tangent/gltf.hpp"


namespace tangent::gltf {
namespace {

using detail::AccessorData;
using detail::Arena;
using detail::VertexSplit;
using detail::kNoCorner;
using detail::splitVertices;
using detail::inChunks;
using Json = nlohmann::ordered_json;

// Elements `source` (in that order) of elements of `size` bytes, `stride` apart from `first`.
std::vector<std::uint8_t> gather(const std::uint8_t* first, std::size_t size, std::size_t stride,
                                const std::vector<std::uint32_t>& source) {
  std::vector<std::uint8_t> out(source.size() * size);
  for (std::size_t i = 0; i < source.size(); ++i) std::memcpy(&out[i * size], first + source[i] * stride, size);
  return out;
}

// Accessor JSON for carried data: type, component type, normalization, min/max, name kept.
Json carriedAccessor(const Json& original, std::size_t count) {
  Json accessor = Json::object();
  for (const char* key : {"componentType", "normalized", "type", "min", "max", "name", "extras", "extensions"}) {
    if (original.contains(key)) accessor[key] = original[key];
  }
  accessor["count"] = count;
  return accessor;
}

// TANGENT as the options ask: float, or normalized SHORT/BYTE rounded to nearest (spec 3.11:
// c = round(f * 32767) or round(f * 127)), which the stored-tangent rules accept.
struct EncodedTangents {
  Json accessor;
  detail::ViewBytes bytes;
  std::size_t stride = 16;
};

template <typename Integer>
std::vector<std::uint8_t> normalizedBytes(const std::vector<float>& values, double scale) {
  std::vector<std::uint8_t> bytes(values.size() * sizeof(Integer));
  for (std::size_t i = 0; i < values.size(); ++i) {
    const auto q = static_cast<Integer>(std::lround(std::clamp(double(values[i]), -1.0, 1.0) * scale));
    std::memcpy(&bytes[i * sizeof(Integer)], &q, sizeof(Integer));
  }
  return bytes;
}

EncodedTangents encodeTangents(std::vector<float> tangents, TangentFormat format) {
  const std::size_t count = tangents.size() / 4;
  switch (format) {
    case TangentFormat::normalizedShort:
      return {Json{{"componentType", TINYGLTF_COMPONENT_TYPE_SHORT}, {"normalized", true}, {"count", count}, {"type", "VEC4"}},
              normalizedBytes<std::int16_t>(tangents, 32767.0), 8};
    case TangentFormat::normalizedByte:
      return {Json{{"componentType", TINYGLTF_COMPONENT_TYPE_BYTE}, {"normalized", true}, {"count", count}, {"type", "VEC4"}},
              normalizedBytes<std::int8_t>(tangents, 127.0), 4};
    case TangentFormat::float32: break;
  }
  return {Json{{"componentType", TINYGLTF_COMPONENT_TYPE_FLOAT}, {"count", count}, {"type", "VEC4"}}, std::move(tangents), 16};
}

// Adds `name` to extensionsUsed and extensionsRequired unless there already.
void declareRequiredExtension(Json& doc, const char* name) {
  for (const char* list : {"extensionsUsed", "extensionsRequired"}) {
    if (!doc.contains(list) || !doc[list].is_array()) doc[list] = Json::array();
    if (std::find(doc[list].begin(), doc[list].end(), Json(name)) == doc[list].end()) doc[list].push_back(name);
  }
}

// min/max of carried data where the stored ones may not hold: Draco's quantization moves
// values, and the validator compares min/max with the data. Per the spec they are in the
// stored (not normalized) units.
void recomputeBounds(Json& accessor, const AccessorData& data) {
  if (!accessor.contains("min") && !accessor.contains("max")) return;
  AccessorData raw = data;
  raw.normalized = false;
  const std::vector<float> values = detail::toFloats(raw);
  std::vector<float> low(values.begin(), values.begin() + data.components), high = low;
  for (std::size_t i = 0; i < values.size(); ++i) {
    const std::size_t c = i % data.components;
    low[c] = std::min(low[c], values[i]);
    high[c] = std::max(high[c], values[i]);
  }
  if (data.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT) {
    accessor["min"] = low;
    accessor["max"] = high;
    return;
  }
  // Integer components: written as integers.
  accessor["min"] = Json::array();
  accessor["max"] = Json::array();
  for (int c = 0; c < data.components; ++c) {
    accessor["min"].push_back(static_cast<std::int64_t>(low[c]));
    accessor["max"].push_back(static_cast<std::int64_t>(high[c]));
  }
}

Json floatAccessor(std::size_t count, const char* type) {
  return Json{{"componentType", TINYGLTF_COMPONENT_TYPE_FLOAT}, {"count", count}, {"type", type}};
}

// What plan() decided for one primitive: where it is, what it needs and, when it is to be
// baked, why. When `bake` is false the result is final (skipped, or kept).
struct PrimitivePlan {
  int mesh = 0;
  int primitive = 0;
  std::string where;  // "<file>: mesh M 'name' primitive P", for messages
  detail::PrimitiveNeeds needs;
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
  detail::PrimitiveCompression compression;
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

// The frames of the primitives of a VertexGroup that share one TANGENT accessor, per vertex of
// the buffer: a primitive joins when its vertices are not split and each vertex it uses has no
// frame yet or the same bits (tangent and every target's delta) as the one it has.
class BufferFrames {
 public:
  BufferFrames(std::size_t vertexCount, std::size_t targetCount)
      : tangents_(vertexCount * 4), claimed_(vertexCount, 0), targetDeltas_(targetCount, std::vector<float>(vertexCount * 3)) {}

  bool agrees(const std::vector<std::uint32_t>& used, const ComputedTangents& part) const {
    for (std::size_t v = 0; v < used.size(); ++v) {
      const std::size_t b = used[v];
      if (!claimed_[b]) continue;
      if (std::memcmp(&tangents_[4 * b], &part.split.tangents[4 * v], 4 * sizeof(float)) != 0) return false;
      for (std::size_t t = 0; t < targetDeltas_.size(); ++t) {
        if (std::memcmp(&targetDeltas_[t][3 * b], &part.targetTangentDeltas[t][3 * v], 3 * sizeof(float)) != 0) return false;
      }
    }
    return true;
  }

  void claim(const std::vector<std::uint32_t>& used, const ComputedTangents& part) {
    for (std::size_t v = 0; v < used.size(); ++v) {
      const std::size_t b = used[v];
      claimed_[b] = 1;
      std::copy_n(&part.split.tangents[4 * v], 4, &tangents_[4 * b]);
      for (std::size_t t = 0; t < targetDeltas_.size(); ++t) std::copy_n(&part.targetTangentDeltas[t][3 * v], 3, &targetDeltas_[t][3 * b]);
    }
  }

  // Every vertex's tangent, those no sharing primitive uses made valid from their normals
  // (target deltas stay 0 there); the object is spent.
  std::vector<float> takeTangents(const std::vector<float>& normals) {
    for (std::size_t b = 0; b < claimed_.size(); ++b) {
      if (!claimed_[b])
        unusedVertexTangent(std::span<const float, 3>(&normals[3 * b], 3), std::span<float, 4>(&tangents_[4 * b], 4));
    }
    return std::move(tangents_);
  }
  std::vector<std::vector<float>>& targetDeltas() { return targetDeltas_; }

 private:
  std::vector<float> tangents_;           // 4 per vertex of the buffer
  std::vector<std::uint8_t> claimed_;     // 1 where a sharing primitive set the vertex's frame
  std::vector<std::vector<float>> targetDeltas_;  // per target, 3 per vertex
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

// Bakes every primitive in four steps: plan (does it need tangents, is it valid), compute
// (tangents, vertex split, morph deltas; reads the document only), emit (new accessors) and
// refer (the primitive's references to them). Compute and emit run once per set of inputs;
// a primitive with the inputs of an earlier one only refers. Primitives that share a vertex
// buffer with different indices are computed and emitted together (bakeVertexGroup). Nothing
// holds a reference into the document across an insertion: refer looks the primitive up after
// emit has appended.
class PrimitiveBaker {
 public:
  PrimitiveBaker(detail::Asset& asset, detail::OutputDocument& output, const BakeOptions& options)
      : asset_(asset), output_(output), options_(options) {}

  // Every primitive's result, in mesh and primitive order.
  std::vector<PrimitiveResult> bakeAll();

 private:
  Json& primitiveJson(const PrimitivePlan& plan) {
    return output_.json()["meshes"][plan.mesh]["primitives"][plan.primitive];
  }
  PrimitivePlan planPrimitive(int meshIndex, int primitiveIndex);
  void decideExisting(std::vector<PrimitivePlan>& plans);
  SharedBake bakeInputs(PrimitivePlan& plan);
  void bakeVertexGroup(const VertexGroup& group, std::vector<PrimitivePlan>& plans);
  std::optional<ComputedTangents> compute(PrimitivePlan& plan);
  std::optional<ComputedTangents> computeWithGeneratedNormals(PrimitivePlan& plan, const detail::PrimitiveGeometry& geometry);
  std::vector<TargetDeltas> readTargetDeltas(const PrimitivePlan& plan, std::size_t vertexCount);
  std::optional<ComputedTangents> computeFrames(PrimitivePlan& plan, const detail::PrimitiveGeometry& geometry,
                                                const std::vector<TargetDeltas>& targets);
  std::optional<StridedMesh> inPlaceMesh(const PrimitivePlan& plan, int& indexComponentType);
  ComputedTangents computeSplit(PrimitivePlan& plan, const StridedMesh& mesh, int indexComponentType);
  Options coreOptions(std::size_t corners);
  Arena* arenaFor(const Options& options);
  const CarriedElements& carriedData(int index, const std::string& what, bool decoded);
  SharedBake emit(const PrimitivePlan& plan, ComputedTangents& computed);
  void refer(PrimitivePlan& plan, const SharedBake& shared);
  void rebuildAttributes(const PrimitivePlan& plan, const ComputedTangents& computed, EmittedAccessors& emitted);
  int addGathered(int index, const CarriedElements& carried, const ComputedTangents& computed);
  void rebuildTargets(const PrimitivePlan& plan, const ComputedTangents& computed, EmittedAccessors& emitted);
  void writeIndices(const PrimitivePlan& plan, ComputedTangents& computed, EmittedAccessors& emitted);
  void writeTangents(const PrimitivePlan& plan, ComputedTangents& computed, EmittedAccessors& emitted);

  detail::Asset& asset_;
  detail::OutputDocument& output_;
  const BakeOptions& options_;
  CachedWorkspace workspace_;  // the thread's cached workspace (tangent.hpp), for every compute
  std::optional<Arena> arena_;                              // bake's own passes over a primitive's corners
  [[maybe_unused]] unsigned arenaThreads_ = 0;              // arena_'s (none without threads)
  std::unordered_map<std::string, SharedBake> baked_;       // by detail::sameInputKey
  std::unordered_map<int, CarriedElements> carried_;        // by accessor (and decoded: + 1 << 30), while one group is emitted
  std::unordered_map<std::size_t, SharedBake> groupBakes_;  // bakeVertexGroup's, by the plan of each input key
};

// Eligibility (a triangle primitive that needs tangents and has what they are computed from)
// and validity (an existing TANGENT that tangent check passes is kept).
PrimitivePlan PrimitiveBaker::planPrimitive(int meshIndex, int primitiveIndex) {
  const Json& doc = output_.json();
  PrimitivePlan plan;
  plan.mesh = meshIndex;
  plan.primitive = primitiveIndex;
  const Json& primitive = primitiveJson(plan);
  plan.where = asset_.path.string() + ": " + detail::primitiveLabel(doc, meshIndex, primitiveIndex);
  PrimitiveResult& result = plan.result;
  result.mesh = meshIndex;
  result.primitive = primitiveIndex;
  if (doc["meshes"][meshIndex].contains("name")) result.meshName = doc["meshes"][meshIndex]["name"].get<std::string>();
  result.action = PrimitiveAction::skipped;

  const detail::PrimitiveNeeds& needs = plan.needs = detail::primitiveNeeds(doc, primitive, options_.all || asset_.fromMeshFile);
  plan.why = detail::bakeReason(needs, asset_.fromMeshFile);
  result.reason = plan.why;
  if (!detail::bakesTangents(needs)) return plan;
  result.texCoord = needs.texCoord;
  if (!primitive.contains("attributes") || !primitive["attributes"].is_object())
    throw InputError(plan.where + ": has no attributes object");
  const Json& attributes = primitive["attributes"];
  const std::string uvName = "TEXCOORD_" + std::to_string(needs.texCoord);
  if (const std::string problem = detail::missingPosition(primitive, needs); !problem.empty())
    throw InputError(plan.where + ": " + problem);
  if (detail::accessorOf(attributes, "NORMAL") < 0) {
    if (options_.normals == NormalsMode::keep) {
      result.reason = "no NORMAL attribute; tangents need normals, primitive left as it is (--normals keep)";
      return plan;
    }
    plan.generatesNormals = true;
  }
  if (detail::accessorOf(attributes, uvName) < 0) {
    // The material names a UV set the primitive lacks: a broken reference, refused (as check
    // and info do). Without a normal texture (--all) there is simply nothing to bake from.
    if (const std::string problem = detail::missingUvSet(primitive, needs); !problem.empty())
      throw InputError(plan.where + ": " + problem);
    result.reason = needs.why + ", but the primitive has no " + uvName + "; left as it is";
    return plan;
  }
  // An existing TANGENT is judged by decideExisting, once every primitive is planned; one
  // without NORMAL is recomputed with the NORMAL bake writes.
  plan.hasTangent = detail::accessorOf(attributes, "TANGENT") >= 0 && !plan.generatesNormals;
  plan.bake = !plan.hasTangent;
  if (plan.generatesNormals) {
    plan.why += std::string("; no NORMAL: ") + toString(options_.normals) + " normals generated and written";
    plan.replacesTangent = detail::accessorOf(attributes, "TANGENT") >= 0;
    if (plan.replacesTangent) result.reason = plan.why + "; the existing TANGENT recomputed from them";
  }
  return plan;
}

// Keep exactly what `tangent check` passes at its default settings: the same function decides.
void PrimitiveBaker::decideExisting(std::vector<PrimitivePlan>& plans) {
  std::vector<detail::PrimitiveToCheck> toCheck;
  std::vector<std::size_t> planOf;
  for (std::size_t i = 0; i < plans.size(); ++i) {
    if (!plans[i].hasTangent) continue;
    toCheck.push_back({&primitiveJson(plans[i]), plans[i].needs, plans[i].where});
    planOf.push_back(i);
  }
  if (toCheck.empty()) return;
  const std::vector<PrimitiveCheck> verdicts = detail::checkPrimitives(asset_, toCheck, CheckOptions{});
  for (std::size_t k = 0; k < planOf.size(); ++k) {
    PrimitivePlan& plan = plans[planOf[k]];
    PrimitiveResult& result = plan.result;
    const PrimitiveCheck& verdict = verdicts[k];
    if (verdict.findings.empty() && !options_.overwrite) {
      result.action = PrimitiveAction::kept;
      result.reason = "valid TANGENT present: tangent check passes it (use --overwrite to recompute)";
      continue;
    }
    for (const CheckFinding& finding : verdict.findings) result.failedChecks.push_back(finding.check);
    result.reason = verdict.findings.empty() ? "TANGENT recomputed (--overwrite)"
                                             : "existing TANGENT fails tangent check (" + detail::findingsSummary(verdict) + "); recomputed";
    plan.replacesTangent = true;
    plan.bake = true;
  }
}

std::vector<PrimitiveResult> PrimitiveBaker::bakeAll() {
  // Every plan first: which primitives share a vertex buffer decides how each is baked.
  std::vector<PrimitivePlan> plans;
  {
    const Json& doc = output_.json();
    const std::size_t meshCount = doc.contains("meshes") ? doc["meshes"].size() : 0;
    for (std::size_t m = 0; m < meshCount; ++m) {
      if (!output_.json()["meshes"][m].contains("primitives")) continue;
      const std::size_t primitiveCount = output_.json()["meshes"][m]["primitives"].size();
      for (std::size_t p = 0; p < primitiveCount; ++p) plans.push_back(planPrimitive(static_cast<int>(m), static_cast<int>(p)));
    }
  }
  decideExisting(plans);
  std::vector<std::string> inputKeys(plans.size());
  std::vector<std::size_t> groupOfPlan(plans.size(), 0);
  std::vector<VertexGroup> groups;
  {
    std::unordered_map<std::string, std::size_t> groupOfVertexKey;
    std::unordered_map<std::string, std::size_t> firstOfInputKey;
    for (std::size_t i = 0; i < plans.size(); ++i) {
      if (!plans[i].bake) continue;
      const Json& primitive = primitiveJson(plans[i]);
      inputKeys[i] = detail::sameInputKey(output_.json(), primitive, plans[i].needs);
      // A primitive whose normals are generated is baked alone (its vertices are split by them).
      const std::string vertexKey = plans[i].generatesNormals ? "generated normals " + std::to_string(i)
                                                               : detail::sameVertexKey(output_.json(), primitive, plans[i].needs);
      if (plans[i].generatesNormals) inputKeys[i] += " normals " + std::string(toString(options_.normals));
      const auto group = groupOfVertexKey.emplace(vertexKey, groups.size());
      if (group.second) groups.emplace_back();
      groupOfPlan[i] = group.first->second;
      if (firstOfInputKey.emplace(inputKeys[i], i).second) groups[groupOfPlan[i]].firstOfInput.push_back(i);
    }
  }
  std::vector<PrimitiveResult> results;
  results.reserve(plans.size());
  for (std::size_t i = 0; i < plans.size(); ++i) {
    PrimitivePlan& plan = plans[i];
    if (plan.bake) {
      auto found = baked_.find(inputKeys[i]);
      if (found == baked_.end()) {
        const VertexGroup& group = groups[groupOfPlan[i]];
        if (group.firstOfInput.size() == 1) {
          found = baked_.emplace(inputKeys[i], bakeInputs(plan)).first;
        } else {
          bakeVertexGroup(group, plans);  // every input key of the group
          for (const std::size_t first : group.firstOfInput) baked_.emplace(inputKeys[first], std::move(groupBakes_[first]));
          groupBakes_.clear();
          found = baked_.find(inputKeys[i]);
        }
      }
      refer(plan, found->second);
    }
    results.push_back(std::move(plan.result));
  }
  return results;
}

// The primitive's inputs alone: its tangents over the whole of its vertex accessors.
SharedBake PrimitiveBaker::bakeInputs(PrimitivePlan& plan) {
  SharedBake shared;
  if (std::optional<ComputedTangents> computed = compute(plan)) {
    shared = emit(plan, *computed);
  } else {
    shared.notBaked = plan.result.reason;
  }
  carried_.clear();
  return shared;
}

// The vertex attributes are read once; each input key's frames come from the vertices its
// corners use. Those whose frames fit BufferFrames share one TANGENT accessor over the whole
// buffer with the original attributes and indices; the others (a vertex split, a frame that
// differs from another primitive's on a shared vertex, strips or fans, compressed data) get
// their own attributes, only the vertices they use, re-indexed. Time and output are linear in
// the buffer plus the corners of the group. Emitted: the rebuilt sets in document order, then
// the shared TANGENT (and target TANGENT deltas).
void PrimitiveBaker::bakeVertexGroup(const VertexGroup& group, std::vector<PrimitivePlan>& plans) {
  const PrimitivePlan& first = plans[group.firstOfInput.front()];
  const detail::PrimitiveGeometry buffer = detail::readVertices(asset_, primitiveJson(first), first.needs, first.where);
  const std::vector<TargetDeltas> targets = readTargetDeltas(first, buffer.vertexCount);
  BufferFrames frames(buffer.vertexCount, targets.size());
  std::vector<std::uint32_t> slotOf(buffer.vertexCount, detail::kNoSlot);
  std::vector<std::size_t> sharing;  // plans whose frames are in `frames`
  for (const std::size_t index : group.firstOfInput) {
    PrimitivePlan& plan = plans[index];
    const Json& primitive = primitiveJson(plan);
    detail::PrimitiveGeometry drawn;
    drawn.vertexCount = buffer.vertexCount;
    detail::readCorners(asset_, primitive, plan.where, drawn);
    const detail::UsedVertices used = detail::usedVertices(drawn.corners, slotOf);
    detail::PrimitiveGeometry part = detail::gatherGeometry(buffer, used);
    part.mode = drawn.mode;
    part.indexComponentType = drawn.indexComponentType;
    std::vector<TargetDeltas> partTargets(targets.size());
    for (std::size_t t = 0; t < targets.size(); ++t) {
      for (auto [whole, gathered] : {std::pair{&targets[t].positions, &partTargets[t].positions},
                                     std::pair{&targets[t].normals, &partTargets[t].normals}}) {
        if (whole->empty()) continue;
        gathered->resize(3 * used.vertices.size());
        for (std::size_t v = 0; v < used.vertices.size(); ++v) std::copy_n(&(*whole)[3 * used.vertices[v]], 3, &(*gathered)[3 * v]);
      }
    }
    std::optional<ComputedTangents> computed = computeFrames(plan, part, partTargets);
    SharedBake& shared = groupBakes_[index];
    if (!computed) {
      shared.notBaked = plan.result.reason;
      continue;
    }
    computed->compression = detail::primitiveCompression(asset_, primitive);
    const bool unsplit = computed->split.source.size() == used.vertices.size();
    if (unsplit && part.mode == 4 && !computed->compression.any() && frames.agrees(used.vertices, *computed)) {
      frames.claim(used.vertices, *computed);
      sharing.push_back(index);
      continue;
    }
    for (std::uint32_t& source : computed->split.source) source = used.vertices[source];
    computed->vertexCount = buffer.vertexCount;
    computed->rebuild = true;
    computed->partOfBuffer = true;
    shared = emit(plan, *computed);
  }
  carried_.clear();
  if (sharing.empty()) return;
  // The shared TANGENT, and each target's TANGENT deltas, over the whole buffer.
  EmittedAccessors emitted;
  EncodedTangents encoded = encodeTangents(frames.takeTangents(buffer.normals), options_.tangentFormat);
  emitted.attributes.emplace_back(
      "TANGENT", output_.addAccessor(encoded.accessor, std::move(encoded.bytes), encoded.stride, detail::kArrayBuffer));
  emitted.targets.resize(targets.size());
  for (std::size_t t = 0; t < targets.size(); ++t) {
    const int deltas = output_.addAccessor(floatAccessor(buffer.vertexCount, "VEC3"), std::move(frames.targetDeltas()[t]), 12,
                                           detail::kArrayBuffer);
    emitted.targets[t].emplace_back("TANGENT", deltas);
  }
  for (const std::size_t index : sharing) {
    SharedBake& shared = groupBakes_[index];
    shared.baked = true;
    shared.emitted = emitted;
    shared.tangents = plans[index].result.tangents;
    shared.verticesIn = plans[index].result.verticesIn;
    shared.verticesOut = plans[index].result.verticesOut;
  }
}

// Tangents per corner from the core, the vertex split, and TANGENT deltas for the morph
// targets (tangents of the morphed shape minus the base ones). Reads the document only.
std::optional<ComputedTangents> PrimitiveBaker::compute(PrimitivePlan& plan) {
  const Json& primitive = primitiveJson(plan);
  int indexComponentType = 0;
  if (const std::optional<StridedMesh> mesh = inPlaceMesh(plan, indexComponentType)) {
    ComputedTangents computed = computeSplit(plan, *mesh, indexComponentType);
    computed.compression = detail::primitiveCompression(asset_, primitive);
    computed.rebuild = computed.split.source.size() != mesh->vertexCount || computed.compression.any();
    return computed;
  }
  const detail::PrimitiveGeometry geometry = detail::readGeometry(asset_, primitive, plan.needs, plan.where, plan.generatesNormals);
  if (geometry.corners.empty()) {
    plan.result.reason = "primitive has no triangles; left as it is";
    return std::nullopt;
  }
  if (plan.generatesNormals) return computeWithGeneratedNormals(plan, geometry);
  std::optional<ComputedTangents> computed = computeFrames(plan, geometry, readTargetDeltas(plan, geometry.vertexCount));
  // Compressed data is written uncompressed: every accessor of a baked primitive is new.
  computed->compression = detail::primitiveCompression(asset_, primitive);
  computed->rebuild = computed->split.source.size() != geometry.vertexCount || geometry.mode != 4 || computed->compression.any();
  return computed;
}

// A primitive without NORMAL: normals generated (detail::generateNormals), its vertices split
// where they differ, tangents computed from them; the vertex split maps back to the input's
// vertices, and emit writes the generated NORMAL beside the gathered attributes.
std::optional<ComputedTangents> PrimitiveBaker::computeWithGeneratedNormals(PrimitivePlan& plan,
                                                                             const detail::PrimitiveGeometry& geometry) {
  const bool smooth = options_.normals == NormalsMode::smooth;
  std::vector<std::uint32_t> source;
  const detail::PrimitiveGeometry expanded = detail::withGeneratedNormals(geometry, smooth, options_.creaseAngleDegrees, source);
  std::vector<TargetDeltas> targets = readTargetDeltas(plan, geometry.vertexCount);
  for (TargetDeltas& target : targets) {
    for (std::vector<float>* deltas : {&target.positions, &target.normals}) {
      if (deltas->empty()) continue;
      std::vector<float> gathered(3 * expanded.vertexCount);
      for (std::size_t v = 0; v < expanded.vertexCount; ++v) std::copy_n(&(*deltas)[3 * source[v]], 3, &gathered[3 * v]);
      *deltas = std::move(gathered);
    }
  }
  std::optional<ComputedTangents> computed = computeFrames(plan, expanded, targets);
  if (!computed) return computed;
  computed->generatedNormals.resize(3 * computed->split.source.size());
  for (std::size_t v = 0; v < computed->split.source.size(); ++v) {
    const std::uint32_t inExpanded = computed->split.source[v];
    std::copy_n(&expanded.normals[3 * inExpanded], 3, &computed->generatedNormals[3 * v]);
    computed->split.source[v] = source[inExpanded];
  }
  computed->vertexCount = geometry.vertexCount;
  computed->indexComponentType = geometry.indexComponentType;
  computed->compression = detail::primitiveCompression(asset_, primitiveJson(plan));
  computed->rebuild = true;
  plan.result.verticesIn = geometry.vertexCount;
  plan.result.normalsGenerated = options_.normals;
  return computed;
}

std::vector<TargetDeltas> PrimitiveBaker::readTargetDeltas(const PrimitivePlan& plan, std::size_t vertexCount) {
  std::vector<TargetDeltas> deltas;
  const Json& primitive = primitiveJson(plan);
  if (!primitive.contains("targets") || !primitive["targets"].is_array()) return deltas;
  for (std::size_t t = 0; t < primitive["targets"].size(); ++t) {
    const Json& target = primitive["targets"][t];
    const std::string targetWhere = plan.where + ": target " + std::to_string(t);
    TargetDeltas& delta = deltas.emplace_back();
    if (const int position = detail::accessorOf(target, "POSITION"); position >= 0)
      delta.positions = detail::readVectors(asset_.model, position, 3, vertexCount, targetWhere + " POSITION");
    if (const int normal = detail::accessorOf(target, "NORMAL"); normal >= 0)
      delta.normals = detail::readVectors(asset_.model, normal, 3, vertexCount, targetWhere + " NORMAL");
  }
  return deltas;
}

// The core's options for `corners` corners, and the arena bake's own passes over them run in
// (null: one thread).
Options PrimitiveBaker::coreOptions(std::size_t corners) {
  Options options = options_.tangents;
  options.uvOrigin = kGltfUvOrigin;
  options.threads = detail::threadsFor(corners, options.threads);
  return options;
}
Arena* PrimitiveBaker::arenaFor(const Options& options) {
#if defined(TANGENT_SERIAL)
  (void)options;
  return nullptr;
#else
  const unsigned threads = threadCount(options);
  if (threads <= 1) return nullptr;
  if (!arena_ || arenaThreads_ != threads) {
    arena_.emplace(static_cast<int>(threads));
    arenaThreads_ = threads;
  }
  return &*arena_;
#endif
}

// The core on arrays it reads where they are (`mesh`: the primitive's own buffer, or arrays
// read for it), and the vertex split.
ComputedTangents PrimitiveBaker::computeSplit(PrimitivePlan& plan, const StridedMesh& mesh, int indexComponentType) {
  PrimitiveResult& result = plan.result;
  ComputedTangents computed;
  computed.vertexCount = mesh.vertexCount;
  computed.indexComponentType = indexComponentType;
  BulkVector<float> cornerTangents(mesh.indexCount * 4);
  BulkVector<std::uint32_t> cornerVertex(mesh.indexCount);
  const Options options = coreOptions(mesh.indexCount);
  result.tangents = computeCornerTangents(mesh, CornerOutputs{cornerTangents, {}, cornerVertex}, options, workspace_.get());
  computed.split = splitVertices(mesh, cornerTangents, std::move(cornerVertex), result.tangents.outputVertices, arenaFor(options));
  result.verticesIn = mesh.vertexCount;
  result.verticesOut = computed.split.source.size();
  return computed;
}

// The core on one geometry (a whole primitive, or its part of a shared buffer): corner frames,
// the vertex split and, per morph target, the TANGENT deltas of the split vertices.
std::optional<ComputedTangents> PrimitiveBaker::computeFrames(PrimitivePlan& plan, const detail::PrimitiveGeometry& geometry,
                                                              const std::vector<TargetDeltas>& targets) {
  PrimitiveResult& result = plan.result;
  const std::vector<std::uint32_t>& corners = geometry.corners;
  if (corners.empty()) {
    result.reason = "primitive has no triangles; left as it is";
    return std::nullopt;
  }
  StridedMesh mesh;  // the arrays, packed: read in place
  mesh.vertexCount = geometry.vertexCount;
  mesh.positions = geometry.positions.data();
  mesh.normals = geometry.normals.data();
  mesh.uvs = geometry.uvs.data();
  mesh.indices = corners.data();
  mesh.indexCount = corners.size();
  ComputedTangents computed = computeSplit(plan, mesh, geometry.indexComponentType);
  const VertexSplit& split = computed.split;
  const Options options = coreOptions(corners.size());
  for (const TargetDeltas& target : targets) {
    std::vector<float> morphedPositions = geometry.positions, morphedNormals = geometry.normals;
    for (std::size_t i = 0; i < target.positions.size(); ++i) morphedPositions[i] += target.positions[i];
    for (std::size_t i = 0; i < target.normals.size(); ++i) morphedNormals[i] += target.normals[i];
    // Readers normalize the morphed normal (spec 3.7.2.2), as they do the base one.
    if (!target.normals.empty()) detail::unitNormals(morphedNormals);
    BulkVector<float> morphedTangents(corners.size() * 4);
    computeCornerTangents({morphedPositions, morphedNormals, geometry.uvs, corners}, CornerOutputs{morphedTangents},
                          options, workspace_.get());
    std::vector<float> deltas(split.source.size() * 3, 0.0f);
    for (std::size_t v = 0; v < split.source.size(); ++v) {
      if (split.firstCorner[v] == kNoCorner) continue;
      const float* morphed = &morphedTangents[4 * std::size_t(split.firstCorner[v])];
      for (int i = 0; i < 3; ++i) deltas[3 * v + i] = morphed[i] - split.tangents[4 * v + i];
    }
    computed.targetTangentDeltas.push_back(std::move(deltas));
  }
  return computed;
}

// The primitive's own bytes as the core reads them, without a copy: where POSITION, NORMAL and
// the UV set are FLOAT accessors with a bufferView and no sparse values, the indices
// UNSIGNED_SHORT or UNSIGNED_INT packed in theirs, the mode a triangle list, no
// KHR_texture_transform turns the UVs, no morph target needs the arrays and no normal is one
// unitNormals would change. Anything else is read by readGeometry (std::nullopt here); so are
// the errors of a malformed accessor, which this gives as readGeometry would.
std::optional<StridedMesh> PrimitiveBaker::inPlaceMesh(const PrimitivePlan& plan, int& indexComponentType) {
  const Json& primitive = primitiveJson(plan);
  if (plan.generatesNormals || primitive.value("mode", 4) != 4) return std::nullopt;
  if (primitive.contains("targets") && !primitive["targets"].empty()) return std::nullopt;
  if (plan.needs.hasNormalTexture && detail::frameTextureTransform(output_.json(), primitive)) return std::nullopt;
  const Json& attributes = primitive["attributes"];
  const std::string uvName = "TEXCOORD_" + std::to_string(plan.needs.texCoord);
  const int positionIndex = detail::accessorOf(attributes, "POSITION"), normalIndex = detail::accessorOf(attributes, "NORMAL");
  const int uvIndex = detail::accessorOf(attributes, uvName), indicesIndex = detail::accessorOf(primitive, "indices");
  if (positionIndex < 0 || normalIndex < 0 || uvIndex < 0 || indicesIndex < 0) return std::nullopt;
  const tinygltf::Model& model = asset_.model;
  auto floats = [&](int index, int type, const std::string& name) -> std::optional<detail::DenseElements> {
    std::optional<detail::DenseElements> dense = detail::denseElements(model, index, plan.where + ": " + name);
    if (!dense || dense->header.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT || dense->header.type != type) return std::nullopt;
    return dense;
  };
  const auto positions = floats(positionIndex, TINYGLTF_TYPE_VEC3, "POSITION");
  const auto normals = floats(normalIndex, TINYGLTF_TYPE_VEC3, "NORMAL");
  const auto uvs = floats(uvIndex, TINYGLTF_TYPE_VEC2, uvName);
  const auto indices = detail::denseElements(model, indicesIndex, plan.where + ": indices");
  if (!positions || !normals || !uvs || !indices) return std::nullopt;
  const std::size_t vertexCount = positions->header.count;
  if (normals->header.count != vertexCount || uvs->header.count != vertexCount) return std::nullopt;
  const int indexType = indices->header.componentType;
  if (indices->header.type != TINYGLTF_TYPE_SCALAR ||
      (indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT && indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) ||
      indices->stride != indices->header.componentSize)
    return std::nullopt;
  const std::size_t cornerCount = indices->header.count - indices->header.count % 3;  // triangleList's rule
  if (cornerCount == 0) return std::nullopt;
  // unitNormals' rule, read only. Lengths squared well inside its band need no square root.
  constexpr double kInside = detail::kNormalLengthKept * 0.8;
  constexpr double kLow = (1 - kInside) * (1 - kInside), kHigh = (1 + kInside) * (1 + kInside);
  for (std::size_t v = 0; v < vertexCount; ++v) {
    float n[3];
    std::memcpy(n, normals->first + v * normals->stride, sizeof n);
    const double squared = double(n[0]) * n[0] + double(n[1]) * n[1] + double(n[2]) * n[2];
    if (squared > kLow && squared < kHigh) continue;
    const double length = std::sqrt(squared);
    if (!(length > 0) || !std::isfinite(length)) continue;  // left for the core's fallback, as unitNormals leaves it
    if (detail::normalNeedsNormalizing(length)) return std::nullopt;
  }
  StridedMesh mesh;
  mesh.vertexCount = vertexCount;
  mesh.positions = positions->first;
  mesh.positionStride = positions->stride;
  mesh.normals = normals->first;
  mesh.normalStride = normals->stride;
  mesh.uvs = uvs->first;
  mesh.uvStride = uvs->stride;
  mesh.indices = indices->first;
  mesh.indexCount = cornerCount;
  mesh.indexType = indexType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? IndexType::uint16 : IndexType::uint32;
  indexComponentType = indexType;
  return mesh;
}

// An accessor rebuilt attributes are gathered from: read where it lies in the loaded buffer
// (no copy of the whole accessor), else decoded once while one primitive or group is emitted
// (the parts of a shared buffer would otherwise each decode the whole of it).
const CarriedElements& PrimitiveBaker::carriedData(int index, const std::string& what, bool decoded) {
  const int key = decoded ? index + (1 << 30) : index;
  auto found = carried_.find(key);
  if (found != carried_.end()) return found->second;
  CarriedElements carried;
  std::optional<detail::DenseElements> dense;
  if (!decoded) dense = detail::denseElements(asset_.model, index, what);
  if (dense) {
    carried.data = std::move(dense->header);
    carried.first = dense->first;
    carried.stride = dense->stride;
  } else {
    carried.data = detail::readAccessor(asset_.model, index, what);
    carried.stride = carried.data.elementSize();
  }
  CarriedElements& stored = carried_.emplace(key, std::move(carried)).first->second;
  if (!dense) stored.first = stored.data.bytes.data();
  return stored;
}

// New accessors in a fixed order (carried attributes, carried target attributes, indices,
// TANGENT, target TANGENT deltas), so that the output's bytes depend on the input only.
SharedBake PrimitiveBaker::emit(const PrimitivePlan& plan, ComputedTangents& computed) {
  SharedBake shared;
  shared.baked = true;
  EmittedAccessors& emitted = shared.emitted;
  emitted.targets.resize(computed.targetTangentDeltas.size());
  if (computed.rebuild) {
    rebuildAttributes(plan, computed, emitted);
    if (!computed.generatedNormals.empty())
      emitted.attributes.emplace_back("NORMAL", output_.addAccessor(floatAccessor(computed.split.source.size(), "VEC3"),
                                                                    std::move(computed.generatedNormals), 12, detail::kArrayBuffer));
    rebuildTargets(plan, computed, emitted);
    writeIndices(plan, computed, emitted);
    emitted.dropDraco = computed.compression.draco;
  }
  writeTangents(plan, computed, emitted);
  shared.tangents = plan.result.tangents;
  shared.verticesIn = plan.result.verticesIn;
  shared.verticesOut = plan.result.verticesOut;
  shared.normalsGenerated = plan.result.normalsGenerated;
  if (computed.compression.any()) {
    std::string names;
    for (const std::string& name : detail::compressionNames(computed.compression)) names += (names.empty() ? "" : ", ") + name;
    shared.compressionNote = "; written uncompressed (was " + names + ")";
  }
  return shared;
}

// The primitive refers to the accessors baked for its inputs, and its result says so.
void PrimitiveBaker::refer(PrimitivePlan& plan, const SharedBake& shared) {
  PrimitiveResult& result = plan.result;
  if (!shared.baked) {
    result.reason = shared.notBaked;
    return;
  }
  const EmittedAccessors& emitted = shared.emitted;
  Json& primitive = primitiveJson(plan);
  for (const auto& [name, index] : emitted.attributes) primitive["attributes"][name] = index;
  for (std::size_t t = 0; t < emitted.targets.size(); ++t) {
    for (const auto& [name, index] : emitted.targets[t]) primitive["targets"][t][name] = index;
  }
  if (emitted.indices >= 0) {
    primitive["indices"] = emitted.indices;  // may insert: members of `primitive` are looked up by name from here on
    if (primitive.contains("mode")) primitive["mode"] = 4;
  }
  if (emitted.dropDraco) {
    primitive["extensions"].erase(detail::kDracoExtension);
    if (primitive["extensions"].empty()) primitive.erase("extensions");
  }
  result.action = PrimitiveAction::baked;
  result.tangentFormat = options_.tangentFormat;
  result.tangents = shared.tangents;
  result.verticesIn = shared.verticesIn;
  result.verticesOut = shared.verticesOut;
  result.normalsGenerated = shared.normalsGenerated;
  if (!plan.replacesTangent) result.reason = plan.why;
  result.reason += shared.compressionNote;
}

// Every attribute but TANGENT, gathered into the split vertices.
void PrimitiveBaker::rebuildAttributes(const PrimitivePlan& plan, const ComputedTangents& computed, EmittedAccessors& emitted) {
  std::vector<std::pair<std::string, int>> carried;  // taken first: the loop below appends to the document
  for (const auto& [name, accessorRef] : primitiveJson(plan)["attributes"].items()) {
    if (name != "TANGENT") carried.emplace_back(name, accessorRef.get<int>());
  }
  for (const auto& [name, index] : carried) {
    const CarriedElements& elements = carriedData(index, plan.where + ": " + name, computed.compression.draco);
    if (elements.data.count != computed.vertexCount)
      throw InputError(plan.where + ": " + name + " (accessor " + std::to_string(index) + ") has " + std::to_string(elements.data.count) +
                       " elements, POSITION has " + std::to_string(computed.vertexCount));
    emitted.attributes.emplace_back(name, addGathered(index, elements, computed));
  }
}

// Accessor `index` (decoded as `data`) gathered into the split vertices, as a new accessor. Its
// min/max are those of the data written where they may not hold: Draco's quantization moves
// values, and a part of a shared buffer spans less than the whole.
int PrimitiveBaker::addGathered(int index, const CarriedElements& carried, const ComputedTangents& computed) {
  const AccessorData& data = carried.data;
  const std::size_t outCount = computed.split.source.size();
  Json accessor = carriedAccessor(output_.json()["accessors"][index], outCount);
  std::vector<std::uint8_t> bytes = gather(carried.first, data.elementSize(), carried.stride, computed.split.source);
  if (computed.partOfBuffer) {
    AccessorData written;  // data's header, the gathered bytes (a copy of data would copy the whole buffer)
    written.componentType = data.componentType;
    written.type = data.type;
    written.normalized = data.normalized;
    written.components = data.components;
    written.componentSize = data.componentSize;
    written.count = outCount;
    written.bytes = std::move(bytes);  // lent for the bounds, then taken back: no copy
    recomputeBounds(accessor, written);
    bytes = std::move(written.bytes);
  } else if (computed.compression.draco) {
    recomputeBounds(accessor, data);
  }
  return output_.addAccessor(std::move(accessor), std::move(bytes), data.elementSize(), detail::kArrayBuffer);
}

// The morph targets' attributes (TANGENT aside), gathered the same way.
void PrimitiveBaker::rebuildTargets(const PrimitivePlan& plan, const ComputedTangents& computed, EmittedAccessors& emitted) {
  if (!primitiveJson(plan).contains("targets")) return;
  const std::size_t targetCount = primitiveJson(plan)["targets"].size();
  emitted.targets.resize(std::max(emitted.targets.size(), targetCount));
  for (std::size_t t = 0; t < targetCount; ++t) {
    std::vector<std::pair<std::string, int>> carried;
    for (const auto& [name, accessorRef] : primitiveJson(plan)["targets"][t].items()) {
      if (name != "TANGENT" && accessorRef.is_number_integer()) carried.emplace_back(name, accessorRef.get<int>());
    }
    for (const auto& [name, index] : carried) {
      const std::string what = plan.where + ": target " + std::to_string(t) + " " + name;
      const CarriedElements& elements = carriedData(index, what, computed.compression.draco);
      if (elements.data.count != computed.vertexCount)
        throw InputError(what + " has " + std::to_string(elements.data.count) + " elements, POSITION has " +
                         std::to_string(computed.vertexCount));
      emitted.targets[t].emplace_back(name, addGathered(index, elements, computed));
    }
  }
}

// Indices of the split vertices as a triangle list: the original component type, widened when
// the split outgrows it (the largest value of each type is primitive restart and not allowed).
// The split's indices (widened where the vertex count needs it), with the name, extras and
// extensions of the indices accessor they replace.
void PrimitiveBaker::writeIndices(const PrimitivePlan& plan, ComputedTangents& computed, EmittedAccessors& emitted) {
  const std::size_t outCount = computed.split.source.size();
  const BulkVector<std::uint32_t>& cornerVertex = computed.split.cornerVertex;
  int indexComponentType = computed.indexComponentType;
  if (outCount - 1 >= 255 && indexComponentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE)
    indexComponentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
  if (outCount - 1 >= 65535 && indexComponentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT)
    indexComponentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  const std::size_t indexSize = detail::componentBytes(indexComponentType);
  Json indexAccessor = {{"componentType", indexComponentType}, {"count", cornerVertex.size()}, {"type", "SCALAR"}};
  const Json& primitive = primitiveJson(plan);
  if (const int original = detail::accessorOf(primitive, "indices"); original >= 0) {
    const Json& accessor = asset_.json["accessors"][static_cast<std::size_t>(original)];
    for (const char* key : {"name", "extras", "extensions"})
      if (accessor.contains(key)) indexAccessor[key] = accessor[key];
  }
  if (indexSize == 4) {  // the core's array is the index data (little-endian, as glTF's)
    emitted.indices = output_.addAccessor(indexAccessor, std::move(computed.split.cornerVertex), 4, detail::kElementArrayBuffer);
    return;
  }
  std::vector<std::uint8_t> indexBytes(cornerVertex.size() * indexSize);
  for (std::size_t c = 0; c < cornerVertex.size(); ++c) {
    const std::uint32_t value = cornerVertex[c];
    if (indexSize == 1) indexBytes[c] = static_cast<std::uint8_t>(value);
    else {
      const auto v16 = static_cast<std::uint16_t>(value);
      std::memcpy(&indexBytes[2 * c], &v16, 2);
    }
  }
  emitted.indices = output_.addAccessor(indexAccessor, std::move(indexBytes), indexSize, detail::kElementArrayBuffer);
}

// TANGENT (with the name and extras of a TANGENT accessor it replaces), then the targets' deltas.
void PrimitiveBaker::writeTangents(const PrimitivePlan& plan, ComputedTangents& computed, EmittedAccessors& emitted) {
  EncodedTangents encoded = encodeTangents(std::move(computed.split.tangents), options_.tangentFormat);
  const Json& primitive = primitiveJson(plan);
  if (primitive.contains("attributes")) {
    if (const int replaced = detail::accessorOf(primitive["attributes"], "TANGENT"); replaced >= 0) {
      const Json& accessor = asset_.json["accessors"][static_cast<std::size_t>(replaced)];
      for (const char* key : {"name", "extras"})
        if (accessor.contains(key)) encoded.accessor[key] = accessor[key];
    }
  }
  emitted.attributes.emplace_back(
      "TANGENT", output_.addAccessor(encoded.accessor, std::move(encoded.bytes), encoded.stride, detail::kArrayBuffer));
  const std::size_t outCount = computed.split.source.size();
  for (std::size_t t = 0; t < computed.targetTangentDeltas.size(); ++t) {
    const int deltas = output_.addAccessor(floatAccessor(outCount, "VEC3"), std::move(computed.targetTangentDeltas[t]), 12,
                                           detail::kArrayBuffer);
    emitted.targets[t].emplace_back("TANGENT", deltas);
  }
}

}  // namespace

namespace {

BakeResult bakeChecked(const std::filesystem::path& input, const std::filesystem::path& output, const BakeOptions& options);

}  // namespace

BakeResult bakeFile(const std::filesystem::path& input, const std::filesystem::path& output, const BakeOptions& options) {
  return detail::throwingInputError(input, [&] { return bakeChecked(input, output, options); });
}

namespace {

BakeResult bakeChecked(const std::filesystem::path& input, const std::filesystem::path& output, const BakeOptions& options) {
  namespace fs = std::filesystem;
  const std::string outExt = output.extension().string();
  if (outExt != ".glb" && outExt != ".gltf")
    throw InputError(output.string() + ": output must end in .glb or .gltf");
  std::error_code ec;
  if (fs::exists(output, ec) && fs::equivalent(input, output, ec))
    throw InputError(output.string() + ": is the input file; bake never writes to its input");

  detail::Asset asset = detail::loadAsset(input, options.assetRoot);
  if (!output.parent_path().empty() && !fs::is_directory(output.parent_path(), ec)) {
    std::error_code made;
    fs::create_directories(output.parent_path(), made);
    if (!fs::is_directory(output.parent_path(), ec))
      throw std::runtime_error(output.parent_path().string() + ": cannot create the output's folder: " +
                               (made ? made.message() : std::string("not a folder")));
  }
  fs::path binPath = output;
  binPath.replace_extension(".bin");
  for (const fs::path& used : detail::referencedFiles(asset)) {
    if ((outExt == ".gltf" && fs::exists(used, ec) && fs::exists(binPath, ec) && fs::equivalent(used, binPath, ec)) ||
        (fs::exists(used, ec) && fs::exists(output, ec) && fs::equivalent(used, output, ec)))
      throw InputError(output.string() + ": would overwrite " + used.string() + ", which the input uses");
  }

  BakeResult result;
  result.warnings = asset.warnings;
  detail::OutputDocument document(asset);
  PrimitiveBaker baker(asset, document, options);
  Json& doc = document.json();
  result.primitives = baker.bakeAll();
  for (const PrimitiveResult& baked : result.primitives) {
    const std::string where = input.string() + ": " + detail::primitiveLabel(doc, baked.mesh, baked.primitive);
    // Consumers of the frame on other UV sets: TANGENT follows the first (the normal texture).
    if (baked.action == PrimitiveAction::baked) {
      const Json& primitive = doc["meshes"][baked.mesh]["primitives"][baked.primitive];
      const std::string other = detail::primitiveNeeds(doc, primitive, options.all || asset.fromMeshFile).otherFrames;
      if (!other.empty()) result.warnings.push_back(where + ": " + other);
    }
    // Non-finite input is baked (its corners get fallback frames) but never silently.
    if (!baked.tangents.nonFiniteTriangles && !baked.tangents.invalidNormals) continue;
    if (baked.tangents.nonFiniteTriangles)
      result.warnings.push_back(where + ": " + std::to_string(baked.tangents.nonFiniteTriangles) +
                                " triangles have non-finite (NaN or infinite) positions or UVs; their corners got fallback frames");
    if (baked.tangents.invalidNormals)
      result.warnings.push_back(where + ": " + std::to_string(baked.tangents.invalidNormals) +
                                " corners have zero or non-finite normals; replaced by their faces' normals");
  }
  // Declared after the loop: no reference into the document is held across the insertion.
  if (std::any_of(result.primitives.begin(), result.primitives.end(),
                  [](const PrimitiveResult& p) { return p.action == PrimitiveAction::baked && p.tangentFormat != TangentFormat::float32; }))
    declareRequiredExtension(doc, "KHR_mesh_quantization");
  result.bytesWritten = document.write(output, options.protectedFiles, options.keepExternalImages);
  result.filesWritten = document.filesWritten();
  result.extensionsRemoved = document.extensionsRemoved();
  return result;
}

}  // namespace

}  // namespace tangent::gltf
