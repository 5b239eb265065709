// SPDX-License-Identifier: MIT
#include "triangle_tangent.hpp"

#include "workspace.hpp"

#include <cmath>

namespace tangent::detail {
namespace {

constexpr double kRelativeZero = kTriangleRelativeZero;

std::uint64_t orderBits(double value) { return bitCast<std::uint64_t>(value == 0.0 ? 0.0 : value); }

bool allFinite(const Vec3& v) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); }

bool finiteTriangle(const std::array<Vec3, 3>& positions, const std::array<Vec2, 3>& uvs) {
  for (int k = 0; k < 3; ++k) {
    if (!allFinite(positions[k]) || !std::isfinite(uvs[k][0]) || !std::isfinite(uvs[k][1])) return false;
  }
  return true;
}

// The corner the triangle is evaluated from: the smallest by its position's and then its UV's
// bit patterns (+0 and -0 alike), compared up to the first that differs (nearly always x).
int canonicalCorner(const std::array<Vec3, 3>& positions, const std::array<Vec2, 3>& uvs) {
  std::uint64_t key[3][5];
  for (int k = 0; k < 3; ++k) {
    for (int a = 0; a < 3; ++a) key[k][a] = orderBits(positions[k][a]);
    for (int a = 0; a < 2; ++a) key[k][3 + a] = orderBits(uvs[k][a]);
  }
  auto less = [&](int x, int y) {
    for (int i = 0; i < 5; ++i) {
      if (key[x][i] != key[y][i]) return key[x][i] < key[y][i];
    }
    return false;
  };
  int start = less(1, 0) ? 1 : 0;
  if (less(2, start)) start = 2;
  return start;
}

}  // namespace

void triangleTangentsAt(const TriangleSource& source, std::size_t first, int count, const bool* wantFaceNormal, int lanes,
                        TriangleLanes& values, TriangleTangent* out) {
  if (lanes == 1) {
    for (int i = 0; i < count; ++i) {
      std::array<Vec3, 3> positions;
      std::array<Vec2, 3> uvs;
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t vertex = source.indices[3 * (first + i) + k];
        const float* p = source.positions + 3 * std::size_t(source.weldOf[vertex]);
        const float* t = source.uvs + 2 * std::size_t(vertex);
        positions[k] = {p[0], p[1], p[2]};
        uvs[k] = {t[0], t[1]};
        for (int a = 0; a < 3; ++a) values.p[k][a][i] = positions[k][a];
      }
      values.start[i] = 0;
      out[i] = triangleTangent(positions, uvs, wantFaceNormal[i]);
    }
    return;
  }
  for (int i = 0; i < count; ++i) {
    out[i] = TriangleTangent{};
    const float* p[3];
    const float* t[3];
    bool finite = true;
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t vertex = source.indices[3 * (first + i) + k];
      p[k] = source.positions + 3 * std::size_t(source.weldOf[vertex]);
      t[k] = source.uvs + 2 * std::size_t(vertex);
      finite = finite && std::isfinite(p[k][0]) && std::isfinite(p[k][1]) && std::isfinite(p[k][2]) &&
               std::isfinite(t[k][0]) && std::isfinite(t[k][1]);
    }
    values.wantFaceNormal[i] = wantFaceNormal[i];
    values.active[i] = finite;
    values.start[i] = 0;
    if (!finite) {
      out[i].kind = TriangleKind::nonFinite;
      continue;  // its lane's values are evaluated, never read
    }
    // canonicalCorner's order on the floats: a float's bits (+0 and -0 alike) order as its
    // double's do, so the same corner.
    auto key = [](float x) { return x == 0.0f ? 0u : bitCast<std::uint32_t>(x); };
    auto less = [&](int x, int y) {
      for (int a = 0; a < 3; ++a) {
        if (key(p[x][a]) != key(p[y][a])) return key(p[x][a]) < key(p[y][a]);
      }
      for (int a = 0; a < 2; ++a) {
        if (key(t[x][a]) != key(t[y][a])) return key(t[x][a]) < key(t[y][a]);
      }
      return false;
    };
    int start = less(1, 0) ? 1 : 0;
    if (less(2, start)) start = 2;
    values.start[i] = start;
    for (int c = 0; c < 3; ++c) {
      const int k = (start + c) % 3;
      for (int a = 0; a < 3; ++a) values.p[c][a][i] = p[k][a];
      for (int a = 0; a < 2; ++a) values.t[c][a][i] = t[k][a];
    }
  }
  for (int i = count; i < 4; ++i) values.active[i] = false;
#if defined(TANGENT_DOUBLE_LANES4)
  if (lanes == 4) {
    evaluateTriangleLanes4(values, out);
    return;
  }
#endif
  evaluateTriangleLanes2(values, 0, out);
  if (count > 2) evaluateTriangleLanes2(values, 2, out);
}

TriangleTangent triangleTangent(const std::array<Vec3, 3>& positions, const std::array<Vec2, 3>& uvs,
                                bool wantFaceNormal) {
  TriangleTangent result;
  if (!finiteTriangle(positions, uvs)) {
    result.kind = TriangleKind::nonFinite;
    return result;
  }
  const int start = canonicalCorner(positions, uvs);
  const Vec3& p0 = positions[start];
  const Vec3& p1 = positions[(start + 1) % 3];
  const Vec3& p2 = positions[(start + 2) % 3];
  const Vec2& t0 = uvs[start];
  const Vec2& t1 = uvs[(start + 1) % 3];
  const Vec2& t2 = uvs[(start + 2) % 3];

  result.coincident = p0 == p1 || p1 == p2 || p0 == p2;
  const Vec3 e1 = p1 - p0;
  const Vec3 e2 = p2 - p0;
  const Vec3 cross = e1 % e2;
  const double crossLength = cross.norm();
  const bool flat = !(crossLength > kRelativeZero * e1.norm() * e2.norm());
  if (!flat) {
    if (wantFaceNormal) result.faceNormal = cross / crossLength;
    result.area = 0.5 * crossLength;
  }

  const double du1 = t1[0] - t0[0], dv1 = t1[1] - t0[1];
  const double du2 = t2[0] - t0[0], dv2 = t2[1] - t0[1];
  const double det = du1 * dv2 - du2 * dv1;
  const bool zeroUvArea = !(std::abs(det) > kRelativeZero * (std::abs(du1 * dv2) + std::abs(du2 * dv1)));
  if (!zeroUvArea && !result.coincident) {
    const Vec3 uDirection = e1 * dv2 - e2 * dv1;  // det * dP/du
    const Vec3 vDirection = e2 * du1 - e1 * du2;  // det * dP/dv
    const double uLength = uDirection.norm();
    const double vLength = vDirection.norm();
    if (uLength > 0 && vLength > 0) {
      const double sign = det > 0 ? 1.0 : -1.0;
      result.orientation = det > 0 ? 1 : -1;
      result.tangent = uDirection * (sign / uLength);
      result.bitangent = vDirection * (sign / vLength);
    }
  }
  if (flat) result.kind = TriangleKind::degenerate;
  else if (zeroUvArea) result.kind = TriangleKind::zeroUvArea;
  else result.kind = result.orientation != 0 ? TriangleKind::usable : TriangleKind::degenerate;
  return result;
}

double cornerAngle(const std::array<Vec3, 3>& positions, int corner) {
  const Vec3 a = positions[(corner + 1) % 3] - positions[corner];
  const Vec3 b = positions[(corner + 2) % 3] - positions[corner];
  const double sine = (a % b).norm();
  const double cosine = a | b;
  if (sine == 0 && cosine == 0) return 0;
  const double angle = angleOf(sine, cosine);
  return std::isfinite(angle) ? angle : 0;
}

// meshoptimizer's default corner weight (meshoptimizer 1.x, src/tangentspace.cpp:
// meshopt_generateTangents without meshopt_TangentCompatible): the angle between corner k's
// two edges projected onto the plane of its unit normal, times the product of the projected
// edge lengths. meshoptimizer adds the triangle's tangent projected onto that plane and made
// unit; this pipeline adds the unit tangent and projects the group's sum (its corners share one
// normal), which is the same sum when the weight is divided by the projection's length.
double projectedEdgeWeight(const std::array<Vec3, 3>& positions, int k, const Vec3& normal, const Vec3& tangent) {
  auto inPlane = [&](const Vec3& v) { return v - normal * (normal | v); };
  const Vec3 first = inPlane(positions[(k + 1) % 3] - positions[k]);
  const Vec3 second = inPlane(positions[(k + 2) % 3] - positions[k]);
  const double tangentInPlane = inPlane(tangent).norm();
  const double edgeProduct = first.norm() * second.norm();
  if (!(tangentInPlane > 0) || !(edgeProduct > 0)) return 0;
  const double angle = angleOf((first % second).norm(), first | second);
  const double weight = angle * edgeProduct / tangentInPlane;
  return std::isfinite(weight) ? weight : 0;
}

Vec3 fixedPerpendicular(const Vec3& n) {
  Vec3 t;
  axisPerpendicular(n.data(), t.data());  // the one rule (workspace.hpp), mikktspace's too
  return t;
}

}  // namespace tangent::detail
