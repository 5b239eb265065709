// SPDX-License-Identifier: MIT
// Gram-Schmidt against the normal, the one statement of it: mikktspace's groups and
// fallbacks (mikktspace/math.hpp) and lengyel's groups (lengyel_groups.cpp) call it.
#pragma once

#include <cmath>

namespace tangent::detail {

// Below this fraction of the sum's length, what is left of it in the tangent plane is noise.
inline constexpr double kInPlaneFloor = 1e-12;

// `sum` made orthogonal to the unit normal n and unit, into out; false (out untouched) where
// the sum is zero or not finite, or nothing of it lies in the tangent plane.
inline bool orthonormalize(const double sum[3], const double n[3], double out[3]) {
  const double sumLength = std::sqrt(sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]);
  if (!(sumLength > 0) || !std::isfinite(sumLength)) return false;
  const double along = n[0] * sum[0] + n[1] * sum[1] + n[2] * sum[2];
  const double t[3] = {sum[0] - n[0] * along, sum[1] - n[1] * along, sum[2] - n[2] * along};
  const double length = std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
  if (!(length > kInPlaneFloor * sumLength)) return false;
  const double scale = 1.0 / length;
  for (int i = 0; i < 3; ++i) out[i] = t[i] * scale;
  return true;
}

}  // namespace tangent::detail
