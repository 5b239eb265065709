// SPDX-License-Identifier: MIT
// Double vectors of lengyel and flat (lengyel.cpp, lengyel_groups.cpp, triangle_tangent.cpp).
// Each operation evaluates in the order OpenMesh's VectorT does (dot and squared norm summed
// from x to z, cross as (y z' - z y', z x' - x z', x y' - y x')), which these methods used
// before they ran on arrays: their outputs kept every bit.
#pragma once

#include <cmath>

namespace tangent::detail {

template <int N>
struct VecN {
  double v[N] = {};
  constexpr VecN() = default;
  constexpr VecN(double x, double y) requires(N == 2) : v{x, y} {}
  constexpr VecN(double x, double y, double z) requires(N == 3) : v{x, y, z} {}
  double& operator[](int i) { return v[i]; }
  double operator[](int i) const { return v[i]; }
  double* data() { return v; }
  const double* data() const { return v; }
  bool operator==(const VecN&) const = default;
  VecN& operator+=(const VecN& o) {
    for (int i = 0; i < N; ++i) v[i] += o.v[i];
    return *this;
  }
  VecN operator+(const VecN& o) const { return VecN(*this) += o; }
  VecN operator-(const VecN& o) const {
    VecN r = *this;
    for (int i = 0; i < N; ++i) r.v[i] -= o.v[i];
    return r;
  }
  VecN operator*(double s) const {
    VecN r = *this;
    for (double& x : r.v) x *= s;
    return r;
  }
  VecN operator/(double s) const {
    VecN r = *this;
    for (double& x : r.v) x /= s;
    return r;
  }
  // Dot product.
  double operator|(const VecN& o) const {
    double sum = v[0] * o.v[0];
    for (int i = 1; i < N; ++i) sum += v[i] * o.v[i];
    return sum;
  }
  double sqrnorm() const { return *this | *this; }
  double norm() const { return std::sqrt(sqrnorm()); }
};

using Vec3 = VecN<3>;
using Vec2 = VecN<2>;

// Cross product.
inline Vec3 operator%(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

}  // namespace tangent::detail
