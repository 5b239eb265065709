// SPDX-License-Identifier: MIT
// Built against the installed package through tangent::openmesh: the quad of core_main.cpp as
// a CornerMesh, every method, and each halfedge's tangent against the array call's bits.
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <vector>

#include <tangent/openmesh.hpp>

int main() {
  const std::vector<float> positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const std::vector<float> normals = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
  const std::vector<float> uvs = {0, 1, 0, 0, 1, 0, 1, 1};
  const std::vector<std::uint32_t> indices = {0, 1, 2, 0, 2, 3};
  const tangent::MeshArrays arrays{positions, normals, uvs, indices};
  int failures = 0;
  for (const auto method : {tangent::Method::mikktspace, tangent::Method::lengyel, tangent::Method::flat}) {
    const tangent::Options options{.method = method, .threads = 1};
    std::vector<float> expected(indices.size() * 4);
    tangent::computeCornerTangents(arrays, expected, options);
    tangent::CornerMesh mesh = tangent::buildCornerMesh(arrays);
    const tangent::Report report = tangent::computeTangents(mesh, options);
    if (report.corners != indices.size() || report.method != method) ++failures;
    for (std::size_t corner = 0; corner < indices.size(); ++corner) {
      const tangent::TangentVec& t = mesh.mesh.property(mesh.tangent, mesh.cornerHalfedge[corner]);
      for (int i = 0; i < 4; ++i) {
        const float value = static_cast<float>(t[i]);
        if (std::memcmp(&value, &expected[4 * corner + i], sizeof value) != 0) {
          std::printf("%s, corner %zu: %g, the array call gives %g\n", std::string(tangent::toString(method)).c_str(), corner,
                      value, expected[4 * corner + i]);
          ++failures;
        }
      }
    }
  }
  std::printf("consumer_openmesh: %s\n", failures == 0 ? "the array call's bits" : "WRONG tangents");
  return failures == 0 ? 0 : 1;
}
