// SPDX-License-Identifier: MIT
// The unit normal of a welded vertex, with the replacement of a zero or non-finite one.
#include "kernel.hpp"
#include <vector>

namespace tangent::detail::mikk {

// The unit normal of a welded vertex; a zero or non-finite one is replaced by the sum of its
// triangles' unit normals (summed in value order), else +z.
V3 Kernel::bucketNormal(std::uint32_t bucket, bool& invalid) const {
  const std::uint32_t first = start_[bucket], last = start_[bucket + 1];
  // The bucket's id is its smallest input vertex, one of its identity: read in bucket order.
  V3 n = a_.normal(bucket);
  n = {n.x == 0 ? 0.0 : n.x, n.y == 0 ? 0.0 : n.y, n.z == 0 ? 0.0 : n.z};
  const double len = length(n);
  invalid = !(len > 0 && std::isfinite(len));
  if (!invalid) return n * (1.0 / len);
  std::vector<std::array<double, 3>> faceNormals;
  for (std::uint32_t i = first; i < last; ++i) {
    const std::size_t t = corners_[i] / 3;
    if (ws_.triangleFlags[t] & (kCoincident | kNonFinite | kFlat)) continue;
    const int f = firstCorner(a_, t);
    const V3 p0 = a_.position(a_.indices[3 * t + f]), p1 = a_.position(a_.indices[3 * t + (f + 1) % 3]),
             p2 = a_.position(a_.indices[3 * t + (f + 2) % 3]);
    const V3 c = cross(p1 - p0, p2 - p0);
    const double l = length(c);
    if (l > 0 && std::isfinite(l)) faceNormals.push_back({c.x / l, c.y / l, c.z / l});
  }
  std::sort(faceNormals.begin(), faceNormals.end());
  V3 sum;
  for (const auto& f : faceNormals) sum = sum + V3{f[0], f[1], f[2]};
  const double sumLength = length(sum);
  if (sumLength > 1e-12 && std::isfinite(sumLength)) return sum * (1.0 / sumLength);
  return {0, 0, 1};
}

}  // namespace tangent::detail::mikk
