// SPDX-License-Identifier: MIT
#include "samplers.hpp"

namespace tangent::viewer {

GLenum glWrap(gltf::TextureSampler::Wrap wrap) {
  switch (wrap) {
    case gltf::TextureSampler::Wrap::clampToEdge: return GL_CLAMP_TO_EDGE;
    case gltf::TextureSampler::Wrap::mirroredRepeat: return GL_MIRRORED_REPEAT;
    case gltf::TextureSampler::Wrap::repeat: break;
  }
  return GL_REPEAT;
}

GLenum glMagFilter(gltf::TextureSampler::Filter filter) {
  // Magnification has no mipmap modes: NEAREST or LINEAR only.
  using Filter = gltf::TextureSampler::Filter;
  return filter == Filter::nearest || filter == Filter::nearestMipmapNearest || filter == Filter::nearestMipmapLinear ? GL_NEAREST
                                                                                                                      : GL_LINEAR;
}

GLenum glMinFilter(gltf::TextureSampler::Filter filter) {
  using Filter = gltf::TextureSampler::Filter;
  switch (filter) {
    case Filter::nearest: return GL_NEAREST;
    case Filter::linear: return GL_LINEAR;
    case Filter::nearestMipmapNearest: return GL_NEAREST_MIPMAP_NEAREST;
    case Filter::linearMipmapNearest: return GL_LINEAR_MIPMAP_NEAREST;
    case Filter::nearestMipmapLinear: return GL_NEAREST_MIPMAP_LINEAR;
    case Filter::linearMipmapLinear:
    case Filter::automatic: break;
  }
  return GL_LINEAR_MIPMAP_LINEAR;
}

GLuint SamplerCache::get(const gltf::TextureSampler& sampler) {
  for (const auto& [settings, object] : samplers_)
    if (settings == sampler) return object.get();
  GLuint id = 0;
  glGenSamplers(1, &id);
  glSamplerParameteri(id, GL_TEXTURE_WRAP_S, static_cast<GLint>(glWrap(sampler.wrapS)));
  glSamplerParameteri(id, GL_TEXTURE_WRAP_T, static_cast<GLint>(glWrap(sampler.wrapT)));
  glSamplerParameteri(id, GL_TEXTURE_MAG_FILTER, static_cast<GLint>(glMagFilter(sampler.magFilter)));
  glSamplerParameteri(id, GL_TEXTURE_MIN_FILTER, static_cast<GLint>(glMinFilter(sampler.minFilter)));
  samplers_.emplace_back(sampler, Sampler(id));
  return id;
}

}  // namespace tangent::viewer
