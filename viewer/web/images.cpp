// SPDX-License-Identifier: MIT
// The web build's image decoding (viewer/textures.hpp): stb_image from Debian's libstb-dev in
// place of OpenImageIO, with the same limits and messages. PNG and JPEG (what glTF's core
// allows); WebP and KTX2 are refused naming the image.
#include <stb_image.h>
#include <stb_image_resize.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cstdio>

#include "../textures.hpp"

namespace tangent::viewer {

bool decodeImage(const gltf::ImageSource& source, DecodedImage& image, std::string& error) {
  std::vector<unsigned char> fileBytes;
  const unsigned char* bytes = nullptr;
  std::size_t size = 0;
  if (!checkImageFile(source, error)) return false;  // also an image with neither file nor bytes
  if (!source.bytes.empty()) {
    bytes = reinterpret_cast<const unsigned char*>(source.bytes.data());
    size = source.bytes.size();
  } else if (!source.file.empty()) {
    std::FILE* in = std::fopen(source.file.string().c_str(), "rb");
    if (!in) {
      error = source.label + ": cannot be decoded: cannot open " + source.file.string();
      return false;
    }
    unsigned char buffer[65536];
    for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, in)) > 0;) fileBytes.insert(fileBytes.end(), buffer, buffer + n);
    std::fclose(in);
    bytes = fileBytes.data();
    size = fileBytes.size();
  }
  int width = 0, height = 0, channels = 0;
  if (!bytes || !stbi_info_from_memory(bytes, static_cast<int>(size), &width, &height, &channels)) {
    error = source.label + ": cannot be decoded: " + (bytes ? stbi_failure_reason() : "no bytes") + " (the web viewer decodes PNG and JPEG)";
    return false;
  }
  if (width <= 0 || height <= 0) {
    error = source.label + ": has no pixels (" + std::to_string(width) + " x " + std::to_string(height) + ")";
    return false;
  }
  if (std::uint64_t(width) * std::uint64_t(height) * 4 > kMaxDecodedImageBytes) {
    error = source.label + ": its header claims " + std::to_string(width) + " x " + std::to_string(height) +
            " pixels, over the viewer's limit; not decoded";
    return false;
  }
  // Four channels out: grey into R, G and B, a missing alpha 255; alpha kept straight.
  unsigned char* pixels = stbi_load_from_memory(bytes, static_cast<int>(size), &width, &height, &channels, 4);
  if (!pixels) {
    error = source.label + ": cannot be read: " + stbi_failure_reason();
    return false;
  }
  image.width = width;
  image.height = height;
  image.rgba.assign(pixels, pixels + static_cast<std::size_t>(width) * height * 4);
  stbi_image_free(pixels);
  return true;
}

bool resizeImage(const DecodedImage& image, int width, int height, std::vector<unsigned char>& rgba) {
  return stbir_resize_uint8(image.rgba.data(), image.width, image.height, 0, rgba.data(), width, height, 0, 4) != 0;
}

bool writePng(const std::string& path, int width, int height, const std::vector<unsigned char>& rgbaBottomUp, std::string& error) {
  stbi_flip_vertically_on_write(1);
  if (!stbi_write_png(path.c_str(), width, height, 4, rgbaBottomUp.data(), width * 4)) {
    error = path + ": cannot be written";
    return false;
  }
  return true;
}

}  // namespace tangent::viewer
