// SPDX-License-Identifier: MIT
// bake for primitives that share one vertex buffer and draw with different indices (a
// VertexGroup): the buffer read once, each part's frames from the vertices it uses, one shared
// TANGENT where the parts' frames agree.
#include <algorithm>
#include <cstring>
#include <optional>
#include <span>

#include "bake/primitive_baker.hpp"
#include "tangent/frame_rules.hpp"

namespace tangent::gltf::detail {
namespace {

using Json = nlohmann::ordered_json;

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

// The part of the buffer one primitive draws: its corners read, the vertices they use gathered
// (in the order usedVertices gives) with the morph targets' deltas of those vertices.
struct BufferPart {
  UsedVertices used;
  PrimitiveGeometry geometry;
  std::vector<TargetDeltas> targets;
};

BufferPart drawnPart(const Asset& asset, const Json& primitive, const std::string& where, const PrimitiveGeometry& buffer,
                     const std::vector<TargetDeltas>& targets, std::vector<std::uint32_t>& slotOf) {
  PrimitiveGeometry drawn;
  drawn.vertexCount = buffer.vertexCount;
  readCorners(asset, primitive, where, drawn);
  BufferPart part;
  part.used = usedVertices(drawn.corners, slotOf);
  part.geometry = gatherGeometry(buffer, part.used);
  part.geometry.mode = drawn.mode;
  part.geometry.indexComponentType = drawn.indexComponentType;
  part.targets.resize(targets.size());
  const std::vector<std::uint32_t>& vertices = part.used.vertices;
  for (std::size_t t = 0; t < targets.size(); ++t) {
    for (auto [whole, gathered] : {std::pair{&targets[t].positions, &part.targets[t].positions},
                                   std::pair{&targets[t].normals, &part.targets[t].normals}}) {
      if (whole->empty()) continue;
      gathered->resize(3 * vertices.size());
      for (std::size_t v = 0; v < vertices.size(); ++v) std::copy_n(&(*whole)[3 * vertices[v]], 3, &(*gathered)[3 * v]);
    }
  }
  return part;
}

}  // namespace

// The vertex attributes are read once; each input key's frames come from the vertices its
// corners use. Those whose frames fit BufferFrames share one TANGENT accessor over the whole
// buffer with the original attributes and indices; the others (a vertex split, a frame that
// differs from another primitive's on a shared vertex, strips or fans, compressed data) get
// their own attributes, only the vertices they use, re-indexed. Time and output are linear in
// the buffer plus the corners of the group. Emitted: the rebuilt sets in document order, then
// the shared TANGENT (and target TANGENT deltas).
void PrimitiveBaker::bakeVertexGroup(const VertexGroup& group, std::vector<PrimitivePlan>& plans) {
  const PrimitivePlan& first = plans[group.firstOfInput.front()];
  const PrimitiveGeometry buffer = readVertices(asset_, primitiveJson(first), first.needs, first.where);
  const std::vector<TargetDeltas> targets = readTargetDeltas(first, buffer.vertexCount);
  BufferFrames frames(buffer.vertexCount, targets.size());
  std::vector<std::uint32_t> slotOf(buffer.vertexCount, kNoSlot);
  std::vector<std::size_t> sharing;  // plans whose frames are in `frames`
  for (const std::size_t index : group.firstOfInput) {
    PrimitivePlan& plan = plans[index];
    const BufferPart part = drawnPart(asset_, primitiveJson(plan), plan.where, buffer, targets, slotOf);
    std::optional<ComputedTangents> computed = computeFrames(plan, part.geometry, part.targets);
    SharedBake& shared = groupBakes_[index];
    if (!computed) {
      shared.notBaked = plan.result.reason;
      continue;
    }
    computed->compression = primitiveCompression(asset_, primitiveJson(plan));
    const std::vector<std::uint32_t>& used = part.used.vertices;
    const bool unsplit = computed->split.source.size() == used.size();
    if (unsplit && part.geometry.mode == 4 && !computed->compression.any() && frames.agrees(used, *computed)) {
      frames.claim(used, *computed);
      sharing.push_back(index);
      continue;
    }
    for (std::uint32_t& source : computed->split.source) source = used[source];
    computed->vertexCount = buffer.vertexCount;
    computed->rebuild = true;
    computed->partOfBuffer = true;
    shared = emit(plan, *computed);
  }
  carried_.clear();
  if (sharing.empty()) return;
  const EmittedAccessors emitted = emitBufferTangents(frames.takeTangents(buffer.normals), frames.targetDeltas(), buffer.vertexCount);
  for (const std::size_t index : sharing) {
    SharedBake& shared = groupBakes_[index];
    shared.baked = true;
    shared.emitted = emitted;
    shared.tangents = plans[index].result.tangents;
    shared.verticesIn = plans[index].result.verticesIn;
    shared.verticesOut = plans[index].result.verticesOut;
  }
}

}  // namespace tangent::gltf::detail
