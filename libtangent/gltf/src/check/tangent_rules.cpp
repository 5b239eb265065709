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
// UVs do to the recomputed frame (referenceAllowance below).
#include "check/tangent_rules.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <utility>

#if !defined(TANGENT_SERIAL)
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#endif

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

namespace {

// One triangle's share of its corners' frames, as MikkTSpace sums them (and Lengyel's angle
// weighting): its tangent direction v = sign * (e1 * dv2 - e2 * dv1) (e: edges from corner 0,
// dv: their V deltas, sign: that of the UV area, held fixed), projected onto each corner's
// normal plane, unit length, times the corner's angle; zero where undefined.
// `weights`: the corners' angles, computed into it where `keepWeights` is false, else taken
// from it (a V moved: the positions, and so the angles, are the same).
constexpr double kHalfPi = 1.57079632679489661923;

inline double norm3(double x, double y, double z) { return std::sqrt(x * x + y * y + z * z); }

// A triangle's UV orientation (the sign of its UV area) and whether rounding UVs by up to eu
// leaves it decided: the area moves by at most 2 eu (|du1| + |du2| + |dv1| + |dv2|) + 8 eu^2.
struct UvOrientation {
  double sign = 1;
  bool decided = true;
};
UvOrientation uvOrientation(const PrimitiveGeometry& geometry, const std::uint32_t* c, double eu) {
  const float* uv[3] = {&geometry.uvs[2 * c[0]], &geometry.uvs[2 * c[1]], &geometry.uvs[2 * c[2]]};
  const double du1 = double(uv[1][0]) - uv[0][0], dv1 = double(uv[1][1]) - uv[0][1];
  const double du2 = double(uv[2][0]) - uv[0][0], dv2 = double(uv[2][1]) - uv[0][1];
  const double area = du1 * dv2 - du2 * dv1;
  const double areaChange = 2 * eu * (std::abs(du1) + std::abs(du2) + std::abs(dv1) + std::abs(dv2)) + 8 * eu * eu;
  return {area < 0 ? -1.0 : 1.0, std::abs(area) > areaChange && std::isfinite(area)};
}

// How far a sum of length `size` can turn when it moves by up to `moved`: asin(moved / size),
// or uncomparable where the movement reaches its length.
float turnDegrees(double moved, double size) {
  return moved < size ? static_cast<float>(std::asin(moved / size) * kDegreesPerRadian) : kUncomparableDegrees;
}

void cornerShares(const double p[3][3], const double v[3], double sign, const float* const normals[3], double weights[3], bool keepWeights,
                  double shares[3][3]) {
  double e1[3], e2[3], direction[3];
  for (int i = 0; i < 3; ++i) {
    e1[i] = p[1][i] - p[0][i];
    e2[i] = p[2][i] - p[0][i];
  }
  const double dv1 = v[1] - v[0], dv2 = v[2] - v[0];
  for (int i = 0; i < 3; ++i) direction[i] = sign * (e1[i] * dv2 - e2[i] * dv1);
  for (int k = 0; k < 3; ++k) {
    for (int i = 0; i < 3; ++i) shares[k][i] = 0;
    const float* n = normals[k];
    const double nLength = std::sqrt(double(n[0]) * n[0] + double(n[1]) * n[1] + double(n[2]) * n[2]);
    const bool hasNormal = nLength > 0 && std::isfinite(nLength);
    auto project = [&](double x[3]) {
      if (!hasNormal) return;
      const double dot = (x[0] * n[0] + x[1] * n[1] + x[2] * n[2]) / (nLength * nLength);
      for (int i = 0; i < 3; ++i) x[i] -= dot * n[i];
    };
    // The corner's angle between its edges projected onto the normal plane; 90 deg where one
    // is zero (MikkTSpace's rule: the dot product of a zero vector).
    if (!keepWeights) {
      const double* here = p[k];
      const double* next = p[(k + 1) % 3];
      const double* prev = p[(k + 2) % 3];
      double a[3] = {next[0] - here[0], next[1] - here[1], next[2] - here[2]};
      double b[3] = {prev[0] - here[0], prev[1] - here[1], prev[2] - here[2]};
      project(a);
      project(b);
      const double cross[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
      const bool zeroEdge = !(norm3(a[0], a[1], a[2]) > 0) || !(norm3(b[0], b[1], b[2]) > 0);
      weights[k] = zeroEdge ? kHalfPi : std::atan2(norm3(cross[0], cross[1], cross[2]), a[0] * b[0] + a[1] * b[1] + a[2] * b[2]);
    }
    const double weight = weights[k];
    double projected[3] = {direction[0], direction[1], direction[2]};
    project(projected);
    const double projectedLength = norm3(projected[0], projected[1], projected[2]);
    if (!(projectedLength > 0) || !std::isfinite(projectedLength) || !std::isfinite(weight)) continue;
    for (int i = 0; i < 3; ++i) shares[k][i] = weight * projected[i] / projectedLength;
  }
}

// Vertices whose `width` floats from `values` are equal, numbered: rounding gives equal values
// equal results, so such vertices (a UV seam's copies of a position, a hard edge's copies of
// a UV) moved together.
std::vector<std::uint32_t> equalValueGroups(const std::vector<float>& values, int width, std::size_t count, std::uint32_t& groups) {
  // Compared as bit patterns: a strict order even with NaN in the data.
  std::vector<std::uint32_t> bits(values.size()), order(count), group(count, 0);
  if (!values.empty()) std::memcpy(bits.data(), values.data(), values.size() * sizeof(float));
  for (std::size_t v = 0; v < count; ++v) order[v] = static_cast<std::uint32_t>(v);
  auto less = [&](std::uint32_t a, std::uint32_t b) {
    return std::lexicographical_compare(&bits[std::size_t(a) * width], &bits[std::size_t(a) * width] + width, &bits[std::size_t(b) * width],
                                        &bits[std::size_t(b) * width] + width);
  };
  std::sort(order.begin(), order.end(), less);
  groups = 0;
  for (std::size_t i = 0; i < count; ++i) {
    if (i > 0 && less(order[i - 1], order[i])) ++groups;
    group[order[i]] = groups;
  }
  if (count) ++groups;
  return group;
}

// The bound this file used first, triangle by triangle (5-8x too loose on gltfpack outputs, but
// cheap): a triangle's tangent direction v = e1 * dv2 - e2 * dv1 moves by at most
//   2 eu (|e1| + |e2|) + 2 sqrt(3) ep (|dv1| + |dv2|) + 8 sqrt(3) ep eu,
// and turns by at most asin(change / |v|); each triangle's unit tangent moves by at most the
// chord 2 sin(turn / 2) (2 when its orientation is undecided), so a vertex's angle-weighted sum
// S moves by at most E = sum a_i chord_i and turns by at most asin(E / |S|). Where it is below
// kCoarseEnoughDegrees, referenceAllowance keeps it and skips the finer computation.
std::vector<float> coarseVertexDegrees(const PrimitiveGeometry& geometry, const InputRounding& rounding) {
  const double eu = rounding.uv, ep = rounding.position, root3 = std::sqrt(3.0);
  const std::size_t triangles = geometry.corners.size() / 3;
  std::vector<double> sum(3 * geometry.vertexCount, 0.0), movement(geometry.vertexCount, 0.0);
  for (std::size_t t = 0; t < triangles; ++t) {
    const std::uint32_t* c = &geometry.corners[3 * t];
    const float* p[3] = {&geometry.positions[3 * c[0]], &geometry.positions[3 * c[1]], &geometry.positions[3 * c[2]]};
    const float* uv[3] = {&geometry.uvs[2 * c[0]], &geometry.uvs[2 * c[1]], &geometry.uvs[2 * c[2]]};
    double e1[3], e2[3];
    for (int i = 0; i < 3; ++i) {
      e1[i] = double(p[1][i]) - p[0][i];
      e2[i] = double(p[2][i]) - p[0][i];
    }
    const double dv1 = double(uv[1][1]) - uv[0][1], dv2 = double(uv[2][1]) - uv[0][1];
    const UvOrientation orientation = uvOrientation(geometry, c, eu);
    const double sign = orientation.sign;
    double v[3] = {sign * (e1[0] * dv2 - e2[0] * dv1), sign * (e1[1] * dv2 - e2[1] * dv1), sign * (e1[2] * dv2 - e2[2] * dv1)};
    const double vLength = std::hypot(v[0], v[1], v[2]);
    double chord = 2;
    if (orientation.decided) {
      const double e1Length = std::hypot(e1[0], e1[1], e1[2]), e2Length = std::hypot(e2[0], e2[1], e2[2]);
      const double change = 2 * eu * (e1Length + e2Length) + 2 * root3 * ep * (std::abs(dv1) + std::abs(dv2)) + 8 * root3 * ep * eu;
      if (change < vLength) chord = 2 * std::sin(std::asin(change / vLength) / 2);
    }
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t vertex = c[k];
      // Corner angle at this vertex: the weight MikkTSpace gives the triangle there.
      const float* here = p[k];
      const float* next = p[(k + 1) % 3];
      const float* prev = p[(k + 2) % 3];
      const float a[3] = {next[0] - here[0], next[1] - here[1], next[2] - here[2]};
      const float b[3] = {prev[0] - here[0], prev[1] - here[1], prev[2] - here[2]};
      const double weight = angleBetweenDegrees(a, b) / kDegreesPerRadian;
      if (!std::isfinite(weight)) continue;
      movement[vertex] += weight * chord;
      // The triangle's tangent projected onto the vertex's normal plane, unit length.
      const float* n = &geometry.normals[3 * vertex];
      const double nLength = length3(n);
      double projected[3] = {v[0], v[1], v[2]};
      if (nLength > 0 && std::isfinite(nLength)) {
        const double dot = (v[0] * n[0] + v[1] * n[1] + v[2] * n[2]) / (nLength * nLength);
        for (int i = 0; i < 3; ++i) projected[i] -= dot * n[i];
      }
      const double projectedLength = std::hypot(projected[0], projected[1], projected[2]);
      if (!(projectedLength > 0) || !std::isfinite(projectedLength)) continue;
      for (int i = 0; i < 3; ++i) sum[3 * vertex + i] += weight * projected[i] / projectedLength;
    }
  }
  std::vector<float> degrees(geometry.vertexCount);
  for (std::size_t v = 0; v < geometry.vertexCount; ++v)
    degrees[v] = turnDegrees(movement[v], std::hypot(sum[3 * v], sum[3 * v + 1], sum[3 * v + 2]));
  return degrees;
}

}  // namespace

// A vertex's frame is the direction of S, the sum of its triangles' shares (cornerShares).
// Rounding moved each position component by up to ep and each UV component by up to eu from
// what the tangents were baked from. U enters a triangle's share only through the sign of its
// UV area: where the rounding can change that sign (the area moves by at most
// 2 eu (|du1| + |du2| + |dv1| + |dv2|) + 8 eu^2), the triangle's orientation is undecided, it
// may join or leave the vertex's group, and its share counts as moving by twice its weight.
// Every other input x_j (a V, a position component; vertices with equal values move together,
// as rounding moves them) moves S by the vector dS_j when it alone moves by its half step,
// recomputed. To first order the joint movement is their sum, so |dS| <= E = sum |dS_j| (the
// inputs' effects on the same triangle added as vectors first: they partly cancel, which the
// triangle-by-triangle worst case (coarseVertexDegrees) does not see; it is 5-8x too loose on
// gltfpack outputs). kSecondOrderMargin covers the products of moves the first order leaves
// out, and S turns by at most asin(E / |S|); where E reaches |S| the vertex cannot be compared.
// Where the coarse bound is already small, it is kept (the finer one is not computed there).
namespace {

constexpr float kCoarseEnoughDegrees = 4.0f;  // a 10 deg turn is caught under it anyway

// Both bounds per vertex (and `allowance`'s orientations). The finer one moves only the inputs
// of triangles with a vertex whose coarse bound exceeds `fineAbove` (-1: every triangle), so it
// holds at those vertices alone.
AllowanceBounds computeAllowanceBounds(const PrimitiveGeometry& geometry, const InputRounding& rounding, float fineAbove,
                                       ReferenceAllowance& allowance) {
  constexpr double kSecondOrderMargin = 1.25;
  AllowanceBounds bounds;
  if (!rounding.any()) return bounds;
  const std::vector<float> coarse = coarseVertexDegrees(geometry, rounding);
  const double eu = rounding.uv, ep = rounding.position;
  const std::size_t triangles = geometry.corners.size() / 3, vertexCount = geometry.vertexCount;
  allowance.vertexDegrees.assign(vertexCount, 0.0f);
  allowance.orientationDecided.assign(triangles, 1);
  std::vector<double> sum(3 * vertexCount, 0.0), movement(vertexCount, 0.0);
  std::vector<double> shares(9 * triangles, 0.0), weights(3 * triangles, 0.0), signs(triangles, 1.0);
  auto load = [&](std::size_t t, double p[3][3], double v[3], const float* normals[3]) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t vertex = geometry.corners[3 * t + k];
      for (int i = 0; i < 3; ++i) p[k][i] = geometry.positions[3 * vertex + i];
      v[k] = geometry.uvs[2 * vertex + 1];
      normals[k] = &geometry.normals[3 * vertex];
    }
  };
  for (std::size_t t = 0; t < triangles; ++t) {
    const std::uint32_t* c = &geometry.corners[3 * t];
    const UvOrientation orientation = uvOrientation(geometry, c, eu);
    signs[t] = orientation.sign;
    if (!orientation.decided) allowance.orientationDecided[t] = 0;
    double p[3][3], v[3];
    const float* normals[3];
    load(t, p, v, normals);
    double share[3][3];
    cornerShares(p, v, signs[t], normals, &weights[3 * t], false, share);
    for (int k = 0; k < 3; ++k) {
      for (int i = 0; i < 3; ++i) {
        shares[9 * t + 3 * k + i] = share[k][i];
        sum[3 * c[k] + i] += share[k][i];
      }
      if (!allowance.orientationDecided[t]) movement[c[k]] += 2 * norm3(share[k][0], share[k][1], share[k][2]);
    }
  }

  // The decided triangles at each vertex that have a share. A triangle without one (its
  // direction exactly zero: a pole's coincident vertices on one UV row) is left out: exact
  // zeros come from exact data, which rounding keeps (tools map a range's ends exactly).
  std::vector<char> moves(triangles, 0);
  for (std::size_t t = 0; t < triangles; ++t)
    moves[t] = allowance.orientationDecided[t] && std::any_of(&shares[9 * t], &shares[9 * t] + 9, [](double x) { return x != 0; });
  std::vector<std::uint32_t> firstTriangle(vertexCount + 1, 0), incident;
  for (std::size_t t = 0; t < triangles; ++t)
    if (moves[t])
      for (int k = 0; k < 3; ++k) ++firstTriangle[geometry.corners[3 * t + k] + 1];
  for (std::size_t v = 0; v < vertexCount; ++v) firstTriangle[v + 1] += firstTriangle[v];
  incident.resize(firstTriangle[vertexCount]);
  {
    std::vector<std::uint32_t> next(firstTriangle.begin(), firstTriangle.end() - 1);
    for (std::size_t t = 0; t < triangles; ++t)
      if (moves[t])
        for (int k = 0; k < 3; ++k) incident[next[geometry.corners[3 * t + k]]++] = static_cast<std::uint32_t>(t);
  }

  // dS_j per input: a group of equal values (equalValueGroups) moved by its half step; |dS_j|
  // for each vertex of the group's triangles, appended to `out` in vertex order.
  std::vector<std::uint32_t> group, members, memberList;
  std::uint32_t groupCount = 0;
  struct Scratch {
    std::vector<std::uint32_t> affected;
    std::vector<std::pair<std::uint32_t, std::array<double, 3>>> changes;
  };
  auto moveGroup = [&](std::uint32_t k, int input, double step, Scratch& scratch, std::vector<std::pair<std::uint32_t, double>>& out) {
    std::vector<std::uint32_t>& affected = scratch.affected;
    affected.clear();
    for (std::uint32_t m = members[k]; m < members[k + 1]; ++m) {
      const std::uint32_t w = memberList[m];
      affected.insert(affected.end(), incident.begin() + firstTriangle[w], incident.begin() + firstTriangle[w + 1]);
    }
    std::sort(affected.begin(), affected.end());
    affected.erase(std::unique(affected.begin(), affected.end()), affected.end());
    const bool needed = std::any_of(affected.begin(), affected.end(), [&](std::uint32_t t) {
      return coarse[geometry.corners[3 * t]] > fineAbove || coarse[geometry.corners[3 * t + 1]] > fineAbove ||
             coarse[geometry.corners[3 * t + 2]] > fineAbove;
    });
    if (!needed) return;
    auto& changes = scratch.changes;
    changes.clear();
    for (const std::uint32_t t : affected) {
      double p[3][3], v[3];
      const float* normals[3];
      load(t, p, v, normals);
      for (int corner = 0; corner < 3; ++corner) {
        if (group[geometry.corners[3 * t + corner]] != k) continue;
        if (input == 0) v[corner] += step; else p[corner][input - 1] += step;
      }
      double share[3][3], moved[3] = {weights[3 * t], weights[3 * t + 1], weights[3 * t + 2]};
      cornerShares(p, v, signs[t], normals, moved, input == 0, share);
      for (int corner = 0; corner < 3; ++corner) {
        const double* base = &shares[9 * t + 3 * corner];
        changes.push_back({geometry.corners[3 * t + corner], {share[corner][0] - base[0], share[corner][1] - base[1], share[corner][2] - base[2]}});
      }
    }
    std::stable_sort(changes.begin(), changes.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    for (std::size_t i = 0; i < changes.size();) {
      std::array<double, 3> total = {0, 0, 0};
      std::size_t j = i;
      for (; j < changes.size() && changes[j].first == changes[i].first; ++j)
        for (int c = 0; c < 3; ++c) total[c] += changes[j].second[c];
      out.push_back({changes[i].first, norm3(total[0], total[1], total[2])});
      i = j;
    }
  };
  // Groups in chunks, a batch of chunks at a time on the oneTBB pool the core uses (its
  // arena and global limits apply; one thread in the web build); the movements are added in
  // group order, so the result does not depend on the thread count.
  constexpr std::uint32_t kChunk = 4096;
#if defined(TANGENT_SERIAL)
  const unsigned threads = 1;
#else
  const unsigned threads = static_cast<unsigned>(std::max(1, tbb::this_task_arena::max_concurrency()));
#endif
  std::vector<Scratch> scratch(threads);
  for (int input = 0; input < 4; ++input) {  // V, then x, y, z
    const double step = input == 0 ? eu : ep;
    if (!(step > 0)) continue;
    if (input == 0 || input == 1) {
      groupCount = 0;
      group = input == 0 ? equalValueGroups(geometry.uvs, 2, vertexCount, groupCount) : equalValueGroups(geometry.positions, 3, vertexCount, groupCount);
      members.assign(groupCount + 1, 0);
      for (std::size_t v = 0; v < vertexCount; ++v) ++members[group[v] + 1];
      for (std::uint32_t k = 0; k < groupCount; ++k) members[k + 1] += members[k];
      memberList.resize(vertexCount);
      std::vector<std::uint32_t> next(members.begin(), members.end() - 1);
      for (std::size_t v = 0; v < vertexCount; ++v) memberList[next[group[v]]++] = static_cast<std::uint32_t>(v);
    }
    const std::uint32_t chunks = (groupCount + kChunk - 1) / kChunk;
    for (std::uint32_t firstChunk = 0; firstChunk < chunks; firstChunk += 4 * threads) {
      const std::uint32_t batch = std::min(chunks - firstChunk, 4 * threads);
      std::vector<std::vector<std::pair<std::uint32_t, double>>> results(batch);
      auto chunk = [&](std::uint32_t c, Scratch& mine) {
        const std::uint32_t first = (firstChunk + c) * kChunk, last = std::min(groupCount, first + kChunk);
        for (std::uint32_t k = first; k < last; ++k) moveGroup(k, input, step, mine, results[c]);
      };
#if defined(TANGENT_SERIAL)
      for (std::uint32_t c = 0; c < batch; ++c) chunk(c, scratch[0]);
#else
      if (threads == 1 || batch == 1) {
        for (std::uint32_t c = 0; c < batch; ++c) chunk(c, scratch[0]);
      } else {
        tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, batch, 1), [&](const tbb::blocked_range<std::uint32_t>& range) {
          // Each thread of the arena has its own scratch (its slot index is below max_concurrency).
          const int slot = tbb::this_task_arena::current_thread_index();
          Scratch& mine = scratch[slot >= 0 && static_cast<unsigned>(slot) < threads ? slot : 0];
          for (std::uint32_t c = range.begin(); c < range.end(); ++c) chunk(c, mine);
        });
      }
#endif
      for (const auto& result : results)
        for (const auto& [vertex, moved] : result) movement[vertex] += moved;
    }
  }
  bounds.coarseDegrees = coarse;
  bounds.fineDegrees.assign(vertexCount, kUncomparableDegrees);
  for (std::size_t v = 0; v < vertexCount; ++v) {
    const double size = std::hypot(sum[3 * v], sum[3 * v + 1], sum[3 * v + 2]);
    const double moved = kSecondOrderMargin * movement[v];
    bounds.fineDegrees[v] = turnDegrees(moved, size);
  }
  return bounds;
}

}  // namespace

ReferenceAllowance referenceAllowance(const PrimitiveGeometry& geometry, const InputRounding& rounding) {
  ReferenceAllowance allowance;
  const AllowanceBounds bounds = computeAllowanceBounds(geometry, rounding, kCoarseEnoughDegrees, allowance);
  for (std::size_t v = 0; v < allowance.vertexDegrees.size(); ++v) {
    const float coarse = bounds.coarseDegrees[v];
    allowance.vertexDegrees[v] = coarse <= kCoarseEnoughDegrees ? coarse : std::min(coarse, bounds.fineDegrees[v]);
  }
  return allowance;
}

AllowanceBounds allowanceBounds(const PrimitiveGeometry& geometry, const InputRounding& rounding) {
  ReferenceAllowance unused;
  return computeAllowanceBounds(geometry, rounding, -1.0f, unused);
}

}  // namespace tangent::gltf::detail
