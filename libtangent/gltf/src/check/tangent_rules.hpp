// SPDX-License-Identifier: MIT
// The one set of rules a stored TANGENT must satisfy, per component type: `tangent check`
// applies them, `bake` keeps a TANGENT exactly when check passes it (it runs check's primitive
// check), and the viewer's loader marks the corners that break them.
//
// glTF 2.0 (3.7.2.1) stores TANGENT as float VEC4 with unit xyz and w = +-1;
// KHR_mesh_quantization also allows normalized BYTE and SHORT, for NORMAL too. Rounding a unit
// vector's components moves it: the limits below follow from the rounding step, derived in
// the README ("Limits for quantized tangents") and in tangent_rules.cpp.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tangent/tangent.hpp"

namespace tangent::gltf::detail {

struct Asset;
struct PrimitiveGeometry;

inline constexpr double kDegreesPerRadian = 57.295779513082320876798;

// The component types glTF allows for TANGENT and NORMAL.
enum class StoredComponent { float32, normalizedShort, normalizedByte };

// nullopt for any other component type (the `format` check's finding).
std::optional<StoredComponent> storedComponentOf(int componentType, bool normalized);
const char* toString(StoredComponent component);

// What rounding may have done to a stored unit vector, and so what the checks accept.
struct StoredVectorRounding {
  int significantBits = 0;       // fewest accepted inside the component (0: float)
  double componentError = 0;     // worst |stored - exact| of one component
  double lengthDeviation = 0;    // worst | |xyz| - 1 | this rounding gives: sqrt(3) * componentError
  double angleDegrees = 0;       // worst direction error: asin(sqrt(3) * componentError)
};
StoredVectorRounding storedVectorRounding(StoredComponent component);

// The largest | |N| - 1 | a stored NORMAL of this component type has from rounding alone, so
// that check does not warn about it: kNormalLengthKept for float, the rounding's length
// deviation for normalized BYTE/SHORT.
double normalLengthWarningLimit(StoredComponent normal);

// Limits for one primitive's TANGENT, from its component type and NORMAL's.
struct StoredTangentLimits {
  StoredComponent tangent = StoredComponent::float32;
  StoredComponent normal = StoredComponent::float32;
  double unitDeviation = 1e-3;        // `unit`: largest accepted | |xyz| - 1 |
  double tangentAngleDegrees = 0;     // direction error of TANGENT's rounding
  double normalAngleDegrees = 0;      // direction error of NORMAL's rounding
};
StoredTangentLimits storedTangentLimits(StoredComponent tangent, StoredComponent normal);

// Largest accepted deviation for `orthogonal` and `reference` given the user's tolerance.
double orthogonalLimitDegrees(const StoredTangentLimits& limits, double toleranceDegrees);
double referenceLimitDegrees(const StoredTangentLimits& limits, double toleranceDegrees, double inputAllowanceDegrees);

// How far positions and UVs (the reference's inputs) may be from what the tangents were baked
// from, when a tool stored them quantized (KHR_mesh_quantization): half a rounding step, in
// the units the reference sees (UVs after the normal texture's KHR_texture_transform scale).
struct InputRounding {
  double position = 0;
  double uv = 0;
  bool any() const { return position > 0 || uv > 0; }
};
InputRounding inputRounding(const Asset& asset, const nlohmann::ordered_json& primitive, int texCoord, bool hasNormalTexture);

// Per vertex: how far the reference frame may turn because of that rounding (degrees, 0 for
// float input; 180 where a triangle's UV orientation is undecided after rounding, so the
// vertex cannot be compared). Per triangle: whether its UV orientation is decided.
struct ReferenceAllowance {
  std::vector<float> vertexDegrees;       // empty when there is no input rounding
  std::vector<char> orientationDecided;   // per triangle; empty when there is no input rounding
  float vertex(std::size_t v) const { return vertexDegrees.empty() ? 0.0f : vertexDegrees[v]; }
  bool decided(std::size_t t) const { return orientationDecided.empty() || orientationDecided[t]; }
};
inline constexpr float kUncomparableDegrees = 180.0f;
ReferenceAllowance referenceAllowance(const PrimitiveGeometry& geometry, const InputRounding& rounding);

// The two bounds referenceAllowance takes the smaller of, per vertex (degrees, empty when
// there is no input rounding): the coarse triangle-by-triangle one and the finer first-order
// one, here computed at every vertex (referenceAllowance computes it only where the coarse
// one exceeds 4 deg). For tests holding each bound to an independent estimate.
struct AllowanceBounds {
  std::vector<float> coarseDegrees;
  std::vector<float> fineDegrees;
};
AllowanceBounds allowanceBounds(const PrimitiveGeometry& geometry, const InputRounding& rounding);

// ---- per-element rules ----

inline bool finite4(const float* t) {
  return std::isfinite(t[0]) && std::isfinite(t[1]) && std::isfinite(t[2]) && std::isfinite(t[3]);
}

inline double length3(const float* v) { return std::sqrt(double(v[0]) * v[0] + double(v[1]) * v[1] + double(v[2]) * v[2]); }

inline double unitDeviation(const float* t) { return std::abs(length3(t) - 1.0); }
inline bool unitOk(const float* t, const StoredTangentLimits& limits) { return unitDeviation(t) <= limits.unitDeviation; }

// Normalized BYTE/SHORT decode +-127/+-32767 to exactly +-1, so w is exact in every form.
inline bool validW(float w) { return w == 1.0f || w == -1.0f; }

// Angle between two 3-vectors in degrees; atan2 keeps it accurate near 0.
inline double angleBetweenDegrees(const float* a, const float* b) {
  const double cross[3] = {double(a[1]) * b[2] - double(a[2]) * b[1], double(a[2]) * b[0] - double(a[0]) * b[2],
                           double(a[0]) * b[1] - double(a[1]) * b[0]};
  const double sine = std::sqrt(cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]);
  const double cosine = double(a[0]) * b[0] + double(a[1]) * b[1] + double(a[2]) * b[2];
  return std::atan2(sine, cosine) * kDegreesPerRadian;
}

// How far xyz leaves the plane normal to n, in degrees; -1 when either is zero or not finite.
inline double offPlaneDegrees(const float* t, const float* n) {
  const double tl = length3(t), nl = length3(n);
  if (!(tl > 0) || !(nl > 0) || !std::isfinite(tl) || !std::isfinite(nl)) return -1;
  const double dot = (double(t[0]) * n[0] + double(t[1]) * n[1] + double(t[2]) * n[2]) / (tl * nl);
  return std::asin(std::clamp(std::abs(dot), 0.0, 1.0)) * kDegreesPerRadian;
}

// Twice the signed UV area of a triangle.
inline double uvAreaTimesTwo(const float* uv0, const float* uv1, const float* uv2) {
  return (double(uv1[0]) - uv0[0]) * (double(uv2[1]) - uv0[1]) - (double(uv2[0]) - uv0[0]) * (double(uv1[1]) - uv0[1]);
}

// Twice the 3D area of a triangle.
inline double areaTimesTwo(const float* p0, const float* p1, const float* p2) {
  const double e1[3] = {double(p1[0]) - p0[0], double(p1[1]) - p0[1], double(p1[2]) - p0[2]};
  const double e2[3] = {double(p2[0]) - p0[0], double(p2[1]) - p0[1], double(p2[2]) - p0[2]};
  return std::hypot(e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]);
}

// glTF's handedness for a triangle's (twice) signed UV area, by the core's rule
// (tangent::handedness): w = -sign(UV area); 0 when undefined.
inline float expectedW(double uvAreaTwice) {
  const float orientation = uvAreaTwice > 0 ? 1.0f : uvAreaTwice < 0 ? -1.0f : 0.0f;
  return tangent::handedness(orientation, tangent::kGltfUvOrigin);
}

// The reference comparison of one corner: too far, or w differs.
inline bool referenceFails(double angleDegrees, float storedW, float computedW, double limitDegrees) {
  return angleDegrees > limitDegrees || (storedW < 0) != (computedW < 0);
}

}  // namespace tangent::gltf::detail
