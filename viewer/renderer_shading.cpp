// SPDX-License-Identifier: MIT
// The shading decisions of a frame: each mesh's shader variant (feature set), culling, and the
// exposure that maps the lights to display values.
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
  // The extensions that read the tangent frame, in the PBR mode (and each in its view).
  if (!material.unlit && (settings.shading == Shading::pbr || settings.view == DebugView::clearcoatNormal) && material.clearcoat > 0) {
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

}  // namespace tangent::viewer
