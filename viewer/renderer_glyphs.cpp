// SPDX-License-Identifier: MIT
// Tangent frames drawn as line glyphs (T red, B green, N blue), on a budget of glyphs.
#include "renderer.hpp"
#include "renderer_internal.hpp"

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <span>

#include "shadow_cube.hpp"
#include "tangent/text.hpp"
#include "textures.hpp"
#include "vertex_layout.hpp"
#include "vertex_weld.hpp"

namespace tangent::viewer {

using namespace renderer_detail;

void Renderer::drawGlyphs(const CameraMatrices& camera, const RenderSettings& settings) {
  if (glyphsBuiltFor_ != settings.maxGlyphs) {
    // Every stride-th corner of all instances together, so that the count stays near maxGlyphs
    // however many instances there are.
    std::size_t corners = 0;
    for (const auto& instance : scene_.instances) corners += scene_.items[instance.item].positions.size() / 3;
    // Each instance as posed: its node's transform now, its deformed corners.
    const std::size_t stride = std::max<std::size_t>(1, corners / std::max(settings.maxGlyphs, 1));
    const float length = 0.04f * boundsRadius();
    std::vector<float> lines;
    std::size_t next = 0;  // the next glyph's corner, counted from the current instance's first
    for (std::size_t i = 0; i < scene_.instances.size(); ++i) {
      const gltf::DrawItem& item = scene_.items[scene_.instances[i].item];
      const std::size_t itemCorners = item.positions.size() / 3;
      if (next >= itemCorners) {
        next -= itemCorners;
        continue;
      }
      const CornerFrames frame = framesOf(i);
      const glm::mat4 model = instances_[i].model;
      const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(model)));
      const float mirror = glm::determinant(glm::mat3(model)) < 0 ? -1.0f : 1.0f;  // see mesh.vert
      for (; next < itemCorners; next += stride) {
        const std::size_t c = next;
        const glm::vec3 p = glm::vec3(model * glm::vec4(glm::make_vec3(&frame.positions[3 * c]), 1));
        const glm::vec3 n = glm::normalize(normalMatrix * glm::make_vec3(&frame.normals[3 * c]));
        const glm::vec3 t = glm::normalize(glm::mat3(model) * glm::make_vec3(&frame.tangents[4 * c]));
        const glm::vec3 b = glm::cross(n, t) * (frame.tangents[4 * c + 3] < 0 ? -mirror : mirror);
        const glm::vec3 axes[3] = {t, b, n};
        const glm::vec3 colors[3] = {{1, 0.2f, 0.2f}, {0.2f, 1, 0.2f}, {0.3f, 0.5f, 1}};
        for (int a = 0; a < 3; ++a) {
          if (!std::isfinite(axes[a].x)) continue;
          const glm::vec3 end = p + axes[a] * length;
          lines.insert(lines.end(), {p.x, p.y, p.z, colors[a].r, colors[a].g, colors[a].b, end.x, end.y, end.z, colors[a].r, colors[a].g, colors[a].b});
        }
      }
      next -= itemCorners;
    }
    glyphArray_ = makeVertexArray();
    glyphBuffer_ = makeBuffer();
    glBindVertexArray(glyphArray_.get());
    glBindBuffer(GL_ARRAY_BUFFER, glyphBuffer_.get());
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(lines.size() * sizeof(float)), lines.data(), GL_STATIC_DRAW);
    setVertexLayout(kLineVertexLayout);
    glyphVertices_ = static_cast<GLsizei>(lines.size() / kLineFloatsPerVertex);
    glyphsBuiltFor_ = settings.maxGlyphs;
  }
  const GLuint program = shaders_.lines();
  glUseProgram(program);
  setUniform(program, "u_viewProjection", camera.projection * camera.view);
  glBindVertexArray(glyphArray_.get());
  glDrawArrays(GL_LINES, 0, glyphVertices_);
}

}  // namespace tangent::viewer
