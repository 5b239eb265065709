// SPDX-License-Identifier: MIT
// Depth passes: the shadow map (directional and spot: a 2D map fitted to the scene; point: a
// cube) and the opaque depth pre-pass.
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

void Renderer::drawDepth(std::span<const GpuInstance* const> instances, const glm::mat4& viewProjection, const RenderSettings& settings,
                         bool blendCasts, bool cullAsLit) {
  BoundMesh bound;
  for (const GpuInstance* instance : instances) {
    const GpuMesh& mesh = meshes_[instance->mesh];
    if (bound.mesh != instance->mesh) {
      const FeatureSet features = alphaTestFeatures(mesh, blendCasts);
      const GLuint program = shaders_.depthOnly(features);
      glUseProgram(program);
      setUniform(program, "u_viewProjection", viewProjection);
      if (has(features, Feature::alphaMask)) {
        const gltf::MaterialDesc& material = *materialOf(scene_, mesh.material);
        setUniform(program, "u_uvScale", settings.uvScale);
        setUniform(program, "u_baseColorFactor", glm::make_vec4(material.baseColor.data()));
        setUniform(program, "u_alphaCutoff",
                   material.alphaMode == gltf::MaterialDesc::AlphaMode::mask ? material.alphaCutoff : kBlendShadowCutoff);
        if (has(features, Feature::baseColorMap)) {
          glActiveTexture(GL_TEXTURE0);
          glBindTexture(GL_TEXTURE_2D, textureOf(material.baseColorTexture));
          glBindSampler(0, samplers_.get(material.baseColorTexture.sampler));
          setUniform(program, "u_baseColorMap", 0);
          setUvUniforms(program, "u_baseColor", material.baseColorTexture);
        }
      }
      if (cullAsLit) applyCulling(mesh, settings);
      glBindVertexArray(mesh.vertexArray.get());
      bound = BoundMesh{instance->mesh, glGetUniformLocation(program, "u_model"), -1, -1, -1};
    }
    if (cullAsLit && bound.mirrored != int(instance->mirrored)) {
      frontFace(instance->mirrored);
      bound.mirrored = instance->mirrored;
    }
    glUniformMatrix4fv(bound.model, 1, GL_FALSE, glm::value_ptr(instance->model));
    drawMesh(mesh);
  }
}

namespace {

// A spot light's shadow map spans its cone (a little wider, for PCF at the edge), at most 160
// degrees across.
float spotShadowHalfAngle(const Light& light) { return std::min(light.spotOuter * 1.05f, glm::radians(80.0f)); }

glm::vec3 shadowUpFor(const glm::vec3& direction) { return std::abs(direction.y) > 0.99f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0); }

// A directional light's orthographic shadow view, fitted to the scene's bounds box as the light
// sees it (its eight corners in the light's view), not to the box's bounding sphere: a flat or
// long scene gets texels that much smaller, and the depth range spans the box's depth only.
struct DirectionalShadowFit {
  glm::mat4 view{1};
  glm::vec3 lo{0}, hi{0};  // the corners' light-view extent (x, y across the light, z along it)
  float nearPlane = 0, farPlane = 1;
};

DirectionalShadowFit directionalShadowFit(const Light& light, glm::vec3 boundsMin, glm::vec3 boundsMax) {
  const glm::vec3 center = (boundsMin + boundsMax) * 0.5f;
  const float radius = std::max(glm::length(boundsMax - boundsMin) * 0.5f, 1e-3f);
  const glm::vec3 direction = glm::normalize(light.direction);
  DirectionalShadowFit fit;
  fit.view = glm::lookAt(center - direction * (2 * radius), center, shadowUpFor(direction));
  fit.lo = glm::vec3(std::numeric_limits<float>::max());
  fit.hi = glm::vec3(-std::numeric_limits<float>::max());
  for (int corner = 0; corner < 8; ++corner) {
    const glm::vec3 p((corner & 1) ? boundsMax.x : boundsMin.x, (corner & 2) ? boundsMax.y : boundsMin.y, (corner & 4) ? boundsMax.z : boundsMin.z);
    const glm::vec3 q(fit.view * glm::vec4(p, 1));
    fit.lo = glm::min(fit.lo, q);
    fit.hi = glm::max(fit.hi, q);
  }
  // A margin of 1% of the radius all round: PCF taps and the normal offset reach past the box,
  // and a flat scene seen along its plane keeps some width.
  const float margin = 0.01f * radius;
  fit.lo -= glm::vec3(margin);
  fit.hi += glm::vec3(margin);
  fit.nearPlane = std::max(-fit.hi.z, 0.01f * radius);
  fit.farPlane = std::max(-fit.lo.z, fit.nearPlane + margin);
  return fit;
}

}  // namespace

glm::mat4 Renderer::lightViewProjection() const {
  const glm::vec3 center = boundsCenter();
  const float radius = boundsRadius();
  const Light& light = lights_[0];
  if (light.directional) {
    const DirectionalShadowFit fit = directionalShadowFit(light, boundsMin_, boundsMax_);
    return glm::ortho(fit.lo.x, fit.hi.x, fit.lo.y, fit.hi.y, fit.nearPlane, fit.farPlane) * fit.view;
  }
  // A point light's shadow is the cube map (shadow_cube.hpp), which this matrix plays no part in.
  if (pointShadow()) return glm::mat4(1);
  // A spot light: a perspective view along its axis over its cone, at most 160 degrees across,
  // between the nearest and farthest points of the scene's bounding sphere.
  const float halfAngle = spotShadowHalfAngle(light);
  const float distance = glm::length(center - light.position);
  const float nearPlane = std::max(distance - radius, 0.01f * radius), farPlane = distance + radius;
  const glm::vec3 direction = glm::normalize(light.direction);
  const glm::mat4 view = glm::lookAt(light.position, light.position + direction, shadowUpFor(direction));
  return glm::perspective(2 * halfAngle, 1.0f, nearPlane, farPlane) * view;
}

float Renderer::shadowBiasScale() const {
  if (lights_.empty() || !lights_[0].directional) return 1.0f;
  const DirectionalShadowFit fit = directionalShadowFit(lights_[0], boundsMin_, boundsMax_);
  return 4 * boundsRadius() / (fit.farPlane - fit.nearPlane);
}

glm::vec2 Renderer::shadowTexelWorld() const {
  const Light& light = lights_[0];
  if (light.directional) {
    const DirectionalShadowFit fit = directionalShadowFit(light, boundsMin_, boundsMax_);
    return {std::max(fit.hi.x - fit.lo.x, fit.hi.y - fit.lo.y) / static_cast<float>(std::max(shadowSize_, 1)), 0.0f};
  }
  if (pointShadow()) return {0.0f, 2.0f / static_cast<float>(std::max(shadowCubeSize_, 1))};  // 90-degree faces
  return {0.0f, 2 * std::tan(spotShadowHalfAngle(light)) / static_cast<float>(std::max(shadowSize_, 1))};
}

bool Renderer::pointShadow() const { return !lights_.empty() && !lights_[0].directional && lights_[0].spotOuter < 0; }

glm::vec2 Renderer::shadowCubeDepthRange() const {
  // A point of the sphere is at least d - r from the light, and its face depth (the largest
  // component of the offset) at least that over sqrt 3; at most d + r.
  const float radius = boundsRadius(), distance = glm::length(boundsCenter() - lights_[0].position);
  return {std::max((distance - radius) / 1.75f, 0.02f * radius), distance + radius};
}

// Depth-only framebuffers draw no colour (glDrawBuffers: GL 3.3 and WebGL2 alike).
const GLenum kNoColour = GL_NONE;

void Renderer::drawShadowMap(const RenderSettings& settings) {
  GLint previous = 0;  // the caller's framebuffer, restored at the end
  glGetIntegerv(GL_FRAMEBUFFER_BINDING, &previous);
  // A point light's cube: faces half the 2D map's size (six faces), at most 1024.
  const int cubeSize = std::clamp(settings.shadowMapSize / 2, 256, 1024);
  if (pointShadow() && (shadowCubeSize_ != cubeSize || !shadowCube_)) {
    shadowCubeSize_ = cubeSize;
    shadowCube_ = makeShadowCube(cubeSize);
    shadowCubeFramebuffer_ = makeFramebuffer();
    glBindFramebuffer(GL_FRAMEBUFFER, shadowCubeFramebuffer_.get());
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_CUBE_MAP_POSITIVE_X, shadowCube_.get(), 0);
    glDrawBuffers(1, &kNoColour);
    glReadBuffer(GL_NONE);
  }
  if (!pointShadow() && (shadowSize_ != settings.shadowMapSize || !shadowTexture_)) {
    shadowSize_ = settings.shadowMapSize;
    shadowTexture_ = makeTexture();
    glBindTexture(GL_TEXTURE_2D, shadowTexture_.get());
    glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, shadowSize_, shadowSize_, 0, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, nullptr);
    // Hardware depth comparison (sampler2DShadow): with LINEAR filtering each tap is itself a
    // bilinear blend of four comparisons.
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    shadowFramebuffer_ = makeFramebuffer();
    glBindFramebuffer(GL_FRAMEBUFFER, shadowFramebuffer_.get());
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, shadowTexture_.get(), 0);
    glDrawBuffers(1, &kNoColour);
    glReadBuffer(GL_NONE);
  }
  glEnable(GL_DEPTH_TEST);  // without it GL writes no depth
  glDepthMask(GL_TRUE);
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(2.0f, 4.0f);
  glDisable(GL_CULL_FACE);
  // Every mesh casts: opaque ones whole, MASK ones cut out at their alphaCutoff, BLEND ones cut
  // out at kBlendShadowCutoff.
  // Grouped by mesh, so that each mesh's state is set once.
  std::vector<const GpuInstance*> casters;
  casters.reserve(instances_.size());
  for (const GpuInstance& instance : instances_) casters.push_back(&instance);
  std::stable_sort(casters.begin(), casters.end(), [](const GpuInstance* a, const GpuInstance* b) { return a->mesh < b->mesh; });
  if (pointShadow()) {
    glBindFramebuffer(GL_FRAMEBUFFER, shadowCubeFramebuffer_.get());
    glViewport(0, 0, shadowCubeSize_, shadowCubeSize_);
    const glm::vec2 range = shadowCubeDepthRange();
    for (int face = 0; face < 6; ++face) {
      glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_CUBE_MAP_POSITIVE_X + face, shadowCube_.get(), 0);
      glClear(GL_DEPTH_BUFFER_BIT);
      drawDepth(casters, cubeFaceViewProjection(lights_[0].position, face, range.x, range.y), settings, true, false);
    }
  } else {
    glBindFramebuffer(GL_FRAMEBUFFER, shadowFramebuffer_.get());
    glViewport(0, 0, shadowSize_, shadowSize_);
    glClear(GL_DEPTH_BUFFER_BIT);
    drawDepth(casters, lightViewProjection(), settings, true, false);
  }
  glDisable(GL_POLYGON_OFFSET_FILL);
  glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(previous));
  ++shadowPasses_;
}

}  // namespace tangent::viewer
