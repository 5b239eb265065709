// SPDX-License-Identifier: MIT
// Images, texture samplers and materials (glTF 2.0 3.8, 3.9; KHR_texture_transform,
// KHR_materials_specular, _clearcoat, _anisotropy, _unlit) for display.
#include "scene_parts.hpp"

#include <algorithm>

#include "read/primitive.hpp"
#include "read/uri.hpp"

namespace tangent::gltf::scene_parts {
namespace {

// glTF's sampler codes (the GL enums' values) as TextureSampler's; an unknown code gives the
// default (repeat, automatic).
TextureSampler::Wrap wrapOf(const Json& sampler, const char* key) {
  switch (sampler.contains(key) && sampler[key].is_number_integer() ? sampler[key].get<int>() : 10497) {
    case 33071: return TextureSampler::Wrap::clampToEdge;
    case 33648: return TextureSampler::Wrap::mirroredRepeat;
    default: return TextureSampler::Wrap::repeat;
  }
}

TextureSampler::Filter filterOf(const Json& sampler, const char* key) {
  using Filter = TextureSampler::Filter;
  switch (sampler.contains(key) && sampler[key].is_number_integer() ? sampler[key].get<int>() : 0) {
    case 9728: return Filter::nearest;
    case 9729: return Filter::linear;
    case 9984: return Filter::nearestMipmapNearest;
    case 9985: return Filter::linearMipmapNearest;
    case 9986: return Filter::nearestMipmapLinear;
    case 9987: return Filter::linearMipmapLinear;
    default: return Filter::automatic;
  }
}

TextureSampler samplerOf(const Json& doc, const Json& texture) {
  TextureSampler sampler;
  const int index = texture.contains("sampler") && texture["sampler"].is_number_integer() ? texture["sampler"].get<int>() : -1;
  if (index < 0 || !doc.contains("samplers") || !doc["samplers"].is_array() || index >= static_cast<int>(doc["samplers"].size()))
    return sampler;
  const Json& json = doc["samplers"][index];
  if (!json.is_object()) return sampler;
  sampler.wrapS = wrapOf(json, "wrapS");
  sampler.wrapT = wrapOf(json, "wrapT");
  sampler.magFilter = filterOf(json, "magFilter");
  sampler.minFilter = filterOf(json, "minFilter");
  return sampler;
}

TextureRef textureRef(const Json& doc, const Json& info) {
  TextureRef ref;
  if (!info.is_object() || !info.contains("index")) return ref;
  const int texture = info["index"].get<int>();
  if (!doc.contains("textures") || texture < 0 || texture >= static_cast<int>(doc["textures"].size())) return ref;
  const Json& textureJson = doc["textures"][texture];
  ref.image = textureJson.value("source", -1);
  ref.sampler = samplerOf(doc, textureJson);
  ref.texCoord = info.value("texCoord", 0);
  if (info.contains("extensions") && info["extensions"].contains("KHR_texture_transform")) {
    const Json& transform = info["extensions"]["KHR_texture_transform"];
    ref.texCoord = transform.value("texCoord", ref.texCoord);
    const std::array<double, 6> m = detail::textureTransformMatrix(transform);
    std::copy(m.begin(), m.end(), ref.uvTransform.begin());
  }
  ref.scale = info.value("scale", info.value("strength", 1.0f));
  return ref;
}

TextureRef colourTextureRef(const Json& doc, const Json& info) {
  TextureRef ref = textureRef(doc, info);
  ref.colour = true;
  return ref;
}

}  // namespace

std::vector<ImageSource> readImages(const detail::Asset& asset) {
  std::vector<ImageSource> images;
  if (!asset.json.contains("images")) return images;
  const auto dir = std::filesystem::absolute(asset.path).parent_path();
  for (std::size_t i = 0; i < asset.json["images"].size(); ++i) {
    const Json& image = asset.json["images"][i];
    ImageSource source;
    // Names the file and the image (and its URI) in the viewer's messages.
    source.label = asset.path.string() + ": image " + std::to_string(i);
    source.mimeType = image.value("mimeType", "");
    if (image.contains("uri") && image["uri"].is_string()) {
      const std::string uri = image["uri"].get<std::string>();
      if (detail::isDataUri(uri)) {
        source.bytes = detail::decodeDataUri(uri, asset.path.string() + ": /images/" + std::to_string(i));
        source.mimeType = uri.substr(5, uri.find(';') - 5);
      } else {
        // loadAsset refused URIs that leave the asset root; a missing file leaves the image empty
        // (loadAsset's warning, among the messages, says so).
        source.label += " '" + uri + "'";
        try {
          source.file = detail::resolveFileUri(uri, dir, asset.root, asset.path.string(), "/images/" + std::to_string(i));
        } catch (const detail::MissingFileError& e) {
          source.missing = e.what();
        }
      }
    } else if (image.contains("bufferView") && image["bufferView"].is_number_integer()) {
      const int viewIndex = image["bufferView"].get<int>();
      if (viewIndex >= 0 && viewIndex < static_cast<int>(asset.model.bufferViews.size())) {
        const auto& view = asset.model.bufferViews[viewIndex];
        const auto& buffer = asset.model.buffers[view.buffer].data;
        if (view.byteOffset <= buffer.size() && view.byteLength <= buffer.size() - view.byteOffset)
          source.bytes.assign(buffer.begin() + view.byteOffset, buffer.begin() + view.byteOffset + view.byteLength);
      }
    }
    images.push_back(std::move(source));
  }
  return images;
}

std::vector<MaterialDesc> readMaterials(const Json& doc) {
  std::vector<MaterialDesc> materials;
  if (!doc.contains("materials")) return materials;
  for (const Json& m : doc["materials"]) {
    MaterialDesc material;
    material.name = m.value("name", "");
    material.doubleSided = m.value("doubleSided", false);
    if (m.contains("pbrMetallicRoughness")) {
      const Json& pbr = m["pbrMetallicRoughness"];
      readFloats(pbr, "baseColorFactor", material.baseColor);
      material.metallic = floatValue(pbr, "metallicFactor", 1.0f);
      material.roughness = floatValue(pbr, "roughnessFactor", 1.0f);
      if (pbr.contains("baseColorTexture")) material.baseColorTexture = colourTextureRef(doc, pbr["baseColorTexture"]);
      if (pbr.contains("metallicRoughnessTexture")) material.metallicRoughnessTexture = textureRef(doc, pbr["metallicRoughnessTexture"]);
    }
    if (m.contains("normalTexture")) material.normalTexture = textureRef(doc, m["normalTexture"]);
    if (m.contains("emissiveTexture")) material.emissiveTexture = colourTextureRef(doc, m["emissiveTexture"]);
    if (m.contains("occlusionTexture")) material.occlusionTexture = textureRef(doc, m["occlusionTexture"]);
    readFloats(m, "emissiveFactor", material.emissive);
    const std::string alphaMode = m.value("alphaMode", "OPAQUE");
    material.alphaMode = alphaMode == "MASK"    ? MaterialDesc::AlphaMode::mask
                         : alphaMode == "BLEND" ? MaterialDesc::AlphaMode::blend
                                                : MaterialDesc::AlphaMode::opaque;
    material.alphaCutoff = floatValue(m, "alphaCutoff", 0.5f);
    material.unlit = m.contains("extensions") && m["extensions"].contains("KHR_materials_unlit");
    if (m.contains("extensions") && m["extensions"].contains("KHR_materials_specular")) {
      const Json& specular = m["extensions"]["KHR_materials_specular"];
      material.hasSpecular = true;
      material.specularFactor = floatValue(specular, "specularFactor", 1.0f);
      readFloats(specular, "specularColorFactor", material.specularColor);
      if (specular.contains("specularTexture")) material.specularTexture = textureRef(doc, specular["specularTexture"]);
      if (specular.contains("specularColorTexture")) material.specularColorTexture = colourTextureRef(doc, specular["specularColorTexture"]);
    }
    if (m.contains("extensions") && m["extensions"].contains("KHR_materials_clearcoat")) {
      const Json& clearcoat = m["extensions"]["KHR_materials_clearcoat"];
      material.clearcoat = floatValue(clearcoat, "clearcoatFactor", 0.0f);
      material.clearcoatRoughness = floatValue(clearcoat, "clearcoatRoughnessFactor", 0.0f);
      if (clearcoat.contains("clearcoatTexture")) material.clearcoatTexture = textureRef(doc, clearcoat["clearcoatTexture"]);
      if (clearcoat.contains("clearcoatRoughnessTexture"))
        material.clearcoatRoughnessTexture = textureRef(doc, clearcoat["clearcoatRoughnessTexture"]);
      if (clearcoat.contains("clearcoatNormalTexture")) material.clearcoatNormalTexture = textureRef(doc, clearcoat["clearcoatNormalTexture"]);
    }
    if (m.contains("extensions") && m["extensions"].contains("KHR_materials_anisotropy")) {
      const Json& anisotropy = m["extensions"]["KHR_materials_anisotropy"];
      material.hasAnisotropy = true;
      material.anisotropyStrength = floatValue(anisotropy, "anisotropyStrength", 0.0f);
      material.anisotropyRotation = floatValue(anisotropy, "anisotropyRotation", 0.0f);
      if (anisotropy.contains("anisotropyTexture")) material.anisotropyTexture = textureRef(doc, anisotropy["anisotropyTexture"]);
    }
    materials.push_back(material);
  }
  return materials;
}

}  // namespace tangent::gltf::scene_parts
