// SPDX-License-Identifier: MIT
// What a primitive is and needs, and reading the geometry tangents are computed from.
// glTF 2.0 spec 3.7.2.1: tangents come from the UV set the normal texture uses;
// KHR_texture_transform on the normal texture may override that set and turns the UVs.
#include "read/primitive.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <set>
#include <unordered_map>

#include "tangent/gltf.hpp"

namespace tangent::gltf::detail {

using Json = nlohmann::ordered_json;

std::string primitiveLabel(const Json& doc, int mesh, int primitive) {
  std::string label = "mesh " + std::to_string(mesh);
  const Json& meshJson = doc["meshes"][mesh];
  if (meshJson.contains("name") && meshJson["name"].is_string()) label += " '" + meshJson["name"].get<std::string>() + "'";
  return label + " primitive " + std::to_string(primitive);
}

const char* toString(FrameConsumer consumer) {
  switch (consumer) {
    case FrameConsumer::normalTexture: return "normalTexture";
    case FrameConsumer::clearcoatNormalTexture: return "clearcoatNormalTexture";
    case FrameConsumer::anisotropy: return "anisotropy";
  }
  return "";
}

namespace {

// The primitive's material, or null (validateDocument has checked the document's types).
const Json* materialOf(const Json& doc, const Json& primitive) {
  if (!primitive.contains("material") || !primitive["material"].is_number_integer() || !doc.contains("materials")) return nullptr;
  const int index = primitive["material"].get<int>();
  if (index < 0 || index >= static_cast<int>(doc["materials"].size())) return nullptr;
  return &doc["materials"][index];
}

const Json* member(const Json& owner, const char* key) {
  return owner.is_object() && owner.contains(key) && owner[key].is_object() ? &owner[key] : nullptr;
}

const Json* extension(const Json& owner, const char* name) {
  const Json* extensions = member(owner, "extensions");
  return extensions ? member(*extensions, name) : nullptr;
}

// A consumer with its texture info (null: anisotropy without a texture), in the order TANGENT
// follows them.
std::vector<std::pair<ConsumerUse, const Json*>> consumersOf(const Json& material) {
  std::vector<std::pair<ConsumerUse, const Json*>> found;
  auto add = [&](FrameConsumer consumer, const Json* info) {
    ConsumerUse use{consumer, 0, false, info != nullptr};
    if (info) {
      use.texCoord = info->contains("texCoord") && (*info)["texCoord"].is_number_integer() ? (*info)["texCoord"].get<int>() : 0;
      const Json* transform = extension(*info, "KHR_texture_transform");
      if (transform && transform->contains("texCoord") && (*transform)["texCoord"].is_number_integer()) {
        use.texCoord = (*transform)["texCoord"].get<int>();
        use.texCoordFromTransform = true;
      }
    }
    found.emplace_back(use, info);
  };
  if (const Json* normal = member(material, "normalTexture")) add(FrameConsumer::normalTexture, normal);
  if (const Json* clearcoat = extension(material, "KHR_materials_clearcoat"))
    if (const Json* normal = member(*clearcoat, "clearcoatNormalTexture")) add(FrameConsumer::clearcoatNormalTexture, normal);
  if (const Json* anisotropy = extension(material, "KHR_materials_anisotropy")) {
    const Json* texture = member(*anisotropy, "anisotropyTexture");
    const bool strength = anisotropy->contains("anisotropyStrength") && (*anisotropy)["anisotropyStrength"].is_number() &&
                          (*anisotropy)["anisotropyStrength"].get<double>() != 0;
    if (texture || strength) add(FrameConsumer::anisotropy, texture);
  }
  return found;
}

const Json* transformOf(const Json* info) { return info ? extension(*info, "KHR_texture_transform") : nullptr; }

// "clearcoatNormalTexture samples TEXCOORD_1" for each consumer whose frame the first one's
// TANGENT does not give: another UV set, or the same set through another transform.
std::string otherFrames(const std::vector<std::pair<ConsumerUse, const Json*>>& consumers) {
  std::string text;
  const auto& [first, firstInfo] = consumers.front();
  const Json none = Json::object();
  const Json& firstTransform = transformOf(firstInfo) ? *transformOf(firstInfo) : none;
  for (std::size_t i = 1; i < consumers.size(); ++i) {
    const auto& [use, info] = consumers[i];
    if (!use.sampled) continue;  // anisotropy without a texture reads TANGENT as it is
    Json transform = transformOf(info) ? *transformOf(info) : none, compared = firstTransform;
    transform.erase("texCoord");
    compared.erase("texCoord");
    std::string why;
    if (use.texCoord != first.texCoord) why = " samples TEXCOORD_" + std::to_string(use.texCoord);
    else if (transform != compared) why = " has another KHR_texture_transform";
    if (!why.empty()) text += std::string(text.empty() ? "" : "; ") + toString(use.consumer) + why;
  }
  if (text.empty()) return text;
  return text + ", but TANGENT follows the " + toString(first.consumer) + " (TEXCOORD_" + std::to_string(first.texCoord) +
         "): one TANGENT cannot give both frames";
}

}  // namespace

const Json* frameTextureTransform(const Json& doc, const Json& primitive) {
  const Json* material = materialOf(doc, primitive);
  if (!material) return nullptr;
  const auto consumers = consumersOf(*material);
  return consumers.empty() ? nullptr : transformOf(consumers.front().second);
}

PrimitiveNeeds primitiveNeeds(const Json& doc, const Json& primitive, bool all) {
  PrimitiveNeeds needs;
  const int mode = primitive.value("mode", 4);
  needs.triangles = mode == 4 || mode == 5 || mode == 6;
  if (const Json* material = materialOf(doc, primitive)) {
    const auto consumers = consumersOf(*material);
    for (const auto& [use, info] : consumers) needs.consumers.push_back(use);
    if (!consumers.empty()) {
      const ConsumerUse& first = needs.consumers.front();
      needs.hasNormalTexture = true;
      needs.texCoord = first.texCoord;
      needs.texCoordFromTransform = first.texCoordFromTransform;
      needs.why = "material " + std::to_string(primitive["material"].get<int>()) + " has " +
                  (first.consumer == FrameConsumer::anisotropy ? std::string("anisotropy (KHR_materials_anisotropy)")
                                                               : "a " + std::string(toString(first.consumer))) +
                  (first.sampled || first.consumer != FrameConsumer::anisotropy ? " on TEXCOORD_" + std::to_string(first.texCoord)
                                                                                 : ", no texture: TEXCOORD_0") +
                  (first.texCoordFromTransform ? " (KHR_texture_transform)" : "");
      needs.otherFrames = otherFrames(consumers);
      // Anisotropy alone, without a texture, on a primitive without UVs: no frame to compute
      // (left as it is, not a broken file as a texture on a missing UV set is).
      if (first.consumer == FrameConsumer::anisotropy && !first.sampled &&
          (!primitive.contains("attributes") || accessorOf(primitive["attributes"], "TEXCOORD_0") < 0)) {
        needs.hasNormalTexture = false;
        needs.texCoord = -1;
        needs.why = "material " + std::to_string(primitive["material"].get<int>()) +
                    " has anisotropy but no texture, and the primitive has no TEXCOORD_0 to compute tangents from";
        return needs.triangles ? needs : (needs.why = "mode " + std::to_string(mode) + " is not triangles", needs);
      }
    }
  }
  if (!needs.hasNormalTexture) {
    if (all) {
      needs.texCoord = 0;
      needs.why = "no normalTexture; --all uses TEXCOORD_0";
    } else {
      needs.why = "material has no normalTexture (use --all to bake anyway)";
    }
  }
  if (!needs.triangles) needs.why = "mode " + std::to_string(mode) + " is not triangles";
  return needs;
}

std::string bakeReason(const PrimitiveNeeds& needs, bool fromMeshFile) {
  return fromMeshFile && !needs.hasNormalTexture && bakesTangents(needs)
             ? "OBJ/PLY/OFF carry no materials: every mesh is baked, from its texture coordinates"
             : needs.why;
}

std::string missingUvSet(const Json& primitive, const PrimitiveNeeds& needs) {
  if (!needs.triangles || !needs.hasNormalTexture) return {};
  const std::string uvName = "TEXCOORD_" + std::to_string(needs.texCoord);
  if (accessorOf(primitive["attributes"], uvName) >= 0) return {};
  return needs.why + ", but the primitive has no " + uvName + " attribute";
}

namespace {

// sameInputKey and sameVertexKey: every input of the tangents, with or without the indices and
// the mode.
std::string inputKey(const Json& doc, const Json& primitive, const PrimitiveNeeds& needs, bool withIndices) {
  auto withoutTangent = [](const Json& map) {
    Json copy = Json::object();
    if (!map.is_object()) return copy;
    for (const auto& [name, value] : map.items()) {
      if (name != "TANGENT") copy[name] = value;
    }
    return copy;
  };
  Json key = Json::array();
  key.push_back(withoutTangent(primitive.value("attributes", Json::object())));
  Json targets = Json::array();
  if (primitive.contains("targets") && primitive["targets"].is_array()) {
    for (const Json& target : primitive["targets"]) targets.push_back(withoutTangent(target));
  }
  key.push_back(std::move(targets));
  if (withIndices) {
    key.push_back(primitive.value("indices", Json(-1)));
    key.push_back(primitive.value("mode", Json(4)));
  }
  const Json* draco = nullptr;
  if (primitive.contains("extensions") && primitive["extensions"].is_object() &&
      primitive["extensions"].contains("KHR_draco_mesh_compression"))
    draco = &primitive["extensions"]["KHR_draco_mesh_compression"];
  key.push_back(draco ? *draco : Json(nullptr));
  key.push_back(needs.texCoord);
  const Json* transform = needs.hasNormalTexture ? frameTextureTransform(doc, primitive) : nullptr;
  key.push_back(transform ? *transform : Json(nullptr));
  return key.dump();
}

}  // namespace

std::string sameInputKey(const Json& doc, const Json& primitive, const PrimitiveNeeds& needs) {
  return inputKey(doc, primitive, needs, true);
}

std::string sameVertexKey(const Json& doc, const Json& primitive, const PrimitiveNeeds& needs) {
  return inputKey(doc, primitive, needs, false);
}

unsigned threadsFor(std::size_t corners, unsigned requested) {
  return corners < kCornersPerExtraThread ? 1u : requested;
}

std::string missingPosition(const Json& primitive, const PrimitiveNeeds& needs) {
  if (!needs.triangles || needs.texCoord < 0) return {};
  if (primitive.contains("attributes") && accessorOf(primitive["attributes"], "POSITION") >= 0) return {};
  return "has no POSITION attribute";
}

int requiredAttributeType(const std::string& semantic) {
  if (semantic == "POSITION" || semantic == "NORMAL") return TINYGLTF_TYPE_VEC3;
  if (semantic.rfind("TEXCOORD_", 0) == 0) return TINYGLTF_TYPE_VEC2;
  return 0;
}

int accessorOf(const Json& object, const std::string& name) {
  auto it = object.find(name);
  return it != object.end() && it->is_number_integer() ? it->get<int>() : -1;
}

// The values of a VEC2/VEC3 float-like accessor; checks type and count.
std::vector<float> readVectors(const tinygltf::Model& model, int accessor, int components, std::size_t expectedCount,
                               const std::string& where) {
  AccessorData data;
  std::vector<float> values = detail::readFloats(model, accessor, where, data);
  if (data.components != components || data.type == TINYGLTF_TYPE_MAT2)
    throw InputError(where + " (accessor " + std::to_string(accessor) + "): expected VEC" + std::to_string(components) +
                     ", found " + detail::typeName(data.type));
  if (expectedCount != 0 && data.count != expectedCount)
    throw InputError(where + " (accessor " + std::to_string(accessor) + "): has " + std::to_string(data.count) +
                     " elements, POSITION has " + std::to_string(expectedCount));
  return values;
}

// KHR_texture_transform: uv' = T * R * S * uv. Rotation and scale change tangent directions.
std::array<double, 6> textureTransformMatrix(const Json& transform) {
  double offset[2] = {0, 0}, scale[2] = {1, 1};
  if (transform.contains("offset") && transform["offset"].size() == 2) {
    offset[0] = transform["offset"][0].get<double>();
    offset[1] = transform["offset"][1].get<double>();
  }
  if (transform.contains("scale") && transform["scale"].size() == 2) {
    scale[0] = transform["scale"][0].get<double>();
    scale[1] = transform["scale"][1].get<double>();
  }
  const double rotation = transform.value("rotation", 0.0);
  const double c = std::cos(rotation), s = std::sin(rotation);
  return {c * scale[0], -s * scale[0], s * scale[1], c * scale[1], offset[0], offset[1]};
}

void applyTextureTransform(std::vector<float>& uvs, const Json& transform) {
  const std::array<double, 6> m = textureTransformMatrix(transform);
  for (std::size_t i = 0; i + 1 < uvs.size(); i += 2) {
    const double u = uvs[i], v = uvs[i + 1];
    uvs[i] = static_cast<float>(m[0] * u + m[2] * v + m[4]);
    uvs[i + 1] = static_cast<float>(m[1] * u + m[3] * v + m[5]);
  }
}

std::vector<std::uint32_t> triangleList(int mode, std::vector<std::uint32_t> vertices) {
  if (mode == 4) {
    vertices.resize(vertices.size() - vertices.size() % 3);
    return vertices;
  }
  std::vector<std::uint32_t> out;
  for (std::size_t i = 0; i + 2 < vertices.size(); ++i) {
    std::uint32_t a, b, c;
    if (mode == 5) {
      a = vertices[i];
      b = vertices[i + 1 + i % 2];
      c = vertices[i + 2 - i % 2];
      if (a == b || b == c || a == c) continue;  // stitching triangles of joined strips draw nothing
    } else {
      a = vertices[i + 1];
      b = vertices[i + 2];
      c = vertices[0];
    }
    out.insert(out.end(), {a, b, c});
  }
  return out;
}


PrimitiveGeometry readGeometry(const Asset& asset, const Json& primitive, const PrimitiveNeeds& needs, const std::string& where,
                               bool normalOptional) {
  PrimitiveGeometry geometry = readVertices(asset, primitive, needs, where, normalOptional);
  readCorners(asset, primitive, where, geometry);
  return geometry;
}

PrimitiveGeometry readVertices(const Asset& asset, const Json& primitive, const PrimitiveNeeds& needs, const std::string& where,
                               bool normalOptional) {
  const tinygltf::Model& model = asset.model;
  const Json& attributes = primitive["attributes"];
  const int positionAccessor = accessorOf(attributes, "POSITION");
  const int normalAccessor = accessorOf(attributes, "NORMAL");
  const std::string uvName = "TEXCOORD_" + std::to_string(needs.texCoord);
  const int uvAccessor = accessorOf(attributes, uvName);
  if (positionAccessor < 0) throw InputError(where + ": has no POSITION attribute");
  if (normalAccessor < 0 && !normalOptional) throw InputError(where + ": has no NORMAL attribute");
  if (uvAccessor < 0) throw InputError(where + ": has no " + uvName + " attribute");

  PrimitiveGeometry geometry;
  AccessorData positionData;
  geometry.positions = readFloats(model, positionAccessor, where + ": POSITION", positionData);
  if (positionData.components != 3 || positionData.type != TINYGLTF_TYPE_VEC3)
    throw InputError(where + ": POSITION (accessor " + std::to_string(positionAccessor) + ") must be VEC3, found " +
                     typeName(positionData.type));
  geometry.vertexCount = positionData.count;
  if (normalAccessor >= 0) {
    geometry.normals = readVectors(model, normalAccessor, 3, geometry.vertexCount, where + ": NORMAL");
    geometry.normalLengths = unitNormals(geometry.normals);
  }
  geometry.uvs = readVectors(model, uvAccessor, 2, geometry.vertexCount, where + ": " + uvName);
  if (const Json* transform = needs.hasNormalTexture ? frameTextureTransform(asset.json, primitive) : nullptr)
    applyTextureTransform(geometry.uvs, *transform);
  return geometry;
}

void readCorners(const Asset& asset, const Json& primitive, const std::string& where, PrimitiveGeometry& geometry) {
  const tinygltf::Model& model = asset.model;
  geometry.mode = primitive.value("mode", 4);
  std::vector<std::uint32_t> sequence;
  const int indicesAccessor = accessorOf(primitive, "indices");
  if (indicesAccessor >= 0) {
    AccessorData indexData;
    sequence = readIndices(model, indicesAccessor, geometry.vertexCount, where + ": indices", indexData);
    geometry.indexComponentType = indexData.componentType;
  } else {
    sequence.resize(geometry.vertexCount);
    std::iota(sequence.begin(), sequence.end(), 0u);
  }
  geometry.corners = triangleList(geometry.mode, std::move(sequence));
}

UsedVertices usedVertices(const std::vector<std::uint32_t>& corners, std::vector<std::uint32_t>& slotOf) {
  UsedVertices used;
  for (const std::uint32_t v : corners) {
    if (slotOf[v] != kNoSlot) continue;
    slotOf[v] = 0;
    used.vertices.push_back(v);
  }
  std::sort(used.vertices.begin(), used.vertices.end());
  for (std::size_t i = 0; i < used.vertices.size(); ++i) slotOf[used.vertices[i]] = static_cast<std::uint32_t>(i);
  used.corners.resize(corners.size());
  for (std::size_t c = 0; c < corners.size(); ++c) used.corners[c] = slotOf[corners[c]];
  for (const std::uint32_t v : used.vertices) slotOf[v] = kNoSlot;
  return used;
}

PrimitiveGeometry gatherGeometry(const PrimitiveGeometry& buffer, const UsedVertices& used) {
  PrimitiveGeometry part;
  const std::size_t n = used.vertices.size();
  part.vertexCount = n;
  part.positions.resize(3 * n);
  if (!buffer.normals.empty()) part.normals.resize(3 * n);  // none where the primitive has no NORMAL
  part.uvs.resize(2 * n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t v = used.vertices[i];
    std::copy_n(&buffer.positions[3 * v], 3, &part.positions[3 * i]);
    if (!buffer.normals.empty()) std::copy_n(&buffer.normals[3 * v], 3, &part.normals[3 * i]);
    std::copy_n(&buffer.uvs[2 * v], 2, &part.uvs[2 * i]);
  }
  part.corners = used.corners;
  return part;
}

void keepUsedVertices(PrimitiveGeometry& buffer, UsedVertices& used) {
  const std::size_t n = used.vertices.size();
  const bool hasNormals = !buffer.normals.empty();
  // used.vertices ascends, so vertex i moves from used.vertices[i] >= i: never over one not yet moved.
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t v = used.vertices[i];
    if (v == i) continue;
    std::copy_n(&buffer.positions[3 * v], 3, &buffer.positions[3 * i]);
    if (hasNormals) std::copy_n(&buffer.normals[3 * v], 3, &buffer.normals[3 * i]);
    std::copy_n(&buffer.uvs[2 * v], 2, &buffer.uvs[2 * i]);
  }
  buffer.vertexCount = n;
  buffer.positions.resize(3 * n);
  if (hasNormals) buffer.normals.resize(3 * n);
  buffer.uvs.resize(2 * n);
  buffer.corners = std::move(used.corners);
}

void verifyMeshData(const Asset& asset) {
  const Json& doc = asset.json;
  const std::string file = asset.path.string();
  // Each accessor is checked once, and an index accessor once per vertex count, however many
  // primitives share it (CAD scenes: 1e5 primitives on a few accessors).
  std::unordered_map<int, std::size_t> countOf;
  std::set<std::pair<int, std::size_t>> indicesChecked;
  // Values the file implies without storing them, every accessor once (meshes, skins and
  // animations alike): within the budget of kImpliedValuesFree.
  std::uint64_t storedBytes = 0;
  for (const tinygltf::Buffer& buffer : asset.model.buffers) storedBytes += buffer.data.size();
  const std::uint64_t impliedBudget =
      std::min(kMaxImpliedValues, kImpliedValuesFree + kImpliedValuesPerStoredByte * storedBytes);
  std::uint64_t implied = 0;
  for (std::size_t a = 0; a < asset.model.accessors.size(); ++a) {
    const std::uint64_t values = impliedValues(asset.model, static_cast<int>(a));
    implied += values;
    if (values > 0 && implied > impliedBudget)
      throw InputError(file + ": /accessors/" + std::to_string(a) + ": has no bufferView: its " +
                       std::to_string(asset.model.accessors[a].count) + " elements are zeros the file does not store, " +
                       std::to_string(values) + " values to compute (" + std::to_string(implied) +
                       " with the accessors before it); a file whose buffers hold " + std::to_string(storedBytes) +
                       " bytes may imply at most " + std::to_string(impliedBudget));
  }
  auto checkAccessor = [&](const tinygltf::Model& model, int accessor, const std::string& where) {
    auto known = countOf.find(accessor);
    if (known != countOf.end()) return known->second;
    const std::size_t count = detail::checkAccessor(model, accessor, where);
    return countOf.emplace(accessor, count).first->second;
  };
  const std::size_t meshCount = doc.contains("meshes") ? doc["meshes"].size() : 0;
  for (std::size_t m = 0; m < meshCount; ++m) {
    const Json& primitives = doc["meshes"][m]["primitives"];
    for (std::size_t p = 0; p < primitives.size(); ++p) {
      const Json& primitive = primitives[p];
      const std::string where = file + ": " + primitiveLabel(doc, static_cast<int>(m), static_cast<int>(p));
      const int position = accessorOf(primitive["attributes"], "POSITION");
      const std::size_t vertexCount = position >= 0 ? checkAccessor(asset.model, position, where + ": POSITION") : 0;
      auto attributes = [&](const Json& map, const std::string& prefix) {
        for (const auto& [name, value] : map.items()) {
          const std::string at = where + ": " + prefix + name;
          const std::size_t count = checkAccessor(asset.model, value.get<int>(), at);
          const int type = asset.model.accessors[value.get<int>()].type;
          if (const int required = requiredAttributeType(name); required != 0 && type != required)
            throw InputError(at + " (accessor " + value.dump() + "): must be " + typeName(required) + ", found " + typeName(type));
          if (position >= 0 && count != vertexCount)
            throw InputError(at + " (accessor " + value.dump() + "): has " + std::to_string(count) + " elements, POSITION has " +
                             std::to_string(vertexCount));
        }
      };
      attributes(primitive["attributes"], "");
      if (primitive.contains("targets")) {
        for (std::size_t t = 0; t < primitive["targets"].size(); ++t)
          attributes(primitive["targets"][t], "target " + std::to_string(t) + " ");
      }
      const int indices = accessorOf(primitive, "indices");
      if (indices >= 0 && position >= 0 && indicesChecked.emplace(indices, vertexCount).second)
        checkIndexRange(asset.model, indices, vertexCount, where + ": indices (accessor " + std::to_string(indices) + ")");
    }
  }
}

}  // namespace tangent::gltf::detail
