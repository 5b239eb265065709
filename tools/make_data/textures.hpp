// SPDX-License-Identifier: MIT
// The textures tangent-make-data writes (PNG through OpenImageIO); each returns false where the
// file cannot be written (OIIO::geterror() says why).
#pragma once

#include <filesystem>
#include <vector>

namespace make_data {

// `pixels`: `channels` bytes per pixel, rows top down.
bool writeImage(const std::filesystem::path& path, int width, int height, int channels, const std::vector<unsigned char>& pixels);
// Tangent-space normal map of circular raised bumps (OpenGL convention, +y up, as glTF wants).
bool writeBumpNormalMap(const std::filesystem::path& path, int size, int bumpsPerSide);
// Specular map with green, white and black regions (RGB: highlight colour, A: strength).
bool writeSpecularRegions(const std::filesystem::path& path, int size);
// A 4 x 4 white RGB image.
bool writeWhite(const std::filesystem::path& path);
// Sphere map: a sky gradient over a darker ground with a bright sun, as seen in a mirror ball.
bool writeSphereMap(const std::filesystem::path& path, int size);
// anisotropy_direction.png: KHR_materials_anisotropy's direction texture for a disc whose UVs
// map [-1, 1]^2 onto the image (u = (x + 1) / 2, v = (1 - y) / 2): circular brushing, the
// direction turning around the centre (RG: the direction in (tangent, bitangent) space mapped
// from [-1, 1], B: strength, fading to half towards the centre where the circles are tight).
bool writeCircularDirections(const std::filesystem::path& path, int size);

}  // namespace make_data
