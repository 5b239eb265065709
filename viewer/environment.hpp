// SPDX-License-Identifier: MIT
// Image-based lighting from a built-in procedural environment (a sky over a ground, with a
// sun), prepared on the CPU at start-up by the split-sum approximation of Karis, "Real Shading
// in Unreal Engine 4" (SIGGRAPH 2013 course notes):
//   - specular: the environment prefiltered with the GGX distribution (N = V = R assumed) into
//     the mip levels of a cube map, roughness = level / (levels - 1), by importance sampling
//     with filtered lookups (Krivanek and Colbert, "Real-time Shading with Filtered Importance
//     Sampling", EGSR 2008: each sample reads the source mip whose texel matches its solid angle);
//   - the BRDF's scale and bias on F0, (A, B) = integral of (1 - Fc, Fc) * f * cos / F0-free,
//     tabulated over (N.V, roughness) with the viewer's BRDF (GGX, Smith height-correlated);
//   - diffuse: irradiance from the first nine spherical harmonics (Ramamoorthi and Hanrahan, "An
//     Efficient Representation for Irradiance Environment Maps", SIGGRAPH 2001).
// The environment is normalized: its mean radiance over the sphere is 1 (in luminance), so the
// renderer scales it to the lights' level.
#pragma once

#include <glm/glm.hpp>

#include <array>
#include <vector>

#include "gl_objects.hpp"

namespace tangent::viewer {

// The procedural environment's radiance towards world direction `direction` (unit; +y up),
// before normalization.
glm::vec3 proceduralSky(const glm::vec3& direction);

// A face-major cube map level: 6 faces of size x size RGB texels, in GL's face order (+X, -X,
// +Y, -Y, +Z, -Z), rows as GL uploads them.
struct CubeLevel {
  int size = 0;
  std::vector<glm::vec3> texels;
};

// The world direction through the centre of texel (x, y) of cube face `face` (GL's convention).
glm::vec3 cubeTexelDirection(int face, int x, int y, int size);

struct EnvironmentMaps {
  std::vector<CubeLevel> specular;      // level i prefiltered for roughness i / (levels - 1)
  std::array<glm::vec3, 9> irradianceSh{};  // E(n) / pi = sum of irradianceSh[i] * basis_i(n) (ibl.glsl)
  int brdfLutSize = 0;
  std::vector<glm::vec2> brdfLut;       // (A, B); x: N.V, y: roughness, texel centres
};

struct EnvironmentOptions {
  int baseSize = 64;        // the sharpest level's face size
  int levels = 6;           // 64, 32, 16, 8, 4, 2
  int specularSamples = 96; // GGX samples per prefiltered texel
  int brdfLutSize = 32;
  int brdfSamples = 256;
};

// Builds the maps on the CPU (about a million samples with the defaults).
EnvironmentMaps buildEnvironment(const EnvironmentOptions& options = {});

// The split-sum (A, B) of the viewer's BRDF at (N.V, roughness), by GGX importance sampling
// (also what the table holds).
glm::vec2 integrateSplitSumBrdf(float nv, float roughness, int samples);

// E(n) / pi from the nine coefficients, as ibl.glsl's environmentIrradiance evaluates it.
glm::vec3 irradianceOverPi(const std::array<glm::vec3, 9>& sh, const glm::vec3& n);

// The maps on the GPU.
struct EnvironmentTextures {
  Texture specularCube;  // GL_TEXTURE_CUBE_MAP, RGB16F, mipmapped by roughness
  Texture brdfLut;       // GL_TEXTURE_2D, RG16F
  std::array<glm::vec3, 9> irradianceSh{};
  float maxLod = 0;      // the roughest level
};

EnvironmentTextures uploadEnvironment(const EnvironmentMaps& maps);

}  // namespace tangent::viewer
