// What a primitive is and needs: shared by bake and info.
#pragma once

#include <nlohmann/json.hpp>
#include <cstdint>
#include <string>
#include <vector>

namespace tangent::gltf::detail {

struct PrimitiveNeeds {
  bool triangles = false;        // mode 4, 5 or 6
  bool compressed = false;       // KHR_draco_mesh_compression
  bool hasNormalTexture = false;
  int texCoord = -1;             // UV set the normal texture samples, -1 when none
  bool texCoordFromTransform = false;  // KHR_texture_transform overrode texCoord
  std::string why;               // human-readable: why tangents are (not) needed
};

PrimitiveNeeds primitiveNeeds(const nlohmann::ordered_json& doc, const nlohmann::ordered_json& primitive, bool all);

// Triangle list (3 vertex indices per triangle) from glTF modes 4, 5 and 6 (spec 3.7.2.1);
// stitching triangles of joined strips (a repeated index) draw nothing and are left out.
std::vector<std::uint32_t> triangleList(int mode, const std::vector<std::uint32_t>& vertices);

// "mesh 0 'Name' primitive 1"
std::string primitiveLabel(const nlohmann::ordered_json& doc, int mesh, int primitive);

}  // namespace tangent::gltf::detail
