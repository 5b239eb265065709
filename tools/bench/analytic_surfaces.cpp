// SPDX-License-Identifier: MIT
#include "analytic_surfaces.hpp"

#include <array>
#include <cmath>
#include <functional>
#include <numbers>
#include <stdexcept>

namespace tangent::bench {
namespace {

using Vec = std::array<double, 3>;

Vec cross(const Vec& a, const Vec& b) { return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}; }
double dot(const Vec& a, const Vec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec normalize(const Vec& a) {
  const double l = std::sqrt(dot(a, a));
  return {a[0] / l, a[1] / l, a[2] / l};
}

struct Sample {
  Vec position, dPdu, dPdv;
  Vec normal;  // outward, unit
};

// A surface as a function of the grid parameters (s, t) in [0, 1]^2, returning position and
// derivatives with respect to the texture coordinates (u, v) it also returns.
using Parametric = std::function<Sample(double s, double t, double& u, double& v)>;

Parametric parametric(const std::string& surface) {
  constexpr double pi = std::numbers::pi;
  if (surface == "sphere") {
    return [](double s, double t, double& u, double& v) {
      // u = s around (phi = 2 pi u), v = t from north to south pole (theta = pi v).
      u = s;
      v = t;
      const double phi = 2 * pi * u, theta = pi * v;
      Sample x;
      // Exact poles: sin(pi) would leave them 1e-16 apart.
      const double st = (t == 0 || t == 1) ? 0.0 : std::sin(theta), ct = t == 0 ? 1.0 : t == 1 ? -1.0 : std::cos(theta);
      x.position = {st * std::cos(phi), ct, -st * std::sin(phi)};
      x.normal = x.position;
      x.dPdu = {-2 * pi * st * std::sin(phi), 0, -2 * pi * st * std::cos(phi)};
      x.dPdv = {pi * ct * std::cos(phi), -pi * st, -pi * ct * std::sin(phi)};
      if (st == 0) x.dPdu = {-std::sin(phi), 0, -std::cos(phi)};  // the direction u moves in near the pole
      return x;
    };
  }
  if (surface == "torus") {
    return [](double s, double t, double& u, double& v) {
      u = s;
      v = t;
      const double a = 2 * pi * u, b = 2 * pi * v, R = 1.0, r = 0.4;
      Sample x;
      x.normal = {std::cos(a) * std::cos(b), std::sin(b), -std::sin(a) * std::cos(b)};
      x.position = {R * std::cos(a) + r * x.normal[0], r * x.normal[1], -R * std::sin(a) + r * x.normal[2]};
      const double ring = R + r * std::cos(b);
      x.dPdu = {-2 * pi * ring * std::sin(a), 0, -2 * pi * ring * std::cos(a)};
      x.dPdv = {-2 * pi * r * std::sin(b) * std::cos(a), 2 * pi * r * std::cos(b), 2 * pi * r * std::sin(b) * std::sin(a)};
      return x;
    };
  }
  if (surface == "cylinder") {
    return [](double s, double t, double& u, double& v) {
      u = s;
      v = t;
      const double a = 2 * pi * u;
      Sample x;
      x.normal = {std::cos(a), 0, -std::sin(a)};
      x.position = {std::cos(a), 2 * v - 1, -std::sin(a)};
      x.dPdu = {-2 * pi * std::sin(a), 0, -2 * pi * std::cos(a)};
      x.dPdv = {0, 2, 0};
      return x;
    };
  }
  if (surface == "heightfield" || surface == "sheared") {
    const double shear = surface == "sheared" ? 0.6 : 0.0;
    return [shear](double s, double t, double& u, double& v) {
      // P(x, y) = (x, y, h(x, y)) over [-1, 1]^2; UVs u = x, v = y + shear x (scaled to [0, 1]).
      // The shear is in v so that dP/du (v held fixed) leans away from the x axis: the
      // tangent itself changes, not only the bitangent.
      const double X = 2 * s - 1, Y = 2 * t - 1;
      const double hx = 0.5 * std::cos(2 * X) * std::cos(3 * Y), hy = -0.75 * std::sin(2 * X) * std::sin(3 * Y);
      u = X / 2;
      v = (Y + shear * X) / 2;
      Sample x;
      x.position = {X, Y, 0.25 * std::sin(2 * X) * std::cos(3 * Y)};
      x.normal = normalize({-hx, -hy, 1});
      // Inverse map: X = 2u, Y = 2v - 2 shear u. Chain rule:
      // dP/du = (2, -2 shear, 2 hx - 2 shear hy); dP/dv = (0, 2, 2 hy).
      x.dPdu = {2, -2 * shear, 2 * hx - 2 * shear * hy};
      x.dPdv = {0, 2, 2 * hy};
      return x;
    };
  }
  throw std::invalid_argument("unknown surface '" + surface + "'");
}

}  // namespace

const std::vector<std::string>& surfaceNames() {
  static const std::vector<std::string> names = {"sphere", "torus", "cylinder", "heightfield", "sheared"};
  return names;
}

AnalyticMesh makeSurface(const std::string& surface, std::size_t targetTriangles) {
  const Parametric f = parametric(surface);
  const int n = std::max(2, static_cast<int>(std::lround(std::sqrt(targetTriangles / 2.0))));
  AnalyticMesh mesh;
  mesh.surface = surface;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      double u = 0, v = 0;
      const Sample x = f(double(i) / n, double(j) / n, u, v);
      for (int k = 0; k < 3; ++k) {
        mesh.positions.push_back(static_cast<float>(x.position[k]));
        mesh.normals.push_back(static_cast<float>(x.normal[k]));
      }
      mesh.uvs.push_back(static_cast<float>(u));
      mesh.uvs.push_back(static_cast<float>(v));
      // Exact frame: dP/du in the tangent plane; w from dP/dv's side of cross(N, T).
      const Vec& nrm = x.normal;
      const double along = dot(x.dPdu, nrm);
      const Vec t = normalize({x.dPdu[0] - along * nrm[0], x.dPdu[1] - along * nrm[1], x.dPdu[2] - along * nrm[2]});
      const double w = dot(cross(nrm, t), x.dPdv) >= 0 ? 1.0 : -1.0;
      mesh.exactTangents.insert(mesh.exactTangents.end(), {static_cast<float>(t[0]), static_cast<float>(t[1]), static_cast<float>(t[2]),
                                                           static_cast<float>(w)});
    }
  }
  // Wind each quad so that its geometric normal agrees with the outward normal.
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const std::uint32_t a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      // The diagonals' cross product: still defined when one edge collapses at a pole.
      const float* pa = &mesh.positions[3 * a];
      const float* pb = &mesh.positions[3 * b];
      const float* pc = &mesh.positions[3 * c];
      const float* pd = &mesh.positions[3 * d];
      const Vec e1 = {double(pd[0]) - pa[0], double(pd[1]) - pa[1], double(pd[2]) - pa[2]};
      const Vec e2 = {double(pc[0]) - pb[0], double(pc[1]) - pb[1], double(pc[2]) - pb[2]};
      const Vec normalAt = {mesh.normals[3 * a] + mesh.normals[3 * d], mesh.normals[3 * a + 1] + mesh.normals[3 * d + 1],
                            mesh.normals[3 * a + 2] + mesh.normals[3 * d + 2]};
      if (dot(cross(e1, e2), normalAt) >= 0) mesh.indices.insert(mesh.indices.end(), {a, b, d, a, d, c});
      else mesh.indices.insert(mesh.indices.end(), {a, d, b, a, c, d});
    }
  }
  return mesh;
}

}  // namespace tangent::bench
