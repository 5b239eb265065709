// SPDX-License-Identifier: MIT
// Where the viewer's shaders and demo data are: beside an installed executable
// (PREFIX/bin/tangent-view finds PREFIX/share/libtangent/{shaders,data}), or in the source tree
// when it runs from the build tree. Never a path compiled in for an installed copy, so an
// installed viewer works wherever it is installed and whatever the source tree does.
#pragma once

#include <filesystem>
#include <system_error>

namespace tangent::viewer {

inline std::filesystem::path executableFolder() {
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::filesystem::path() : self.parent_path();
}

// name: "shaders" or "data".
inline std::filesystem::path resourceFolder(const char* name) {
  namespace fs = std::filesystem;
  const fs::path folder = executableFolder();
  std::error_code ec;
  if (!folder.empty() && fs::equivalent(folder, TANGENT_BUILD_BIN_DIR, ec))
    return fs::path(std::string(name) == "shaders" ? TANGENT_SOURCE_SHADER_DIR : TANGENT_SOURCE_DATA_DIR);
  return (folder / TANGENT_INSTALLED_RESOURCES / name).lexically_normal();
}

}  // namespace tangent::viewer
