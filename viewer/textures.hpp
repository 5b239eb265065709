// SPDX-License-Identifier: MIT
// Images decoded through OpenImageIO (files or embedded bytes) into GL textures.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "gl_objects.hpp"
#include "tangent/scene.hpp"

namespace tangent::viewer {

struct DecodedImage {
  int width = 0, height = 0;
  std::vector<unsigned char> rgba;  // rows as stored (glTF's UV origin is the first row)
  // What the decoder itself said while decoding (libpng's warnings, which it writes to stderr),
  // each naming the image: for the note channel, never straight to the terminal.
  std::vector<std::string> notes;
};

// An image file (source.file) under the input rule of every reader (tangent/input_file.hpp): a
// regular file of bounded size, and not empty. False + error naming the image otherwise, also
// for an image with neither file nor bytes (ImageSource::missing says why); true for an embedded
// image.
bool checkImageFile(const gltf::ImageSource& source, std::string& error);

// The most memory an image may take decoded, as RGBA8: 1 GiB, a 16384 x 16384 texture. The
// header's size is checked before decoding, so that a small file claiming 60000 x 60000 pixels is
// refused instead of asking for 14 GB.
inline constexpr std::uint64_t kMaxDecodedImageBytes = std::uint64_t(1) << 30;

// RGBA8 pixels of an image (grey spread to RGB, alpha 255 when absent); false + error, which
// names the image (ImageSource::label), also for a file checkImageFile refuses and for one over
// kMaxDecodedImageBytes.
bool decodeImage(const gltf::ImageSource& source, DecodedImage& image, std::string& error);

// Downscales an image wider or taller than maxSize (GL_MAX_TEXTURE_SIZE) to fit, keeping its
// aspect ratio; returns a note naming it (`label`) and both sizes, or "" when it fits already.
// A resampled copy at width x height into rgba (OpenImageIO; stb_image_resize on the web).
bool resizeImage(const DecodedImage& image, int width, int height, std::vector<unsigned char>& rgba);

std::string fitTextureSize(DecodedImage& image, int maxSize, const std::string& label);

// What a colour texture whose image is missing or cannot be decoded shows instead: a checker of
// kMissingImageCells x kMissingImageCells cells over the UV square, magenta and near-black
// (kMissingImageCellTexels texels across each, so that bilinear filtering keeps the cells
// sharp), a pattern no asset means. Data textures (normals, metallic-roughness, occlusion) are
// left out instead: a checker there would read as relief or metal.
inline constexpr int kMissingImageCells = 8;
inline constexpr int kMissingImageCellTexels = 8;
DecodedImage missingImageChecker();

// GL_MAX_TEXTURE_SIZE of the current context.
int maxTextureSize();

// A mipmapped, repeating texture: SRGB8_ALPHA8 storage for colour (the sampler decodes it to
// linear), RGBA8 for data (normals, metallic-roughness, occlusion, specular strength).
Texture uploadTexture(const DecodedImage& image, bool srgb);

// decodeImage, fitTextureSize, then uploadTexture; on failure an empty Texture. Errors and notes
// (the decoder's own among them) go to `messages`.
Texture loadTexture(const gltf::ImageSource& source, bool srgb, std::vector<std::string>& messages);

// Writes RGBA8 pixels (rows bottom-up, as glReadPixels gives them) as a PNG; false + error.
bool writePng(const std::string& path, int width, int height, const std::vector<unsigned char>& rgbaBottomUp, std::string& error);

}  // namespace tangent::viewer
