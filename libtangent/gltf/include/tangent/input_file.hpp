// SPDX-License-Identifier: MIT
// The one rule for every file the tools and the viewer open to read (glTF, mesh files, images,
// a sphere map, a second file to compare with): a regular file of bounded size. A folder, a FIFO
// (which blocks the reader until someone writes), a device (/dev/zero never ends) or a file past
// the limit is refused by name before anything reads it.
#pragma once

#include <cstdint>
#include <filesystem>

namespace tangent::gltf {

// Largest input file read whole (a GLB cannot be larger than 4 GiB).
inline constexpr std::uintmax_t kMaxInputBytes = std::uintmax_t(4) << 30;

// The size of `path` when it is a regular file below kMaxInputBytes; else throws InputError
// "<file>: <why>" (missing, a name too long, a directory, not a regular file, too large).
// `kind` names what was expected in the directory case: "a glTF file", "an image".
std::uintmax_t requireInputFile(const std::filesystem::path& path, const char* kind);

}  // namespace tangent::gltf
