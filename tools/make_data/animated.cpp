// SPDX-License-Identifier: MIT
// --animated: a skinned and a morphing asset, each with a "bend" animation (the README's images).

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numbers>

#include "document_writer.hpp"
#include "families.hpp"
#include "textures.hpp"

namespace make_data {

namespace {

// An animation of one LINEAR sampler driving `path` of `node`.
Json animation(const std::string& name, std::size_t input, std::size_t output, int node, const std::string& path) {
  Json sampler = {{"input", input}, {"output", output}, {"interpolation", "LINEAR"}};
  Json target = {{"node", node}, {"path", path}};
  Json channel = {{"sampler", 0}, {"target", target}};
  return {{"name", name}, {"samplers", Json::array({sampler})}, {"channels", Json::array({channel})}};
}

// The material of the skinned and morphing assets: the bump normal map on a light grey.
Json bumpsOnly() {
  return {{"materials", {{{"name", "Bumps"},
                          {"pbrMetallicRoughness", {{"baseColorFactor", {0.8, 0.8, 0.8, 1}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.5}}},
                          {"normalTexture", {{"index", 0}}}}}},
          {"textures", {{{"source", 0}, {"sampler", 0}}}},
          {"samplers", {{{"magFilter", 9729}, {"minFilter", 9987}, {"wrapS", 10497}, {"wrapT", 10497}}}},
          {"images", {{{"uri", "bumps_normal.png"}, {"mimeType", "image/png"}}}}};
}

// skinned.gltf: a normal-mapped cylinder (radius 0.35, 2 high) skinned to two joints, Root at
// the origin and Bend at y = 1 (its child), blended linearly from y = 0.8 to 1.2; the animation
// "bend" turns Bend 90 degrees about z at 1 s and back at 2 s (LINEAR). No TANGENT: bake adds it.
void writeSkinned(const std::filesystem::path& dir) {
  DocumentWriter writer;
  const MeshData mesh = cylinder(21, 32, 0.35f, 2.0f);
  const float origin[3] = {0, 0, 0};
  writer.addMesh(mesh, "Cylinder", 0, origin);
  const std::size_t vertices = mesh.positions.size() / 3;
  std::vector<std::uint16_t> joints;
  std::vector<float> weights;
  for (std::size_t v = 0; v < vertices; ++v) {
    const float bend = std::clamp((mesh.positions[3 * v + 1] - 0.8f) / 0.4f, 0.0f, 1.0f);
    // A joint of weight 0 is given as 0 (the validator's ACCESSOR_JOINTS_USED_ZERO_WEIGHT).
    joints.insert(joints.end(), {0, static_cast<std::uint16_t>(bend > 0 ? 1 : 0), 0, 0});
    weights.insert(weights.end(), {1 - bend, bend, 0, 0});
  }
  writer.lastPrimitive()["attributes"]["JOINTS_0"] = writer.addAccessor(joints.data(), vertices, 5123, "VEC4", 34962);
  writer.lastPrimitive()["attributes"]["WEIGHTS_0"] = writer.addAccessor(weights.data(), vertices, 5126, "VEC4", 34962);
  writer.node(0)["skin"] = 0;
  writer.addNode({{"name", "Root"}, {"children", {2}}});
  writer.addNode({{"name", "Bend"}, {"translation", {0.0, 1.0, 0.0}}});
  // Inverse bind matrices (column-major): the joints' world transforms at rest undone.
  const float inverseBind[32] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1};
  const std::size_t bindMatrices = writer.addAccessor(inverseBind, 2, 5126, "MAT4");
  const float times[3] = {0, 1, 2};
  const float h = static_cast<float>(std::sqrt(0.5));
  const float rotations[12] = {0, 0, 0, 1, 0, 0, h, h, 0, 0, 0, 1};
  const std::size_t input = writer.addAccessor(times, 3, 5126, "SCALAR"), output = writer.addAccessor(rotations, 3, 5126, "VEC4");
  Json extra = bumpsOnly();
  extra["skins"] = {{{"joints", {1, 2}}, {"skeleton", 1}, {"inverseBindMatrices", bindMatrices}}};
  extra["animations"] = Json::array({animation("bend", input, output, 2, "rotation")});
  writer.write(dir, "skinned", extra);
}

// morphing.gltf: a normal-mapped 2 x 2 grid facing +z with one morph target that bends it about
// the y axis into an arc of 135 degrees (radius 2 / (0.75 pi), its width kept), POSITION and
// NORMAL deltas analytic; the animation "bend" takes the weight from 0 to 1 at 1 s and back at
// 2 s (LINEAR). No TANGENT: bake adds it and its deltas.
void writeMorphing(const std::filesystem::path& dir) {
  DocumentWriter writer;
  const MeshData mesh = grid(24);
  const float origin[3] = {0, 0, 0};
  writer.addMesh(mesh, "Sheet", 0, origin);
  const std::size_t vertices = mesh.positions.size() / 3;
  const double radius = 2.0 / (0.75 * std::numbers::pi);
  std::vector<float> positionDeltas, normalDeltas;
  for (std::size_t v = 0; v < vertices; ++v) {
    const double x = mesh.positions[3 * v], angle = x / radius;
    positionDeltas.insert(positionDeltas.end(), {static_cast<float>(radius * std::sin(angle) - x), 0.0f, static_cast<float>(radius * std::cos(angle) - radius)});
    normalDeltas.insert(normalDeltas.end(), {static_cast<float>(std::sin(angle)), 0.0f, static_cast<float>(std::cos(angle) - 1)});
  }
  const std::size_t positions = writer.addAccessor(positionDeltas.data(), vertices, 5126, "VEC3", 34962);
  // A POSITION morph target needs its bounds (glTF 2.0 3.7.2.2).
  float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
  for (std::size_t i = 0; i < positionDeltas.size(); ++i) lo[i % 3] = std::min(lo[i % 3], positionDeltas[i]), hi[i % 3] = std::max(hi[i % 3], positionDeltas[i]);
  writer.accessor(positions)["min"] = {lo[0], lo[1], lo[2]};
  writer.accessor(positions)["max"] = {hi[0], hi[1], hi[2]};
  writer.lastPrimitive()["targets"] = {{{"POSITION", positions}, {"NORMAL", writer.addAccessor(normalDeltas.data(), vertices, 5126, "VEC3", 34962)}}};
  writer.lastMesh()["weights"] = {0.0};
  const float times[3] = {0, 1, 2}, weights[3] = {0, 1, 0};
  const std::size_t input = writer.addAccessor(times, 3, 5126, "SCALAR"), output = writer.addAccessor(weights, 3, 5126, "SCALAR");
  Json extra = bumpsOnly();
  extra["animations"] = Json::array({animation("bend", input, output, 0, "weights")});
  writer.write(dir, "morphing", extra);
}

}  // namespace

int writeAnimated(const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  if (!writeBumpNormalMap(dir / "bumps_normal.png", 256, 4)) {
    return 1;  // writeImage said which file and why
  }
  writeSkinned(dir);
  writeMorphing(dir);
  std::cout << "wrote " << dir.string() << ": skinned.gltf, morphing.gltf and bumps_normal.png\n";
  return 0;
}

}  // namespace make_data
