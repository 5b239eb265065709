// SPDX-License-Identifier: MIT
// Tangent frames drawn as line glyphs (T red, B green, N blue), on a budget of glyphs; in the
// anisotropy-direction view, KHR_materials_anisotropy's direction (amber) instead.
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

namespace {

// A texture's texel at a UV as the GL sampler would wrap it (nearest: a glyph needs no filter).
glm::vec4 texelAt(const DecodedImage& image, const gltf::TextureRef& ref, float u0, float v0) {
  const glm::vec3 uv = uvTransformMatrix(ref) * glm::vec3(u0, v0, 1);
  const float u = uv.x, v = uv.y;
  auto wrap = [](float x, int size, gltf::TextureSampler::Wrap mode) {
    if (!std::isfinite(x)) return 0;
    const float scaled = std::floor(x * static_cast<float>(size));
    const long long i = static_cast<long long>(std::clamp(scaled, -1e9f, 1e9f));
    const long long n = size;
    switch (mode) {
      case gltf::TextureSampler::Wrap::clampToEdge: return static_cast<int>(std::clamp<long long>(i, 0, n - 1));
      case gltf::TextureSampler::Wrap::mirroredRepeat: {
        const long long period = ((i % (2 * n)) + 2 * n) % (2 * n);
        return static_cast<int>(period < n ? period : 2 * n - 1 - period);
      }
      default: return static_cast<int>(((i % n) + n) % n);
    }
  };
  const int x = wrap(u, image.width, ref.sampler.wrapS), y = wrap(v, image.height, ref.sampler.wrapT);
  const unsigned char* p = &image.rgba[4 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(image.width) + static_cast<std::size_t>(x))];
  return glm::vec4(p[0], p[1], p[2], p[3]) / 255.0f;
}

// KHR_materials_anisotropy's direction at a corner in (T, B) coordinates and its strength, as
// anisotropy.glsl computes them: the texture's RG as a direction (T's where it encodes none),
// turned by anisotropyRotation; strength = anisotropyStrength times the texture's B.
glm::vec3 anisotropyAt(const gltf::MaterialDesc& material, const DecodedImage* image, const gltf::DrawItem& item, std::size_t corner) {
  glm::vec2 direction{1, 0};
  float strength = material.anisotropyStrength;
  if (image) {
    const int set = material.anisotropyTexture.texCoord == 1 ? 1 : 0;
    const auto& uvs = item.uvSets[static_cast<std::size_t>(set)];
    if (uvs.size() >= 2 * corner + 2) {
      const glm::vec4 texel = texelAt(*image, material.anisotropyTexture, uvs[2 * corner], uvs[2 * corner + 1]);
      direction = glm::vec2(texel) * 2.0f - 1.0f;
      if (glm::dot(direction, direction) < 1e-6f) direction = {1, 0};
      strength *= texel.b;
    }
  }
  direction = glm::normalize(direction);
  const float c = std::cos(material.anisotropyRotation), s = std::sin(material.anisotropyRotation);
  return {c * direction.x - s * direction.y, s * direction.x + c * direction.y, std::clamp(strength, 0.0f, 1.0f)};
}

}  // namespace

// The glyph lines (position, colour; two vertices a line): every stride-th corner of all
// instances together, so that the count stays near maxGlyphs however many instances there are,
// each instance as posed (its node's transform now, its deformed corners). The T/B/N axes, or in
// the anisotropy-direction view the anisotropy's direction where a material has the extension.
std::vector<float> Renderer::glyphLines(const RenderSettings& settings, bool anisotropy) const {
  std::size_t corners = 0;
  for (const auto& instance : scene_.instances) corners += scene_.items[instance.item].positions.size() / 3;
  const std::size_t stride = std::max<std::size_t>(1, corners / std::max(settings.maxGlyphs, 1));
  const float length = 0.04f * boundsRadius();
  std::vector<float> lines;
  auto line = [&](const glm::vec3& p, const glm::vec3& axis, float scale, const glm::vec3& colour) {
    if (!std::isfinite(axis.x) || !std::isfinite(axis.y) || !std::isfinite(axis.z)) return;
    const glm::vec3 end = p + axis * (length * scale);
    lines.insert(lines.end(), {p.x, p.y, p.z, colour.r, colour.g, colour.b, end.x, end.y, end.z, colour.r, colour.g, colour.b});
  };
  std::size_t next = 0;  // the next glyph's corner, counted from the current instance's first
  for (std::size_t i = 0; i < scene_.instances.size(); ++i) {
    const gltf::DrawItem& item = scene_.items[scene_.instances[i].item];
    const std::size_t itemCorners = item.positions.size() / 3;
    const gltf::MaterialDesc* material =
        item.material >= 0 && static_cast<std::size_t>(item.material) < scene_.materials.size() ? &scene_.materials[static_cast<std::size_t>(item.material)] : nullptr;
    if (anisotropy && !(material && material->hasAnisotropy)) {  // no direction: its corners pass
      while (next < itemCorners) next += stride;
    }
    if (next >= itemCorners) {
      next -= itemCorners;
      continue;
    }
    // The direction texture's pixels as uploaded (none where it has none or it could not be
    // decoded: the direction is then T's, as the shader's without a map).
    const int imageIndex = material ? material->anisotropyTexture.image : -1;
    const DecodedImage* directions =
        imageIndex >= 0 && static_cast<std::size_t>(imageIndex) < directionImages_.size() && directionImages_[static_cast<std::size_t>(imageIndex)].width > 0
            ? &directionImages_[static_cast<std::size_t>(imageIndex)]
            : nullptr;
    const CornerFrames frame = framesOf(i);
    const glm::mat4 model = instances_[i].model;
    const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(model)));
    const float mirror = glm::determinant(glm::mat3(model)) < 0 ? -1.0f : 1.0f;  // see mesh.vert
    for (; next < itemCorners; next += stride) {
      const std::size_t c = next;
      const glm::vec3 p = glm::vec3(model * glm::vec4(glm::make_vec3(&frame.positions[3 * c]), 1));
      const glm::vec3 n = glm::normalize(normalMatrix * glm::make_vec3(&frame.normals[3 * c]));
      const glm::vec3 t = glm::normalize(glm::mat3(model) * glm::make_vec3(&frame.tangents[4 * c]));
      const float handedness = frame.tangents[4 * c + 3] < 0 ? -mirror : mirror;
      if (anisotropy) {
        // In the surface: T made orthogonal to N, as the shader's frame; lifted off it by a tenth
        // of a glyph, or the depth test would hide a line lying in a flat surface.
        const glm::vec3 surfaceT = glm::normalize(t - n * glm::dot(n, t));
        const glm::vec3 surfaceB = glm::cross(n, surfaceT) * handedness;
        const glm::vec3 a = anisotropyAt(*material, directions, item, c);
        line(p + n * (0.1f * length), glm::normalize(surfaceT * a.x + surfaceB * a.y), std::max(a.z, 0.15f), {1.0f, 0.7f, 0.1f});
        continue;
      }
      line(p, t, 1, {1, 0.2f, 0.2f});
      line(p, glm::cross(n, t) * handedness, 1, {0.2f, 1, 0.2f});
      line(p, n, 1, {0.3f, 0.5f, 1});
    }
    next -= itemCorners;
  }
  return lines;
}

void Renderer::drawGlyphs(const CameraMatrices& camera, const RenderSettings& settings) {
  const bool anisotropy = settings.view == DebugView::anisotropyDirection;
  if (glyphsBuiltFor_ != settings.maxGlyphs || glyphsShowAnisotropy_ != anisotropy) {
    const std::vector<float> lines = glyphLines(settings, anisotropy);
    glyphArray_ = makeVertexArray();
    glyphBuffer_ = makeBuffer();
    glBindVertexArray(glyphArray_.get());
    glBindBuffer(GL_ARRAY_BUFFER, glyphBuffer_.get());
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(lines.size() * sizeof(float)), lines.data(), GL_STATIC_DRAW);
    setVertexLayout(kLineVertexLayout);
    glyphVertices_ = static_cast<GLsizei>(lines.size() / kLineFloatsPerVertex);
    glyphsBuiltFor_ = settings.maxGlyphs;
    glyphsShowAnisotropy_ = anisotropy;
  }
  const GLuint program = shaders_.lines();
  glUseProgram(program);
  setUniform(program, "u_viewProjection", camera.projection * camera.view);
  glBindVertexArray(glyphArray_.get());
  glDrawArrays(GL_LINES, 0, glyphVertices_);
}

}  // namespace tangent::viewer
