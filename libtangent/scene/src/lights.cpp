// SPDX-License-Identifier: MIT
// KHR_lights_punctual: the lights the document defines, placed by the nodes that refer to them.
#include "scene_parts.hpp"

#include <cmath>

#include "tangent/text.hpp"

namespace tangent::gltf::scene_parts {
namespace {

LightDesc lightAt(const Json& definition, const glm::mat4& world) {
  LightDesc light;
  const std::string type = definition.value("type", "directional");
  light.type = type == "point" ? LightDesc::Type::point : type == "spot" ? LightDesc::Type::spot : LightDesc::Type::directional;
  light.name = definition.value("name", "");
  readFloats(definition, "color", light.color);
  light.intensity = floatValue(definition, "intensity", 1.0f);
  light.range = floatValue(definition, "range", 0.0f);
  if (definition.contains("spot")) {
    light.innerConeAngle = floatValue(definition["spot"], "innerConeAngle", 0.0f);
    light.outerConeAngle = floatValue(definition["spot"], "outerConeAngle", 0.785398f);
  }
  const glm::vec3 position = glm::vec3(world * glm::vec4(0, 0, 0, 1));
  const glm::vec3 direction = glm::normalize(glm::vec3(world * glm::vec4(0, 0, -1, 0)));
  light.position = {position.x, position.y, position.z};
  light.direction = {direction.x, direction.y, direction.z};
  return light;
}

// What makes a light unusable, or "" when nothing does: a value that is not finite (its own, or
// its place and direction, as its node puts them).
std::string lightProblem(const LightDesc& light) {
  if (!allFinite(light.color)) return "color not finite";
  if (!std::isfinite(light.intensity)) return "intensity not finite";
  if (!std::isfinite(light.range)) return "range not finite";
  if (!std::isfinite(light.innerConeAngle) || !std::isfinite(light.outerConeAngle)) return "spot cone angle not finite";
  if (!allFinite(light.position) || !allFinite(light.direction)) return "position or direction not finite (its node's transform)";
  return "";
}

}  // namespace

// The KHR_lights_punctual lights the document defines (nodes refer to them by index).
std::vector<Json> lightDefinitionsOf(const Json& doc) {
  std::vector<Json> lightDefinitions;
  if (doc.contains("extensions") && doc["extensions"].contains("KHR_lights_punctual") &&
      doc["extensions"]["KHR_lights_punctual"].contains("lights")) {
    for (const Json& light : doc["extensions"]["KHR_lights_punctual"]["lights"]) lightDefinitions.push_back(light);
  }
  return lightDefinitions;
}

// A node's KHR_lights_punctual reference (`reference`) placed by its world transform into
// scene.lights, or a message saying why it was left out.
void addNodeLight(const Json& reference, int nodeIndex, const glm::mat4& world, const std::vector<Json>& lightDefinitions,
                  const std::string& file, Scene& scene) {
  const bool hasIndex = reference.contains("light") && reference["light"].is_number_integer();
  const std::int64_t lightIndex = hasIndex ? reference["light"].get<std::int64_t>() : -1;
  const std::string where = file + ": node " + std::to_string(nodeIndex) + ": KHR_lights_punctual light ";
  if (lightIndex < 0 || lightIndex >= static_cast<std::int64_t>(lightDefinitions.size())) {
    const std::string named = reference.contains("light") ? text::dumpJson(reference["light"]) : std::string("(none)");
    scene.messages.push_back(where + named + " is not one of the file's " + std::to_string(lightDefinitions.size()) +
                             " light(s); left out");
    return;
  }
  LightDesc light = lightAt(lightDefinitions[static_cast<std::size_t>(lightIndex)], world);
  light.definition = static_cast<int>(lightIndex);
  light.node = nodeIndex;
  if (const std::string problem = lightProblem(light); !problem.empty())
    scene.messages.push_back(where + std::to_string(lightIndex) + ": " + problem + "; left out");
  else
    scene.lights.push_back(std::move(light));
}

}  // namespace tangent::gltf::scene_parts
