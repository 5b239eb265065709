// The per-element rules `tangent check` applies, shared with the scene loader that marks the
// failing corners for the viewer.
#pragma once

#include <algorithm>
#include <cmath>

namespace tangent::gltf::detail {

inline constexpr double kDegreesPerRadian = 57.295779513082320876798;

inline bool finite4(const float* t) {
  return std::isfinite(t[0]) && std::isfinite(t[1]) && std::isfinite(t[2]) && std::isfinite(t[3]);
}

inline double length3(const float* v) { return std::sqrt(double(v[0]) * v[0] + double(v[1]) * v[1] + double(v[2]) * v[2]); }

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

// glTF's handedness for a triangle's UV orientation: w = -sign(UV area); 0 when undefined.
inline float expectedW(double uvAreaTwice) { return uvAreaTwice > 0 ? -1.0f : uvAreaTwice < 0 ? 1.0f : 0.0f; }

}  // namespace tangent::gltf::detail
