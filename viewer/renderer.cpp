// SPDX-License-Identifier: MIT
// The scene on the GPU: meshes packed and uploaded, instances placed, poses applied, the compare
// sets and textures; the renderer's shared helpers (renderer_internal.hpp). The passes are in
// renderer_shadows.cpp, renderer_lit.cpp and renderer_glyphs.cpp, the variants in renderer_shading.cpp.
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

namespace tangent::viewer::renderer_detail {

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
void packMeshCorner(const gltf::DrawItem& item, const CornerFrames& frame, std::size_t c, float* corner) {
  for (const VertexAttribute& attribute : kMeshVertexLayout) {
    float* out = corner + attribute.offset;
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

std::vector<float> packMeshVertices(const gltf::DrawItem& item, const CornerFrames& frame) {
  const std::size_t corners = item.positions.size() / 3;
  std::vector<float> data(corners * kMeshFloatsPerVertex);
  for (std::size_t c = 0; c < corners; ++c) packMeshCorner(item, frame, c, &data[c * kMeshFloatsPerVertex]);
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
glm::mat3 uvTransformMatrix(const gltf::TextureRef& ref) {
  const auto& t = ref.uvTransform;
  return glm::mat3(t[0], t[1], 0, t[2], t[3], 0, t[4], t[5], 1);
}

void setUvUniforms(GLuint program, const std::string& prefix, const gltf::TextureRef& ref) {
  setUniform(program, (prefix + "UvSet").c_str(), ref.texCoord == 1 ? 1 : 0);
  setUniform(program, (prefix + "UvTransform").c_str(), uvTransformMatrix(ref));
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

// A node whose transform mirrors (negative determinant) turns its triangles' winding around, so
// its front faces are the clockwise ones (glTF 2.0 3.7.4).
void frontFace(bool mirrored) { glFrontFace(mirrored ? GL_CW : GL_CCW); }

const gltf::MaterialDesc* materialOf(const gltf::Scene& scene, int material) {
  return material >= 0 && material < static_cast<int>(scene.materials.size()) ? &scene.materials[material] : nullptr;
}

}  // namespace tangent::viewer::renderer_detail

namespace tangent::viewer {

using namespace renderer_detail;

namespace {

// How the materials use each image: each is uploaded as they use it, sRGB where it holds
// colour, linear where it holds data, both when used both ways; an anisotropy direction
// texture's pixels are kept on the CPU as well (the anisotropy-direction view's glyphs read them).
struct ImageUses {
  std::vector<bool> asColour, asData, asDirection;
};

// The uses of each image; a message for each texture on a UV set past TEXCOORD_1.
ImageUses imageUses(const gltf::Scene& scene, std::vector<std::string>& messages) {
  const std::size_t imageCount = scene.images.size();
  ImageUses uses{std::vector<bool>(imageCount), std::vector<bool>(imageCount), std::vector<bool>(imageCount)};
  for (const auto& material : scene.materials) {
    const int direction = material.anisotropyTexture.image;
    if (material.hasAnisotropy && direction >= 0 && direction < static_cast<int>(imageCount)) uses.asDirection[direction] = true;
    for (const gltf::TextureRef* ref : textureRefs(material)) {
      if (ref->image < 0 || ref->image >= static_cast<int>(imageCount)) continue;
      (ref->colour ? uses.asColour : uses.asData)[ref->image] = true;
      if (ref->texCoord > 1)
        messages.push_back("material '" + text::quoted(material.name) + "': texCoord " + std::to_string(ref->texCoord) +
                           " shown with TEXCOORD_0 (the viewer reads sets 0 and 1)");
    }
  }
  return uses;
}

// Each used image decoded, fitted to the GL's size limit and uploaded into `linear` and `srgb`
// (one slot per image; empty where unused or left out), the direction images' pixels kept in
// `kept` (empty elsewhere), its notes and errors in `messages`.
void uploadImages(const gltf::Scene& scene, const ImageUses& uses, std::vector<Texture>& linear, std::vector<Texture>& srgb,
                  std::vector<DecodedImage>& kept, std::vector<std::string>& messages) {
  const std::size_t imageCount = scene.images.size();
  linear.resize(imageCount);
  srgb.resize(imageCount);
  kept.assign(imageCount, DecodedImage{});
  const int maxSize = maxTextureSize();
  for (std::size_t i = 0; i < imageCount; ++i) {
    if (!uses.asColour[i] && !uses.asData[i]) continue;
    DecodedImage image;
    std::string error;
    const bool decoded = decodeImage(scene.images[i], image, error);
    messages.insert(messages.end(), image.notes.begin(), image.notes.end());
    if (!decoded) {
      // Colour textures show a checker instead, so that the gap is seen; data textures are left out.
      messages.push_back(error + (uses.asColour[i] ? "; drawn as a magenta checker" : "; left out"));
      if (uses.asColour[i]) srgb[i] = uploadTexture(missingImageChecker(), true);
      continue;
    }
    if (std::string note = fitTextureSize(image, maxSize, scene.images[i].label); !note.empty()) messages.push_back(std::move(note));
    if (uses.asColour[i]) srgb[i] = uploadTexture(image, true);
    if (uses.asData[i]) linear[i] = uploadTexture(image, false);
    if (uses.asDirection[i]) kept[i] = std::move(image);
  }
}

}  // namespace

// The scene's images, meshes (a copy of its own for each deformed instance), instances, bounds
// and lights uploaded in place of the last scene's.
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
  meshUploads_ = 0;
  uploadImages(scene_, imageUses(scene_, messages), textures_, srgbTextures_, directionImages_, messages);
  auto upload = [&](const gltf::DrawItem& item, GLenum usage) {
    GpuMesh mesh;
    mesh.material = item.material;
    mesh.hasColors = !item.colors.empty();
    mesh.vertexArray = makeVertexArray();
    mesh.vertices = makeBuffer();
    if (usage == GL_STATIC_DRAW) mesh.indices = makeBuffer();
    glBindVertexArray(mesh.vertexArray.get());
    glBindBuffer(GL_ARRAY_BUFFER, mesh.vertices.get());
    setVertexLayout(kMeshVertexLayout);
    fillMeshBuffers(mesh, item, itemFrames(item, compareTangentsOf(static_cast<std::size_t>(&item - scene_.items.data()))));
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
  // No sets for none: what setScene uploaded already (10^7 triangles: 8 s and 1 GB again).
  if (perItem.empty() && compareTangents_.empty()) return;
  compareTangents_ = std::move(perItem);
  // Every mesh's vertices again (each deforming instance's own buffer starts from its item's),
  // then the pose again, which deforms the new set along.
  auto upload = [&](std::size_t item, std::size_t mesh) {
    fillMeshBuffers(meshes_[mesh], scene_.items[item], itemFrames(scene_.items[item], compareTangentsOf(item)));
  };
  for (std::size_t item = 0; item < scene_.items.size(); ++item) upload(item, item);  // setScene uploads items first
  for (const DeformedInstance& deformed : deformed_) upload(scene_.instances[deformed.instance].item, instances_[deformed.instance].mesh);
  if (const std::optional<PoseTime> pose = pose_) {
    pose_.reset();
    setPose(*pose);
  }
}

void Renderer::uploadDeformed(const DeformedInstance& deformed) {
  fillMeshBuffers(meshes_[instances_[deformed.instance].mesh], scene_.items[scene_.instances[deformed.instance].item],
                  framesOf(deformed.instance));
}

void Renderer::fillMeshBuffers(GpuMesh& mesh, const gltf::DrawItem& item, const CornerFrames& frame) {
  const std::size_t corners = item.positions.size() / 3;
  mesh.count = static_cast<GLsizei>(corners);
  ++meshUploads_;
  glBindVertexArray(mesh.vertexArray.get());  // the element buffer binding is the vertex array's
  glBindBuffer(GL_ARRAY_BUFFER, mesh.vertices.get());
  if (!mesh.indices) {
    // Rewritten at every pose: as many floats each time (GL_DYNAMIC_DRAW).
    const std::vector<float> data = packMeshVertices(item, frame);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(data.size() * sizeof(float)), data.data(), GL_DYNAMIC_DRAW);
  } else {
    // Welded as the corners are packed: the packed corners are never all in memory at once.
    const WeldedVertices welded = weldPackedCorners(corners, kMeshFloatsPerVertex,
                                                    [&](std::size_t c, float* out) { packMeshCorner(item, frame, c, out); });
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

}  // namespace tangent::viewer
