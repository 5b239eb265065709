// SPDX-License-Identifier: MIT
// --materials: scenes whose features read the tangent frame (anisotropy, clearcoat) or COLOR_0.

#include <algorithm>
#include <cmath>
#include <iostream>

#include "document_writer.hpp"
#include "families.hpp"
#include "tangent/tangent.hpp"
#include "textures.hpp"

namespace make_data {

namespace {

const Json kSampler = {{"magFilter", 9729}, {"minFilter", 9987}, {"wrapS", 10497}, {"wrapT", 10497}};
const float kOrigin[3] = {0, 0, 0};
const double kTowardsScene[3] = {-0.2, -0.25, -1.0};  // from above and to the right of the front camera

// anisotropy_disc.gltf
void writeAnisotropyDisc(const std::filesystem::path& dir) {
  DocumentWriter writer;
  writer.addMesh(disc(12, 96, 1.0f), "BrushedDisc", 0, kOrigin);
  writer.addNode(sunNode("Sun", kTowardsScene));
  Json anisotropy = {{"anisotropyStrength", 0.8}, {"anisotropyRotation", 0.5}, {"anisotropyTexture", {{"index", 0}}}};
  Json extra = {
      {"extensionsUsed", {"KHR_materials_anisotropy", "KHR_lights_punctual"}},
      {"extensions", {{"KHR_lights_punctual", oneSun(3.0)}}},
      {"materials", {{{"name", "BrushedMetal"},
                      {"pbrMetallicRoughness", {{"baseColorFactor", {0.9, 0.9, 0.9, 1}}, {"metallicFactor", 1.0}, {"roughnessFactor", 0.35}}},
                      {"extensions", {{"KHR_materials_anisotropy", anisotropy}}}}}},
      {"textures", {{{"source", 0}, {"sampler", 0}}}},
      {"samplers", {kSampler}},
      {"images", {{{"uri", "anisotropy_direction.png"}, {"mimeType", "image/png"}}}}};
  writer.write(dir, "anisotropy_disc", extra);
}

// TANGENT as the clearcoat normal texture reads it: MikkTSpace (libtangent's default, what
// `tangent bake` writes) on TEXCOORD_1 through its KHR_texture_transform (u' = c s u + s s v + o,
// v' = -s s u + c s v, as tangent/primitive.cpp applies it). The sphere's corners of one
// vertex share every input, so they get one tangent: the vertex's.
void setClearcoatTangents(MeshData& sphere, double rotation, double scale) {
  const double c = std::cos(rotation), s = std::sin(rotation);
  std::vector<float> uvs(sphere.uvs.size());
  for (std::size_t i = 0; i < uvs.size(); i += 2) {
    const double u = sphere.uvs[i] / 2, v = sphere.uvs[i + 1];  // TEXCOORD_1 (below)
    uvs[i] = static_cast<float>(scale * (c * u + s * v) + 0.1);
    uvs[i + 1] = static_cast<float>(scale * (-s * u + c * v));
  }
  const std::vector<std::uint32_t> indices(sphere.indices.begin(), sphere.indices.end());
  std::vector<float> corners(indices.size() * 4);
  tangent::computeCornerTangents({sphere.positions, sphere.normals, uvs, indices}, corners);
  // The pole copies no triangle uses keep any unit frame.
  for (std::size_t v = 0; v < sphere.positions.size() / 3; ++v) sphere.tangents.insert(sphere.tangents.end(), {1.0f, 0.0f, 0.0f, 1.0f});
  for (std::size_t corner = 0; corner < indices.size(); ++corner)
    std::copy_n(&corners[4 * corner], 4, &sphere.tangents[4 * indices[corner]]);
}

// clearcoat_sphere.gltf
void writeClearcoatSphere(const std::filesystem::path& dir) {
  DocumentWriter writer;
  MeshData sphere = uvSphere(64, 32, 1.0f);
  const double rotation = 0.6, scale = 3.0;  // the clearcoat normal texture's transform (uniform scale)
  setClearcoatTangents(sphere, rotation, scale);
  writer.addMesh(sphere, "CoatedSphere", 0, kOrigin);
  // TEXCOORD_1: the sphere's UVs once around (TEXCOORD_0 goes twice), the transform tiles them.
  std::vector<float> uv1(sphere.uvs);
  for (std::size_t i = 0; i < uv1.size(); i += 2) uv1[i] *= 0.5f;
  writer.lastPrimitive()["attributes"]["TEXCOORD_1"] = writer.addAccessor(uv1.data(), uv1.size() / 2, 5126, "VEC2", 34962);
  writer.addNode(sunNode("Sun", kTowardsScene));
  Json transform = {{"rotation", rotation}, {"scale", {scale, scale}}, {"offset", {0.1, 0.0}}};
  Json clearcoat = {{"clearcoatFactor", 1.0},
                    {"clearcoatRoughnessFactor", 0.08},
                    {"clearcoatNormalTexture", {{"index", 0}, {"texCoord", 1}, {"scale", 0.8}, {"extensions", {{"KHR_texture_transform", transform}}}}}};
  Json extra = {
      {"extensionsUsed", {"KHR_materials_clearcoat", "KHR_texture_transform", "KHR_lights_punctual"}},
      {"extensions", {{"KHR_lights_punctual", oneSun(3.0)}}},
      {"materials", {{{"name", "CoatedPaint"},
                      {"pbrMetallicRoughness", {{"baseColorFactor", {0.7, 0.08, 0.05, 1}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.7}}},
                      {"extensions", {{"KHR_materials_clearcoat", clearcoat}}}}}},
      {"textures", {{{"source", 0}, {"sampler", 0}}}},
      {"samplers", {kSampler}},
      {"images", {{{"uri", "bumps_normal.png"}, {"mimeType", "image/png"}}}}};
  writer.write(dir, "clearcoat_sphere", extra);
}

// vertex_colors.gltf
void writeVertexColours(const std::filesystem::path& dir) {
  DocumentWriter writer;
  const MeshData mesh = grid(16);
  writer.addMesh(mesh, "ColouredGrid", 0, kOrigin);
  std::vector<std::uint8_t> colours;
  for (std::size_t v = 0; v < mesh.positions.size() / 3; ++v) {
    const double s = (mesh.positions[3 * v] + 1) / 2;  // 0 at x = -1, 1 at x = 1
    const double rgb[3] = {std::clamp(1 - 2 * s, 0.0, 1.0), 1 - std::abs(2 * s - 1), std::clamp(2 * s - 1, 0.0, 1.0)};
    for (double c : rgb) colours.push_back(static_cast<std::uint8_t>(std::lround(c * 255)));
    colours.push_back(255);
  }
  const std::size_t colour = writer.addAccessor(colours.data(), colours.size() / 4, 5121, "VEC4", 34962);
  writer.accessor(colour)["normalized"] = true;
  writer.lastPrimitive()["attributes"]["COLOR_0"] = colour;
  writer.addNode(sunNode("Sun", kTowardsScene));
  Json extra = {
      {"extensionsUsed", {"KHR_lights_punctual"}},
      {"extensions", {{"KHR_lights_punctual", oneSun(3.0)}}},
      {"materials", {{{"name", "VertexColoured"},
                      {"pbrMetallicRoughness", {{"baseColorFactor", {1, 1, 1, 1}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.8}}}}}}};
  writer.write(dir, "vertex_colors", extra);
}

}  // namespace

// The material scenes (--materials), each lit by one sun from near the front camera so that the
// highlights face the viewer (tangent-view --camera front):
// - anisotropy_disc.gltf: a brushed-metal disc (KHR_materials_anisotropy: strength 0.8, rotation
//   0.5 rad, a circular direction texture), no normal map: anisotropy alone reads the frame.
// - clearcoat_sphere.gltf: a rough red sphere under a smooth clearcoat (KHR_materials_clearcoat)
//   whose clearcoatNormalTexture (the bumps) samples TEXCOORD_1 through a rotated
//   KHR_texture_transform; no normalTexture.
// - vertex_colors.gltf: a grid whose COLOR_0 (normalized unsigned bytes, RGBA) shades from red
//   through green to blue across x, over a white base colour.
// With TANGENT where a consumer of the frame needs it (the validator asks for it): the disc's
// and the sphere's, written analytically; `tangent check` compares them with MikkTSpace's.
int writeMaterialScenes(const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  if (!writeBumpNormalMap(dir / "bumps_normal.png", 256, 4) || !writeCircularDirections(dir / "anisotropy_direction.png", 64)) {
    return 1;  // writeImage said which file and why
  }
  writeAnisotropyDisc(dir);
  writeClearcoatSphere(dir);
  writeVertexColours(dir);
  std::cout << "wrote " << dir.string() << ": anisotropy_disc.gltf, clearcoat_sphere.gltf, vertex_colors.gltf and their textures\n";
  return 0;
}

}  // namespace make_data
