// SPDX-License-Identifier: MIT
// GL sampler objects for glTF samplers (glTF 2.0 3.8.4): one per distinct wrapping and
// filtering, bound beside a texture's unit, so that an image two textures sample differently is
// still uploaded once.
#pragma once

#include <utility>
#include <vector>

#include "gl_objects.hpp"
#include "tangent/scene.hpp"

namespace tangent::viewer {

// The GL enums of a glTF sampler. A filter the file leaves out is what the Khronos glTF Sample
// Viewer uses then: LINEAR when magnifying, LINEAR_MIPMAP_LINEAR (trilinear) when minifying.
GLenum glWrap(gltf::TextureSampler::Wrap wrap);
GLenum glMagFilter(gltf::TextureSampler::Filter filter);
GLenum glMinFilter(gltf::TextureSampler::Filter filter);

class SamplerCache {
 public:
  // The sampler object of these settings, made on first use (needs a current GL context).
  GLuint get(const gltf::TextureSampler& sampler);
  void clear() { samplers_.clear(); }

 private:
  std::vector<std::pair<gltf::TextureSampler, Sampler>> samplers_;  // a handful per scene
};

}  // namespace tangent::viewer
