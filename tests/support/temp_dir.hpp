// SPDX-License-Identifier: MIT
// A fresh directory per test, removed afterwards: tests never share files.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <random>
#include <string>

namespace tangent::testing {

class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::random_device random;
    path_ = std::filesystem::temp_directory_path() /
            ("libtangent-" + std::string(info ? info->name() : "test") + "-" + std::to_string(random()));
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

// ../shared/assets beside the checkout, or "" when absent.
inline std::filesystem::path sharedAssets() {
  const std::filesystem::path dir = std::filesystem::path(TANGENT_SOURCE_DIR) / ".." / "shared" / "assets";
  return std::filesystem::is_directory(dir) ? dir : std::filesystem::path();
}

}  // namespace tangent::testing
