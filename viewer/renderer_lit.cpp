// SPDX-License-Identifier: MIT
// The frame: the passes in order (shadows, depth, opaque, BLEND sorted back to front, glyphs)
// and the lit pass's per-mesh state (bindMesh).
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
#include <utility>

#include "shadow_cube.hpp"
#include "tangent/text.hpp"
#include "textures.hpp"
#include "vertex_layout.hpp"
#include "vertex_weld.hpp"

namespace tangent::viewer {

using namespace renderer_detail;

void Renderer::prepareViewData(const RenderSettings& settings) {
  if (settings.view == DebugView::tangentError) {
    // Morphing instances: their tangents against fresh ones on the morphed mesh, computed when
    // this view first shows a pose (a MikkTSpace run per instance).
    for (DeformedInstance& deformed : deformed_) {
      if (deformed.errorsCurrent) continue;
      deformed.tangentErrorDegrees = morphedTangentErrors(scene_.items[scene_.instances[deformed.instance].item], deformed.weights);
      deformed.errorsCurrent = true;
      uploadDeformed(deformed);
    }
  }
  if (settings.split || settings.view == DebugView::compareAngle) {
    // Morphing instances whose compare set is the fresh one: MikkTSpace on the morphed corners
    // (then skinned), computed when a view first shows the pose.
    for (DeformedInstance& deformed : deformed_) {
      if (!deformed.compareStale) continue;
      const gltf::DrawInstance& source = scene_.instances[deformed.instance];
      deformItem(scene_.items[source.item], deformed.weights, deformed.joints, deformed.corners, compareTangentsOf(source.item),
                 CompareMorph::recompute);
      deformed.compareStale = false;
      uploadDeformed(deformed);
    }
  }
  if (settings.ibl && settings.shading == Shading::pbr && settings.view == DebugView::lit && !environment_) {
    const auto start = std::chrono::steady_clock::now();
    environment_ = uploadEnvironment(buildEnvironment());
    environmentMilliseconds_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }
}

void Renderer::refreshShadowMap(const RenderSettings& settings, FrameStats& stats) {
  if (!shadowsDrawn(settings)) return;
  // The map depends on the scene, light 0's direction and the map size only: a camera that
  // moves reuses it.
  const ShadowKey key{glm::normalize(lights_[0].direction), lights_[0].directional ? glm::vec3(0) : lights_[0].position, pointShadow(),
                      settings.shadowMapSize, sceneVersion_, settings.uvScale};
  if (!(key == shadowKey_) || !(pointShadow() ? shadowCube_ : shadowTexture_)) {
    drawShadowMap(settings);
    shadowKey_ = key;
    stats.depthPass = true;
    stats.shadowDrawCalls += static_cast<int>(instances_.size()) * (pointShadow() ? 6 : 1);
  }
}

// Opaque and masked meshes front to back (less overdraw): the mesh with the nearest instance
// first, its instances front to back, so that each mesh's state is set once. Then blended
// instances back to front over them, one by one (the order matters), as the Khronos glTF
// Sample Viewer draws them: sorted by the view-space depth of their centre, with depth test
// and depth writes on, so that a closed blended mesh hides its own far side.
Renderer::DrawOrder Renderer::drawOrder(const CameraMatrices& camera, const RenderSettings& settings) const {
  auto blended = [&](const GpuMesh& mesh) {
    return mesh.material >= 0 && mesh.material < static_cast<int>(scene_.materials.size()) &&
           scene_.materials[mesh.material].alphaMode == gltf::MaterialDesc::AlphaMode::blend && settings.view == DebugView::lit;
  };
  struct Ordered {
    float distance;  // opaque: from the eye; blended: view-space depth (-z)
    const GpuInstance* instance;
  };
  std::vector<Ordered> opaqueOrder, transparentOrder;
  std::vector<float> nearestOfMesh(meshes_.size(), std::numeric_limits<float>::max());
  for (const GpuInstance& instance : instances_) {
    if (blended(meshes_[instance.mesh])) {
      transparentOrder.push_back({-(camera.view * glm::vec4(instance.centerWorld, 1)).z, &instance});
    } else {
      const float distance = glm::length(instance.centerWorld - camera.eye);
      opaqueOrder.push_back({distance, &instance});
      nearestOfMesh[instance.mesh] = std::min(nearestOfMesh[instance.mesh], distance);
    }
  }
  std::stable_sort(opaqueOrder.begin(), opaqueOrder.end(), [&](const Ordered& a, const Ordered& b) {
    const float nearA = nearestOfMesh[a.instance->mesh], nearB = nearestOfMesh[b.instance->mesh];
    if (nearA != nearB) return nearA < nearB;
    if (a.instance->mesh != b.instance->mesh) return a.instance->mesh < b.instance->mesh;
    return a.distance < b.distance;
  });
  std::stable_sort(transparentOrder.begin(), transparentOrder.end(),
                   [](const Ordered& a, const Ordered& b) { return a.distance > b.distance; });
  DrawOrder order;
  order.opaque.reserve(opaqueOrder.size());
  for (const Ordered& entry : opaqueOrder) order.opaque.push_back(entry.instance);
  for (const Ordered& entry : transparentOrder) order.transparent.push_back(entry.instance);
  return order;
}

// The whole scene with one tangent set, into the framebuffer's scissor box (when enabled).
void Renderer::drawScene(const DrawOrder& order, const CameraMatrices& camera, const RenderSettings& settings, TangentSet tangents,
                         FrameStats& stats) {
  const bool prePass = settings.depthPrePass && settings.view == DebugView::lit && !order.opaque.empty();
  glDepthMask(GL_TRUE);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  if (prePass) {
    // Depth of the opaque and masked meshes first, so that the shading pass below runs the
    // fragment shader once per pixel; same culling, same invariant positions, GL_LEQUAL.
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    drawDepth(order.opaque, camera.projection * camera.view, settings, false, true);
    stats.drawCalls += static_cast<int>(order.opaque.size());
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
  }
  drawInstances(order.opaque, camera, settings, tangents, stats);
  if (prePass) {
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
  }
  if (!order.transparent.empty()) {
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    drawInstances(order.transparent, camera, settings, tangents, stats);
    glDisable(GL_BLEND);
  }
  glFrontFace(GL_CCW);
  glDisable(GL_CULL_FACE);
}

FrameStats Renderer::render(const CameraMatrices& camera, const RenderSettings& settings, int width, int height) {
  FrameStats stats;
  prepareViewData(settings);
  refreshShadowMap(settings, stats);
  glViewport(0, 0, width, height);
  glClearColor(0.16f, 0.17f, 0.19f, 1.0f);
  const DrawOrder order = drawOrder(camera, settings);
  stats.exposure = exposure(settings);
  // Split view: the same scene twice, each into its side of the divider, then the divider.
  const bool split = dividerShown(settings);
  const int divider = std::clamp(static_cast<int>(std::lround(settings.splitPosition * static_cast<float>(width))), 0, width);
  if (split) {
    glEnable(GL_SCISSOR_TEST);
    glScissor(divider, 0, width - divider, height);
    drawScene(order, camera, settings, TangentSet::compare, stats);
    glScissor(0, 0, divider, height);
  }
  drawScene(order, camera, settings, TangentSet::file, stats);
  if (settings.glyphs) {
    drawGlyphs(camera, settings);  // the file's frames, left of the divider in the split view
    ++stats.drawCalls;
  }
  if (split) {
    glScissor(std::max(divider - 1, 0), 0, 2, height);
    glClearColor(0.85f, 0.85f, 0.85f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glClearColor(0.16f, 0.17f, 0.19f, 1.0f);
    glDisable(GL_SCISSOR_TEST);
  }
  glBindVertexArray(0);
  return stats;
}

void Renderer::drawInstances(std::span<const GpuInstance* const> instances, const CameraMatrices& camera, const RenderSettings& settings,
                             TangentSet tangents, FrameStats& stats) {
  BoundMesh bound;
  for (const GpuInstance* instance : instances) {
    const GpuMesh& mesh = meshes_[instance->mesh];
    if (bound.mesh != instance->mesh) {
      const GLuint program = bindMesh(mesh, camera, settings, tangents);
      applyCulling(mesh, settings);
      bound = BoundMesh{instance->mesh, glGetUniformLocation(program, "u_model"), glGetUniformLocation(program, "u_normalMatrix"),
                        glGetUniformLocation(program, "u_mirror"), -1};
    }
    drawInstance(*instance, bound);
    ++stats.drawCalls;
    stats.triangles += static_cast<std::size_t>(mesh.count / 3);
  }
}

void Renderer::drawInstance(const GpuInstance& instance, BoundMesh& bound) {
  if (bound.mirrored != int(instance.mirrored)) {
    frontFace(instance.mirrored);
    glUniform1f(bound.mirror, instance.mirrored ? -1.0f : 1.0f);
    bound.mirrored = instance.mirrored;
  }
  glUniformMatrix4fv(bound.model, 1, GL_FALSE, glm::value_ptr(instance.model));
  const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(instance.model)));
  glUniformMatrix3fv(bound.normalMatrix, 1, GL_FALSE, glm::value_ptr(normalMatrix));
  drawMesh(meshes_[instance.mesh]);
}

namespace {

// The material's factors (those its maps scale) and the specular-map mode's settings.
void setMaterialUniforms(GLuint program, const gltf::MaterialDesc& material, const RenderSettings& settings) {
  setUniform(program, "u_baseColorFactor", glm::make_vec4(material.baseColor.data()));
  setUniform(program, "u_emissiveFactor", glm::make_vec3(material.emissive.data()));
  setUniform(program, "u_roughness", material.roughness);
  setUniform(program, "u_metallic", material.metallic);
  setUniform(program, "u_normalScale", material.normalTexture.scale);
  setUniform(program, "u_occlusionStrength", material.occlusionTexture.scale);
  setUniform(program, "u_specularColorFactor", material.hasSpecular ? glm::make_vec3(material.specularColor.data()) : glm::vec3(1));
  setUniform(program, "u_specularStrength", material.hasSpecular ? material.specularFactor : 1.0f);
  setUniform(program, "u_shininess", material.hasSpecular ? settings.shininess : 0.0f);  // 0: derive from roughness
  setUniform(program, "u_reflectivity", settings.reflectivity);
}

// Each light's position or direction, colours (photometric: colour x intensity, lux or
// candela, and range), attenuation and spot cone.
void setLightUniforms(GLuint program, const std::vector<Light>& lights, bool physical) {
  const int lightCount = static_cast<int>(lights.size());  // at most kMaxLights (lightsFrom)
  for (int i = 0; i < lightCount; ++i) {
    const Light& light = lights[i];
    const std::string index = "[" + std::to_string(i) + "]";
    setUniform(program, ("u_lightPosition" + index).c_str(),
               light.directional ? glm::vec4(glm::normalize(light.direction), 0) : glm::vec4(light.position, 1));
    if (physical) {
      // Illuminance (lux) or intensity (candela) times colour; ambient radiance a share of it.
      setUniform(program, ("u_lightDiffuse" + index).c_str(), light.color * light.intensity);
      setUniform(program, ("u_lightAmbient" + index).c_str(), light.color * (light.intensity * kAmbientShare / glm::pi<float>()));
      setUniform(program, ("u_lightRange" + index).c_str(), light.range);
    } else {
      setUniform(program, ("u_lightAmbient" + index).c_str(), light.ambient);
      setUniform(program, ("u_lightDiffuse" + index).c_str(), light.diffuse);
    }
    setUniform(program, ("u_lightSpecular" + index).c_str(), light.specular);
    setUniform(program, ("u_lightAttenuation" + index).c_str(), light.attenuation);
    setUniform(program, ("u_lightSpotDirection" + index).c_str(), light.direction);
    glUniform2f(glGetUniformLocation(program, ("u_lightSpotCos" + index).c_str()),
                light.spotInner >= 0 ? std::cos(light.spotInner) : 0.0f, light.spotOuter >= 0 ? std::cos(light.spotOuter) : -2.0f);
  }
}

// Texture units handed out in order to one program's samplers.
class TextureUnits {
 public:
  explicit TextureUnits(GLuint program) : program_(program) {}
  // `sampler` 0: the texture's own parameters (the viewer's maps); a file's textures sample
  // through their glTF sampler.
  void bind(const char* name, GLenum target, GLuint texture, GLuint sampler = 0) {
    glActiveTexture(GL_TEXTURE0 + unit_);
    glBindTexture(target, texture);
    glBindSampler(static_cast<GLuint>(unit_), sampler);
    setUniform(program_, name, unit_);
    ++unit_;
  }

 private:
  GLuint program_;
  int unit_ = 0;
};

// What every mesh's program reads of the camera and the settings, and the material's blending.
void setPassUniforms(GLuint program, const CameraMatrices& camera, const RenderSettings& settings, TangentSet tangents,
                     const gltf::MaterialDesc& material, const glm::mat4& lightViewProjection, float exposure) {
  setUniform(program, "u_viewProjection", camera.projection * camera.view);
  setUniform(program, "u_view", camera.view);
  setUniform(program, "u_lightViewProjection", lightViewProjection);
  setUniform(program, "u_eyeWorld", camera.eye);
  setUniform(program, "u_uvScale", settings.uvScale);
  setUniform(program, "u_useNormalMap", settings.normalMapping ? 1 : 0);
  setUniform(program, "u_useSpecular", settings.specular ? 1 : 0);
  setUniform(program, "u_flipGreen", settings.flipGreen ? 1 : 0);
  setUniform(program, "u_compareSide", tangents == TangentSet::compare ? 1 : 0);
  setUniform(program, "u_specularModel", settings.shading == Shading::phong ? 1 : 0);
  setUniform(program, "u_blend", material.alphaMode == gltf::MaterialDesc::AlphaMode::blend ? 1 : 0);
  setUniform(program, "u_alphaCutoff", material.alphaCutoff);
  setUniform(program, "u_exposure", exposure);
}

// The material's maps that the program's features read, each with its UV set and transform,
// and the clearcoat and anisotropy factors. `mapOf`: a texture reference's texture and sampler.
template <class MapOf>
void bindMaterialMaps(TextureUnits& units, GLuint program, FeatureSet features, const gltf::MaterialDesc& material, MapOf mapOf) {
  auto bindMap = [&](const char* prefix, const gltf::TextureRef& ref) {
    const auto [texture, sampler] = mapOf(ref);
    units.bind((std::string("u_") + prefix + "Map").c_str(), GL_TEXTURE_2D, texture, sampler);
    setUvUniforms(program, std::string("u_") + prefix, ref);
  };
  if (has(features, Feature::baseColorMap)) bindMap("baseColor", material.baseColorTexture);
  if (has(features, Feature::normalMap)) {
    const auto [texture, sampler] = mapOf(material.normalTexture);
    units.bind("u_normalMap", GL_TEXTURE_2D, texture, sampler);
  }
  if (has(features, Feature::specularMap)) bindMap("specular", material.specularTexture);
  if (has(features, Feature::specularColorMap)) bindMap("specularColor", material.specularColorTexture);
  if (has(features, Feature::metallicRoughnessMap)) bindMap("metallicRoughness", material.metallicRoughnessTexture);
  if (has(features, Feature::emissiveMap)) bindMap("emissive", material.emissiveTexture);
  if (has(features, Feature::occlusionMap)) bindMap("occlusion", material.occlusionTexture);
  if (has(features, Feature::clearcoat)) {
    setUniform(program, "u_clearcoat", material.clearcoat);
    setUniform(program, "u_clearcoatRoughness", material.clearcoatRoughness);
    setUniform(program, "u_clearcoatNormalScale", material.clearcoatNormalTexture.scale);
  }
  if (has(features, Feature::clearcoatMap)) bindMap("clearcoat", material.clearcoatTexture);
  if (has(features, Feature::clearcoatRoughnessMap)) bindMap("clearcoatRoughness", material.clearcoatRoughnessTexture);
  if (has(features, Feature::clearcoatNormalMap)) bindMap("clearcoatNormal", material.clearcoatNormalTexture);
  if (has(features, Feature::anisotropy))
    setUniform(program, "u_anisotropy",
               glm::vec3(std::cos(material.anisotropyRotation), std::sin(material.anisotropyRotation), material.anisotropyStrength));
  if (has(features, Feature::anisotropyMap)) bindMap("anisotropy", material.anisotropyTexture);
}

// Image-based lighting: the prefiltered specular cube, the BRDF table, the irradiance as
// spherical harmonics, and the environment's share of the light.
void bindEnvironment(TextureUnits& units, GLuint program, const EnvironmentTextures& environment, const RenderSettings& settings) {
  units.bind("u_environmentMap", GL_TEXTURE_CUBE_MAP, environment.specularCube.get());
  units.bind("u_brdfLut", GL_TEXTURE_2D, environment.brdfLut.get());
  setUniform(program, "u_environmentMaxLod", environment.maxLod);
  setUniform(program, "u_environmentScale", settings.iblIntensity * kEnvironmentShare / kAmbientShare);
  glUniform3fv(glGetUniformLocation(program, "u_irradianceSh"), 9, &environment.irradianceSh[0].x);
}

}  // namespace

// The program for the mesh's features, its uniforms and textures, and its vertex array.
GLuint Renderer::bindMesh(const GpuMesh& mesh, const CameraMatrices& camera, const RenderSettings& settings, TangentSet tangents) {
  gltf::MaterialDesc material;  // without one, glTF's default material (metallic 1, roughness 1, white; glTF 2.0 3.9.1)
  if (const gltf::MaterialDesc* own = materialOf(scene_, mesh.material)) material = *own;
  const FeatureSet features = featuresFor(mesh, settings);
  const int lightCount = static_cast<int>(lights_.size());  // at most kMaxLights (lightsFrom)
  const GLuint program = shaders_.mesh(features, settings.view, settings.toneMapping, lightCount);
  glUseProgram(program);
  setPassUniforms(program, camera, settings, tangents, material,
                  has(features, Feature::shadows) ? lightViewProjection() : glm::mat4(1), exposure(settings));
  setMaterialUniforms(program, material, settings);
  setLightUniforms(program, lights_, has(features, Feature::physicalLights));

  TextureUnits units(program);
  bindMaterialMaps(units, program, features, material,
                   [&](const gltf::TextureRef& ref) { return std::pair<GLuint, GLuint>(textureOf(ref), samplers_.get(ref.sampler)); });
  if (has(features, Feature::reflection)) units.bind("u_sphereMap", GL_TEXTURE_2D, sphereMap_.get());
  if (has(features, Feature::ibl) && environment_) bindEnvironment(units, program, *environment_, settings);
  if (has(features, Feature::pointShadows)) {
    units.bind("u_shadowCube", GL_TEXTURE_CUBE_MAP, shadowCube_.get());
    const glm::vec2 range = shadowCubeDepthRange();
    setUniform(program, "u_shadowCubeDepth", glm::vec3(range, 4 * boundsRadius()));  // biases: fractions of the 2D map's depth range
  } else if (has(features, Feature::shadows)) {
    units.bind("u_shadowMap", GL_TEXTURE_2D, shadowTexture_.get());
  }
  if (has(features, Feature::shadows)) {
    setUniform(program, "u_pcfRadius", settings.pcfRadius);
    setUniform(program, "u_shadowBiasConstant", settings.shadowBiasConstant * shadowBiasScale());
    setUniform(program, "u_shadowBiasSlope", settings.shadowBiasSlope * shadowBiasScale());
    setUniform(program, "u_shadowTexelWorld", shadowTexelWorld());
  }
  glBindVertexArray(mesh.vertexArray.get());
  return program;
}

}  // namespace tangent::viewer
