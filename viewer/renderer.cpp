// SPDX-License-Identifier: MIT
#include "renderer.hpp"

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
namespace {

// Enables and points every attribute of a layout at the bound GL_ARRAY_BUFFER of packed floats.
void setVertexLayout(std::span<const VertexAttribute> layout) {
  const auto stride = static_cast<GLsizei>(floatsPerVertex(layout) * sizeof(float));
  for (const VertexAttribute& attribute : layout) {
    glEnableVertexAttribArray(attribute.location);
    glVertexAttribPointer(attribute.location, attribute.components, GL_FLOAT, GL_FALSE, stride,
                          reinterpret_cast<const void*>(static_cast<std::uintptr_t>(attribute.offset * sizeof(float))));
  }
}

// A draw item's corners packed as kMeshVertexLayout says; positions, normals and tangents from
// `frame` (the item's own, or deformed ones).
std::vector<float> packMeshVertices(const gltf::DrawItem& item, const CornerFrames& frame) {
  const std::size_t corners = item.positions.size() / 3;
  std::vector<float> data(corners * kMeshFloatsPerVertex);
  for (const VertexAttribute& attribute : kMeshVertexLayout) {
    for (std::size_t c = 0; c < corners; ++c) {
      float* out = &data[c * kMeshFloatsPerVertex + attribute.offset];
      const auto n = static_cast<std::size_t>(attribute.components);
      switch (attribute.source) {
        case VertexSource::position: std::copy_n(&frame.positions[n * c], n, out); break;
        case VertexSource::normal: std::copy_n(&frame.normals[n * c], n, out); break;
        case VertexSource::tangent: std::copy_n(&frame.tangents[n * c], n, out); break;
        case VertexSource::uvNormal: std::copy_n(&item.uvNormal[n * c], n, out); break;
        case VertexSource::uv0: std::copy_n(&item.uvSets[0][n * c], n, out); break;
        case VertexSource::uv1: std::copy_n(&item.uvSets[1][n * c], n, out); break;
        case VertexSource::tangentError: *out = frame.tangentErrorDegrees[c]; break;
        case VertexSource::cornerProblems: *out = static_cast<float>(item.cornerProblems[c]); break;
        case VertexSource::compareTangent: std::copy_n(&frame.compareTangents[n * c], n, out); break;
        case VertexSource::color:
          if (item.colors.empty()) std::fill_n(out, n, 1.0f);
          else std::copy_n(&item.colors[n * c], n, out);
          break;
      }
    }
  }
  return data;
}

void setUniform(GLuint program, const char* name, const glm::mat4& m) {
  glUniformMatrix4fv(glGetUniformLocation(program, name), 1, GL_FALSE, glm::value_ptr(m));
}
void setUniform(GLuint program, const char* name, const glm::mat3& m) {
  glUniformMatrix3fv(glGetUniformLocation(program, name), 1, GL_FALSE, glm::value_ptr(m));
}
void setUniform(GLuint program, const char* name, const glm::vec2& v) { glUniform2fv(glGetUniformLocation(program, name), 1, glm::value_ptr(v)); }
void setUniform(GLuint program, const char* name, const glm::vec3& v) { glUniform3fv(glGetUniformLocation(program, name), 1, glm::value_ptr(v)); }
void setUniform(GLuint program, const char* name, const glm::vec4& v) { glUniform4fv(glGetUniformLocation(program, name), 1, glm::value_ptr(v)); }
void setUniform(GLuint program, const char* name, float v) { glUniform1f(glGetUniformLocation(program, name), v); }
void setUniform(GLuint program, const char* name, int v) { glUniform1i(glGetUniformLocation(program, name), v); }

// A texture's UV set and KHR_texture_transform, for textureUv() in mesh.frag.
void setUvUniforms(GLuint program, const std::string& prefix, const gltf::TextureRef& ref) {
  const auto& t = ref.uvTransform;
  setUniform(program, (prefix + "UvSet").c_str(), ref.texCoord == 1 ? 1 : 0);
  setUniform(program, (prefix + "UvTransform").c_str(), glm::mat3(t[0], t[1], 0, t[2], t[3], 0, t[4], t[5], 1));
}

// Every texture a material may sample.
std::array<const gltf::TextureRef*, 11> textureRefs(const gltf::MaterialDesc& m) {
  return {&m.baseColorTexture,  &m.normalTexture,          &m.emissiveTexture,           &m.metallicRoughnessTexture,
          &m.occlusionTexture,  &m.specularTexture,        &m.specularColorTexture,      &m.clearcoatTexture,
          &m.clearcoatRoughnessTexture, &m.clearcoatNormalTexture, &m.anisotropyTexture};
}

float maxChannel(const glm::vec3& c) { return std::max({c.r, c.g, c.b}); }

// Light `light`'s direction from `point` and its attenuation there (distance and cone), as
// lighting.glsl's lightAt has them in the light's units.
float attenuationAt(const Light& light, const glm::vec3& point, bool physical, glm::vec3& toLight) {
  if (light.directional) {
    toLight = -glm::normalize(light.direction);
    return 1;
  }
  const glm::vec3 offset = light.position - point;
  const float d = std::max(glm::length(offset), 1e-6f);
  toLight = offset / d;
  const float c = glm::dot(-toLight, glm::normalize(light.direction));
  float attenuation = 1;
  if (physical) {
    attenuation = 1 / std::max(d * d, 1e-8f);
    if (light.range > 0) attenuation *= std::clamp(1 - std::pow(d / light.range, 4.0f), 0.0f, 1.0f);
    if (light.spotOuter >= 0) {
      const float cone = std::clamp((c - std::cos(light.spotOuter)) / std::max(std::cos(light.spotInner) - std::cos(light.spotOuter), 1e-3f), 0.0f, 1.0f);
      attenuation *= cone * cone;
    }
  } else {
    attenuation = 1 / std::max(light.attenuation.x + light.attenuation.y * d + light.attenuation.z * d * d, 1e-6f);
    if (light.spotOuter >= 0) attenuation *= glm::smoothstep(std::cos(light.spotOuter), std::cos(light.spotInner), c);
  }
  return attenuation;
}

// Where a light is judged from: the scene's centre, or, for a point or spot light inside the
// scene, a tenth of the scene's radius from the light towards the centre.
glm::vec3 pointLitFrom(const Light& light, glm::vec3 center, float radius) {
  if (light.directional || glm::length(light.position - center) >= 0.1f * radius) return center;
  return light.position - glm::normalize(light.position - center + glm::vec3(0, 1e-6f, 0)) * (0.1f * radius);
}

// The illuminance (lux) a light of the file gives at the scene's centre, judged from where
// pointLitFrom says; 0 where that is not a positive number (inf intensity times black is NaN).
float illuminanceAtCenter(const Light& light, glm::vec3 center, float radius) {
  glm::vec3 toLight;
  const float e = maxChannel(light.color) * light.intensity * attenuationAt(light, pointLitFrom(light, center, radius), true, toLight);
  return e > 0 ? e : 0;
}

// The file's lights (at most kMaxLights: the one place the count is capped; what is left out
// goes to `messages`), the one that casts the shadow first; the default rig where it has none.
std::vector<Light> lightsFrom(const gltf::Scene& scene, glm::vec3 center, float radius, std::vector<std::string>& messages) {
  std::vector<Light> lights;
  for (const auto& source : scene.lights) {
    Light light;
    const glm::vec3 color(source.color[0], source.color[1], source.color[2]);
    light.directional = source.type == gltf::LightDesc::Type::directional;
    light.position = glm::vec3(source.position[0], source.position[1], source.position[2]);
    light.direction = glm::normalize(glm::vec3(source.direction[0], source.direction[1], source.direction[2]));
    // KHR_lights_punctual intensities (lux, candela) mapped to Blinn-Phong colours.
    light.diffuse = color * (light.directional ? std::min(source.intensity, 4.0f) : 1.0f);
    light.specular = light.diffuse;
    light.ambient = light.diffuse * kAmbientShare;
    light.physical = true;
    light.color = color;
    light.intensity = source.intensity;
    light.range = source.range;
    if (!light.directional) light.attenuation = glm::vec3(1.0f, 0.0f, 1.0f / std::max(source.intensity, 1e-3f));
    if (source.type == gltf::LightDesc::Type::spot) {
      light.spotInner = source.innerConeAngle;
      light.spotOuter = source.outerConeAngle;
    }
    lights.push_back(light);
  }
  // More lights than a program shades with: the kMaxLights brightest at the centre are kept, in
  // the file's order, and the panel says which were left out (by their index in the file).
  if (lights.size() > static_cast<std::size_t>(kMaxLights)) {
    std::vector<float> illuminance;
    for (const Light& light : lights) illuminance.push_back(illuminanceAtCenter(light, center, radius));
    std::vector<std::size_t> order(lights.size());
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return illuminance[a] > illuminance[b]; });
    std::vector<std::size_t> left(order.begin() + kMaxLights, order.end());
    order.resize(kMaxLights);
    std::sort(order.begin(), order.end());
    std::sort(left.begin(), left.end(), [&](std::size_t a, std::size_t b) {
      return std::pair(scene.lights[a].definition, scene.lights[a].node) < std::pair(scene.lights[b].definition, scene.lights[b].node);
    });
    std::string named;
    for (std::size_t i : left) {
      const gltf::LightDesc& source = scene.lights[i];
      named += (named.empty() ? "" : ", ") + std::to_string(source.definition) + (source.name.empty() ? "" : " '" + text::quoted(source.name) + "'") +
               " (node " + std::to_string(source.node) + ")";
    }
    std::vector<Light> kept;
    for (std::size_t i : order) kept.push_back(lights[i]);
    messages.push_back(std::to_string(lights.size()) + " punctual lights in the scene: the viewer shades with the " + std::to_string(kMaxLights) +
                       " brightest at its centre; left out: light " + named);
    lights = std::move(kept);
  }
  // Light 0 casts the shadow: the first directional light, when there is one; else the point
  // or spot light that gives the scene's centre the most illuminance.
  std::stable_partition(lights.begin(), lights.end(), [](const Light& light) { return light.directional; });
  if (!lights.empty() && !lights[0].directional) {
    const auto strongest = std::max_element(lights.begin(), lights.end(), [&](const Light& a, const Light& b) {
      return illuminanceAtCenter(a, center, radius) < illuminanceAtCenter(b, center, radius);
    });
    std::rotate(lights.begin(), strongest, strongest + 1);
  }
  if (!lights.empty()) return lights;
  // Default rig: a key light that casts the shadow and a cool fill, both directional. The
  // environment (image-based lighting in pbr, else the ambient sky) lights what they miss; a back
  // and a spot light were two more loop trips per fragment, a third of llvmpipe's lit frame.
  Light key;
  key.direction = glm::normalize(glm::vec3(-0.35f, -1.0f, -0.45f));
  key.diffuse = glm::vec3(0.85f);
  key.ambient = glm::vec3(2 * kAmbientShare);
  Light fill;
  fill.direction = glm::normalize(glm::vec3(0.8f, -0.2f, -0.4f));
  fill.diffuse = glm::vec3(0.22f, 0.24f, 0.3f);
  fill.specular = glm::vec3(0.1f);
  fill.ambient = glm::vec3(0);
  return {key, fill};
}

// BLEND materials cast shadows cut out where their alpha is below this, as MASK materials do
// at their alphaCutoff: a half-transparent surface casts where it is mostly opaque.
constexpr float kBlendShadowCutoff = 0.5f;

// A node whose transform mirrors (negative determinant) turns its triangles' winding around, so
// its front faces are the clockwise ones (glTF 2.0 3.7.4).
void frontFace(bool mirrored) { glFrontFace(mirrored ? GL_CW : GL_CCW); }

const gltf::MaterialDesc* materialOf(const gltf::Scene& scene, int material) {
  return material >= 0 && material < static_cast<int>(scene.materials.size()) ? &scene.materials[material] : nullptr;
}

}  // namespace

void Renderer::setScene(gltf::Scene scene, std::vector<std::string>& messages) {
  scene_ = std::move(scene);
  meshes_.clear();
  instances_.clear();
  deformed_.clear();
  compareTangents_.clear();
  textures_.clear();
  srgbTextures_.clear();
  samplers_.clear();
  glyphsBuiltFor_ = -1;
  ++sceneVersion_;
  shadowPasses_ = 0;
  // Each image is uploaded as the materials use it: sRGB where it holds colour, linear where
  // it holds data; both when used both ways.
  const std::size_t imageCount = scene_.images.size();
  std::vector<bool> usedAsColour(imageCount), usedAsData(imageCount);
  for (const auto& material : scene_.materials) {
    for (const gltf::TextureRef* ref : textureRefs(material)) {
      if (ref->image < 0 || ref->image >= static_cast<int>(imageCount)) continue;
      (ref->colour ? usedAsColour : usedAsData)[ref->image] = true;
      if (ref->texCoord > 1)
        messages.push_back("material '" + text::quoted(material.name) + "': texCoord " + std::to_string(ref->texCoord) +
                           " shown with TEXCOORD_0 (the viewer reads sets 0 and 1)");
    }
  }
  textures_.resize(imageCount);
  srgbTextures_.resize(imageCount);
  const int maxSize = maxTextureSize();
  for (std::size_t i = 0; i < imageCount; ++i) {
    if (!usedAsColour[i] && !usedAsData[i]) continue;
    DecodedImage image;
    std::string error;
    const bool decoded = decodeImage(scene_.images[i], image, error);
    messages.insert(messages.end(), image.notes.begin(), image.notes.end());
    if (!decoded) {
      // Colour textures show a checker instead, so that the gap is seen; data textures are left out.
      messages.push_back(error + (usedAsColour[i] ? "; drawn as a magenta checker" : "; left out"));
      if (usedAsColour[i]) srgbTextures_[i] = uploadTexture(missingImageChecker(), true);
      continue;
    }
    if (std::string note = fitTextureSize(image, maxSize, scene_.images[i].label); !note.empty()) messages.push_back(std::move(note));
    if (usedAsColour[i]) srgbTextures_[i] = uploadTexture(image, true);
    if (usedAsData[i]) textures_[i] = uploadTexture(image, false);
  }
  auto upload = [&](const gltf::DrawItem& item, GLenum usage) {
    GpuMesh mesh;
    mesh.material = item.material;
    mesh.hasColors = !item.colors.empty();
    const std::vector<float> data = packMeshVertices(item, itemFrames(item, compareTangentsOf(static_cast<std::size_t>(&item - scene_.items.data()))));
    mesh.vertexArray = makeVertexArray();
    mesh.vertices = makeBuffer();
    if (usage == GL_STATIC_DRAW) mesh.indices = makeBuffer();
    glBindVertexArray(mesh.vertexArray.get());
    glBindBuffer(GL_ARRAY_BUFFER, mesh.vertices.get());
    setVertexLayout(kMeshVertexLayout);
    fillMeshBuffers(mesh, data);
    meshes_.push_back(std::move(mesh));
  };
  for (const auto& item : scene_.items) upload(item, GL_STATIC_DRAW);
  instances_.reserve(scene_.instances.size());
  for (std::size_t i = 0; i < scene_.instances.size(); ++i) {
    const gltf::DrawInstance& source = scene_.instances[i];
    GpuInstance instance;
    instance.mesh = source.item;
    const gltf::DrawItem& item = scene_.items[source.item];
    // A morphing or skinned instance gets vertices of its own, deformed on the CPU per pose.
    if (deforms(source)) {
      instance.mesh = static_cast<std::uint32_t>(meshes_.size());
      upload(item, GL_DYNAMIC_DRAW);
      deformed_.push_back({static_cast<std::uint32_t>(i), {}});
    }
    placeInstance(instance, glm::make_mat4(source.world.data()), item);
    instances_.push_back(instance);
  }
  glBindVertexArray(0);
  boundsMin_ = glm::make_vec3(scene_.boundsMin.data());
  boundsMax_ = glm::make_vec3(scene_.boundsMax.data());
  lights_ = lightsFrom(scene_, boundsCenter(), boundsRadius(), messages);
  pose_.reset();
  exposureBoundsMin_ = boundsMin_;  // the rest pose's, once setPose has posed it
  exposureBoundsMax_ = boundsMax_;
  restPoseMeasured_ = false;
}

bool Renderer::deforms(const gltf::DrawInstance& instance) const {
  if (scene_.nodes.empty() || instance.node >= scene_.nodes.size()) return false;
  const gltf::DrawItem& item = scene_.items[instance.item];
  return !item.morphTargets.empty() || (scene_.nodes[instance.node].skin >= 0 && item.influencesPerCorner > 0);
}

void Renderer::placeInstance(GpuInstance& instance, const glm::mat4& model, const gltf::DrawItem& item) {
  instance.model = model;
  instance.mirrored = glm::determinant(glm::mat3(model)) < 0;
  const glm::vec3 centerObject = (glm::make_vec3(item.boundsMin.data()) + glm::make_vec3(item.boundsMax.data())) * 0.5f;
  instance.centerWorld = item.boundsMin[0] <= item.boundsMax[0] ? glm::vec3(model * glm::vec4(centerObject, 1)) : glm::vec3(0);
}

CornerFrames Renderer::framesOf(std::size_t instance) const {
  for (const DeformedInstance& deformed : deformed_)
    if (deformed.instance == instance && !deformed.corners.positions.empty()) {
      const gltf::DrawItem& item = scene_.items[scene_.instances[instance].item];
      return {deformed.corners.positions, deformed.corners.normals, deformed.corners.tangents,
              deformed.tangentErrorDegrees.empty() ? std::span<const float>(item.tangentErrorDegrees) : deformed.tangentErrorDegrees,
              deformed.corners.compareTangents};
    }
  const std::uint32_t item = scene_.instances[instance].item;
  return itemFrames(scene_.items[item], compareTangentsOf(item));
}

bool Renderer::compareIsFresh(std::size_t item) const {
  const gltf::DrawItem& drawItem = scene_.items[item];
  const bool given = item < compareTangents_.size() && compareTangents_[item].size() == drawItem.tangents.size();
  return !given && drawItem.computedTangents.size() == drawItem.tangents.size();
}

std::span<const float> Renderer::compareTangentsOf(std::size_t item) const {
  const gltf::DrawItem& drawItem = scene_.items[item];
  if (item < compareTangents_.size() && compareTangents_[item].size() == drawItem.tangents.size()) return compareTangents_[item];
  if (drawItem.computedTangents.size() == drawItem.tangents.size()) return drawItem.computedTangents;
  return drawItem.tangents;
}

void Renderer::setCompareTangents(std::vector<std::vector<float>> perItem) {
  compareTangents_ = std::move(perItem);
  // Every mesh's vertices again (each deforming instance's own buffer starts from its item's),
  // then the pose again, which deforms the new set along.
  auto upload = [&](std::size_t item, std::size_t mesh) {
    fillMeshBuffers(meshes_[mesh], packMeshVertices(scene_.items[item], itemFrames(scene_.items[item], compareTangentsOf(item))));
  };
  for (std::size_t item = 0; item < scene_.items.size(); ++item) upload(item, item);  // setScene uploads items first
  for (const DeformedInstance& deformed : deformed_) upload(scene_.instances[deformed.instance].item, instances_[deformed.instance].mesh);
  if (const std::optional<PoseTime> pose = pose_) {
    pose_.reset();
    setPose(*pose);
  }
}

void Renderer::uploadDeformed(const DeformedInstance& deformed) {
  fillMeshBuffers(meshes_[instances_[deformed.instance].mesh],
                  packMeshVertices(scene_.items[scene_.instances[deformed.instance].item], framesOf(deformed.instance)));
}

void Renderer::fillMeshBuffers(GpuMesh& mesh, std::span<const float> corners) {
  mesh.count = static_cast<GLsizei>(corners.size() / kMeshFloatsPerVertex);
  glBindVertexArray(mesh.vertexArray.get());  // the element buffer binding is the vertex array's
  glBindBuffer(GL_ARRAY_BUFFER, mesh.vertices.get());
  if (!mesh.indices) {
    // Rewritten at every pose: as many floats each time (GL_DYNAMIC_DRAW).
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(corners.size() * sizeof(float)), corners.data(), GL_DYNAMIC_DRAW);
  } else {
    const WeldedVertices welded = weldVertices(corners, kMeshFloatsPerVertex);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(welded.vertices.size() * sizeof(float)), welded.vertices.data(), GL_STATIC_DRAW);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, mesh.indices.get());
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(welded.indices.size() * sizeof(std::uint32_t)), welded.indices.data(),
                 GL_STATIC_DRAW);
  }
  glBindVertexArray(0);
}

void Renderer::drawMesh(const GpuMesh& mesh) {
  if (mesh.indices) glDrawElements(GL_TRIANGLES, mesh.count, GL_UNSIGNED_INT, nullptr);
  else glDrawArrays(GL_TRIANGLES, 0, mesh.count);
}

bool Renderer::setPose(PoseTime time) {
  if (scene_.nodes.empty() || (pose_ && *pose_ == time)) return false;
  // Auto exposure is judged on the rest pose's bounds whatever the first pose asked for, so that
  // every time of every animation shows the asset at one exposure.
  if (!restPoseMeasured_ && time != PoseTime{}) setPose(PoseTime{});
  pose_ = time;
  const ScenePose pose = poseScene(scene_, time);
  for (std::size_t i = 0; i < scene_.instances.size(); ++i) {
    const gltf::DrawInstance& source = scene_.instances[i];
    if (source.node < pose.world.size()) placeInstance(instances_[i], pose.world[source.node], scene_.items[source.item]);
  }
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  auto grow = [&](const glm::vec3& p) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return;
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  };
  std::vector<char> isDeformed(instances_.size(), 0);
  for (DeformedInstance& deformed : deformed_) {
    const gltf::DrawInstance& source = scene_.instances[deformed.instance];
    const gltf::DrawItem& item = scene_.items[source.item];
    const int skin = scene_.nodes[source.node].skin;
    deformed.joints.clear();
    if (skin >= 0 && item.influencesPerCorner > 0) deformed.joints = jointMatrices(scene_.skins[skin], pose, source.node);
    // A fresh compare set is recomputed on the morphed corners only when a view shows it (render).
    deformItem(item, pose.weights[source.node], deformed.joints, deformed.corners, compareTangentsOf(source.item));
    deformed.compareStale = compareIsFresh(source.item) && morphs(item, pose.weights[source.node]);
    if (deformed.weights != pose.weights[source.node]) {
      deformed.weights = pose.weights[source.node];
      deformed.tangentErrorDegrees.clear();  // the load's until the error view asks (render)
      deformed.errorsCurrent = item.morphTargets.empty();
    }
    uploadDeformed(deformed);
    // Bounds and draw order from the deformed corners.
    const glm::mat4& model = instances_[deformed.instance].model;
    glm::vec3 itemLo(std::numeric_limits<float>::max()), itemHi(-std::numeric_limits<float>::max());
    for (std::size_t c = 0; c < deformed.corners.positions.size() / 3; ++c) {
      const glm::vec3 p = glm::vec3(model * glm::vec4(glm::make_vec3(&deformed.corners.positions[3 * c]), 1));
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) continue;
      itemLo = glm::min(itemLo, p);
      itemHi = glm::max(itemHi, p);
    }
    if (itemLo.x <= itemHi.x) {
      grow(itemLo);
      grow(itemHi);
      instances_[deformed.instance].centerWorld = (itemLo + itemHi) * 0.5f;
    }
    isDeformed[deformed.instance] = 1;
  }
  for (std::size_t i = 0; i < instances_.size(); ++i) {
    if (isDeformed[i]) continue;
    const gltf::DrawItem& item = scene_.items[scene_.instances[i].item];
    if (item.boundsMin[0] > item.boundsMax[0]) continue;
    for (int corner = 0; corner < 8; ++corner)
      grow(glm::vec3(instances_[i].model * glm::vec4(corner & 1 ? item.boundsMax[0] : item.boundsMin[0], corner & 2 ? item.boundsMax[1] : item.boundsMin[1],
                                                     corner & 4 ? item.boundsMax[2] : item.boundsMin[2], 1)));
  }
  if (lo.x <= hi.x) {
    boundsMin_ = lo;
    boundsMax_ = hi;
  }
  ++sceneVersion_;  // the shadow map and the glyphs follow the pose
  glyphsBuiltFor_ = -1;
  if (!restPoseMeasured_ && time == PoseTime{}) {
    exposureBoundsMin_ = boundsMin_;
    exposureBoundsMax_ = boundsMax_;
    restPoseMeasured_ = true;
  }
  return true;
}

bool Renderer::loadSphereMap(const std::filesystem::path& file, std::vector<std::string>& messages) {
  gltf::ImageSource source;
  source.file = file;
  source.label = file.string();
  sphereMap_ = loadTexture(source, true, messages);
  return static_cast<bool>(sphereMap_);
}

GLuint Renderer::textureOf(const gltf::TextureRef& ref) const {
  const auto& textures = ref.colour ? srgbTextures_ : textures_;
  if (ref.image < 0 || ref.image >= static_cast<int>(textures.size())) return 0;
  return textures[ref.image].get();
}

namespace {

// Whether two texture references read the same texels at every fragment: the same image,
// sampler, UV set and transform. Their colour spaces may differ where the channel one of them
// reads is linear in both (an sRGB texture's alpha).
bool sameTexels(const gltf::TextureRef& a, const gltf::TextureRef& b) {
  return a.image == b.image && a.sampler == b.sampler && a.texCoord == b.texCoord && a.uvTransform == b.uvTransform;
}

// The maps mesh.frag reads through textureUv(), each with the feature that has it read.
struct UvMappedMap {
  Feature feature;
  gltf::TextureRef gltf::MaterialDesc::*texture;
};
constexpr std::array<UvMappedMap, 10> kUvMappedMaps{{
    {Feature::baseColorMap, &gltf::MaterialDesc::baseColorTexture},
    {Feature::specularMap, &gltf::MaterialDesc::specularTexture},
    {Feature::specularColorMap, &gltf::MaterialDesc::specularColorTexture},
    {Feature::metallicRoughnessMap, &gltf::MaterialDesc::metallicRoughnessTexture},
    {Feature::emissiveMap, &gltf::MaterialDesc::emissiveTexture},
    {Feature::occlusionMap, &gltf::MaterialDesc::occlusionTexture},
    {Feature::clearcoatMap, &gltf::MaterialDesc::clearcoatTexture},
    {Feature::clearcoatRoughnessMap, &gltf::MaterialDesc::clearcoatRoughnessTexture},
    {Feature::clearcoatNormalMap, &gltf::MaterialDesc::clearcoatNormalTexture},
    {Feature::anisotropyMap, &gltf::MaterialDesc::anisotropyTexture},
}};

}  // namespace

FeatureSet Renderer::featuresFor(const GpuMesh& mesh, const RenderSettings& settings) const {
  FeatureSet features = 0;
  if (shadowsDrawn(settings)) features |= static_cast<FeatureSet>(Feature::shadows);
  if (shadowsDrawn(settings) && pointShadow()) features |= static_cast<FeatureSet>(Feature::pointShadows);
  if (settings.reflectivity > 0 && sphereMap_) features |= static_cast<FeatureSet>(Feature::reflection);
  if (settings.shading == Shading::pbr) features |= static_cast<FeatureSet>(Feature::pbr);
  if (physicalLights(settings)) features |= static_cast<FeatureSet>(Feature::physicalLights);
  if (std::all_of(lights_.begin(), lights_.end(), [](const Light& light) { return light.directional; }))
    features |= static_cast<FeatureSet>(Feature::directionalLights);
  if (settings.ibl && settings.shading == Shading::pbr) features |= static_cast<FeatureSet>(Feature::ibl);
  if (has(features, Feature::shadows) && settings.pcfRadius > 0) features |= static_cast<FeatureSet>(Feature::pcf);
  if (settings.bitangent == BitangentMode::perVertex) features |= static_cast<FeatureSet>(Feature::bitangentPerVertex);
  if (mesh.hasColors) features |= static_cast<FeatureSet>(Feature::vertexColor);
  if (mesh.material < 0 || mesh.material >= static_cast<int>(scene_.materials.size())) return features;
  const auto& material = scene_.materials[mesh.material];
  if (material.unlit) {
    // Unlit: base colour and alpha only.
    features &= ~(kShadowFeatures | static_cast<FeatureSet>(Feature::reflection) | static_cast<FeatureSet>(Feature::physicalLights) |
                  static_cast<FeatureSet>(Feature::ibl));
    features |= static_cast<FeatureSet>(Feature::unlit);
  }
  if (material.alphaMode == gltf::MaterialDesc::AlphaMode::mask) features |= static_cast<FeatureSet>(Feature::alphaMask);
  if (textureOf(material.occlusionTexture)) features |= static_cast<FeatureSet>(Feature::occlusionMap);
  if (textureOf(material.baseColorTexture)) features |= static_cast<FeatureSet>(Feature::baseColorMap);
  if (textureOf(material.normalTexture)) features |= static_cast<FeatureSet>(Feature::normalMap);
  if (textureOf(material.specularTexture)) features |= static_cast<FeatureSet>(Feature::specularMap);
  if (textureOf(material.specularColorTexture)) features |= static_cast<FeatureSet>(Feature::specularColorMap);
  if (textureOf(material.metallicRoughnessTexture)) features |= static_cast<FeatureSet>(Feature::metallicRoughnessMap);
  // One fetch where two maps read the same texels: the specular extension's strength-in-alpha
  // packing, and glTF's occlusion-roughness-metallic packing (occlusion in R).
  if (has(features, Feature::specularMap) && has(features, Feature::specularColorMap) &&
      sameTexels(material.specularTexture, material.specularColorTexture))
    features = (features & ~static_cast<FeatureSet>(Feature::specularMap)) | static_cast<FeatureSet>(Feature::specularInColorMap);
  if (has(features, Feature::occlusionMap) && has(features, Feature::metallicRoughnessMap) &&
      sameTexels(material.occlusionTexture, material.metallicRoughnessTexture))
    features = (features & ~static_cast<FeatureSet>(Feature::occlusionMap)) | static_cast<FeatureSet>(Feature::occlusionInMetallicRoughnessMap);
  if (textureOf(material.emissiveTexture)) features |= static_cast<FeatureSet>(Feature::emissiveMap);
  // The extensions that read the tangent frame, in the PBR mode (and anisotropy in its view).
  if (!material.unlit && settings.shading == Shading::pbr && material.clearcoat > 0) {
    features |= static_cast<FeatureSet>(Feature::clearcoat);
    if (textureOf(material.clearcoatTexture)) features |= static_cast<FeatureSet>(Feature::clearcoatMap);
    if (textureOf(material.clearcoatRoughnessTexture)) features |= static_cast<FeatureSet>(Feature::clearcoatRoughnessMap);
    if (textureOf(material.clearcoatNormalTexture)) features |= static_cast<FeatureSet>(Feature::clearcoatNormalMap);
  }
  if (!material.unlit && material.hasAnisotropy && (settings.shading == Shading::pbr || settings.view == DebugView::anisotropyDirection)) {
    features |= static_cast<FeatureSet>(Feature::anisotropy);
    if (textureOf(material.anisotropyTexture)) features |= static_cast<FeatureSet>(Feature::anisotropyMap);
  }
  // The textures mesh.frag samples through textureUv() (the normal map's UVs come ready).
  const bool anyUvTransform = std::any_of(kUvMappedMaps.begin(), kUvMappedMaps.end(), [&](const UvMappedMap& map) {
    const gltf::TextureRef& ref = material.*map.texture;
    return has(features, map.feature) && (ref.texCoord != 0 || ref.uvTransform != gltf::TextureRef{}.uvTransform);
  });
  if (anyUvTransform) features |= static_cast<FeatureSet>(Feature::uvTransforms);
  return features;
}

bool Renderer::shadowsDrawn(const RenderSettings& settings) const {
  return settings.shadows && !instances_.empty() && !lights_.empty() && settings.view == DebugView::lit;
}

bool Renderer::physicalLights(const RenderSettings& settings) const {
  return settings.shading == Shading::pbr && !lights_.empty() && lights_[0].physical;
}

float Renderer::exposure(const RenderSettings& settings) const {
  if (settings.exposure > 0) return settings.exposure;
  const float white = whiteRadiance(settings);
  return white > 0 ? kAutoExposureWhite / white : 1.0f;
}

float Renderer::whiteRadiance(const RenderSettings& settings) const {
  if (lights_.empty()) return 0;
  const bool physical = physicalLights(settings);
  // At the centre of the rest pose's bounds (not the current pose's: the exposure holds still
  // through an animation); a light inside the scene at a tenth of the scene's radius from it.
  const glm::vec3 center = (exposureBoundsMin_ + exposureBoundsMax_) * 0.5f;
  const float radius = glm::max(glm::length(exposureBoundsMax_ - exposureBoundsMin_) * 0.5f, 1e-3f);
  struct Arrival {
    glm::vec3 toLight;
    float direct;   // radiance of a white Lambertian surface facing the light
    float ambient;  // the light's ambient radiance there
  };
  std::vector<Arrival> arrivals;
  for (const Light& light : lights_) {
    const glm::vec3 point = pointLitFrom(light, center, radius);
    Arrival arrival{};
    const float attenuation = attenuationAt(light, point, physical, arrival.toLight);
    if (physical) {
      // Illuminance over pi; ambient as bindMesh sets it.
      arrival.direct = maxChannel(light.color) * light.intensity * attenuation / glm::pi<float>();
      arrival.ambient = maxChannel(light.color) * light.intensity * kAmbientShare / glm::pi<float>() * attenuation;
    } else {
      arrival.direct = maxChannel(light.diffuse) * attenuation;
      arrival.ambient = maxChannel(light.ambient) * attenuation;
    }
    arrivals.push_back(arrival);
  }
  const Arrival& brightest = *std::max_element(arrivals.begin(), arrivals.end(), [](const Arrival& a, const Arrival& b) { return a.direct < b.direct; });
  const glm::vec3 n = brightest.toLight;
  float direct = 0, ambient = 0;
  for (const Arrival& arrival : arrivals) {
    direct += arrival.direct * std::max(glm::dot(n, arrival.toLight), 0.0f);
    ambient += arrival.ambient;
  }
  // The ambient or environment term as mesh.frag shades it for a white diffuse surface.
  if (settings.shading != Shading::pbr) return direct + ambient;
  if (!settings.ibl) return direct + ambient * (0.2f + 0.8f * (n.y + 1));
  const float environment = environment_ ? maxChannel(irradianceOverPi(environment_->irradianceSh, n)) : 1.0f;
  return direct + ambient * settings.iblIntensity * (kEnvironmentShare / kAmbientShare) * environment;
}

FeatureSet Renderer::alphaTestFeatures(const GpuMesh& mesh, bool blendCasts) const {
  const gltf::MaterialDesc* material = materialOf(scene_, mesh.material);
  if (!material) return 0;
  const bool tested = material->alphaMode == gltf::MaterialDesc::AlphaMode::mask ||
                      (blendCasts && material->alphaMode == gltf::MaterialDesc::AlphaMode::blend);
  if (!tested) return 0;
  FeatureSet features = static_cast<FeatureSet>(Feature::alphaMask);
  if (textureOf(material->baseColorTexture)) features |= static_cast<FeatureSet>(Feature::baseColorMap);
  return features;
}

// Culling as glTF defines it for a mesh: back faces are culled unless the material is
// doubleSided. Which faces are front is the instance's (frontFace).
void Renderer::applyCulling(const GpuMesh& mesh, const RenderSettings& settings) const {
  const gltf::MaterialDesc* material = materialOf(scene_, mesh.material);
  if ((material && material->doubleSided) || settings.view == DebugView::faceOrientation) glDisable(GL_CULL_FACE);
  else glEnable(GL_CULL_FACE), glCullFace(GL_BACK);
}

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

FrameStats Renderer::render(const CameraMatrices& camera, const RenderSettings& settings, int width, int height) {
  FrameStats stats;
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
  if (shadowsDrawn(settings)) {
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
  glViewport(0, 0, width, height);
  glClearColor(0.16f, 0.17f, 0.19f, 1.0f);

  // Opaque and masked meshes front to back (less overdraw): the mesh with the nearest instance
  // first, its instances front to back, so that each mesh's state is set once. Then blended
  // instances back to front over them, one by one (the order matters), as the Khronos glTF
  // Sample Viewer draws them: sorted by the view-space depth of their centre, with depth test
  // and depth writes on, so that a closed blended mesh hides its own far side.
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
  std::vector<const GpuInstance*> opaque, transparent;
  opaque.reserve(opaqueOrder.size());
  for (const Ordered& entry : opaqueOrder) opaque.push_back(entry.instance);
  for (const Ordered& entry : transparentOrder) transparent.push_back(entry.instance);
  stats.exposure = exposure(settings);
  const bool prePass = settings.depthPrePass && settings.view == DebugView::lit && !opaque.empty();
  // The whole scene with one tangent set, into the framebuffer's scissor box (when enabled).
  auto drawScene = [&](TangentSet tangents) {
    glDepthMask(GL_TRUE);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    if (prePass) {
      // Depth of the opaque and masked meshes first, so that the shading pass below runs the
      // fragment shader once per pixel; same culling, same invariant positions, GL_LEQUAL.
      glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
      drawDepth(opaque, camera.projection * camera.view, settings, false, true);
      stats.drawCalls += static_cast<int>(opaque.size());
      glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
      glDepthFunc(GL_LEQUAL);
      glDepthMask(GL_FALSE);
    }
    drawInstances(opaque, camera, settings, tangents, stats);
    if (prePass) {
      glDepthFunc(GL_LESS);
      glDepthMask(GL_TRUE);
    }
    if (!transparent.empty()) {
      glEnable(GL_BLEND);
      glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
      drawInstances(transparent, camera, settings, tangents, stats);
      glDisable(GL_BLEND);
    }
    glFrontFace(GL_CCW);
    glDisable(GL_CULL_FACE);
  };
  // Split view: the same scene twice, each into its side of the divider, then the divider.
  const bool split = dividerShown(settings);
  const int divider = std::clamp(static_cast<int>(std::lround(settings.splitPosition * static_cast<float>(width))), 0, width);
  if (split) {
    glEnable(GL_SCISSOR_TEST);
    glScissor(divider, 0, width - divider, height);
    drawScene(TangentSet::compare);
    glScissor(0, 0, divider, height);
  }
  drawScene(TangentSet::file);
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

GLuint Renderer::bindMesh(const GpuMesh& mesh, const CameraMatrices& camera, const RenderSettings& settings, TangentSet tangents) {
  gltf::MaterialDesc material;  // without one, glTF's default material (metallic 1, roughness 1, white; glTF 2.0 3.9.1)
  if (const gltf::MaterialDesc* own = materialOf(scene_, mesh.material)) material = *own;
  const FeatureSet features = featuresFor(mesh, settings);
  const int lightCount = static_cast<int>(lights_.size());  // at most kMaxLights (lightsFrom)
  const GLuint program = shaders_.mesh(features, settings.view, settings.toneMapping, lightCount);
  glUseProgram(program);
  setUniform(program, "u_viewProjection", camera.projection * camera.view);
  setUniform(program, "u_view", camera.view);
  setUniform(program, "u_lightViewProjection", has(features, Feature::shadows) ? lightViewProjection() : glm::mat4(1));
  setUniform(program, "u_eyeWorld", camera.eye);
  setUniform(program, "u_uvScale", settings.uvScale);
  setUniform(program, "u_useNormalMap", settings.normalMapping ? 1 : 0);
  setUniform(program, "u_useSpecular", settings.specular ? 1 : 0);
  setUniform(program, "u_flipGreen", settings.flipGreen ? 1 : 0);
  setUniform(program, "u_compareSide", tangents == TangentSet::compare ? 1 : 0);
  setUniform(program, "u_specularModel", settings.shading == Shading::phong ? 1 : 0);
  setUniform(program, "u_blend", material.alphaMode == gltf::MaterialDesc::AlphaMode::blend ? 1 : 0);
  setUniform(program, "u_alphaCutoff", material.alphaCutoff);
  setUniform(program, "u_exposure", exposure(settings));

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

  for (int i = 0; i < lightCount; ++i) {
    const Light& light = lights_[i];
    const std::string index = "[" + std::to_string(i) + "]";
    setUniform(program, ("u_lightPosition" + index).c_str(),
               light.directional ? glm::vec4(glm::normalize(light.direction), 0) : glm::vec4(light.position, 1));
    if (has(features, Feature::physicalLights)) {
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

  int unit = 0;
  // `sampler` 0: the texture's own parameters (the viewer's maps); a file's textures sample
  // through their glTF sampler.
  auto bind = [&](const char* name, GLuint texture, GLuint sampler = 0) {
    glActiveTexture(GL_TEXTURE0 + unit);
    glBindTexture(GL_TEXTURE_2D, texture);
    glBindSampler(static_cast<GLuint>(unit), sampler);
    setUniform(program, name, unit);
    ++unit;
  };
  auto bindMap = [&](const char* prefix, const gltf::TextureRef& ref) {
    bind((std::string("u_") + prefix + "Map").c_str(), textureOf(ref), samplers_.get(ref.sampler));
    setUvUniforms(program, std::string("u_") + prefix, ref);
  };
  if (has(features, Feature::baseColorMap)) bindMap("baseColor", material.baseColorTexture);
  if (has(features, Feature::normalMap)) bind("u_normalMap", textureOf(material.normalTexture), samplers_.get(material.normalTexture.sampler));
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
  if (has(features, Feature::reflection)) bind("u_sphereMap", sphereMap_.get());
  if (has(features, Feature::ibl) && environment_) {
    glActiveTexture(GL_TEXTURE0 + unit);
    glBindTexture(GL_TEXTURE_CUBE_MAP, environment_->specularCube.get());
    glBindSampler(static_cast<GLuint>(unit), 0);
    setUniform(program, "u_environmentMap", unit++);
    bind("u_brdfLut", environment_->brdfLut.get());
    setUniform(program, "u_environmentMaxLod", environment_->maxLod);
    setUniform(program, "u_environmentScale", settings.iblIntensity * kEnvironmentShare / kAmbientShare);
    glUniform3fv(glGetUniformLocation(program, "u_irradianceSh"), 9, &environment_->irradianceSh[0].x);
  }
  if (has(features, Feature::pointShadows)) {
    glActiveTexture(GL_TEXTURE0 + unit);
    glBindTexture(GL_TEXTURE_CUBE_MAP, shadowCube_.get());
    glBindSampler(static_cast<GLuint>(unit), 0);
    setUniform(program, "u_shadowCube", unit++);
    const glm::vec2 range = shadowCubeDepthRange();
    setUniform(program, "u_shadowCubeDepth", glm::vec3(range, 4 * boundsRadius()));  // biases: fractions of the 2D map's depth range
  } else if (has(features, Feature::shadows)) {
    bind("u_shadowMap", shadowTexture_.get());
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
