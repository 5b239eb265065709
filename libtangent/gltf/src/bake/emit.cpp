// SPDX-License-Identifier: MIT
// bake's emit and refer phases: new accessors for TANGENT and, where vertices split, every
// carried attribute and the indices, in a fixed order; then the primitive's references to them.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "bake/primitive_baker.hpp"
#include "entry_point.hpp"
#include "tangent/bulk_buffer.hpp"

namespace tangent::gltf::detail {
namespace {

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
  ViewBytes bytes;
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

// min/max of carried data where the stored ones may not hold: Draco's quantization moves
// values, and the validator compares min/max with the data. Per the spec they are in the
// stored (not normalized) units.
void recomputeBounds(Json& accessor, const AccessorData& data) {
  if (!accessor.contains("min") && !accessor.contains("max")) return;
  AccessorData raw = data;
  raw.normalized = false;
  const std::vector<float> values = toFloats(raw);
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
}  // namespace

// An accessor rebuilt attributes are gathered from: read where it lies in the loaded buffer
// (no copy of the whole accessor), else decoded once while one primitive or group is emitted
// (the parts of a shared buffer would otherwise each decode the whole of it).
const CarriedElements& PrimitiveBaker::carriedData(int index, const std::string& what, bool decoded) {
  const int key = decoded ? index + (1 << 30) : index;
  auto found = carried_.find(key);
  if (found != carried_.end()) return found->second;
  CarriedElements carried;
  std::optional<DenseElements> dense;
  if (!decoded) dense = denseElements(asset_.model, index, what);
  if (dense) {
    carried.data = std::move(dense->header);
    carried.first = dense->first;
    carried.stride = dense->stride;
  } else {
    carried.data = readAccessor(asset_.model, index, what);
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
                                                                    std::move(computed.generatedNormals), 12, kArrayBuffer));
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
    for (const std::string& name : compressionNames(computed.compression)) names += (names.empty() ? "" : ", ") + name;
    shared.compressionNote = "; written uncompressed (was " + names + ")";
  }
  return shared;
}

// The TANGENT the sharing primitives of a vertex group refer to, over the whole buffer, and
// each target's TANGENT deltas.
EmittedAccessors PrimitiveBaker::emitBufferTangents(std::vector<float> tangents, std::vector<std::vector<float>>& targetDeltas,
                                                    std::size_t vertexCount) {
  EmittedAccessors emitted;
  EncodedTangents encoded = encodeTangents(std::move(tangents), options_.tangentFormat);
  emitted.attributes.emplace_back(
      "TANGENT", output_.addAccessor(encoded.accessor, std::move(encoded.bytes), encoded.stride, kArrayBuffer));
  emitted.targets.resize(targetDeltas.size());
  for (std::size_t t = 0; t < targetDeltas.size(); ++t) {
    const int deltas = output_.addAccessor(floatAccessor(vertexCount, "VEC3"), std::move(targetDeltas[t]), 12, kArrayBuffer);
    emitted.targets[t].emplace_back("TANGENT", deltas);
  }
  return emitted;
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
    primitive["extensions"].erase(kDracoExtension);
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
  return output_.addAccessor(std::move(accessor), std::move(bytes), data.elementSize(), kArrayBuffer);
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
  const std::size_t indexSize = componentBytes(indexComponentType);
  Json indexAccessor = {{"componentType", indexComponentType}, {"count", cornerVertex.size()}, {"type", "SCALAR"}};
  const Json& primitive = primitiveJson(plan);
  if (const int original = accessorOf(primitive, "indices"); original >= 0) {
    const Json& accessor = asset_.json["accessors"][static_cast<std::size_t>(original)];
    for (const char* key : {"name", "extras", "extensions"})
      if (accessor.contains(key)) indexAccessor[key] = accessor[key];
  }
  if (indexSize == 4) {  // the core's array is the index data (little-endian, as glTF's)
    emitted.indices = output_.addAccessor(indexAccessor, std::move(computed.split.cornerVertex), 4, kElementArrayBuffer);
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
  emitted.indices = output_.addAccessor(indexAccessor, std::move(indexBytes), indexSize, kElementArrayBuffer);
}

// TANGENT (with the name and extras of a TANGENT accessor it replaces), then the targets' deltas.
void PrimitiveBaker::writeTangents(const PrimitivePlan& plan, ComputedTangents& computed, EmittedAccessors& emitted) {
  EncodedTangents encoded = encodeTangents(std::move(computed.split.tangents), options_.tangentFormat);
  const Json& primitive = primitiveJson(plan);
  if (primitive.contains("attributes")) {
    if (const int replaced = accessorOf(primitive["attributes"], "TANGENT"); replaced >= 0) {
      const Json& accessor = asset_.json["accessors"][static_cast<std::size_t>(replaced)];
      for (const char* key : {"name", "extras"})
        if (accessor.contains(key)) encoded.accessor[key] = accessor[key];
    }
  }
  emitted.attributes.emplace_back(
      "TANGENT", output_.addAccessor(encoded.accessor, std::move(encoded.bytes), encoded.stride, kArrayBuffer));
  const std::size_t outCount = computed.split.source.size();
  for (std::size_t t = 0; t < computed.targetTangentDeltas.size(); ++t) {
    const int deltas = output_.addAccessor(floatAccessor(outCount, "VEC3"), std::move(computed.targetTangentDeltas[t]), 12,
                                           kArrayBuffer);
    emitted.targets[t].emplace_back("TANGENT", deltas);
  }
}

}  // namespace tangent::gltf::detail
