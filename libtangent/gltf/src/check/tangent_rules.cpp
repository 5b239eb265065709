// SPDX-License-Identifier: MIT
// The limits of the stored-tangent rules (tangent_rules.hpp), derived from the rounding step of
// the component types glTF 2.0 and KHR_mesh_quantization allow:
//
// A normalized component c of n bits decodes to c / (2^(n-1) - 1) (spec 3.11): step
// s = 1/127 (BYTE) or 1/32767 (SHORT), rounding error <= s/2 per component. Tools often store
// fewer significant bits b inside the component (gltfpack -vn, gltf-transform quantize's
// quantizeNormal, default 10): the value is rounded to 1/(2^(b-1) - 1) first, then to s, so the
// error is <= 0.5/(2^(b-1) - 1) + s/2. The xyz error vector e has |e| <= sqrt(3) * that, hence
//   | |xyz| - 1 | <= |e|             (triangle inequality)
//   direction error <= asin(|e|)      (the widest angle of a ball of radius |e| around a unit vector)
// We accept BYTE at its full 8 bits and SHORT down to 10 significant bits:
//   BYTE:  e1 = 0.5/127 = 3.94e-3, |xyz| within 6.82e-3, angle <= 0.391 deg
//   SHORT: e1 = 0.5/511 + 0.5/32767 = 9.94e-4, |xyz| within 1.72e-3, angle <= 0.0986 deg
//   FLOAT: |xyz| within 1e-3 (writers' own rounding), angle 0.
// `orthogonal` compares TANGENT with NORMAL, both rounded: tolerance + both angles. `reference`
// compares TANGENT with a frame recomputed from the rounded NORMAL (projection onto a plane tilted
// by d turns a direction by at most d): tolerance + both angles, plus what rounded positions and
// UVs do to the recomputed frame (referenceAllowance, in reference_allowance.cpp).
#include "check/tangent_rules.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <utility>

#include "read/accessors.hpp"
#include "read/compression.hpp"
#include "read/asset.hpp"
#include "read/primitive.hpp"

namespace tangent::gltf::detail {
namespace {

using Json = nlohmann::ordered_json;

constexpr double kFloatUnitDeviation = 1e-3;  // float writers' rounding and normalization
constexpr int kByteBits = 8;
constexpr int kFewestShortBits = 10;           // gltf-transform quantize's default for normals
constexpr int kFewestSpreadBits = 8;           // the coarsest grid looked for in 16-bit positions and UVs
constexpr int kMostDracoBits = 30;             // Draco's limit on quantization bits

double gridStep(int bits) { return 1.0 / double((1 << (bits - 1)) - 1); }

// The storage step of one decoded component: 0 for float, 1 for unnormalized integers.
double storageStep(int componentType, bool normalized) {
  if (componentType == TINYGLTF_COMPONENT_TYPE_FLOAT) return 0;
  if (!normalized) return 1;
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return 1.0 / 127;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1.0 / 255;
    case TINYGLTF_COMPONENT_TYPE_SHORT: return 1.0 / 32767;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 1.0 / 65535;
    default: return 0;
  }
}

// The smallest positive gap between two values of one component: no larger than the grid step
// where the values lie on a grid, a bound from above on what rounding to it moved them.
double smallestGap(const std::vector<float>& values, int components, std::size_t count, double start) {
  double gap = start;
  std::vector<float> column;
  column.reserve(count);
  for (int component = 0; component < components; ++component) {
    column.clear();
    for (std::size_t i = 0; i < count; ++i) column.push_back(values[i * components + component]);
    std::sort(column.begin(), column.end());
    for (std::size_t i = 1; i < column.size(); ++i) {
      const double d = double(column[i]) - column[i - 1];
      if (d > 0 && std::isfinite(d)) gap = std::min(gap, d);
    }
  }
  return gap;
}

// Normalized 16-bit data may hold b < 16 significant bits in one of two layouts:
//  - in the low bits, 0 .. 2^b - 1, scaled back by KHR_texture_transform or the node (gltfpack
//    -vt/-vp): the grid is the storage step itself;
//  - spread over the whole range (gltf-transform quantize, meshoptimizer's quantizeUnorm
//    rescaled): a b-bit value k is stored as k's bits repeated, (k << (16 - b)) | (k >> (2b - 16)),
//    or as round(k * 65535 / (2^b - 1)); both approximate k / (2^b - 1).
// A smallest-gap estimate cannot tell these apart: on a regular mesh the gaps are the mesh's
// spacing, many grid steps wide. The stored integers can: the coarsest b whose spread grid holds
// every magnitude exactly is the grid; none holds them all when the data use their full
// precision or the low-bits layout. Sign (SHORT) takes one bit: b counts the magnitude's bits plus it.
bool onSpreadGrid(std::uint32_t magnitude, int valueBits, int storageBits) {
  const std::uint32_t k = magnitude >> (storageBits - valueBits);
  const int low = 2 * valueBits - storageBits;  // fewer than half the bits: repeated once, the rest 0
  const std::uint32_t replicated = (k << (storageBits - valueBits)) | (low >= 0 ? k >> low : 0);
  if (replicated == magnitude) return true;
  const double storageMax = double((1u << storageBits) - 1), valueMax = double((1u << valueBits) - 1);
  const double nearest = std::round(double(magnitude) * valueMax / storageMax);
  return std::lround(nearest * storageMax / valueMax) == long(magnitude);
}

// The decoded step of the grid normalized 16-bit `data` lies on (see onSpreadGrid).
double normalizedShortGridStep(const AccessorData& data) {
  const bool isSigned = data.componentType == TINYGLTF_COMPONENT_TYPE_SHORT;
  const int storageBits = isSigned ? 15 : 16;
  std::vector<std::uint32_t> magnitudes(data.count * data.components);
  for (std::size_t i = 0; i < magnitudes.size(); ++i) {
    std::uint16_t raw = 0;
    std::memcpy(&raw, &data.bytes[2 * i], 2);
    // SHORT -32768 decodes as -1, as 32767 does (spec 3.11).
    magnitudes[i] = isSigned ? std::min<std::uint32_t>(std::abs(int(std::int16_t(raw))), 32767) : raw;
  }
  std::sort(magnitudes.begin(), magnitudes.end());
  magnitudes.erase(std::unique(magnitudes.begin(), magnitudes.end()), magnitudes.end());
  for (int valueBits = kFewestSpreadBits - (isSigned ? 1 : 0); valueBits < storageBits; ++valueBits) {
    const bool fits = std::all_of(magnitudes.begin(), magnitudes.end(),
                                  [&](std::uint32_t m) { return onSpreadGrid(m, valueBits, storageBits); });
    if (fits) return 1.0 / double((1u << valueBits) - 1);
  }
  return 1.0 / double((1u << storageBits) - 1);
}

// Draco quantizes an attribute to b bits over one range for all its components (the widest
// component's) from each component's minimum, and decodes to float: min_c + q * range / (2^b - 1).
// The coarsest b whose grid holds every decoded value (to float's rounding) is the grid; where
// none does, the smallest gap between values, which is at least the step.
double dracoGridStep(const std::vector<float>& values, int components, std::size_t count) {
  if (count == 0) return 0;
  std::vector<double> minimum(components, std::numeric_limits<double>::infinity()), maximum(components, -minimum[0]);
  for (std::size_t i = 0; i < count; ++i)
    for (int c = 0; c < components; ++c) {
      minimum[c] = std::min(minimum[c], double(values[i * components + c]));
      maximum[c] = std::max(maximum[c], double(values[i * components + c]));
    }
  double range = 0, magnitude = 0;
  for (int c = 0; c < components; ++c) {
    range = std::max(range, maximum[c] - minimum[c]);
    magnitude = std::max({magnitude, std::abs(minimum[c]), std::abs(maximum[c])});
  }
  if (!(range > 0) || !std::isfinite(range)) return 0;
  constexpr double kFloatEpsilon = 1.2e-7;
  for (int bits = kFewestSpreadBits; bits <= kMostDracoBits; ++bits) {
    const double step = range / double((1u << bits) - 1);
    const double slack = 4 * kFloatEpsilon * (magnitude + range) / step;  // float decoding's error, in steps
    if (slack > 0.05) break;  // finer grids cannot be told apart from float data
    bool fits = true;
    for (std::size_t i = 0; i < count && fits; ++i)
      for (int c = 0; c < components && fits; ++c) {
        const double q = (double(values[i * components + c]) - minimum[c]) / step;
        fits = std::abs(q - std::round(q)) <= slack + 1e-6;
      }
    if (fits) return step;
  }
  const double gap = smallestGap(values, components, count, std::numeric_limits<double>::infinity());
  return std::isfinite(gap) ? gap : 0;
}

// Half the rounding step of a position or UV accessor, in its decoded units.
// `dracoFloats`: the accessor was decoded from a Draco stream (dracoGridStep).
double halfRoundingStep(const tinygltf::Model& model, int accessor, const std::string& where, bool dracoFloats) {
  if (accessor < 0 || static_cast<std::size_t>(accessor) >= model.accessors.size()) return 0;
  // The declared type first: other float data is never read here.
  const tinygltf::Accessor& declared = model.accessors[static_cast<std::size_t>(accessor)];
  if (dracoFloats && declared.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT) {
    const AccessorData data = readAccessor(model, accessor, where);
    return dracoGridStep(toFloats(data), data.components, data.count) / 2;
  }
  const double storage = storageStep(declared.componentType, declared.normalized);
  if (storage == 0) return 0;
  if (!declared.normalized || componentBytes(declared.componentType) == 1) return storage / 2;
  // Rounded to the grid, then (spread layouts) to the storage step.
  const double grid = normalizedShortGridStep(readAccessor(model, accessor, where));
  return grid > storage ? (grid + storage) / 2 : storage / 2;
}

}  // namespace

std::optional<StoredComponent> storedComponentOf(int componentType, bool normalized) {
  if (componentType == TINYGLTF_COMPONENT_TYPE_FLOAT) return StoredComponent::float32;
  if (normalized && componentType == TINYGLTF_COMPONENT_TYPE_SHORT) return StoredComponent::normalizedShort;
  if (normalized && componentType == TINYGLTF_COMPONENT_TYPE_BYTE) return StoredComponent::normalizedByte;
  return std::nullopt;
}

const char* toString(StoredComponent component) {
  switch (component) {
    case StoredComponent::float32: return "float";
    case StoredComponent::normalizedShort: return "normalized SHORT";
    case StoredComponent::normalizedByte: return "normalized BYTE";
  }
  return "?";
}

StoredVectorRounding storedVectorRounding(StoredComponent component) {
  StoredVectorRounding rounding;
  switch (component) {
    case StoredComponent::float32:
      rounding.lengthDeviation = kFloatUnitDeviation;
      return rounding;
    case StoredComponent::normalizedByte:
      rounding.significantBits = kByteBits;
      rounding.componentError = gridStep(kByteBits) / 2;
      break;
    case StoredComponent::normalizedShort:
      rounding.significantBits = kFewestShortBits;
      rounding.componentError = gridStep(kFewestShortBits) / 2 + gridStep(16) / 2;
      break;
  }
  const double vectorError = std::sqrt(3.0) * rounding.componentError;
  rounding.lengthDeviation = vectorError;
  rounding.angleDegrees = std::asin(vectorError) * kDegreesPerRadian;
  return rounding;
}

double normalLengthWarningLimit(StoredComponent normal) {
  if (normal == StoredComponent::float32) return kNormalLengthKept;
  return std::max(kNormalLengthKept, storedVectorRounding(normal).lengthDeviation);
}

StoredTangentLimits storedTangentLimits(StoredComponent tangent, StoredComponent normal) {
  StoredTangentLimits limits;
  limits.tangent = tangent;
  limits.normal = normal;
  const StoredVectorRounding t = storedVectorRounding(tangent), n = storedVectorRounding(normal);
  limits.unitDeviation = std::max(kFloatUnitDeviation, t.lengthDeviation);
  limits.tangentAngleDegrees = t.angleDegrees;
  limits.normalAngleDegrees = n.angleDegrees;
  return limits;
}

double orthogonalLimitDegrees(const StoredTangentLimits& limits, double toleranceDegrees) {
  return toleranceDegrees + limits.tangentAngleDegrees + limits.normalAngleDegrees;
}

double referenceLimitDegrees(const StoredTangentLimits& limits, double toleranceDegrees, double inputAllowanceDegrees) {
  return toleranceDegrees + limits.tangentAngleDegrees + limits.normalAngleDegrees + inputAllowanceDegrees;
}

InputRounding inputRounding(const Asset& asset, const Json& primitive, int texCoord, bool hasNormalTexture) {
  InputRounding rounding;
  const Json& attributes = primitive["attributes"];
  const bool draco = primitiveCompression(asset, primitive).draco;
  rounding.position = halfRoundingStep(asset.model, accessorOf(attributes, "POSITION"), asset.path.string() + ": POSITION", draco);
  rounding.uv = halfRoundingStep(asset.model, accessorOf(attributes, "TEXCOORD_" + std::to_string(texCoord)),
                                 asset.path.string() + ": TEXCOORD_" + std::to_string(texCoord), draco);
  // The reference sees UVs after the frame texture's KHR_texture_transform: its scale scales the step.
  const Json* frameTransform = rounding.uv > 0 && hasNormalTexture ? frameTextureTransform(asset.json, primitive) : nullptr;
  if (frameTransform) {
    const Json& transform = *frameTransform;
    if (transform.contains("scale") && transform["scale"].size() == 2)
      rounding.uv *= std::max(std::abs(transform["scale"][0].get<double>()), std::abs(transform["scale"][1].get<double>()));
    // A rotation mixes the two components: each moves by up to (|cos| + |sin|) times as much.
    if (transform.contains("rotation") && transform["rotation"].is_number()) {
      const double rotation = transform["rotation"].get<double>();
      rounding.uv *= std::abs(std::cos(rotation)) + std::abs(std::sin(rotation));
    }
  }
  return rounding;
}

}  // namespace tangent::gltf::detail
