// SPDX-License-Identifier: MIT
// KHR_draco_mesh_compression (KhronosGroup/glTF, extensions/2.0/Khronos/KHR_draco_mesh_compression):
// a primitive's attributes and indices decoded from the Draco stream in the extension's
// bufferView. Each glTF attribute named in the extension's `attributes` map is the Draco
// attribute with that unique id; the primitive's accessors describe the decoded data (type,
// componentType, normalized, count), and their decoded values become plain accessor data.
#include <draco/compression/decode.h>

#include <cstring>
#include <map>
#include <new>

#include "read/accessors.hpp"
#include "read/compression.hpp"
#include "read/primitive.hpp"
#include "tangent/gltf.hpp"

namespace tangent::gltf::detail {
namespace {

using Json = nlohmann::ordered_json;

class PrimitiveDecoder {
 public:
  PrimitiveDecoder(Asset& asset, std::size_t mesh, std::size_t primitive, std::map<int, std::string>& decodedAccessors)
      : asset_(asset), primitive_(asset.json["meshes"][mesh]["primitives"][primitive]), decodedAccessors_(decodedAccessors),
        element_("meshes[" + std::to_string(mesh) + "].primitives[" + std::to_string(primitive) + "]"),
        where_(asset.path.string() + ": " + element_ + " " + kDracoExtension + ": ") {}

  void decode();

 private:
  [[noreturn]] void fail(const std::string& what) const { throw InputError(where_ + what); }
  std::unique_ptr<draco::Mesh> decodeStream(const Json& extension) const;
  // The accessor `accessorIndex` (named `role`) now reads `bytes`, in a new buffer and view.
  void replaceAccessorData(int accessorIndex, const std::string& role, std::vector<unsigned char> bytes);
  void decodeAttribute(const draco::Mesh& mesh, const std::string& name, int accessorIndex, std::uint32_t uniqueId);
  void decodeIndices(const draco::Mesh& mesh, int accessorIndex);

  Asset& asset_;
  const Json& primitive_;
  std::map<int, std::string>& decodedAccessors_;  // accessor -> the element that decoded it
  std::string element_;
  std::string where_;
};

std::unique_ptr<draco::Mesh> PrimitiveDecoder::decodeStream(const Json& extension) const {
  const int viewIndex = accessorOf(extension, "bufferView");
  const auto& model = asset_.model;
  if (viewIndex < 0 || viewIndex >= static_cast<int>(model.bufferViews.size()))
    fail("bufferView " + (extension.contains("bufferView") ? extension["bufferView"].dump() : std::string("(missing)")) +
         " does not exist");
  const tinygltf::BufferView& view = model.bufferViews[viewIndex];
  if (view.buffer < 0 || view.buffer >= static_cast<int>(model.buffers.size()))
    fail("bufferView " + std::to_string(viewIndex) + " names a buffer that does not exist");
  const auto& buffer = model.buffers[view.buffer].data;
  if (view.byteOffset > buffer.size() || view.byteLength > buffer.size() - view.byteOffset)
    fail("bufferView " + std::to_string(viewIndex) + " (offset " + std::to_string(view.byteOffset) + ", length " +
         std::to_string(view.byteLength) + ") lies outside the " + std::to_string(buffer.size()) + " bytes loaded for its buffer");
  draco::DecoderBuffer stream;
  stream.Init(reinterpret_cast<const char*>(buffer.data() + view.byteOffset), view.byteLength);
  draco::Decoder decoder;
  try {
    auto decoded = decoder.DecodeMeshFromBuffer(&stream);
    if (!decoded.ok()) fail("the Draco stream in bufferView " + std::to_string(viewIndex) + " cannot be decoded: " + decoded.status().error_msg_string());
    std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
    if (!mesh) fail("the Draco stream in bufferView " + std::to_string(viewIndex) + " holds no mesh");
    return mesh;
  } catch (const std::bad_alloc&) {
    fail("the Draco stream in bufferView " + std::to_string(viewIndex) + " claims more data than can be allocated");
  } catch (const std::length_error&) {
    fail("the Draco stream in bufferView " + std::to_string(viewIndex) + " claims more data than can be allocated");
  }
}

void PrimitiveDecoder::replaceAccessorData(int accessorIndex, const std::string& role, std::vector<unsigned char> bytes) {
  auto [it, inserted] = decodedAccessors_.emplace(accessorIndex, element_ + " " + role);
  if (!inserted)
    fail(role + " (accessor " + std::to_string(accessorIndex) + ") is also decoded by " + it->second +
         "; one accessor cannot hold two Draco primitives' data");
  auto& model = asset_.model;
  tinygltf::Buffer buffer;
  buffer.data = std::move(bytes);
  const std::size_t length = buffer.data.size();
  model.buffers.push_back(std::move(buffer));
  tinygltf::BufferView view;
  view.buffer = static_cast<int>(model.buffers.size()) - 1;
  view.byteOffset = 0;
  view.byteLength = length;
  model.bufferViews.push_back(view);
  tinygltf::Accessor& accessor = model.accessors[accessorIndex];
  accessor.bufferView = static_cast<int>(model.bufferViews.size()) - 1;
  accessor.byteOffset = 0;
  accessor.sparse = {};
}

template <typename T>
bool convertAll(const draco::Mesh& mesh, const draco::PointAttribute& attribute, int components, std::vector<unsigned char>& out) {
  const std::size_t points = mesh.num_points();
  out.resize(points * components * sizeof(T));
  std::vector<T> value(components);
  for (std::size_t p = 0; p < points; ++p) {
    const draco::AttributeValueIndex index = attribute.mapped_index(draco::PointIndex(static_cast<std::uint32_t>(p)));
    if (index.value() >= attribute.size()) return false;
    if (!attribute.ConvertValue<T>(index, static_cast<std::int8_t>(components), value.data())) return false;
    std::memcpy(&out[p * components * sizeof(T)], value.data(), components * sizeof(T));
  }
  return true;
}

void PrimitiveDecoder::decodeAttribute(const draco::Mesh& mesh, const std::string& name, int accessorIndex, std::uint32_t uniqueId) {
  const auto& model = asset_.model;
  if (accessorIndex < 0 || accessorIndex >= static_cast<int>(model.accessors.size()))
    fail(name + ": accessor " + std::to_string(accessorIndex) + " does not exist");
  const tinygltf::Accessor& accessor = model.accessors[accessorIndex];
  const draco::PointAttribute* attribute = mesh.GetAttributeByUniqueId(uniqueId);
  if (!attribute) fail(name + ": the Draco stream has no attribute with unique id " + std::to_string(uniqueId));
  const int components = componentCount(accessor.type);
  if (components == 0 || componentBytes(accessor.componentType) == 0)
    fail(name + " (accessor " + std::to_string(accessorIndex) + "): invalid type or componentType");
  if (attribute->num_components() != components)
    fail(name + ": the Draco attribute has " + std::to_string(attribute->num_components()) + " components, accessor " +
         std::to_string(accessorIndex) + " is " + typeName(accessor.type));
  if (accessor.count != mesh.num_points())
    fail(name + ": accessor " + std::to_string(accessorIndex) + " has count " + std::to_string(accessor.count) +
         ", the Draco stream decodes " + std::to_string(mesh.num_points()) + " vertices");
  std::vector<unsigned char> bytes;
  bool ok = false;
  switch (accessor.componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: ok = convertAll<std::int8_t>(mesh, *attribute, components, bytes); break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: ok = convertAll<std::uint8_t>(mesh, *attribute, components, bytes); break;
    case TINYGLTF_COMPONENT_TYPE_SHORT: ok = convertAll<std::int16_t>(mesh, *attribute, components, bytes); break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: ok = convertAll<std::uint16_t>(mesh, *attribute, components, bytes); break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: ok = convertAll<std::uint32_t>(mesh, *attribute, components, bytes); break;
    default: ok = convertAll<float>(mesh, *attribute, components, bytes); break;
  }
  if (!ok) fail(name + ": the Draco attribute's values cannot be converted to " + componentTypeName(accessor.componentType));
  replaceAccessorData(accessorIndex, name, std::move(bytes));
}

void PrimitiveDecoder::decodeIndices(const draco::Mesh& mesh, int accessorIndex) {
  const auto& model = asset_.model;
  if (accessorIndex < 0 || accessorIndex >= static_cast<int>(model.accessors.size()))
    fail("indices: accessor " + std::to_string(accessorIndex) + " does not exist");
  const tinygltf::Accessor& accessor = model.accessors[accessorIndex];
  const std::size_t indexSize = componentBytes(accessor.componentType);
  if (accessor.type != TINYGLTF_TYPE_SCALAR ||
      (accessor.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
       accessor.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
       accessor.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
    fail("indices (accessor " + std::to_string(accessorIndex) + ") must be SCALAR of an unsigned integer type");
  const std::size_t faces = mesh.num_faces();
  if (accessor.count != 3 * faces)
    fail("indices: accessor " + std::to_string(accessorIndex) + " has count " + std::to_string(accessor.count) +
         ", the Draco stream decodes " + std::to_string(faces) + " triangles (" + std::to_string(3 * faces) + " indices)");
  const std::uint64_t largest = indexSize == 1 ? 0xffu : indexSize == 2 ? 0xffffu : 0xffffffffu;
  std::vector<unsigned char> bytes(3 * faces * indexSize);
  for (std::size_t f = 0; f < faces; ++f) {
    const draco::Mesh::Face& face = mesh.face(draco::FaceIndex(static_cast<std::uint32_t>(f)));
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t point = face[c].value();
      if (point >= mesh.num_points())
        fail("indices: decoded index " + std::to_string(point) + " at position " + std::to_string(3 * f + c) +
             " is out of range (the stream decodes " + std::to_string(mesh.num_points()) + " vertices)");
      if (point > largest)
        fail("indices: decoded index " + std::to_string(point) + " does not fit accessor " + std::to_string(accessorIndex) +
             "'s " + componentTypeName(accessor.componentType));
      std::memcpy(&bytes[(3 * f + c) * indexSize], &point, indexSize);  // little-endian: the low bytes
    }
  }
  replaceAccessorData(accessorIndex, "indices", std::move(bytes));
}

void PrimitiveDecoder::decode() {
  const Json& extension = primitive_["extensions"][kDracoExtension];
  if (!extension.is_object()) fail("must be an object");
  const int mode = primitive_.value("mode", 4);
  if (mode != 4) fail("mode " + std::to_string(mode) + " is not decoded; only triangle lists (mode 4) are");
  const int indices = accessorOf(primitive_, "indices");
  if (indices < 0) fail("the primitive has no indices accessor for the decoded triangles");
  if (!extension.contains("attributes") || !extension["attributes"].is_object())
    fail("attributes is required and must be an object");
  const Json& attributes = primitive_.contains("attributes") ? primitive_["attributes"] : Json::object();
  for (const auto& [name, id] : extension["attributes"].items()) {
    if (!id.is_number_integer() || id.get<std::int64_t>() < 0 || id.get<std::int64_t>() > 0xffffffffLL)
      fail("attributes." + name + " must be a non-negative integer id");
    if (accessorOf(attributes, name) < 0) fail("attributes." + name + " names an attribute the primitive does not have");
  }
  const std::unique_ptr<draco::Mesh> mesh = decodeStream(extension);
  for (const auto& [name, id] : extension["attributes"].items())
    decodeAttribute(*mesh, name, accessorOf(attributes, name), id.get<std::uint32_t>());
  decodeIndices(*mesh, indices);
}

}  // namespace

void decodeDracoPrimitives(Asset& asset) {
  const Json& doc = asset.json;
  if (!doc.contains("meshes")) return;
  std::map<int, std::string> decodedAccessors;
  for (std::size_t m = 0; m < doc["meshes"].size(); ++m) {
    const Json& mesh = doc["meshes"][m];
    if (!mesh.contains("primitives")) continue;
    for (std::size_t p = 0; p < mesh["primitives"].size(); ++p) {
      const Json& primitive = mesh["primitives"][p];
      if (primitive.contains("extensions") && primitive["extensions"].is_object() &&
          primitive["extensions"].contains(kDracoExtension))
        PrimitiveDecoder(asset, m, p, decodedAccessors).decode();
    }
  }
}

}  // namespace tangent::gltf::detail
