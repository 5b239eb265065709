// SPDX-License-Identifier: MIT
// Draws a gltf::Scene: optional depth pass from light 0 into a shadow map, then the meshes
// with the shader variant each material needs, then tangent-frame glyphs.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "environment.hpp"
#include "gl_objects.hpp"
#include "pose.hpp"
#include "samplers.hpp"
#include "shader_library.hpp"
#include "textures.hpp"
#include "tangent/scene.hpp"

namespace tangent::viewer {

struct Light {
  bool directional = true;
  glm::vec3 position{0, 4, 0};
  glm::vec3 direction{0, -1, 0};  // where it points
  glm::vec3 ambient{0.05f}, diffuse{0.8f}, specular{1.0f};
  glm::vec3 attenuation{1, 0, 0};  // k0, k1, k2
  float spotInner = -1, spotOuter = -1;  // cone half-angles in radians; < 0: no cone
  // From KHR_lights_punctual: PBR mode reads these, in the extension's units, instead of the
  // colours and k0 k1 k2 above (which the specular-map mode keeps using).
  bool physical = false;
  glm::vec3 color{1};
  float intensity = 1;  // lux (directional) or candela (point, spot)
  float range = 0;      // 0: infinite
};

// The share of a light's direct illuminance that the viewer adds as ambient (sky) light.
inline constexpr float kAmbientShare = 0.06f;
// With image-based lighting (pbr), the environment's mean radiance is this share of the lights'
// direct level instead, times RenderSettings::iblIntensity: bright enough that metals, which
// show nothing but their surroundings, read as metals.
inline constexpr float kEnvironmentShare = 0.2f;
// Auto exposure puts a white Lambertian surface facing the brightest light here: where Khronos
// PBR Neutral stops being linear, so that a light surface's bumps keep their contrast instead
// of being compressed towards 1.
inline constexpr float kAutoExposureWhite = 0.76f;

// Where the normal-mapping frame's bitangent comes from (Substance's "compute tangent space per
// fragment" choice): per fragment, B = cross(N, T) * w from the interpolated N and T (MikkTSpace's
// recommendation), or per vertex, B = cross(N, T) * w at each vertex, interpolated.
enum class BitangentMode : std::uint8_t { perFragment, perVertex };

struct BitangentModeInfo {
  BitangentMode mode;
  const char* name;  // for --bitangent and the panel
};

inline constexpr BitangentModeInfo kBitangentModes[] = {
    {BitangentMode::perFragment, "per-fragment"},
    {BitangentMode::perVertex, "per-vertex"},
};

struct RenderSettings {
  DebugView view = DebugView::lit;
  bool normalMapping = true;
  bool specular = true;
  bool shadows = true;
  int pcfRadius = 1;         // 0 off, 1 = 3x3, 2 = 5x5
  int shadowMapSize = 2048;
  float shadowBiasConstant = 0.0008f;
  float shadowBiasSlope = 0.0015f;
  bool flipGreen = false;
  Shading shading = Shading::pbr;
  float shininess = 48;      // specular-map mode, for KHR_materials_specular materials
  float reflectivity = 0;    // sphere-map reflection mix
  float uvScale = 1;
  bool glyphs = false;
  int maxGlyphs = 4000;
  ToneMapping toneMapping = ToneMapping::khrPbrNeutral;
  float exposure = 0;        // linear factor before tone mapping; <= 0: automatic (Renderer::exposure)
  bool depthPrePass = false; // opaque meshes' depth first, then shading with GL_LEQUAL and no depth writes
  BitangentMode bitangent = BitangentMode::perFragment;
  // Split view: left of the divider the file's TANGENT, right of it the compare set
  // (Renderer::setCompareTangents); not in the compare-angle view, which shows both at once.
  bool split = false;
  float splitPosition = 0.5f;  // the divider, as a fraction of the width from the left
  bool ibl = true;           // pbr: image-based lighting from the built-in environment (else a plain sky term)
  float iblIntensity = 1;    // factor on the environment's radiance
};

// Whether the split view's divider is on screen: the split view, which the compare-angle view
// (both sets at once) replaces.
inline bool dividerShown(const RenderSettings& settings) { return settings.split && settings.view != DebugView::compareAngle; }

// Which tangents a draw shades with: the file's TANGENT (or those computed at load when it has
// none), or the compare set.
enum class TangentSet : std::uint8_t { file, compare };

// Positions (3 per corner), normals (3) and tangents (4) of a primitive's corners: its own, or
// as deformed by the pose.
struct CornerFrames {
  std::span<const float> positions, normals, tangents;
  std::span<const float> tangentErrorDegrees;  // 1 per corner, for the error view
  std::span<const float> compareTangents;      // 4 per corner, the set compared with `tangents`
};
inline CornerFrames itemFrames(const gltf::DrawItem& item, std::span<const float> compareTangents) {
  return {item.positions, item.normals, item.tangents, item.tangentErrorDegrees, compareTangents};
}

struct CameraMatrices {
  glm::mat4 view{1}, projection{1};
  glm::vec3 eye{0, 0, 5};
};

struct FrameStats {
  int drawCalls = 0;        // the camera's passes: depth pre-pass, shading, glyphs
  int shadowDrawCalls = 0;  // into the shadow map, in the frames that redraw it (depthPass)
  std::size_t triangles = 0;
  bool depthPass = false;  // the shadow map was redrawn this frame
  float exposure = 1;      // the exposure used
};

class Renderer {
 public:
  explicit Renderer(ShaderLibrary& shaders) : shaders_(shaders) {}

  // Uploads each item once and decodes textures; problems go to `messages`.
  void setScene(gltf::Scene scene, std::vector<std::string>& messages);
  // Errors and notes go to `messages`.
  bool loadSphereMap(const std::filesystem::path& file, std::vector<std::string>& messages);

  // Poses the scene (node transforms, morph weights, skins) at `time`, deforming morphing and
  // skinned instances on the CPU and updating the bounds; the rest pose until called. Returns
  // whether anything changed (false for a scene without nodes to pose, or the same time).
  bool setPose(PoseTime time);
  // The tangent set the split view's right side and the compare-angle view compare with the
  // file's: per scene item, 4 floats per corner (deformed with the pose as the file's are). An
  // item without a set of its corner count, and every item when `perItem` is empty (the default),
  // compares with its freshly computed tangents (DrawItem::computedTangents).
  void setCompareTangents(std::vector<std::vector<float>> perItem);
  // Draws into the bound framebuffer of the given size.
  FrameStats render(const CameraMatrices& camera, const RenderSettings& settings, int width, int height);

  std::vector<Light>& lights() { return lights_; }
  glm::vec3 boundsCenter() const { return (boundsMin_ + boundsMax_) * 0.5f; }
  glm::vec3 boundsMin() const { return boundsMin_; }
  glm::vec3 boundsMax() const { return boundsMax_; }
  float boundsRadius() const { return glm::max(glm::length(boundsMax_ - boundsMin_) * 0.5f, 1e-3f); }
  const gltf::Scene& scene() const { return scene_; }
  // Shadow-map depth passes drawn since the scene was set: one per change of scene, light 0's
  // direction or map size, not one per frame.
  int shadowPasses() const { return shadowPasses_; }
  // Meshes packed and uploaded since the scene was set (its own upload of each included).
  int meshUploads() const { return meshUploads_; }
  // The lit colour's factor before tone mapping: settings.exposure when > 0; else (auto) the
  // factor that shows a white Lambertian surface facing the brightest light, lit by every light
  // and the ambient or environment term, at kAutoExposureWhite. Decided once per asset: at the
  // rest pose's bounds, so that it holds still across times and animations.
  float exposure(const RenderSettings& settings) const;
  // That surface's radiance at the rest pose's centre before exposure (0 without lights).
  float whiteRadiance(const RenderSettings& settings) const;
  // PBR mode with the file's KHR_lights_punctual lights: in the extension's units.
  bool physicalLights(const RenderSettings& settings) const;
  // Whether light 0's shadow is drawn: asked for, something to shadow and a light, in the lit
  // view. The shadow map's pass and the variants' shadow features (kShadowFeatures) follow it.
  bool shadowsDrawn(const RenderSettings& settings) const;
  // Milliseconds the image-based lighting's maps took to prepare (CPU and upload), once, on the
  // first frame that needs them; 0 before.
  double environmentMilliseconds() const { return environmentMilliseconds_; }

 private:
  // One per scene item: its corners on the GPU, uploaded once however many nodes show it.
  struct GpuMesh {
    VertexArray vertexArray;
    Buffer vertices;
    Buffer indices;       // welded (vertex_weld.hpp) where the mesh is static; none where a pose rewrites its corners
    GLsizei count = 0;    // corners drawn
    int material = -1;
    bool hasColors = false;  // COLOR_0: the vertexColor feature
  };
  // One per scene instance: a mesh where a node puts it.
  struct GpuInstance {
    std::uint32_t mesh = 0;  // index into meshes_
    glm::mat4 model{1};
    bool mirrored = false;     // negative determinant: its front faces are the clockwise ones
    glm::vec3 centerWorld{0};  // of its bounds, for draw order
  };
  // What a run of draws has bound: an instance of the mesh bound last sets its transform only.
  struct BoundMesh {
    std::uint32_t mesh = std::numeric_limits<std::uint32_t>::max();  // none yet
    GLint model = -1, normalMatrix = -1, mirror = -1;  // the program's uniform locations (-1: absent)
    int mirrored = -1;  // the front face set for: -1 not yet, 0 counter-clockwise, 1 clockwise
  };
  // What the shadow map was drawn for; a frame that matches it reuses the map.
  struct ShadowKey {
    glm::vec3 direction{0};
    glm::vec3 position{0};  // of a point or spot light
    bool cube = false;      // a point light's cube map
    int size = 0;
    int sceneVersion = -1;
    float uvScale = 1;  // alpha-tested materials' cut-outs move with it
    bool operator==(const ShadowKey&) const = default;
  };
  // Each instance with the shader variant its material needs, in the order given.
  void drawInstances(std::span<const GpuInstance* const> instances, const CameraMatrices& camera, const RenderSettings& settings,
                     TangentSet tangents, FrameStats& stats);
  // Binds a mesh's program, material, lights and vertices for drawInstance; returns the program.
  GLuint bindMesh(const GpuMesh& mesh, const CameraMatrices& camera, const RenderSettings& settings, TangentSet tangents);
  // Sets the instance's transform (and front face) and draws it.
  void drawInstance(const GpuInstance& instance, BoundMesh& bound);
  void drawShadowMap(const RenderSettings& settings);
  // render()'s phases: the views' lazily computed data (morphed error and compare tangents, the
  // environment), the shadow map where its key changed, the draw order, and the scene drawn with
  // one tangent set (into the scissor box of its side in the split view).
  void prepareViewData(const RenderSettings& settings);
  void refreshShadowMap(const RenderSettings& settings, FrameStats& stats);
  struct DrawOrder {
    std::vector<const GpuInstance*> opaque;       // the nearest mesh first, its instances front to back
    std::vector<const GpuInstance*> transparent;  // BLEND, back to front
  };
  DrawOrder drawOrder(const CameraMatrices& camera, const RenderSettings& settings) const;
  void drawScene(const DrawOrder& order, const CameraMatrices& camera, const RenderSettings& settings, TangentSet tangents,
                 FrameStats& stats);
  // Depth only: each instance through the depth program of its mesh's alpha test (MASK, or BLEND
  // by the shadow rule when `blendCasts`), under `viewProjection`.
  void drawDepth(std::span<const GpuInstance* const> instances, const glm::mat4& viewProjection, const RenderSettings& settings,
                 bool blendCasts, bool cullAsLit);
  FeatureSet alphaTestFeatures(const GpuMesh& mesh, bool blendCasts) const;
  // Whether a scene instance morphs or is skinned (and so has vertices of its own).
  bool deforms(const gltf::DrawInstance& instance) const;
  void placeInstance(GpuInstance& instance, const glm::mat4& model, const gltf::DrawItem& item);
  // Scene instance i's corners as drawn: deformed when it deforms, else its item's.
  CornerFrames framesOf(std::size_t instance) const;
  // Scene item i's compare set: compareTangents_[i] when it fits, else its fresh tangents.
  std::span<const float> compareTangentsOf(std::size_t item) const;
  // Whether item i's compare set is its freshly computed tangents (no set given for it).
  bool compareIsFresh(std::size_t item) const;
  void applyCulling(const GpuMesh& mesh, const RenderSettings& settings) const;
  void drawGlyphs(const CameraMatrices& camera, const RenderSettings& settings);
  std::vector<float> glyphLines(const RenderSettings& settings, bool anisotropy) const;
  glm::mat4 lightViewProjection() const;
  // A shadow-map texel's world size at a fragment: x + y * the fragment's distance from light 0
  // (shadows.glsl's u_shadowTexelWorld, for the normal offset).
  glm::vec2 shadowTexelWorld() const;
  // The factor on the depth biases that keeps them fractions of 4 scene radii in world units
  // (as the cube map's are) whatever depth range the directional map's fit spans; 1 otherwise.
  float shadowBiasScale() const;
  // Light 0 is a point light (not a spot): its shadow is the depth cube map.
  bool pointShadow() const;
  // The cube faces' near and far planes: every point of the scene's bounding sphere lies between
  // them in the face it falls in.
  glm::vec2 shadowCubeDepthRange() const;
  FeatureSet featuresFor(const GpuMesh& mesh, const RenderSettings& settings) const;
  GLuint textureOf(const gltf::TextureRef& ref) const;

  ShaderLibrary& shaders_;
  gltf::Scene scene_;
  std::vector<GpuMesh> meshes_;
  std::vector<GpuInstance> instances_;  // parallel to scene_.instances
  // A morphing or skinned instance: its corners at the current pose (empty until posed).
  struct DeformedInstance {
    std::uint32_t instance = 0;  // index into scene_.instances and instances_
    DeformedCorners corners;
    std::vector<float> weights;  // the morph weights of the pose
    // The error view's angles at this pose (morphedTangentErrors); empty: the item's, from load.
    std::vector<float> tangentErrorDegrees;
    bool errorsCurrent = false;  // tangentErrorDegrees belong to the pose drawn
    std::vector<glm::mat4> joints;  // the skin's joint matrices at the pose (empty: unskinned)
    // The compare set is the fresh one and this pose morphs: until the split or compare-angle
    // view shows it, it holds the file's deltas added, not the fresh generator on the morphed corners.
    bool compareStale = false;
  };
  // Packs a deformed instance's corners into its vertex buffer.
  void uploadDeformed(const DeformedInstance& deformed);
  // An item's corners, packed (kMeshVertexLayout) with `frame`'s positions, normals and tangents,
  // into a mesh's buffers: welded as they are packed where it has indices, else all at once.
  void fillMeshBuffers(GpuMesh& mesh, const gltf::DrawItem& item, const CornerFrames& frame);
  // Its triangles, with the vertex array bound.
  static void drawMesh(const GpuMesh& mesh);
  std::vector<DeformedInstance> deformed_;
  std::optional<PoseTime> pose_;  // the pose drawn; none: the rest pose as loaded
  std::vector<std::vector<float>> compareTangents_;  // per scene item (setCompareTangents)
  std::vector<Texture> textures_;      // per scene image, linear data (empty when unused or failed)
  std::vector<Texture> srgbTextures_;  // per scene image, sRGB colour (empty when unused or failed)
  Texture sphereMap_;
  SamplerCache samplers_;  // the glTF samplers the materials' textures name
  std::optional<EnvironmentTextures> environment_;  // built on first use, kept across scenes
  double environmentMilliseconds_ = 0;
  std::vector<Light> lights_;
  glm::vec3 boundsMin_{-1}, boundsMax_{1};
  // The rest pose's bounds, which auto exposure is judged at (whiteRadiance); measured by the
  // first setPose after setScene (which poses the rest first when asked for another pose).
  glm::vec3 exposureBoundsMin_{-1}, exposureBoundsMax_{1};
  bool restPoseMeasured_ = false;
  Framebuffer shadowFramebuffer_;
  Texture shadowTexture_;
  int shadowSize_ = 0;
  Framebuffer shadowCubeFramebuffer_;
  Texture shadowCube_;
  int shadowCubeSize_ = 0;
  ShadowKey shadowKey_;
  int sceneVersion_ = 0;
  int shadowPasses_ = 0;
  int meshUploads_ = 0;
  VertexArray glyphArray_;
  Buffer glyphBuffer_;
  GLsizei glyphVertices_ = 0;
  int glyphsBuiltFor_ = -1;
  bool glyphsShowAnisotropy_ = false;  // what the glyphs were built for: directions, or frames
  // Per image, the pixels of those an anisotropy texture uses (empty elsewhere, and where one
  // could not be decoded), as uploaded: the glyphs sample them where the shader samples the GL's.
  std::vector<DecodedImage> directionImages_;
};

}  // namespace tangent::viewer
