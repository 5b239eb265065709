// SPDX-License-Identifier: MIT
#include "document_writer.hpp"

#include <cmath>

namespace make_data {

Json sharedMaterials(const std::string& imagePrefix) {
  Json specular = {{"specularFactor", 1.0}, {"specularTexture", {{"index", 2}}}, {"specularColorTexture", {{"index", 2}}}};
  return {
      {"extensionsUsed", {"KHR_materials_specular", "KHR_lights_punctual"}},
      {"materials",
       {{{"name", "BumpsSpecular"},
         // Mid grey over the white texture: room above the diffuse for the highlights to show.
         {"pbrMetallicRoughness", {{"baseColorFactor", {0.55, 0.55, 0.55, 1.0}}, {"baseColorTexture", {{"index", 1}}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.35}}},
         {"normalTexture", {{"index", 0}}},
         {"extensions", {{"KHR_materials_specular", specular}}}},
        {{"name", "Ground"},
         {"pbrMetallicRoughness", {{"baseColorFactor", {0.85, 0.85, 0.85, 1}}, {"baseColorTexture", {{"index", 1}}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.9}}}}}},
      {"textures", {{{"source", 0}, {"sampler", 0}}, {{"source", 1}, {"sampler", 0}}, {{"source", 2}, {"sampler", 0}}}},
      {"samplers", {{{"magFilter", 9729}, {"minFilter", 9987}, {"wrapS", 10497}, {"wrapT", 10497}}}},
      {"images",
       {{{"uri", imagePrefix + "bumps_normal.png"}, {"mimeType", "image/png"}},
        {{"uri", imagePrefix + "white.png"}, {"mimeType", "image/png"}},
        {{"uri", imagePrefix + "specular_regions.png"}, {"mimeType", "image/png"}}}}};
}

Json sunNode(const std::string& name, const double (&direction)[3]) {
  const double length = std::sqrt(direction[0] * direction[0] + direction[1] * direction[1] + direction[2] * direction[2]);
  const double d[3] = {direction[0] / length, direction[1] / length, direction[2] / length};
  double q[4] = {d[1], -d[0], 0.0, 1.0 - d[2]};  // x, y, z, w for a = (0, 0, -1)
  const double qLength = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  for (double& c : q) c /= qLength;
  return {{"name", name}, {"rotation", {q[0], q[1], q[2], q[3]}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}};
}

Json oneSun(double intensity) {
  Json lights = Json::object();
  lights["lights"] = Json::array({Json{{"name", "Sun"}, {"type", "directional"}, {"color", {1.0, 1.0, 1.0}}, {"intensity", intensity}}});
  return lights;
}

}  // namespace make_data
