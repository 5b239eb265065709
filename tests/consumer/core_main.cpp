// SPDX-License-Identifier: MIT
// Built against the installed package: tangents of a quad whose u runs along +y through the
// public array API. Exits 1 when a tangent differs from the value worked out by hand.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

#include <tangent/tangent.hpp>

// The core's headers include no OpenMesh header (OpenMesh's config.h defines OM_VERSION): an
// arrays-only program needs none on its include path.
#ifdef OM_VERSION
#error "tangent/tangent.hpp included an OpenMesh header"
#endif

int main() {
  // Unit quad in the xy plane facing +z, texture turned a quarter: u = y, v = 1 - x. The
  // tangent (direction of increasing u) is +y everywhere. With v increasing along -x the
  // bitangent is -x = cross(N, T), so the UV frame is right-handed: w = +1 with a bottom-left
  // UV origin, and glTF's top-left origin negates it.
  const std::vector<float> positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const std::vector<float> normals = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
  const std::vector<float> uvs = {0, 1, 0, 0, 1, 0, 1, 1};
  const std::vector<std::uint32_t> indices = {0, 1, 2, 0, 2, 3};
  int failures = 0;
  for (const auto [origin, expectedW] : {std::pair{tangent::UvOrigin::bottomLeft, 1.0f}, std::pair{tangent::UvOrigin::topLeft, -1.0f}}) {
    std::vector<float> tangents(indices.size() * 4, NAN);
    const tangent::Report report =
        tangent::computeCornerTangents({positions, normals, uvs, indices}, tangents, {.uvOrigin = origin, .threads = 1});
    if (report.corners != indices.size() || report.method != tangent::Method::mikktspace) {
      std::printf("report: %llu corners, method %s\n", static_cast<unsigned long long>(report.corners), std::string(tangent::toString(report.method)).c_str());
      ++failures;
    }
    for (std::size_t corner = 0; corner < indices.size(); ++corner) {
      const float* t = &tangents[4 * corner];
      if (std::abs(t[0]) > 1e-6f || std::abs(t[1] - 1) > 1e-6f || std::abs(t[2]) > 1e-6f || t[3] != expectedW) {
        std::printf("corner %zu: tangent %g %g %g %g, expected 0 1 0 %g\n", corner, t[0], t[1], t[2], t[3], expectedW);
        ++failures;
      }
    }
  }
  std::printf("consumer_core: %s\n", failures == 0 ? "tangents as expected" : "WRONG tangents");
  return failures == 0 ? 0 : 1;
}
