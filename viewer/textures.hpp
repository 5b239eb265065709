// SPDX-License-Identifier: MIT
// Images decoded through OpenImageIO (files or embedded bytes) into GL textures.
#pragma once

#include <string>
#include <vector>

#include "gl_objects.hpp"
#include "tangent/scene.hpp"

namespace tangent::viewer {

struct DecodedImage {
  int width = 0, height = 0;
  std::vector<unsigned char> rgba;  // rows as stored (glTF's UV origin is the first row)
};

// RGBA8 pixels of an image (grey spread to RGB, alpha 255 when absent); false + error.
bool decodeImage(const gltf::ImageSource& source, DecodedImage& image, std::string& error);

// A mipmapped, repeating texture: SRGB8_ALPHA8 storage for colour (the sampler decodes it to
// linear), RGBA8 for data (normals, metallic-roughness, occlusion, specular strength).
Texture uploadTexture(const DecodedImage& image, bool srgb);

// decodeImage then uploadTexture; on failure an empty Texture and `error` says why.
Texture loadTexture(const gltf::ImageSource& source, bool srgb, std::string& error);

// Writes RGBA8 pixels (rows bottom-up, as glReadPixels gives them) as a PNG; false + error.
bool writePng(const std::string& path, int width, int height, const std::vector<unsigned char>& rgbaBottomUp, std::string& error);

}  // namespace tangent::viewer
