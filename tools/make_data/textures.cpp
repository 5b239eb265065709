// SPDX-License-Identifier: MIT
#include "textures.hpp"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <iostream>
#include <span>

#include "tangent/output.hpp"

namespace make_data {

// Encoded in memory (the format from the name's extension), then written as every output of
// the project is (tangent/output.hpp): atomically, never through a link to another kind of
// file. False, said on stderr naming the file, where either fails.
bool writeImage(const std::filesystem::path& path, int width, int height, int channels, const std::vector<unsigned char>& pixels) {
  auto out = OIIO::ImageOutput::create(path.string());
  std::vector<unsigned char> encoded;
  OIIO::Filesystem::IOVecOutput memory(encoded);
  OIIO::Filesystem::IOProxy* proxy = &memory;
  OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::UINT8);
  spec.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
  const bool encodedOk = out && out->supports("ioproxy") && out->open(path.string(), spec) &&
                         out->write_image(OIIO::TypeDesc::UINT8, pixels.data()) && out->close();
  if (!encodedOk) {
    std::cerr << "tangent-make-data: " << path.string() << ": cannot encode the image: " << (out ? out->geterror() : OIIO::geterror())
              << "\n";
    return false;
  }
  try {
    tangent::output::writeFileAtomic(path, {std::span<const std::uint8_t>(encoded.data(), encoded.size())});
  } catch (const std::exception& e) {
    std::cerr << "tangent-make-data: " << e.what() << "\n";
    return false;
  }
  return true;
}

bool writeBumpNormalMap(const std::filesystem::path& path, int size, int bumpsPerSide) {
  std::vector<unsigned char> pixels(static_cast<std::size_t>(size) * size * 3);
  const double cell = double(size) / bumpsPerSide, radius = cell * 0.35;
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const double cx = std::fmod(x + 0.5, cell) - cell / 2;
      const double cy = -(std::fmod(y + 0.5, cell) - cell / 2);  // image rows go down, +y is up
      const double r = std::hypot(cx, cy);
      double n[3] = {0, 0, 1};
      if (r < radius) {
        // Height h = sqrt(R^2 - r^2) scaled; normal = normalize(-dh/dx, -dh/dy, 1).
        const double h = std::sqrt(radius * radius - r * r) + 1e-6;
        const double slope = 0.6;
        n[0] = slope * cx / h;
        n[1] = slope * cy / h;
        const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + 1);
        for (double& c : n) c /= length;
      }
      for (int k = 0; k < 3; ++k)
        pixels[(static_cast<std::size_t>(y) * size + x) * 3 + k] = static_cast<unsigned char>(std::lround((n[k] * 0.5 + 0.5) * 255));
    }
  }
  return writeImage(path, size, size, 3, pixels);
}

bool writeSpecularRegions(const std::filesystem::path& path, int size) {
  std::vector<unsigned char> pixels(static_cast<std::size_t>(size) * size * 4);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const int region = (x * 3) / size;  // vertical bands: green, white, black
      const unsigned char colors[3][3] = {{40, 255, 60}, {255, 255, 255}, {0, 0, 0}};
      unsigned char* p = &pixels[(static_cast<std::size_t>(y) * size + x) * 4];
      for (int c = 0; c < 3; ++c) p[c] = colors[region][c];
      p[3] = region == 2 ? 0 : 255;
    }
  }
  return writeImage(path, size, size, 4, pixels);
}

bool writeWhite(const std::filesystem::path& path) { return writeImage(path, 4, 4, 3, std::vector<unsigned char>(4 * 4 * 3, 255)); }


bool writeSphereMap(const std::filesystem::path& path, int size) {
  std::vector<unsigned char> pixels(static_cast<std::size_t>(size) * size * 3);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const double sx = (x + 0.5) / size * 2 - 1, sy = 1 - (y + 0.5) / size * 2;
      const double r2 = sx * sx + sy * sy;
      double color[3] = {0.1, 0.1, 0.12};
      if (r2 <= 1) {
        const double up = sy;  // reflection's up component grows with image height
        const double sky = std::clamp(up * 0.5 + 0.5, 0.0, 1.0);
        color[0] = 0.35 + 0.25 * sky;
        color[1] = 0.35 + 0.35 * sky;
        color[2] = 0.40 + 0.55 * sky;
        if (up < 0) color[0] = color[1] = color[2] = 0.25 + 0.1 * (1 + up);
        const double sun = std::exp(-((sx - 0.35) * (sx - 0.35) + (sy - 0.45) * (sy - 0.45)) * 60);
        for (double& c : color) c = std::min(1.0, c + sun);
      }
      for (int c = 0; c < 3; ++c) pixels[(static_cast<std::size_t>(y) * size + x) * 3 + c] = static_cast<unsigned char>(std::lround(color[c] * 255));
    }
  }
  return writeImage(path, size, size, 3, pixels);
}

bool writeCircularDirections(const std::filesystem::path& path, int size) {
  std::vector<unsigned char> pixels(static_cast<std::size_t>(size) * size * 3);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      // Tangent space: T = +u = +x, B = up in the image (-v) = +y.
      const double px = (x + 0.5) / size * 2 - 1, py = 1 - (y + 0.5) / size * 2;
      const double r = std::hypot(px, py);
      const double dx = r > 1e-6 ? -py / r : 1, dy = r > 1e-6 ? px / r : 0;  // counter-clockwise around the centre
      unsigned char* p = &pixels[(static_cast<std::size_t>(y) * size + x) * 3];
      p[0] = static_cast<unsigned char>(std::lround((dx * 0.5 + 0.5) * 255));
      p[1] = static_cast<unsigned char>(std::lround((dy * 0.5 + 0.5) * 255));
      p[2] = static_cast<unsigned char>(std::lround(std::clamp(0.5 + r, 0.5, 1.0) * 255));
    }
  }
  return writeImage(path, size, size, 3, pixels);
}

}  // namespace make_data
