// SPDX-License-Identifier: MIT
// Every feature define the C++ side can emit is used by the GLSL, and every define the GLSL
// tests is one the C++ side can emit.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <set>

#include "shader_features.hpp"

namespace {

TEST(ShaderDefines, CppTableAndGlslAgree) {
  namespace fs = std::filesystem;
  std::set<std::string> cpp;
  for (const auto& entry : tangent::viewer::kFeatureDefines) cpp.insert(entry.define);
  for (const auto& entry : tangent::viewer::kDebugViews)
    if (entry.define) cpp.insert(entry.define);

  std::set<std::string> glsl;
  const std::regex tested(R"re((?:#\s*(?:ifdef|ifndef)\s+|defined\s*\(\s*)([A-Z][A-Z0-9_]+))re");
  std::size_t files = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(TANGENT_SOURCE_DIR) / "shaders")) {
    std::ifstream in(entry.path());
    const std::string text(std::istreambuf_iterator<char>(in), {});
    ++files;
    for (auto it = std::sregex_iterator(text.begin(), text.end(), tested); it != std::sregex_iterator(); ++it) glsl.insert((*it)[1].str());
  }
  ASSERT_GT(files, 5u);
  EXPECT_EQ(cpp, glsl);
}

TEST(ShaderDefines, VariantTextHasOneLinePerFeature) {
  using tangent::viewer::Feature;
  const auto features = static_cast<tangent::viewer::FeatureSet>(Feature::normalMap) | static_cast<tangent::viewer::FeatureSet>(Feature::shadows);
  EXPECT_EQ(tangent::viewer::definesFor(features, tangent::viewer::DebugView::handedness),
            "#define HAS_NORMAL_MAP\n#define USE_SHADOWS\n#define DEBUG_HANDEDNESS\n");
  EXPECT_EQ(tangent::viewer::definesFor(0, tangent::viewer::DebugView::lit), "");
}

}  // namespace
