// SPDX-License-Identifier: MIT
#include "textures.hpp"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <vector>

namespace tangent::viewer {
namespace {

std::string extensionFor(const std::string& mimeType) {
  if (mimeType == "image/jpeg") return ".jpg";
  if (mimeType == "image/webp") return ".webp";
  if (mimeType == "image/ktx2") return ".ktx2";
  return ".png";
}

}  // namespace

bool decodeImage(const gltf::ImageSource& source, DecodedImage& image, std::string& error) {
  std::unique_ptr<OIIO::ImageInput> input;
  OIIO::Filesystem::IOMemReader memory(source.bytes.data(), source.bytes.size());
  // glTF's alpha is straight (unassociated): keep colour as stored, not premultiplied.
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  if (!source.bytes.empty()) {
    // With a configuration given, OIIO takes the proxy from it, not from the third argument.
    OIIO::Filesystem::IOProxy* proxy = &memory;
    config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
    input = OIIO::ImageInput::open("embedded" + extensionFor(source.mimeType), &config, &memory);
  } else if (!source.file.empty()) {
    input = OIIO::ImageInput::open(source.file.string(), &config);
  }
  if (!input) {
    error = source.label + ": cannot be decoded: " + OIIO::geterror();
    return false;
  }
  const OIIO::ImageSpec& spec = input->spec();
  const int width = spec.width, height = spec.height, channels = spec.nchannels;
  std::vector<unsigned char> pixels(static_cast<std::size_t>(width) * height * channels);
  if (!input->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT8, pixels.data())) {
    error = source.label + ": cannot be read: " + input->geterror();
    return false;
  }
  input->close();
  image.width = width;
  image.height = height;
  image.rgba.assign(static_cast<std::size_t>(width) * height * 4, 255);
  for (std::size_t p = 0; p < static_cast<std::size_t>(width) * height; ++p) {
    for (int c = 0; c < 4; ++c) {
      if (c < channels) image.rgba[4 * p + c] = pixels[p * channels + c];
      else if (c < 3) image.rgba[4 * p + c] = pixels[p * channels];  // grey: spread the one channel
    }
  }
  return true;
}

Texture uploadTexture(const DecodedImage& image, bool srgb) {
  Texture texture = makeTexture();
  glBindTexture(GL_TEXTURE_2D, texture.get());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  // glTF's UV origin is the image's first row: upload rows as stored, sample uv as given.
  glTexImage2D(GL_TEXTURE_2D, 0, srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, image.width, image.height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
               image.rgba.data());
  glGenerateMipmap(GL_TEXTURE_2D);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
  return texture;
}

Texture loadTexture(const gltf::ImageSource& source, bool srgb, std::string& error) {
  DecodedImage image;
  if (!decodeImage(source, image, error)) return {};
  return uploadTexture(image, srgb);
}

bool writePng(const std::string& path, int width, int height, const std::vector<unsigned char>& rgbaBottomUp, std::string& error) {
  auto out = OIIO::ImageOutput::create(path);
  if (!out) {
    error = path + ": " + OIIO::geterror();
    return false;
  }
  OIIO::ImageSpec spec(width, height, 4, OIIO::TypeDesc::UINT8);
  if (!out->open(path, spec)) {
    error = path + ": " + out->geterror();
    return false;
  }
  const std::ptrdiff_t row = static_cast<std::ptrdiff_t>(width) * 4;
  // Start at the last row and step backwards: top-down image from bottom-up pixels.
  const bool ok = out->write_image(OIIO::TypeDesc::UINT8, rgbaBottomUp.data() + row * (height - 1), 4, -row);
  if (!out->close() || !ok) {
    error = path + ": " + out->geterror();
    return false;
  }
  return true;
}

}  // namespace tangent::viewer
