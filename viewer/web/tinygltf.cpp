// SPDX-License-Identifier: MIT
// The web build's tinygltf and stb_image: Debian ships tinygltf as a native library and stb as
// headers, so the web viewer compiles their implementations here, once. The library never lets
// tinygltf decode images (libtangent/gltf/src/read/asset.cpp); the viewer's decoder is
// viewer/web/images.cpp.
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_RESIZE_IMPLEMENTATION
#include <stb_image.h>
#include <stb_image_write.h>
#include <stb_image_resize.h>

#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_INCLUDE_STB_IMAGE
#define TINYGLTF_NO_INCLUDE_STB_IMAGE_WRITE
#include <tiny_gltf.h>
