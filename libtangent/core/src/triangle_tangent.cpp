// SPDX-License-Identifier: MIT
#include "triangle_tangent.hpp"

#include "workspace.hpp"

#include <bit>
#include <cmath>
#include <tuple>

namespace tangent::detail {
namespace {

// Below this fraction of the operands' magnitude a result is rounding noise (~64 ulps).
constexpr double kRelativeZero = 1e-14;

std::uint64_t orderBits(double value) { return bitCast<std::uint64_t>(value == 0.0 ? 0.0 : value); }

auto cornerKey(const Vec3& p, const Vec2& uv) {
  return std::make_tuple(orderBits(p[0]), orderBits(p[1]), orderBits(p[2]), orderBits(uv[0]), orderBits(uv[1]));
}

bool allFinite(const Vec3& v) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); }

}  // namespace

TriangleTangent triangleTangent(const std::array<Vec3, 3>& positions, const std::array<Vec2, 3>& uvs,
                                bool wantFaceNormal) {
  TriangleTangent result;
  for (int k = 0; k < 3; ++k) {
    if (!allFinite(positions[k]) || !std::isfinite(uvs[k][0]) || !std::isfinite(uvs[k][1])) {
      result.kind = TriangleKind::nonFinite;
      return result;
    }
  }
  int start = 0;
  for (int k = 1; k < 3; ++k) {
    if (cornerKey(positions[k], uvs[k]) < cornerKey(positions[start], uvs[start])) start = k;
  }
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
  const double angle = std::atan2(sine, cosine);
  return std::isfinite(angle) ? angle : 0;
}

Vec3 fixedPerpendicular(const Vec3& n) {
  Vec3 t;
  axisPerpendicular(n.data(), t.data());  // the one rule (workspace.hpp), mikktspace's too
  return t;
}

}  // namespace tangent::detail
