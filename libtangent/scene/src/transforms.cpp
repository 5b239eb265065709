// SPDX-License-Identifier: MIT
// Node transforms (glTF 2.0 3.5.3: matrix, or T * R * S), the nodes that cannot be used, and the
// roots the walk starts from.
#include "scene_parts.hpp"

#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

namespace tangent::gltf::scene_parts {
namespace {

// What makes a node's own transform unusable, or "" when nothing does: a value of its matrix,
// translation, rotation or scale that is not finite (NaN, or 1e39, past a float's range). Such
// a node is shown with the identity instead (flattenScene says so, once per node).
std::string transformProblem(const Json& node) {
  if (node.contains("matrix") && node["matrix"].is_array() && node["matrix"].size() == 16) {
    std::array<float, 16> matrix{};
    readFloats(node, "matrix", matrix);
    if (!allFinite(matrix)) return "matrix not finite";
  }
  std::array<float, 3> translation{0, 0, 0}, scale{1, 1, 1};
  std::array<float, 4> rotation{0, 0, 0, 1};
  readFloats(node, "translation", translation);
  readFloats(node, "rotation", rotation);
  readFloats(node, "scale", scale);
  if (!allFinite(translation)) return "translation not finite";
  if (!allFinite(rotation)) return "rotation not finite";
  if (!allFinite(scale)) return "scale not finite";
  return "";
}

}  // namespace

// The node's local transform; the identity where transformProblem finds one (`usable` false).
glm::mat4 localTransform(const Json& node, bool usable) {
  if (!usable) return glm::mat4(1);
  if (node.contains("matrix") && node["matrix"].size() == 16) {
    glm::mat4 m;
    for (int i = 0; i < 16; ++i) glm::value_ptr(m)[i] = jsonFloat(node["matrix"][i]);
    return m;
  }
  std::array<float, 3> t{0, 0, 0}, s{1, 1, 1};
  std::array<float, 4> r{0, 0, 0, 1};
  readFloats(node, "translation", t);
  readFloats(node, "scale", s);
  readFloats(node, "rotation", r);
  const glm::quat q(r[3], r[0], r[1], r[2]);
  return glm::translate(glm::mat4(1), glm::vec3(t[0], t[1], t[2])) * glm::mat4_cast(q) * glm::scale(glm::mat4(1), glm::vec3(s[0], s[1], s[2]));
}

// Nodes whose own transform is unusable: shown with the identity, each named once.
std::vector<char> unusableTransforms(const Json& doc, std::size_t nodeCount, const std::string& file, std::vector<std::string>& messages) {
  std::vector<char> unusableTransform(nodeCount, 0);
  for (std::size_t n = 0; n < nodeCount; ++n) {
    if (const std::string problem = transformProblem(doc["nodes"][n]); !problem.empty()) {
      unusableTransform[n] = 1;
      messages.push_back(file + ": node " + std::to_string(n) + ": " + problem + "; treated as identity");
    }
  }
  return unusableTransform;
}

// The nodes the walk starts from: the default scene's, or, in a file without one, every node
// without a parent.
std::vector<int> rootNodes(const Json& doc) {
  std::vector<int> roots;
  const int sceneIndex = doc.value("scene", 0);
  const std::size_t nodeCount = doc.contains("nodes") ? doc["nodes"].size() : 0;
  if (doc.contains("scenes") && sceneIndex >= 0 && sceneIndex < static_cast<int>(doc["scenes"].size())) {
    for (const Json& root : doc["scenes"][sceneIndex].value("nodes", Json::array())) roots.push_back(root.get<int>());
  } else if (nodeCount > 0) {
    std::vector<char> isChild(nodeCount, 0);
    for (const Json& node : doc["nodes"]) {
      if (!node.contains("children")) continue;
      for (const Json& child : node["children"]) isChild[child.get<std::size_t>()] = 1;
    }
    for (std::size_t n = 0; n < nodeCount; ++n)
      if (!isChild[n]) roots.push_back(static_cast<int>(n));
  }
  return roots;
}

}  // namespace tangent::gltf::scene_parts
