// SPDX-License-Identifier: MIT
#include "read/accessors.hpp"

#include <algorithm>
#include <cstring>

#include "tangent/gltf.hpp"

namespace tangent::gltf::detail {

int componentCount(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    case TINYGLTF_TYPE_MAT2: return 4;
    case TINYGLTF_TYPE_MAT3: return 9;
    case TINYGLTF_TYPE_MAT4: return 16;
    default: return 0;
  }
}

std::size_t componentBytes(int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;  // INT (5124) and DOUBLE are not valid in glTF 2.0 accessors
  }
}

const char* typeName(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return "SCALAR";
    case TINYGLTF_TYPE_VEC2: return "VEC2";
    case TINYGLTF_TYPE_VEC3: return "VEC3";
    case TINYGLTF_TYPE_VEC4: return "VEC4";
    case TINYGLTF_TYPE_MAT2: return "MAT2";
    case TINYGLTF_TYPE_MAT3: return "MAT3";
    case TINYGLTF_TYPE_MAT4: return "MAT4";
    default: return "unknown type";
  }
}

const char* componentTypeName(int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return "BYTE";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "UNSIGNED_BYTE";
    case TINYGLTF_COMPONENT_TYPE_SHORT: return "SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "UNSIGNED_SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "UNSIGNED_INT";
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return "FLOAT";
    default: return "unknown component type";
  }
}

namespace {

[[noreturn]] void fail(const std::string& where, int accessorIndex, const std::string& what) {
  throw InputError(where + " (accessor " + std::to_string(accessorIndex) + "): " + what);
}

// Bytes [offset, offset + length) of bufferView `viewIndex`, checked against its buffer.
const std::uint8_t* viewRange(const tinygltf::Model& model, int viewIndex, std::size_t offset, std::size_t length,
                              const std::string& where, int accessorIndex, const char* role) {
  if (viewIndex < 0 || viewIndex >= static_cast<int>(model.bufferViews.size()))
    fail(where, accessorIndex, std::string(role) + " bufferView " + std::to_string(viewIndex) + " does not exist");
  const tinygltf::BufferView& view = model.bufferViews[viewIndex];
  if (view.buffer < 0 || view.buffer >= static_cast<int>(model.buffers.size()))
    fail(where, accessorIndex, "bufferView " + std::to_string(viewIndex) + " names buffer " + std::to_string(view.buffer) +
                                   ", which does not exist");
  const auto& buffer = model.buffers[view.buffer].data;
  if (view.byteOffset > buffer.size() || view.byteLength > buffer.size() - view.byteOffset)
    fail(where, accessorIndex, "bufferView " + std::to_string(viewIndex) + " (offset " + std::to_string(view.byteOffset) +
                                   ", length " + std::to_string(view.byteLength) + ") lies outside buffer " +
                                   std::to_string(view.buffer) + " (" + std::to_string(buffer.size()) + " bytes loaded)");
  if (offset > view.byteLength || length > view.byteLength - offset)
    fail(where, accessorIndex, std::string(role) + " data (offset " + std::to_string(offset) + ", " + std::to_string(length) +
                                   " bytes) overruns bufferView " + std::to_string(viewIndex) + " (" +
                                   std::to_string(view.byteLength) + " bytes)");
  return buffer.data() + view.byteOffset + offset;
}

std::uint32_t readUnsigned(const std::uint8_t* p, int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return *p;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      std::uint16_t v;
      std::memcpy(&v, p, 2);
      return v;
    }
    default: {
      std::uint32_t v;
      std::memcpy(&v, p, 4);
      return v;
    }
  }
}

// glTF 2.0 3.7.2.1: indices are SCALAR of an unsigned integer type.
[[noreturn]] void indexOutOfRange(const std::string& where, std::uint32_t index, std::size_t position, std::size_t vertexCount) {
  throw InputError(where + ": index " + std::to_string(index) + " at position " + std::to_string(position) +
                   " is out of range (the primitive has " + std::to_string(vertexCount) + " vertices)");
}

// Throws for the first index not below vertexCount: one pass for the largest (which the
// compiler vectorizes), a second only to name a bad one.
void requireBelow(const std::vector<std::uint32_t>& indices, std::size_t vertexCount, const std::string& where) {
  std::uint32_t largest = 0;
  for (const std::uint32_t index : indices) largest = std::max(largest, index);
  if (indices.empty() || largest < vertexCount) return;
  for (std::size_t i = 0; i < indices.size(); ++i) {
    if (indices[i] >= vertexCount) indexOutOfRange(where, indices[i], i, vertexCount);
  }
}

// The largest of `count` unsigned indices of type T, `stride` bytes apart (any alignment).
template <typename T>
std::uint32_t largestIndex(const std::uint8_t* first, std::size_t stride, std::size_t count) {
  std::uint32_t largest = 0;
  if (stride == sizeof(T)) {
    for (std::size_t i = 0; i < count; ++i) {
      T value;
      std::memcpy(&value, first + i * sizeof(T), sizeof(T));
      largest = std::max<std::uint32_t>(largest, value);
    }
    return largest;
  }
  for (std::size_t i = 0; i < count; ++i) {
    T value;
    std::memcpy(&value, first + i * stride, sizeof(T));
    largest = std::max<std::uint32_t>(largest, value);
  }
  return largest;
}

void requireIndexType(const AccessorData& data, const std::string& where) {
  if (data.type != TINYGLTF_TYPE_SCALAR ||
      (data.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
       data.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
       data.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
    throw InputError(where + ": indices must be SCALAR of UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT, not " +
                     typeName(data.type) + " of " + componentTypeName(data.componentType));
}

// Where an accessor's bytes are, every range checked against the bytes actually loaded,
// before anything is allocated for it.
struct AccessorLayout {
  AccessorData header;               // all but bytes
  const std::uint8_t* dense = nullptr;  // first element, or null (zeros)
  std::size_t stride = 0;
  std::size_t sparseCount = 0;
  int sparseIndexType = 0;
  const std::uint8_t* sparseIndices = nullptr;
  const std::uint8_t* sparseValues = nullptr;
};

AccessorLayout locate(const tinygltf::Model& model, int accessorIndex, const std::string& where) {
  if (accessorIndex < 0 || accessorIndex >= static_cast<int>(model.accessors.size()))
    fail(where, accessorIndex, "accessor does not exist (the file has " + std::to_string(model.accessors.size()) + ")");
  const tinygltf::Accessor& accessor = model.accessors[accessorIndex];
  AccessorLayout layout;
  AccessorData& data = layout.header;
  data.componentType = accessor.componentType;
  data.type = accessor.type;
  data.normalized = accessor.normalized;
  data.components = componentCount(accessor.type);
  data.componentSize = componentBytes(accessor.componentType);
  data.count = accessor.count;
  if (data.components == 0) fail(where, accessorIndex, "invalid type " + std::to_string(accessor.type));
  if (data.componentSize == 0) fail(where, accessorIndex, "invalid componentType " + std::to_string(accessor.componentType));
  if (data.count == 0) fail(where, accessorIndex, "count is 0");
  if (data.count > (std::size_t(1) << 31) / data.elementSize())
    fail(where, accessorIndex, "count " + std::to_string(data.count) + " is over the limit of 2 GiB per accessor");
  const std::size_t elementSize = data.elementSize();

  if (accessor.bufferView >= 0) {
    if (static_cast<std::size_t>(accessor.bufferView) >= model.bufferViews.size())
      fail(where, accessorIndex, "bufferView " + std::to_string(accessor.bufferView) + " does not exist");
    const auto& view = model.bufferViews[accessor.bufferView];
    layout.stride = view.byteStride == 0 ? elementSize : view.byteStride;
    if (view.byteStride != 0 && (view.byteStride < elementSize || view.byteStride % data.componentSize != 0))
      fail(where, accessorIndex, "byteStride " + std::to_string(view.byteStride) + " does not fit " +
                                     std::to_string(elementSize) + "-byte elements");
    if (accessor.byteOffset % data.componentSize != 0)
      fail(where, accessorIndex, "byteOffset " + std::to_string(accessor.byteOffset) + " is not a multiple of the component size");
    const std::size_t span = layout.stride * (data.count - 1) + elementSize;
    layout.dense = viewRange(model, accessor.bufferView, accessor.byteOffset, span, where, accessorIndex, "element");
  }

  if (accessor.sparse.isSparse) {
    const auto& sparse = accessor.sparse;
    if (sparse.count <= 0 || static_cast<std::size_t>(sparse.count) > data.count)
      fail(where, accessorIndex, "sparse.count " + std::to_string(sparse.count) + " is not in 1.." + std::to_string(data.count));
    layout.sparseIndexType = sparse.indices.componentType;
    const std::size_t indexSize = componentBytes(layout.sparseIndexType);
    if (layout.sparseIndexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
        layout.sparseIndexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        layout.sparseIndexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
      fail(where, accessorIndex, "sparse.indices.componentType must be an unsigned integer type");
    layout.sparseCount = static_cast<std::size_t>(sparse.count);
    layout.sparseIndices = viewRange(model, sparse.indices.bufferView, static_cast<std::size_t>(sparse.indices.byteOffset),
                                     layout.sparseCount * indexSize, where, accessorIndex, "sparse index");
    layout.sparseValues = viewRange(model, sparse.values.bufferView, static_cast<std::size_t>(sparse.values.byteOffset),
                                    layout.sparseCount * elementSize, where, accessorIndex, "sparse value");
    // glTF 2.0 3.6.2.3: sparse indices strictly increase.
    std::int64_t previous = -1;
    for (std::size_t i = 0; i < layout.sparseCount; ++i) {
      const std::uint32_t target = readUnsigned(layout.sparseIndices + i * indexSize, layout.sparseIndexType);
      if (target >= data.count)
        fail(where, accessorIndex, "sparse index " + std::to_string(target) + " is out of range (count " + std::to_string(data.count) + ")");
      if (target <= previous)
        fail(where, accessorIndex, "/accessors/" + std::to_string(accessorIndex) + "/sparse/indices: index " + std::to_string(target) +
                                       " at position " + std::to_string(i) + " follows " + std::to_string(previous) +
                                       "; sparse indices must strictly increase");
      previous = target;
    }
  }
  return layout;
}

}  // namespace

std::uint64_t impliedValues(const tinygltf::Model& model, int accessorIndex) {
  const tinygltf::Accessor& accessor = model.accessors[accessorIndex];
  if (accessor.bufferView >= 0) return 0;
  return static_cast<std::uint64_t>(accessor.count) * static_cast<std::uint64_t>(componentCount(accessor.type));
}

AccessorData readAccessor(const tinygltf::Model& model, int accessorIndex, const std::string& where) {
  const AccessorLayout layout = locate(model, accessorIndex, where);
  AccessorData data = layout.header;
  const std::size_t elementSize = data.elementSize();
  data.bytes.assign(data.count * elementSize, 0);
  if (layout.dense) {
    for (std::size_t i = 0; i < data.count; ++i)
      std::memcpy(&data.bytes[i * elementSize], layout.dense + i * layout.stride, elementSize);
  }
  const std::size_t indexSize = componentBytes(layout.sparseIndexType);
  for (std::size_t i = 0; i < layout.sparseCount; ++i) {
    const std::uint32_t target = readUnsigned(layout.sparseIndices + i * indexSize, layout.sparseIndexType);
    std::memcpy(&data.bytes[target * elementSize], layout.sparseValues + i * elementSize, elementSize);
  }
  return data;
}

std::optional<DenseElements> denseElements(const tinygltf::Model& model, int accessorIndex, const std::string& where) {
  const AccessorLayout layout = locate(model, accessorIndex, where);
  if (!layout.dense || layout.sparseCount != 0) return std::nullopt;
  return DenseElements{layout.header, layout.dense, layout.stride};
}

std::size_t checkAccessor(const tinygltf::Model& model, int accessorIndex, const std::string& where) {
  return locate(model, accessorIndex, where).header.count;
}

void checkIndexRange(const tinygltf::Model& model, int accessorIndex, std::size_t vertexCount, const std::string& where) {
  const AccessorLayout layout = locate(model, accessorIndex, where);
  if (layout.sparseCount != 0) {
    toIndices(readAccessor(model, accessorIndex, where), vertexCount, where);
    return;
  }
  const AccessorData& data = layout.header;
  requireIndexType(data, where);
  if (!layout.dense) {
    if (vertexCount == 0) throw InputError(where + ": index 0 is out of range (the primitive has no vertices)");
    return;
  }
  // One typed pass for the largest (which the compiler vectorizes where the indices are packed),
  // a second only to name a bad one: at a million triangles the switch per element was most of
  // this check.
  const std::uint32_t largest = data.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE
                                    ? largestIndex<std::uint8_t>(layout.dense, layout.stride, data.count)
                                : data.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT
                                    ? largestIndex<std::uint16_t>(layout.dense, layout.stride, data.count)
                                    : largestIndex<std::uint32_t>(layout.dense, layout.stride, data.count);
  if (largest < vertexCount) return;
  for (std::size_t i = 0; i < data.count; ++i) {
    const std::uint32_t index = readUnsigned(layout.dense + i * layout.stride, data.componentType);
    if (index >= vertexCount) indexOutOfRange(where, index, i, vertexCount);
  }
}

std::vector<float> toFloats(const AccessorData& data) {
  const std::size_t n = data.count * data.components;
  std::vector<float> out(n);
  const std::uint8_t* p = data.bytes.data();
  for (std::size_t i = 0; i < n; ++i, p += data.componentSize) {
    float value = 0;
    switch (data.componentType) {
      case TINYGLTF_COMPONENT_TYPE_FLOAT: std::memcpy(&value, p, 4); break;
      case TINYGLTF_COMPONENT_TYPE_BYTE: {
        const auto c = static_cast<std::int8_t>(*p);
        value = data.normalized ? std::max(c / 127.0f, -1.0f) : c;
        break;
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: value = data.normalized ? *p / 255.0f : *p; break;
      case TINYGLTF_COMPONENT_TYPE_SHORT: {
        std::int16_t c;
        std::memcpy(&c, p, 2);
        value = data.normalized ? std::max(c / 32767.0f, -1.0f) : c;
        break;
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        std::uint16_t c;
        std::memcpy(&c, p, 2);
        value = data.normalized ? c / 65535.0f : c;
        break;
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
        std::uint32_t c;
        std::memcpy(&c, p, 4);
        value = static_cast<float>(c);
        break;
      }
      default: break;
    }
    out[i] = value;
  }
  return out;
}

std::vector<std::uint32_t> toIndices(const AccessorData& data, std::size_t vertexCount, const std::string& where) {
  requireIndexType(data, where);
  std::vector<std::uint32_t> out(data.count);
  for (std::size_t i = 0; i < data.count; ++i) out[i] = readUnsigned(&data.bytes[i * data.componentSize], data.componentType);
  requireBelow(out, vertexCount, where);
  return out;
}

std::vector<float> readFloats(const tinygltf::Model& model, int accessorIndex, const std::string& where, AccessorData& header) {
  const AccessorLayout layout = locate(model, accessorIndex, where);
  header = layout.header;
  if (!layout.dense || layout.sparseCount != 0 || header.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
    return toFloats(readAccessor(model, accessorIndex, where));
  const std::size_t elementSize = header.elementSize();
  std::vector<float> out(header.count * header.components);
  auto* target = reinterpret_cast<std::uint8_t*>(out.data());
  if (layout.stride == elementSize) {
    std::memcpy(target, layout.dense, header.count * elementSize);
  } else {
    for (std::size_t i = 0; i < header.count; ++i) std::memcpy(target + i * elementSize, layout.dense + i * layout.stride, elementSize);
  }
  return out;
}

std::vector<std::uint32_t> readIndices(const tinygltf::Model& model, int accessorIndex, std::size_t vertexCount,
                                       const std::string& where, AccessorData& header) {
  const AccessorLayout layout = locate(model, accessorIndex, where);
  header = layout.header;
  const std::string values = where + " (accessor " + std::to_string(accessorIndex) + ")";
  if (!layout.dense || layout.sparseCount != 0) return toIndices(readAccessor(model, accessorIndex, where), vertexCount, values);
  requireIndexType(header, values);
  std::vector<std::uint32_t> out(header.count);
  for (std::size_t i = 0; i < header.count; ++i) out[i] = readUnsigned(layout.dense + i * layout.stride, header.componentType);
  requireBelow(out, vertexCount, values);
  return out;
}

}  // namespace tangent::gltf::detail
