// SPDX-License-Identifier: MIT
// What the renderer's files (renderer.cpp and renderer_*.cpp, one pass or concern each) share:
// vertex packing, uniforms, the lights' photometry, a few rules of glTF's.
#pragma once

#include <array>
#include <span>
#include <string>
#include <vector>

#include "renderer.hpp"
#include "vertex_layout.hpp"

namespace tangent::viewer::renderer_detail {

// Enables and points every attribute of a layout at the bound GL_ARRAY_BUFFER of packed floats.
void setVertexLayout(std::span<const VertexAttribute> layout);

// A draw item's corners packed as kMeshVertexLayout says; positions, normals and tangents from
// `frame` (the item's own, or deformed ones): all of them, or corner c alone into
// kMeshFloatsPerVertex floats at `corner`.
std::vector<float> packMeshVertices(const gltf::DrawItem& item, const CornerFrames& frame);
void packMeshCorner(const gltf::DrawItem& item, const CornerFrames& frame, std::size_t c, float* corner);

void setUniform(GLuint program, const char* name, const glm::mat4& m);
void setUniform(GLuint program, const char* name, const glm::mat3& m);
void setUniform(GLuint program, const char* name, const glm::vec2& v);
void setUniform(GLuint program, const char* name, const glm::vec3& v);
void setUniform(GLuint program, const char* name, const glm::vec4& v);
void setUniform(GLuint program, const char* name, float v);
void setUniform(GLuint program, const char* name, int v);
// A texture's UV set and KHR_texture_transform, for textureUv() in mesh.frag.
void setUvUniforms(GLuint program, const std::string& prefix, const gltf::TextureRef& ref);
// KHR_texture_transform as textureUv() applies it: uv' = M * (u, v, 1).
glm::mat3 uvTransformMatrix(const gltf::TextureRef& ref);

// Every texture a material may sample.
std::array<const gltf::TextureRef*, 11> textureRefs(const gltf::MaterialDesc& m);

float maxChannel(const glm::vec3& c);
// Light `light`'s direction from `point` and its attenuation there (distance and cone), as
// lighting.glsl's lightAt has them in the light's units.
float attenuationAt(const Light& light, const glm::vec3& point, bool physical, glm::vec3& toLight);

// Where a light is judged from: the scene's centre, or, for a point or spot light inside the
// scene, a tenth of the scene's radius from the light towards the centre.
glm::vec3 pointLitFrom(const Light& light, glm::vec3 center, float radius);

// The illuminance (lux) a light of the file gives at the scene's centre, judged from where
// pointLitFrom says; 0 where that is not a positive number (inf intensity times black is NaN).
float illuminanceAtCenter(const Light& light, glm::vec3 center, float radius);

// The file's lights (at most kMaxLights: the one place the count is capped; what is left out
// goes to `messages`), the one that casts the shadow first; the default rig where it has none.
std::vector<Light> lightsFrom(const gltf::Scene& scene, glm::vec3 center, float radius, std::vector<std::string>& messages);

// BLEND materials cast shadows cut out where their alpha is below this, as MASK materials do
// at their alphaCutoff: a half-transparent surface casts where it is mostly opaque.
inline constexpr float kBlendShadowCutoff = 0.5f;
// A node whose transform mirrors (negative determinant) turns its triangles' winding around, so
// its front faces are the clockwise ones (glTF 2.0 3.7.4).
void frontFace(bool mirrored);

const gltf::MaterialDesc* materialOf(const gltf::Scene& scene, int material);

}  // namespace tangent::viewer::renderer_detail
