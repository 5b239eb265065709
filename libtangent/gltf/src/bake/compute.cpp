// SPDX-License-Identifier: MIT
// bake's compute phase: the core's corner tangents and vertex split for a primitive, read in
// place where its accessors allow; generated normals; the morph targets' TANGENT deltas. Reads
// the document only.
#include <cmath>
#include <cstring>
#include <optional>

#include "bake/primitive_baker.hpp"
#include "read/normals.hpp"
#include "tangent/bulk_buffer.hpp"

namespace tangent::gltf::detail {
namespace {
using Json = nlohmann::ordered_json;
// From this many corners (a million triangles) bake's core call frees its scratch as it goes
// (TangentWorkspace::setReleaseAsItGoes): at 4e6 triangles the bake's peak fell from 2.45x to
// 2.13x its input + output (lengyel 4.02x -> 3.21x), for the page faults of a fresh workspace
// in its next such call.
constexpr std::size_t kReleaseAsItGoesCorners = std::size_t(3) << 20;
}  // namespace

// Tangents per corner from the core, the vertex split, and TANGENT deltas for the morph
// targets (tangents of the morphed shape minus the base ones). Reads the document only.
std::optional<ComputedTangents> PrimitiveBaker::compute(PrimitivePlan& plan) {
  const Json& primitive = primitiveJson(plan);
  int indexComponentType = 0;
  if (const std::optional<StridedMesh> mesh = inPlaceMesh(plan, indexComponentType)) {
    ComputedTangents computed = computeSplit(plan, *mesh, indexComponentType);
    computed.compression = primitiveCompression(asset_, primitive);
    computed.rebuild = computed.split.source.size() != mesh->vertexCount || computed.compression.any();
    return computed;
  }
  const PrimitiveGeometry geometry = readGeometry(asset_, primitive, plan.needs, plan.where, plan.generatesNormals);
  if (geometry.corners.empty()) {
    plan.result.reason = "primitive has no triangles; left as it is";
    return std::nullopt;
  }
  if (plan.generatesNormals) return computeWithGeneratedNormals(plan, geometry);
  std::optional<ComputedTangents> computed = computeFrames(plan, geometry, readTargetDeltas(plan, geometry.vertexCount));
  // Compressed data is written uncompressed: every accessor of a baked primitive is new.
  computed->compression = primitiveCompression(asset_, primitive);
  computed->rebuild = computed->split.source.size() != geometry.vertexCount || geometry.mode != 4 || computed->compression.any();
  return computed;
}

// A primitive without NORMAL: normals generated (detail::generateNormals), its vertices split
// where they differ, tangents computed from them; the vertex split maps back to the input's
// vertices, and emit writes the generated NORMAL beside the gathered attributes.
std::optional<ComputedTangents> PrimitiveBaker::computeWithGeneratedNormals(PrimitivePlan& plan,
                                                                             const PrimitiveGeometry& geometry) {
  const bool smooth = options_.normals == NormalsMode::smooth;
  std::vector<std::uint32_t> source;
  const PrimitiveGeometry expanded = withGeneratedNormals(geometry, smooth, options_.creaseAngleDegrees, source);
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
  computed->compression = primitiveCompression(asset_, primitiveJson(plan));
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
    if (const int position = accessorOf(target, "POSITION"); position >= 0)
      delta.positions = readVectors(asset_.model, position, 3, vertexCount, targetWhere + " POSITION");
    if (const int normal = accessorOf(target, "NORMAL"); normal >= 0)
      delta.normals = readVectors(asset_.model, normal, 3, vertexCount, targetWhere + " NORMAL");
  }
  return deltas;
}

// The core's options for `corners` corners, and the arena bake's own passes over them run in
// (null: one thread).
Options PrimitiveBaker::coreOptions(std::size_t corners) {
  Options options = options_.tangents;
  options.uvOrigin = kGltfUvOrigin;
  options.threads = threadsFor(corners, options.threads);
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
  {
    // A primitive of a million triangles and more: its workspace (70-170 bytes a triangle) is
    // freed array by array as the call finishes with each, for a lower peak.
    TangentWorkspace& workspace = workspace_.get();
    const bool wasReleasing = workspace.releasesAsItGoes();
    workspace.setReleaseAsItGoes(wasReleasing || mesh.indexCount >= kReleaseAsItGoesCorners);
    struct Restore {
      TangentWorkspace& workspace;
      bool release;
      ~Restore() { workspace.setReleaseAsItGoes(release); }
    } restore{workspace, wasReleasing};
    result.tangents = computeCornerTangents(mesh, CornerOutputs{cornerTangents, {}, cornerVertex}, options, workspace);
  }
  computed.split = splitVertices(mesh, cornerTangents, std::move(cornerVertex), result.tangents.outputVertices, arenaFor(options));
  result.verticesIn = mesh.vertexCount;
  result.verticesOut = computed.split.source.size();
  return computed;
}

// The core on one geometry (a whole primitive, or its part of a shared buffer): corner frames,
// the vertex split and, per morph target, the TANGENT deltas of the split vertices.
std::optional<ComputedTangents> PrimitiveBaker::computeFrames(PrimitivePlan& plan, const PrimitiveGeometry& geometry,
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
    if (!target.normals.empty()) unitNormals(morphedNormals);
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
  if (plan.needs.hasNormalTexture && frameTextureTransform(output_.json(), primitive)) return std::nullopt;
  const Json& attributes = primitive["attributes"];
  const std::string uvName = "TEXCOORD_" + std::to_string(plan.needs.texCoord);
  const int positionIndex = accessorOf(attributes, "POSITION"), normalIndex = accessorOf(attributes, "NORMAL");
  const int uvIndex = accessorOf(attributes, uvName), indicesIndex = accessorOf(primitive, "indices");
  if (positionIndex < 0 || normalIndex < 0 || uvIndex < 0 || indicesIndex < 0) return std::nullopt;
  const tinygltf::Model& model = asset_.model;
  auto floats = [&](int index, int type, const std::string& name) -> std::optional<DenseElements> {
    std::optional<DenseElements> dense = denseElements(model, index, plan.where + ": " + name);
    if (!dense || dense->header.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT || dense->header.type != type) return std::nullopt;
    return dense;
  };
  const auto positions = floats(positionIndex, TINYGLTF_TYPE_VEC3, "POSITION");
  const auto normals = floats(normalIndex, TINYGLTF_TYPE_VEC3, "NORMAL");
  const auto uvs = floats(uvIndex, TINYGLTF_TYPE_VEC2, uvName);
  const auto indices = denseElements(model, indicesIndex, plan.where + ": indices");
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
  constexpr double kInside = kNormalLengthKept * 0.8;
  constexpr double kLow = (1 - kInside) * (1 - kInside), kHigh = (1 + kInside) * (1 + kInside);
  for (std::size_t v = 0; v < vertexCount; ++v) {
    float n[3];
    std::memcpy(n, normals->first + v * normals->stride, sizeof n);
    const double squared = double(n[0]) * n[0] + double(n[1]) * n[1] + double(n[2]) * n[2];
    if (squared > kLow && squared < kHigh) continue;
    const double length = std::sqrt(squared);
    if (!(length > 0) || !std::isfinite(length)) continue;  // left for the core's fallback, as unitNormals leaves it
    if (normalNeedsNormalizing(length)) return std::nullopt;
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

}  // namespace tangent::gltf::detail
