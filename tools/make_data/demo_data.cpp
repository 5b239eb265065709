// SPDX-License-Identifier: MIT
// The bundled demo data (data/demo/): bake's default input, the viewer's demo scene and the
// primitives of its panel, with their textures.

#include <cmath>
#include <iostream>
#include <utility>

#include "document_writer.hpp"
#include "families.hpp"
#include "textures.hpp"

namespace make_data {

namespace {

// Where the demo scene's sun shines: down and across, so that from the default (iso) camera
// the spheres are lit and their shadows fall beside them. The viewer test predicts the shadow.
constexpr double kSunDirection[3] = {0.7, -0.6, -0.3};

// bake's default input (demo.gltf): a sphere and mirrored quads with the bump map, a plain ground.
void writeBakeInput(const std::filesystem::path& dir) {
  DocumentWriter demo;
  const float sphereAt[3] = {0, 0, 0}, quadsAt[3] = {0, 0.5f, 1.5f}, groundAt[3] = {0, 0, 0};
  demo.addMesh(uvSphere(32, 16, 1.0f), "Sphere", 0, sphereAt);
  demo.addMesh(mirroredQuads(), "MirroredQuads", 0, quadsAt);
  demo.addMesh(plane(4.0f, -1.0f), "Ground", 1, groundAt);
  Json extra = {
      {"materials", {{{"name", "Bumps"}, {"pbrMetallicRoughness", {{"baseColorFactor", {1, 1, 1, 1}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.4}}},
                      {"normalTexture", {{"index", 0}}}},
                     {{"name", "PlainGround"}, {"pbrMetallicRoughness", {{"baseColorFactor", {0.8, 0.8, 0.8, 1}}, {"metallicFactor", 0.0}}}}}},
      {"textures", {{{"source", 0}, {"sampler", 0}}}},
      {"samplers", {{{"magFilter", 9729}, {"minFilter", 9987}, {"wrapS", 10497}, {"wrapT", 10497}}}},
      {"images", {{{"uri", "bumps_normal.png"}, {"mimeType", "image/png"}}}}};
  demo.write(dir, "demo", extra);
}

// The viewer's demo scene (scene.gltf): spheres on a plane under a directional light and a lamp.
void writeViewerScene(const std::filesystem::path& dir) {
  DocumentWriter scene;
  const float groundAt[3] = {0, 0, 0};
  MeshData ground = plane(4.0f, 0.0f);
  scene.addMesh(ground, "Ground", 1, groundAt);
  const float positions[3][3] = {{-1.6f, 0.7f, 0.3f}, {0.0f, 0.7f, -0.4f}, {1.6f, 0.7f, 0.3f}};
  const char* sphereNames[3] = {"SphereLeft", "SphereMiddle", "SphereRight"};
  for (int i = 0; i < 3; ++i) scene.addMesh(uvSphere(48, 24, 0.7f), sphereNames[i], 0, positions[i]);
  // Sun: KHR_lights_punctual lights shine along their node's -z; the rotation turns -z to
  // kSunDirection (q = normalize(1 + dot(a, b), cross(a, b)) for unit a, b).
  const double length = std::sqrt(kSunDirection[0] * kSunDirection[0] + kSunDirection[1] * kSunDirection[1] + kSunDirection[2] * kSunDirection[2]);
  const double d[3] = {kSunDirection[0] / length, kSunDirection[1] / length, kSunDirection[2] / length};
  double q[4] = {d[1], -d[0], 0.0, 1.0 - d[2]};  // x, y, z, w for a = (0, 0, -1)
  const double qLength = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  for (double& c : q) c /= qLength;
  scene.addNode({{"name", "Sun"}, {"rotation", {q[0], q[1], q[2], q[3]}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  Json extra = sharedMaterials("");
  Json sun = {{"name", "Sun"}, {"type", "directional"}, {"color", {1.0, 0.97, 0.9}}, {"intensity", 1.0}};
  Json lamp = {{"name", "Lamp"}, {"type", "point"}, {"color", {0.4, 0.5, 0.9}}, {"intensity", 4.0}};
  Json lights = Json::object();
  lights["lights"] = Json::array({sun, lamp});
  extra["extensions"] = Json::object();
  extra["extensions"]["KHR_lights_punctual"] = lights;
  scene.addNode({{"name", "Lamp"}, {"translation", {-2.5, 2.0, 2.5}}, {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
  scene.write(dir, "scene", extra);
}

// Primitives to choose in the viewer's panel: beside the textures, so that each file stays
// inside its own folder (the loader's default asset root).
void writePanelPrimitives(const std::filesystem::path& dir) {
  const std::pair<const char*, MeshData> primitives[] = {
      {"quad", quad(1.0f)}, {"cube", cube(0.8f)}, {"sphere", uvSphere(48, 24, 1.0f)}, {"torus", torus(64, 24, 0.9f, 0.35f)}};
  for (const auto& [name, mesh] : primitives) {
    DocumentWriter writer;
    const float origin[3] = {0, 0, 0};
    writer.addMesh(mesh, name, 0, origin);
    Json extra = sharedMaterials("");
    extra["extensionsUsed"] = {"KHR_materials_specular"};
    writer.write(dir, name, extra);
  }
}

}  // namespace

int writeDemoData(const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  if (!writeBumpNormalMap(dir / "bumps_normal.png", 256, 4)) {
    return 1;  // writeImage said which file and why
  }
  writeBakeInput(dir);
  if (!writeSpecularRegions(dir / "specular_regions.png", 96) || !writeWhite(dir / "white.png") || !writeSphereMap(dir / "spheremap.png", 256)) {
    return 1;  // writeImage said which file and why
  }
  writeViewerScene(dir);
  writePanelPrimitives(dir);
  std::cout << "wrote " << dir.string() << ": demo.gltf, scene.gltf, {quad,cube,sphere,torus}.gltf and their textures\n";
  return 0;
}
}  // namespace make_data
