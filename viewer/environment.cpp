// SPDX-License-Identifier: MIT
// The split-sum image-based lighting of environment.hpp; the papers it follows are named there.
#include "environment.hpp"

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace tangent::viewer {
namespace {

constexpr float kPi = glm::pi<float>();

float luminance(const glm::vec3& c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

// The i-th of n points of the Hammersley set in [0, 1)^2 (radical inverse in base 2).
glm::vec2 hammersley(std::uint32_t i, std::uint32_t n) {
  std::uint32_t bits = i;
  bits = (bits << 16u) | (bits >> 16u);
  bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
  bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
  bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
  bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
  return {static_cast<float>(i) / static_cast<float>(n), static_cast<float>(bits) * 2.3283064365386963e-10f};
}

// A half vector drawn from the GGX distribution D(h) (h.n)around n = +z, for GGX alpha `alpha`:
// cos^2(theta) = (1 - u) / (1 + (alpha^2 - 1) u) inverts the CDF of D(h) (h.n) in theta.
glm::vec3 sampleGgxHalfVector(glm::vec2 u, float alpha) {
  const float phi = 2 * kPi * u.x;
  const float cosTheta = std::sqrt((1 - u.y) / (1 + (alpha * alpha - 1) * u.y));
  const float sinTheta = std::sqrt(std::max(0.0f, 1 - cosTheta * cosTheta));
  return {sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta};
}

float distributionGgx(float nh, float alpha) {
  const float a2 = alpha * alpha;
  const float d = nh * nh * (a2 - 1) + 1;
  return a2 / (kPi * d * d);
}

// V = G / (4 |N.L| |N.V|), Smith height-correlated: pbr.glsl's visibilityGgx.
float visibilityGgx(float nl, float nv, float alpha) {
  const float a2 = alpha * alpha;
  const float l = nl + std::sqrt(a2 + (1 - a2) * nl * nl);
  const float v = nv + std::sqrt(a2 + (1 - a2) * nv * nv);
  return 1 / (l * v);
}

// An orthonormal frame around n: columns t, b, n.
glm::mat3 frameAround(const glm::vec3& n) {
  const glm::vec3 up = std::abs(n.z) < 0.999f ? glm::vec3(0, 0, 1) : glm::vec3(1, 0, 0);
  const glm::vec3 t = glm::normalize(glm::cross(up, n));
  return {t, glm::cross(n, t), n};
}

// The solid angle of texel (x, y) of a face of `size`, up to the factor (2 / size)^2.
float texelSolidAngleWeight(int x, int y, int size) {
  const float s = 2 * (static_cast<float>(x) + 0.5f) / static_cast<float>(size) - 1;
  const float t = 2 * (static_cast<float>(y) + 0.5f) / static_cast<float>(size) - 1;
  return 1 / std::pow(1 + s * s + t * t, 1.5f);
}

// Bilinear lookup of a cube level in `direction`, clamped at face edges.
glm::vec3 sampleCube(const CubeLevel& level, const glm::vec3& direction) {
  const glm::vec3 a = glm::abs(direction);
  int face;
  float sc, tc, ma;
  // GL's table of major axes (OpenGL 4.6 8.13): s = (sc / |ma| + 1) / 2, t = (tc / |ma| + 1) / 2.
  if (a.x >= a.y && a.x >= a.z) {
    face = direction.x > 0 ? 0 : 1;
    ma = a.x;
    sc = direction.x > 0 ? -direction.z : direction.z;
    tc = -direction.y;
  } else if (a.y >= a.z) {
    face = direction.y > 0 ? 2 : 3;
    ma = a.y;
    sc = direction.x;
    tc = direction.y > 0 ? direction.z : -direction.z;
  } else {
    face = direction.z > 0 ? 4 : 5;
    ma = a.z;
    sc = direction.z > 0 ? direction.x : -direction.x;
    tc = -direction.y;
  }
  const int size = level.size;
  const float x = std::clamp((sc / ma + 1) * 0.5f * static_cast<float>(size) - 0.5f, 0.0f, static_cast<float>(size - 1));
  const float y = std::clamp((tc / ma + 1) * 0.5f * static_cast<float>(size) - 0.5f, 0.0f, static_cast<float>(size - 1));
  const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);
  const int x1 = std::min(x0 + 1, size - 1), y1 = std::min(y0 + 1, size - 1);
  const float fx = x - static_cast<float>(x0), fy = y - static_cast<float>(y0);
  const glm::vec3* texels = &level.texels[static_cast<std::size_t>(face) * size * size];
  auto at = [&](int tx, int ty) { return texels[static_cast<std::size_t>(ty) * size + tx]; };
  return glm::mix(glm::mix(at(x0, y0), at(x1, y0), fx), glm::mix(at(x0, y1), at(x1, y1), fx), fy);
}

// The source and its box-filtered mip chain down to 1 x 1, for filtered importance sampling.
std::vector<CubeLevel> mipChain(CubeLevel source) {
  std::vector<CubeLevel> chain{std::move(source)};
  while (chain.back().size > 1) {
    const CubeLevel& fine = chain.back();
    CubeLevel coarse{fine.size / 2, {}};
    coarse.texels.resize(static_cast<std::size_t>(6) * coarse.size * coarse.size);
    for (int face = 0; face < 6; ++face)
      for (int y = 0; y < coarse.size; ++y)
        for (int x = 0; x < coarse.size; ++x) {
          const glm::vec3* f = &fine.texels[static_cast<std::size_t>(face) * fine.size * fine.size];
          const auto at = [&](int tx, int ty) { return f[static_cast<std::size_t>(ty) * fine.size + tx]; };
          coarse.texels[(static_cast<std::size_t>(face) * coarse.size + y) * coarse.size + x] =
              0.25f * (at(2 * x, 2 * y) + at(2 * x + 1, 2 * y) + at(2 * x, 2 * y + 1) + at(2 * x + 1, 2 * y + 1));
        }
    chain.push_back(std::move(coarse));
  }
  return chain;
}

glm::vec3 sampleChain(const std::vector<CubeLevel>& chain, const glm::vec3& direction, float lod) {
  lod = std::clamp(lod, 0.0f, static_cast<float>(chain.size() - 1));
  const auto lower = static_cast<std::size_t>(lod);
  const std::size_t upper = std::min(lower + 1, chain.size() - 1);
  return glm::mix(sampleCube(chain[lower], direction), sampleCube(chain[upper], direction), lod - static_cast<float>(lower));
}

// One level of the specular map: the GGX-weighted mean of the environment around each texel's
// direction, with N = V = R (Karis 2013), weighted by N.L as Karis' course notes do.
CubeLevel prefilterLevel(const std::vector<CubeLevel>& chain, int size, float roughness, int samples) {
  CubeLevel level{size, {}};
  level.texels.resize(static_cast<std::size_t>(6) * size * size);
  const float alpha = std::max(roughness * roughness, 1e-3f);
  const float sourceTexelSolidAngle = 4 * kPi / (6.0f * static_cast<float>(chain[0].size * chain[0].size));
  for (int face = 0; face < 6; ++face)
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        const glm::vec3 n = cubeTexelDirection(face, x, y, size);
        const glm::mat3 frame = frameAround(n);
        glm::vec3 sum(0);
        float weight = 0;
        for (int i = 0; i < samples; ++i) {
          const glm::vec3 hLocal = sampleGgxHalfVector(hammersley(static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(samples)), alpha);
          const glm::vec3 h = frame * hLocal;
          const glm::vec3 l = 2 * glm::dot(n, h) * h - n;
          const float nl = glm::dot(n, l);
          if (nl <= 0) continue;
          // pdf(l) = D(h) (n.h) / (4 v.h), and v.h = n.h when v = n.
          const float pdf = distributionGgx(hLocal.z, alpha) / 4;
          const float sampleSolidAngle = 1 / (static_cast<float>(samples) * pdf + 1e-6f);
          const float lod = 0.5f * std::log2(sampleSolidAngle / sourceTexelSolidAngle) + 1;
          sum += sampleChain(chain, l, lod) * nl;
          weight += nl;
        }
        level.texels[(static_cast<std::size_t>(face) * size + y) * size + x] = weight > 0 ? sum / weight : glm::vec3(0);
      }
  return level;
}

// Projection onto the nine real spherical harmonics, then the clamped cosine's convolution
// (A0 = pi, A1 = 2 pi / 3, A2 = pi / 4, Ramamoorthi and Hanrahan 2001), divided by pi and with
// each basis function's constant folded in, so that ibl.glsl evaluates E(n) / pi as the dot
// product with (1, y, z, x, xy, yz, 3z^2 - 1, xz, x^2 - y^2).
std::array<glm::vec3, 9> irradianceSh(const CubeLevel& level) {
  constexpr std::array<float, 9> kBasisConstant = {0.282095f, 0.488603f, 0.488603f, 0.488603f, 1.092548f,
                                                   1.092548f, 0.315392f, 1.092548f, 0.546274f};
  constexpr std::array<float, 9> kCosineLobe = {kPi, 2 * kPi / 3, 2 * kPi / 3, 2 * kPi / 3, kPi / 4, kPi / 4, kPi / 4, kPi / 4, kPi / 4};
  std::array<glm::vec3, 9> coefficients{};
  const int size = level.size;
  const float texelArea = (2.0f / static_cast<float>(size)) * (2.0f / static_cast<float>(size));
  for (int face = 0; face < 6; ++face)
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        const glm::vec3 d = cubeTexelDirection(face, x, y, size);
        const float solidAngle = texelSolidAngleWeight(x, y, size) * texelArea;
        const glm::vec3 radiance = level.texels[(static_cast<std::size_t>(face) * size + y) * size + x] * solidAngle;
        const std::array<float, 9> basis = {1, d.y, d.z, d.x, d.x * d.y, d.y * d.z, 3 * d.z * d.z - 1, d.x * d.z, d.x * d.x - d.y * d.y};
        for (int i = 0; i < 9; ++i) coefficients[i] += radiance * (kBasisConstant[i] * basis[i]);
      }
  for (int i = 0; i < 9; ++i) coefficients[i] *= kBasisConstant[i] * kCosineLobe[i] / kPi;
  return coefficients;
}

}  // namespace

glm::vec3 irradianceOverPi(const std::array<glm::vec3, 9>& sh, const glm::vec3& n) {
  const glm::vec3 e = sh[0] + sh[1] * n.y + sh[2] * n.z + sh[3] * n.x + sh[4] * (n.x * n.y) + sh[5] * (n.y * n.z) +
                      sh[6] * (3 * n.z * n.z - 1) + sh[7] * (n.x * n.z) + sh[8] * (n.x * n.x - n.y * n.y);
  return glm::max(e, glm::vec3(0));
}

glm::vec3 proceduralSky(const glm::vec3& direction) {
  // Sky: a warm, bright horizon fading to a blue zenith; ground: a dim brown, meeting the sky in
  // a soft horizon line two degrees wide; a sun towards the default rig's key light.
  const glm::vec3 horizon(1.2f, 1.12f, 1.0f), zenith(0.5f, 0.65f, 0.95f), ground(0.22f, 0.19f, 0.16f);
  const float up = std::max(direction.y, 0.0f);
  const glm::vec3 sky = glm::mix(horizon, zenith, std::sqrt(up));
  const glm::vec3 below = ground * (0.6f + 0.4f * (1 + std::min(direction.y, 0.0f)));
  const float t = std::clamp((direction.y + 0.02f) / 0.04f, 0.0f, 1.0f);
  glm::vec3 radiance = glm::mix(below, sky, t * t * (3 - 2 * t));
  const glm::vec3 sun = glm::normalize(glm::vec3(0.35f, 1.0f, 0.45f));
  const float c = glm::dot(direction, sun);
  if (c > 0.9996f) radiance += glm::vec3(100.0f, 95.0f, 85.0f);  // a disk 1.6 degrees in radius
  radiance += glm::vec3(1.0f, 0.9f, 0.7f) * (0.8f * std::exp((c - 1) * 40.0f));  // and its glow
  return radiance;
}

glm::vec3 cubeTexelDirection(int face, int x, int y, int size) {
  const float s = 2 * (static_cast<float>(x) + 0.5f) / static_cast<float>(size) - 1;
  const float t = 2 * (static_cast<float>(y) + 0.5f) / static_cast<float>(size) - 1;
  glm::vec3 d;
  switch (face) {
    case 0: d = {1, -t, -s}; break;
    case 1: d = {-1, -t, s}; break;
    case 2: d = {s, 1, t}; break;
    case 3: d = {s, -1, -t}; break;
    case 4: d = {s, -t, 1}; break;
    default: d = {-s, -t, -1}; break;
  }
  return glm::normalize(d);
}

glm::vec2 integrateSplitSumBrdf(float nv, float roughness, int samples) {
  // N = +z, V in the xz plane. With pdf(l) = D (n.h) / (4 v.h), each sample of f cos / pdf is
  // F V_vis 4 (n.l) (v.h) / (n.h); F = F0 (1 - Fc) + Fc splits it into the scale A and bias B.
  const glm::vec3 v(std::sqrt(std::max(0.0f, 1 - nv * nv)), 0, nv);
  const float alpha = std::max(roughness * roughness, 0.0025f);  // pbr.glsl's floor
  glm::vec2 sum(0);
  for (int i = 0; i < samples; ++i) {
    const glm::vec3 h = sampleGgxHalfVector(hammersley(static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(samples)), alpha);
    const float vh = glm::dot(v, h);
    const glm::vec3 l = 2 * vh * h - v;
    const float nl = l.z, nh = h.z;
    if (nl <= 0 || vh <= 0) continue;
    const float g = visibilityGgx(nl, nv, alpha) * 4 * nl * vh / nh;
    const float fc = std::pow(1 - vh, 5.0f);
    sum += glm::vec2((1 - fc) * g, fc * g);
  }
  return sum / static_cast<float>(samples);
}

EnvironmentMaps buildEnvironment(const EnvironmentOptions& options) {
  EnvironmentMaps maps;
  CubeLevel source{options.baseSize, {}};
  source.texels.resize(static_cast<std::size_t>(6) * source.size * source.size);
  double weightedLuminance = 0, totalWeight = 0;
  for (int face = 0; face < 6; ++face)
    for (int y = 0; y < source.size; ++y)
      for (int x = 0; x < source.size; ++x) {
        // 2 x 2 samples per texel, so that the sun's disk is not a single aliased texel.
        glm::vec3 radiance(0);
        for (int sy = 0; sy < 2; ++sy)
          for (int sx = 0; sx < 2; ++sx)
            radiance += 0.25f * proceduralSky(cubeTexelDirection(face, 2 * x + sx, 2 * y + sy, 2 * source.size));
        source.texels[(static_cast<std::size_t>(face) * source.size + y) * source.size + x] = radiance;
        const float w = texelSolidAngleWeight(x, y, source.size);
        weightedLuminance += static_cast<double>(luminance(radiance) * w);
        totalWeight += w;
      }
  const auto normalize = static_cast<float>(totalWeight / weightedLuminance);
  for (glm::vec3& texel : source.texels) texel *= normalize;
  maps.irradianceSh = irradianceSh(source);
  const std::vector<CubeLevel> chain = mipChain(source);
  maps.specular.push_back(source);
  for (int level = 1; level < options.levels; ++level) {
    const float roughness = static_cast<float>(level) / static_cast<float>(options.levels - 1);
    maps.specular.push_back(prefilterLevel(chain, std::max(options.baseSize >> level, 1), roughness, options.specularSamples));
  }
  maps.brdfLutSize = options.brdfLutSize;
  maps.brdfLut.resize(static_cast<std::size_t>(options.brdfLutSize) * options.brdfLutSize);
  for (int y = 0; y < options.brdfLutSize; ++y)
    for (int x = 0; x < options.brdfLutSize; ++x) {
      const float nv = (static_cast<float>(x) + 0.5f) / static_cast<float>(options.brdfLutSize);
      const float roughness = (static_cast<float>(y) + 0.5f) / static_cast<float>(options.brdfLutSize);
      maps.brdfLut[static_cast<std::size_t>(y) * options.brdfLutSize + x] = integrateSplitSumBrdf(nv, roughness, options.brdfSamples);
    }
  return maps;
}

EnvironmentTextures uploadEnvironment(const EnvironmentMaps& maps) {
  EnvironmentTextures textures;
  textures.irradianceSh = maps.irradianceSh;
  textures.maxLod = static_cast<float>(maps.specular.size() - 1);
  textures.specularCube = makeTexture();
  glBindTexture(GL_TEXTURE_CUBE_MAP, textures.specularCube.get());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  for (std::size_t level = 0; level < maps.specular.size(); ++level) {
    const CubeLevel& cube = maps.specular[level];
    const std::size_t faceTexels = static_cast<std::size_t>(cube.size) * cube.size;
    for (int face = 0; face < 6; ++face)
      glTexImage2D(GL_TEXTURE_CUBE_MAP_POSITIVE_X + face, static_cast<GLint>(level), GL_RGB16F, cube.size, cube.size, 0, GL_RGB, GL_FLOAT,
                   &cube.texels[face * faceTexels]);
  }
  glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_BASE_LEVEL, 0);
  glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAX_LEVEL, static_cast<GLint>(maps.specular.size() - 1));
  glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  for (const GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R}) glTexParameteri(GL_TEXTURE_CUBE_MAP, wrap, GL_CLAMP_TO_EDGE);
  if (kDesktopGl) glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);  // filter across face edges (always on in WebGL2)
  textures.brdfLut = makeTexture();
  glBindTexture(GL_TEXTURE_2D, textures.brdfLut.get());
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RG16F, maps.brdfLutSize, maps.brdfLutSize, 0, GL_RG, GL_FLOAT, maps.brdfLut.data());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  return textures;
}

}  // namespace tangent::viewer
