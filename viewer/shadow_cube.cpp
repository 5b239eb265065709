// SPDX-License-Identifier: MIT
#include "shadow_cube.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <array>
#include <utility>

namespace tangent::viewer {

glm::mat4 cubeFaceViewProjection(const glm::vec3& light, int face, float nearPlane, float farPlane) {
  // Face direction and the up vector that makes window x the face's s and window y its t.
  static const std::array<std::pair<glm::vec3, glm::vec3>, 6> kFaces = {{
      {{1, 0, 0}, {0, -1, 0}},
      {{-1, 0, 0}, {0, -1, 0}},
      {{0, 1, 0}, {0, 0, 1}},
      {{0, -1, 0}, {0, 0, -1}},
      {{0, 0, 1}, {0, -1, 0}},
      {{0, 0, -1}, {0, -1, 0}},
  }};
  const auto& [direction, up] = kFaces[static_cast<std::size_t>(face)];
  return glm::perspective(glm::radians(90.0f), 1.0f, nearPlane, farPlane) * glm::lookAt(light, light + direction, up);
}

Texture makeShadowCube(int size) {
  Texture cube = makeTexture();
  glBindTexture(GL_TEXTURE_CUBE_MAP, cube.get());
  for (int face = 0; face < 6; ++face)
    glTexImage2D(GL_TEXTURE_CUBE_MAP_POSITIVE_X + face, 0, GL_DEPTH_COMPONENT24, size, size, 0, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, nullptr);
  glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  for (const GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R}) glTexParameteri(GL_TEXTURE_CUBE_MAP, wrap, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
  return cube;
}

}  // namespace tangent::viewer
