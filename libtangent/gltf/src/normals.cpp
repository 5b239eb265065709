// SPDX-License-Identifier: MIT
// NORMAL as glTF readers treat it (normals.hpp).
#include "normals.hpp"

#include <cmath>

namespace tangent::gltf::detail {

bool normalNeedsNormalizing(double length) { return std::abs(length - 1.0) > kNormalLengthKept; }

double NormalLengths::worstDeviation() const { return std::abs(worstLength - 1.0); }

NormalLengths unitNormals(std::span<float> normals) {
  NormalLengths found;
  for (std::size_t i = 0; i + 2 < normals.size(); i += 3) {
    float* n = &normals[i];
    const double length = std::sqrt(double(n[0]) * n[0] + double(n[1]) * n[1] + double(n[2]) * n[2]);
    if (!(length > 0) || !std::isfinite(length)) {
      ++found.zero;
      continue;
    }
    if (std::abs(length - 1.0) > found.worstDeviation()) found.worstLength = length;
    if (!normalNeedsNormalizing(length)) continue;
    ++found.normalized;
    for (int k = 0; k < 3; ++k) n[k] = static_cast<float>(n[k] / length);
  }
  return found;
}

}  // namespace tangent::gltf::detail
