// What a primitive is and needs: shared by bake and info.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

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

// "mesh 0 'Name' primitive 1"
std::string primitiveLabel(const nlohmann::ordered_json& doc, int mesh, int primitive);

}  // namespace tangent::gltf::detail
