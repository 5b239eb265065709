// SPDX-License-Identifier: MIT
// The feature defines shader variants are compiled from: one table, used by the renderer and
// by the test that checks every name here is used by the GLSL and vice versa.
#pragma once

#include <cstdint>
#include <string>

namespace tangent::viewer {

enum class Feature : std::uint32_t {
  baseColorMap = 1u << 0,
  normalMap = 1u << 1,
  specularMap = 1u << 2,       // KHR_materials_specular specularTexture (strength in A)
  specularColorMap = 1u << 3,  // KHR_materials_specular specularColorTexture (RGB)
  metallicRoughnessMap = 1u << 4,
  emissiveMap = 1u << 5,
  shadows = 1u << 6,
  reflection = 1u << 7,        // sphere-map reflection
  occlusionMap = 1u << 8,
  alphaMask = 1u << 9,         // alphaMode MASK: discard below alphaCutoff
  unlit = 1u << 10,            // KHR_materials_unlit
  pbr = 1u << 11,              // metallic-roughness shading (else the specular-map mode)
  // Bits from 16 up: this session's additions, apart from any others appended above.
  physicalLights = 1u << 16,   // KHR_lights_punctual in its units (lux, candela), range window
  ibl = 1u << 17,              // image-based lighting from the built-in environment (pbr only)
  pointShadows = 1u << 18,     // with shadows: light 0 is a point light, its shadow a depth cube map
  // With specularColorMap: specularTexture is the same texture (KHR_materials_specular's packing,
  // strength in A, colour in RGB), read once from the colour map (an sRGB texture's A is linear).
  specularInColorMap = 1u << 19,
  // Every light is directional (the default rig): lighting.glsl leaves the positional code out.
  directionalLights = 1u << 20,
  // With metallicRoughnessMap: occlusionTexture is the same texture (glTF's ORM packing,
  // occlusion in R), read once from the metallic-roughness map.
  occlusionInMetallicRoughnessMap = 1u << 21,
  // With shadows: PCF over more than one bilinear comparison (RenderSettings::pcfRadius > 0).
  pcf = 1u << 22,
  // The normal-mapping frame's bitangent per vertex, interpolated (else per fragment).
  bitangentPerVertex = 1u << 23,
  // Some texture of the material (the normal map apart, whose UVs the vertices carry ready)
  // reads TEXCOORD_1 or has a KHR_texture_transform; else they all read TEXCOORD_0 as stored.
  uvTransforms = 1u << 24,
  // PBR: KHR_materials_clearcoat (a factor above 0), its textures: factor (R), roughness (G),
  // normal map (through textureUv(), with the primitive's TANGENT).
  clearcoat = 1u << 25,
  clearcoatMap = 1u << 26,
  clearcoatRoughnessMap = 1u << 27,
  clearcoatNormalMap = 1u << 28,
  // PBR: KHR_materials_anisotropy (the extension's anisotropic GGX) and its direction texture.
  anisotropy = 1u << 29,
  anisotropyMap = 1u << 30,
  // COLOR_0 multiplies the base colour (a primitive with the attribute).
  vertexColor = 1u << 31,
};

enum class DebugView : std::uint8_t {
  lit,
  geometryNormal,
  tangent,
  bitangent,
  shadingNormal,
  uv,
  handedness,
  tangentError,
  faceOrientation,
  handednessWorld,  // after faceOrientation: keys 1-9 keep their views
  compareAngle,     // the per-pixel angle between the file's frames and the compare set's
  anisotropyDirection,  // KHR_materials_anisotropy's direction in world space as colour
  clearcoatNormal,      // KHR_materials_clearcoat's normal (its own normal map) in world space
};

struct FeatureDefine {
  Feature feature;
  const char* define;
};

inline constexpr FeatureDefine kFeatureDefines[] = {
    {Feature::baseColorMap, "HAS_BASE_COLOR_MAP"},
    {Feature::normalMap, "HAS_NORMAL_MAP"},
    {Feature::specularMap, "HAS_SPECULAR_MAP"},
    {Feature::specularColorMap, "HAS_SPECULAR_COLOR_MAP"},
    {Feature::metallicRoughnessMap, "HAS_METALLIC_ROUGHNESS_MAP"},
    {Feature::emissiveMap, "HAS_EMISSIVE_MAP"},
    {Feature::shadows, "USE_SHADOWS"},
    {Feature::reflection, "USE_REFLECTION"},
    {Feature::occlusionMap, "HAS_OCCLUSION_MAP"},
    {Feature::alphaMask, "ALPHA_MASK"},
    {Feature::physicalLights, "LIGHTS_PHYSICAL"},
    {Feature::unlit, "MATERIAL_UNLIT"},
    {Feature::pbr, "SHADING_PBR"},
    {Feature::ibl, "USE_IBL"},
    {Feature::pointShadows, "POINT_SHADOWS"},
    {Feature::specularInColorMap, "SPECULAR_IN_COLOR_MAP"},
    {Feature::directionalLights, "LIGHTS_DIRECTIONAL"},
    {Feature::occlusionInMetallicRoughnessMap, "OCCLUSION_IN_METALLIC_ROUGHNESS_MAP"},
    {Feature::pcf, "SHADOW_PCF"},
    {Feature::bitangentPerVertex, "BITANGENT_PER_VERTEX"},
    {Feature::uvTransforms, "HAS_UV_TRANSFORMS"},
    {Feature::clearcoat, "MATERIAL_CLEARCOAT"},
    {Feature::clearcoatMap, "HAS_CLEARCOAT_MAP"},
    {Feature::clearcoatRoughnessMap, "HAS_CLEARCOAT_ROUGHNESS_MAP"},
    {Feature::clearcoatNormalMap, "HAS_CLEARCOAT_NORMAL_MAP"},
    {Feature::anisotropy, "MATERIAL_ANISOTROPY"},
    {Feature::anisotropyMap, "HAS_ANISOTROPY_MAP"},
    {Feature::vertexColor, "HAS_VERTEX_COLOR"},
};

// The lit view's shading: glTF's metallic-roughness model, or the tutorials' specular-map
// mode with Blinn-Phong (half vector) or Phong (reflection vector) highlights.
enum class Shading : std::uint8_t { pbr, blinnPhong, phong };

struct ShadingInfo {
  Shading shading;
  const char* name;  // for --shading and the panel
};

inline constexpr ShadingInfo kShadings[] = {
    {Shading::pbr, "pbr"},
    {Shading::blinnPhong, "blinn-phong"},
    {Shading::phong, "phong"},
};

struct DebugViewInfo {
  DebugView view;
  const char* define;  // nullptr for the lit view
  const char* name;    // for --view and the panel
};

inline constexpr DebugViewInfo kDebugViews[] = {
    {DebugView::lit, nullptr, "lit"},
    {DebugView::geometryNormal, "DEBUG_GEOMETRY_NORMAL", "geometry-normal"},
    {DebugView::tangent, "DEBUG_TANGENT", "tangent"},
    {DebugView::bitangent, "DEBUG_BITANGENT", "bitangent"},
    {DebugView::shadingNormal, "DEBUG_SHADING_NORMAL", "shading-normal"},
    {DebugView::uv, "DEBUG_UV", "uv"},
    {DebugView::handedness, "DEBUG_HANDEDNESS", "handedness"},
    {DebugView::tangentError, "DEBUG_TANGENT_ERROR", "error"},
    {DebugView::faceOrientation, "DEBUG_FACE_ORIENTATION", "face-orientation"},
    {DebugView::handednessWorld, "DEBUG_HANDEDNESS_WORLD", "handedness-world"},
    {DebugView::compareAngle, "DEBUG_COMPARE_ANGLE", "compare-angle"},
    {DebugView::anisotropyDirection, "DEBUG_ANISOTROPY_DIRECTION", "anisotropy-direction"},
    {DebugView::clearcoatNormal, "DEBUG_CLEARCOAT_NORMAL", "clearcoat-normal"},
};

// Tone mapping of the lit views' linear colour before the sRGB encoding, as the Khronos glTF
// Sample Viewer offers it; unlit materials and the debug views are never tone mapped.
enum class ToneMapping : std::uint8_t { none, khrPbrNeutral, acesNarkowicz };

struct ToneMappingInfo {
  ToneMapping toneMapping;
  const char* define;  // nullptr: none
  const char* name;    // for --tone-map and the panel
};

inline constexpr ToneMappingInfo kToneMappings[] = {
    {ToneMapping::none, nullptr, "none"},
    {ToneMapping::khrPbrNeutral, "TONEMAP_KHR_PBR_NEUTRAL", "khr-pbr-neutral"},
    {ToneMapping::acesNarkowicz, "TONEMAP_ACES_NARKOWICZ", "aces"},
};

using FeatureSet = std::uint32_t;

// The most lights a mesh program reads (lighting.glsl's kMaxLights); each program is compiled
// for the number it lights with, its LIGHT_COUNT (ShaderLibrary::mesh).
inline constexpr int kMaxLights = 4;

inline bool has(FeatureSet set, Feature feature) { return (set & static_cast<std::uint32_t>(feature)) != 0; }

// Light 0's shadow: the features a variant drawn without it leaves out.
inline constexpr FeatureSet kShadowFeatures =
    static_cast<FeatureSet>(Feature::shadows) | static_cast<FeatureSet>(Feature::pointShadows) | static_cast<FeatureSet>(Feature::pcf);

// "#define X\n" lines for a variant.
inline std::string definesFor(FeatureSet features, DebugView view, ToneMapping toneMapping = ToneMapping::none) {
  std::string text;
  for (const auto& entry : kFeatureDefines) {
    if (has(features, entry.feature)) text += std::string("#define ") + entry.define + "\n";
  }
  for (const auto& entry : kDebugViews) {
    if (entry.view == view && entry.define) text += std::string("#define ") + entry.define + "\n";
  }
  for (const auto& entry : kToneMappings) {
    if (entry.toneMapping == toneMapping && entry.define) text += std::string("#define ") + entry.define + "\n";
  }
  return text;
}

}  // namespace tangent::viewer
