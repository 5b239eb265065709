// SPDX-License-Identifier: MIT
#include "tangent/frame_rules.hpp"

#include <cmath>

#include "workspace.hpp"

namespace tangent {

void unusedVertexTangent(std::span<const float, 3> normal, std::span<float, 4> tangent) {
  // -0 taken as +0 and made unit by the reciprocal, as the kernel reads a vertex's normal
  // (mikktspace/normals.cpp), so that its fixed frames and this give the same bits.
  double n[3] = {normal[0] == 0 ? 0.0 : normal[0], normal[1] == 0 ? 0.0 : normal[1], normal[2] == 0 ? 0.0 : normal[2]};
  const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (!(length > 0) || !std::isfinite(length)) {
    n[0] = 0, n[1] = 0, n[2] = 1;
  } else {
    for (double& x : n) x *= 1.0 / length;
  }
  double t[3];
  detail::axisPerpendicular(n, t);
  for (int i = 0; i < 3; ++i) tangent[i] = static_cast<float>(t[i]);
  tangent[3] = 1.0f;
}

}  // namespace tangent
