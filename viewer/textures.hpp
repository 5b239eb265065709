// Images decoded through OpenImageIO (files or embedded bytes) into GL textures.
#pragma once

#include <string>

#include "gl_objects.hpp"
#include "tangent/scene.hpp"

namespace tangent::viewer {

// A mipmapped RGBA8 texture; on failure an empty Texture and `error` says why.
Texture loadTexture(const gltf::ImageSource& source, std::string& error);

// Writes RGBA8 pixels (rows bottom-up, as glReadPixels gives them) as a PNG; false + error.
bool writePng(const std::string& path, int width, int height, const std::vector<unsigned char>& rgbaBottomUp, std::string& error);

}  // namespace tangent::viewer
