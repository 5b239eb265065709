// SPDX-License-Identifier: MIT
// A screenshot as the viewer tests read it: RGB floats 0..1 (sRGB-encoded, as written), rows top
// down, through OpenImageIO.
#pragma once

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <array>
#include <cstddef>
#include <filesystem>
#include <vector>

namespace tangent::testing {

struct Image {
  int width = 0, height = 0;
  std::vector<float> rgb;  // top-down rows, 0..1
  const float* pixel(int x, int y) const { return &rgb[(static_cast<std::size_t>(y) * width + x) * 3]; }
  std::array<float, 3> at(int x, int y) const {
    const float* p = pixel(x, y);
    return {p[0], p[1], p[2]};
  }
  float luma(int x, int y) const {
    const auto c = at(x, y);
    return 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2];
  }
};

// The PNG at `path`; an empty image (and a test failure) where it cannot be read.
inline Image readPng(const std::filesystem::path& path) {
  Image image;
  auto in = OIIO::ImageInput::open(path.string());
  if (!in) {
    ADD_FAILURE() << "cannot read " << path << ": " << OIIO::geterror();
    return image;
  }
  image.width = in->spec().width;
  image.height = in->spec().height;
  image.rgb.resize(static_cast<std::size_t>(image.width) * image.height * 3);
  in->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, image.rgb.data());
  return image;
}

}  // namespace tangent::testing
