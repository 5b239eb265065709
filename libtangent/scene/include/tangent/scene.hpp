// SPDX-License-Identifier: MIT
// A glTF file flattened for display: every triangle primitive the default scene shows, once,
// as a draw item in object space, one vertex per corner, with the file's tangents (or computed
// ones when the file has none), freshly computed tangents, and what `tangent check` says of each
// corner (checkCorners, tangent/verdict.hpp); and every node that shows it as an instance: which
// item, where. A mesh that 100,000 nodes share is read and its tangents computed once. Images are
// referenced, never decoded here (the viewer decodes them).
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "tangent/check.hpp"
#include "tangent/tangent.hpp"
#include "tangent/verdict.hpp"

namespace tangent::gltf {

// A texture's glTF sampler (glTF 2.0 3.8.4): wrapping per axis and filtering; `automatic` where
// the file leaves a filter out (the viewer then uses linear, trilinear when minifying).
struct TextureSampler {
  enum class Wrap { repeat, clampToEdge, mirroredRepeat };
  enum class Filter { automatic, nearest, linear, nearestMipmapNearest, linearMipmapNearest, nearestMipmapLinear, linearMipmapLinear };
  Wrap wrapS = Wrap::repeat, wrapT = Wrap::repeat;
  Filter magFilter = Filter::automatic, minFilter = Filter::automatic;
  bool operator==(const TextureSampler&) const = default;
};

struct TextureRef {
  int image = -1;      // index into Scene::images; -1 when absent
  TextureSampler sampler;
  int texCoord = 0;    // UV set (KHR_texture_transform's override applied)
  float scale = 1;     // normalTexture.scale, occlusionTexture.strength
  // KHR_texture_transform as a column-major 2x3 matrix: uv' = (t0 u + t2 v + t4, t1 u + t3 v + t5).
  // DrawItem::uvNormal has the normal texture's applied already; the others apply it to uvSets.
  std::array<float, 6> uvTransform{1, 0, 0, 1, 0, 0};
  bool colour = false;  // sRGB-encoded (base colour, emissive, specular colour), else linear data
};

struct ImageSource {
  std::filesystem::path file;       // external image, or empty
  std::vector<std::uint8_t> bytes;  // embedded image (bufferView or data URI), or empty
  std::string mimeType;
  std::string label;                // for messages
  std::string missing;              // why it has neither file nor bytes (a URI naming no file), or ""
};

struct MaterialDesc {
  std::string name;
  std::array<float, 4> baseColor{1, 1, 1, 1};
  float metallic = 1, roughness = 1;
  std::array<float, 3> emissive{0, 0, 0};
  TextureRef baseColorTexture, normalTexture, emissiveTexture, metallicRoughnessTexture, occlusionTexture;
  enum class AlphaMode { opaque, mask, blend } alphaMode = AlphaMode::opaque;
  float alphaCutoff = 0.5f;
  bool unlit = false;        // KHR_materials_unlit
  bool hasSpecular = false;  // KHR_materials_specular
  float specularFactor = 1;
  std::array<float, 3> specularColor{1, 1, 1};
  TextureRef specularTexture, specularColorTexture;
  bool doubleSided = false;
  // KHR_materials_clearcoat: a coat layer (factor, roughness; textures' R and G) with a normal map
  // of its own (its own UV set and transform; `scale` as normalTexture's). Factor 0: no coat.
  float clearcoat = 0, clearcoatRoughness = 0;
  TextureRef clearcoatTexture, clearcoatRoughnessTexture, clearcoatNormalTexture;
  // KHR_materials_anisotropy: strength, rotation (radians, counter-clockwise from the tangent in
  // the (T, B) plane) and a texture (RG: a direction in (T, B) space, B: strength).
  bool hasAnisotropy = false;
  float anisotropyStrength = 0, anisotropyRotation = 0;
  TextureRef anisotropyTexture;
};

struct LightDesc {
  enum class Type { directional, point, spot } type = Type::directional;
  std::string name;
  int definition = -1;  // index in the file's KHR_lights_punctual lights (one node or more use it)
  int node = -1;        // the node that places this one
  std::array<float, 3> color{1, 1, 1};
  float intensity = 1;
  float range = 0;  // 0: infinite
  std::array<float, 3> position{0, 0, 0};
  std::array<float, 3> direction{0, 0, -1};  // where the light points, world space
  float innerConeAngle = 0, outerConeAngle = 0.785398f;
};

// DrawItem::tangents' w where the corner has no tangent frame (glTF's w is +1 or -1).
inline constexpr float kUndefinedTangentW = 0.0f;

// Computed tangents (4 per corner): w = kUndefinedTangentW where the core gave the fixed axis
// (FrameSource::fixed), the frames nothing defines. The load marks DrawItem's sets with it,
// and the viewer the sets it computes afresh on deformed corners.
inline void markUndefinedFrames(std::span<const FrameSource> sources, std::span<float> tangents) {
  for (std::size_t c = 0; c < sources.size(); ++c)
    if (sources[c] == FrameSource::fixed) tangents[4 * c + 3] = kUndefinedTangentW;
}

// A morph target of a primitive (glTF 2.0 3.7.2.2): deltas added, times the target's weight, to
// the attributes. Per corner, as DrawItem's arrays; empty where the target lacks the attribute.
struct MorphTarget {
  std::vector<float> positions;  // 3 per corner
  std::vector<float> normals;    // 3
  std::vector<float> tangents;   // 3: TANGENT deltas are xyz, w stays the base's
};

// One triangle primitive of a mesh, as every node that shows it draws it.
struct DrawItem {
  PrimitiveIndex primitive;  // which primitive of the file: how check's findings and verdicts name it
  std::string label;  // "mesh 0 'Name' primitive 1", for messages
  int material = -1;  // -1: default material
  // Of the finite positions; boundsMin > boundsMax when there is none.
  std::array<float, 3> boundsMin{0, 0, 0}, boundsMax{0, 0, 0};  // object space
  // One entry per corner (3 per triangle).
  std::vector<float> positions;      // 3 per corner, object space
  std::vector<float> normals;        // 3
  std::vector<float> uvNormal;       // 2, the normal texture's UV set (transform applied)
  std::array<std::vector<float>, 2> uvSets;  // 2 each, TEXCOORD_0 and _1 as stored (zeros when absent)
  std::vector<float> tangents;       // 4, the file's TANGENT, or computed when it has none
  std::vector<float> colors;         // 4, COLOR_0 as RGBA (A 1 for RGB); empty when absent
  // 4, freshly computed as `tangent check` computes its reference (options.check's method and
  // weighting; without NORMAL, from the flat normals bake and check generate)
  std::vector<float> computedTangents;
  Options freshOptions;  // what computedTangents were computed with; deformed corners are recomputed alike
  // In `computedTangents` (and in `tangents` where the file has no TANGENT), w =
  // kUndefinedTangentW at a corner whose frame nothing defines: no triangle with usable UVs
  // meets the corner's vertex or its neighbours (a primitive without TEXCOORD, a UV island of
  // zero area), so the core gave it a fixed axis perpendicular to the normal
  // (FrameSource::fixed). Shading treats it as +1; the views of the frame show their
  // "no tangent" colour. The file's TANGENT is kept as written.
  // Per corner, from check's verdict (CornerVerdict) with options.check: the angle between the
  // file's tangent and check's reference where check compared them (agrees or disagrees), else
  // 0; and the CornerProblem bits of the checks that fail there. Zero where check judges no
  // corner (a primitive it skips, without TANGENT, or failing present or format).
  std::vector<float> tangentErrorDegrees;
  std::vector<std::uint8_t> cornerProblems;
  bool tangentsFromFile = false;
  bool hasUvs = false;
  Report report;  // of the fresh computation
  std::vector<MorphTarget> morphTargets;  // the primitive's targets, in the file's order
  // Skin influences (JOINTS_n / WEIGHTS_n, every pair the file has): influencesPerCorner per
  // corner, each a joint (an index into the skin's joints) and its weight; 0 when unskinned.
  int influencesPerCorner = 0;
  std::vector<std::uint16_t> joints;
  std::vector<float> jointWeights;
};

// A node showing a draw item.
struct DrawInstance {
  std::uint32_t item = 0;         // index into Scene::items
  std::array<float, 16> world{};  // column-major node transform, in the rest pose
  std::uint32_t node = 0;         // the glTF node: an index into Scene::nodes when they are kept
};

// A glTF node as posing needs it (kept only for a file with animations, skins or morph targets).
struct SceneNode {
  int parent = -1;
  // The local transform: `matrix` when the node has one, else T * R * S (glTF 2.0 3.5.3).
  bool hasMatrix = false;
  std::array<float, 16> matrix{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  std::array<float, 3> translation{0, 0, 0};
  std::array<float, 4> rotation{0, 0, 0, 1};  // quaternion x, y, z, w
  std::array<float, 3> scale{1, 1, 1};
  std::vector<float> weights;  // morph target weights: node.weights, else its mesh's weights
  int skin = -1;               // index into Scene::skins
};

// glTF 2.0 3.7.3: joint j's matrix is inverse(world(mesh node)) * world(joints[j]) *
// inverseBindMatrices[j].
struct Skin {
  std::vector<std::uint32_t> joints;                     // node indices
  std::vector<std::array<float, 16>> inverseBindMatrices;  // column-major; identity when absent
};

// glTF 2.0 3.11: keyframes of one property. CUBICSPLINE outputs hold (in-tangent, value,
// out-tangent) per keyframe.
struct AnimationSampler {
  enum class Interpolation { step, linear, cubicSpline } interpolation = Interpolation::linear;
  std::vector<float> times;   // seconds, increasing
  std::vector<float> values;  // components per element: 3 (translation, scale), 4 (rotation), targets (weights)
};

struct AnimationChannel {
  enum class Path { translation, rotation, scale, weights } path = Path::translation;
  std::uint32_t node = 0;
  std::uint32_t sampler = 0;  // index into Animation::samplers
};

struct Animation {
  std::string name;
  std::vector<AnimationSampler> samplers;
  std::vector<AnimationChannel> channels;
  float duration = 0;  // the last keyframe time of any sampler
};

// CheckOptions as the viewer judges by default: `all`, so that every primitive it shows with a
// UV set is judged, as `tangent check --all` judges it.
inline CheckOptions viewerCheckOptions() {
  CheckOptions options;
  options.all = true;
  return options;
}

struct SceneOptions {
  // How the fresh tangents are computed (method, weighting) and each corner judged: check's
  // options (its assetRoot is not read; assetRoot below is).
  CheckOptions check = viewerCheckOptions();
  bool judge = true;          // false: no check run, cornerProblems and tangentErrorDegrees zero
  bool negateFileW = false;   // for tests and demonstrations: flip the file's handedness (shown,
                              // not judged: the verdicts are check's, on the file as stored)
  std::filesystem::path assetRoot;  // folder buffer and image URIs may not leave (empty: the file's)
};

struct Scene {
  std::vector<DrawItem> items;          // one per (mesh, primitive) shown, however many nodes show it
  std::vector<DrawInstance> instances;  // one per (node, primitive), in document order (depth first)
  std::vector<MaterialDesc> materials;
  std::vector<ImageSource> images;
  std::vector<LightDesc> lights;  // KHR_lights_punctual, in world space
  // For posing (animation, skinning, morph weights): every node of the file, in its order, when
  // the file has animations, skins or morph targets; empty otherwise (instances' `world` is the
  // whole story then).
  std::vector<SceneNode> nodes;
  std::vector<Skin> skins;
  std::vector<Animation> animations;  // those that could be read; the others are in `messages`
  std::array<float, 3> boundsMin{0, 0, 0}, boundsMax{0, 0, 0};  // world space
  std::vector<std::string> messages;  // what was skipped or substituted, for the panel
};

// Throws InputError on unreadable input.
Scene loadScene(const std::filesystem::path& input, const SceneOptions& options = {});

}  // namespace tangent::gltf
