// SPDX-License-Identifier: MIT
// Decoding glTF accessors (glTF 2.0 spec, section 3.6 "Binary Data Storage"): byteStride,
// normalized and plain integer components (KHR_mesh_quantization), sparse substitution,
// accessors without a bufferView (zeros). Every bound is checked; errors name the accessor.
#pragma once

#include <tiny_gltf.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace tangent::gltf::detail {

// An accessor's elements, tightly packed, sparse values applied.
struct AccessorData {
  int componentType = 0;
  int type = 0;
  bool normalized = false;
  int components = 0;
  std::size_t componentSize = 0;
  std::size_t count = 0;
  std::vector<std::uint8_t> bytes;  // count * components * componentSize
  std::size_t elementSize() const { return components * componentSize; }
};

int componentCount(int type);          // 0 when unknown
std::size_t componentBytes(int componentType);  // 0 when unknown
const char* typeName(int type);
const char* componentTypeName(int componentType);

// Work for data a file declares but does not store: an accessor without a bufferView is
// count zeros, which a 4 KB file can declare by the billion, and each of them is a value
// decoded, a vertex welded or an index of a triangle baked. The values the accessors of a
// file's meshes imply without storing them (count times components, each accessor once) may
// number kImpliedValuesFree plus kImpliedValuesPerStoredByte for each byte the file's buffers
// hold (a morph target's sparse accessor is as long as the stored POSITION it moves), and never
// more than kMaxImpliedValues (2 GiB decoded); loading refuses more, naming the accessor.
// Everything else bake, check and info allocate is bounded by the bytes the file stores.
inline constexpr std::uint64_t kImpliedValuesFree = std::uint64_t(1) << 20;
inline constexpr std::uint64_t kImpliedValuesPerStoredByte = 4;
inline constexpr std::uint64_t kMaxImpliedValues = std::uint64_t(1) << 29;

// The values accessor `accessorIndex` implies beyond those the file stores for it: count
// times components when it has no bufferView, else 0. The index must exist.
std::uint64_t impliedValues(const tinygltf::Model& model, int accessorIndex);

// `where` prefixes every error message ("file.glb: mesh 0 primitive 0: NORMAL").
AccessorData readAccessor(const tinygltf::Model& model, int accessorIndex, const std::string& where);

// The checks of readAccessor (every range against the loaded bytes, sparse targets) without
// copying anything; returns the element count.
std::size_t checkAccessor(const tinygltf::Model& model, int accessorIndex, const std::string& where);
// The same for an index accessor, and every index < vertexCount.
void checkIndexRange(const tinygltf::Model& model, int accessorIndex, std::size_t vertexCount, const std::string& where);

// An accessor's elements where they lie in the loaded buffer, for reading in place: the first
// element and the bytes from one to the next. Only for an accessor with a bufferView and no
// sparse values (else std::nullopt); every range is checked as readAccessor checks it, with the
// same errors. `header` gets the type and counts (its bytes stay empty).
struct DenseElements {
  AccessorData header;
  const std::uint8_t* first = nullptr;
  std::size_t stride = 0;
};
std::optional<DenseElements> denseElements(const tinygltf::Model& model, int accessorIndex, const std::string& where);

// Element values as floats; normalized integers follow the spec's decoding (max(c / 127, -1)...).
std::vector<float> toFloats(const AccessorData& data);

// Index values; checks the component type is an unsigned integer and each value < vertexCount.
std::vector<std::uint32_t> toIndices(const AccessorData& data, std::size_t vertexCount, const std::string& where);

// readAccessor then toFloats / toIndices, without the packed copy in between where the
// accessor has a bufferView and no sparse values (the usual case). `header` gets the
// accessor's type and counts (its bytes stay empty). readIndices names values out of range as
// `where (accessor N)`, as toIndices does.
std::vector<float> readFloats(const tinygltf::Model& model, int accessorIndex, const std::string& where, AccessorData& header);
std::vector<std::uint32_t> readIndices(const tinygltf::Model& model, int accessorIndex, std::size_t vertexCount,
                                       const std::string& where, AccessorData& header);

}  // namespace tangent::gltf::detail
