// SPDX-License-Identifier: MIT
// Every feature define the C++ side can emit is used by the GLSL, and every define the GLSL
// tests is one the C++ side can emit.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <set>

#include "shader_features.hpp"
#include "vertex_layout.hpp"

namespace {

TEST(ShaderDefines, CppTableAndGlslAgree) {
  namespace fs = std::filesystem;
  std::set<std::string> cpp;
  for (const auto& entry : tangent::viewer::kFeatureDefines) cpp.insert(entry.define);
  for (const auto& entry : tangent::viewer::kDebugViews)
    if (entry.define) cpp.insert(entry.define);
  for (const auto& entry : tangent::viewer::kToneMappings)
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

// `layout(location = N) in TYPE NAME;` lines of a shader file, by name: location and floats.
std::map<std::string, std::pair<unsigned, int>> declaredInputs(const std::string& file) {
  std::ifstream in(std::filesystem::path(TANGENT_SOURCE_DIR) / "shaders" / file);
  const std::string text(std::istreambuf_iterator<char>(in), {});
  const std::regex input(R"re(layout\s*\(\s*location\s*=\s*(\d+)\s*\)\s*in\s+(float|vec2|vec3|vec4)\s+(\w+)\s*;)re");
  std::map<std::string, std::pair<unsigned, int>> inputs;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), input); it != std::sregex_iterator(); ++it) {
    const std::string type = (*it)[2].str();
    inputs[(*it)[3].str()] = {static_cast<unsigned>(std::stoul((*it)[1].str())), type == "float" ? 1 : type[3] - '0'};
  }
  return inputs;
}

template <std::size_t N>
std::map<std::string, std::pair<unsigned, int>> tableInputs(const tangent::viewer::VertexAttribute (&layout)[N]) {
  std::map<std::string, std::pair<unsigned, int>> inputs;
  for (const auto& attribute : layout) inputs[attribute.name] = {attribute.location, attribute.components};
  return inputs;
}

// The GLSL declares exactly the table's inputs (the shadow pass a subset of the mesh's); the
// linked programs are checked too, under Xvfb (viewer.Viewer.LinkedProgramsMatchTheVertexLayoutTables).
TEST(ShaderDefines, VertexInputsMatchTheLayoutTables) {
  const auto mesh = tableInputs(tangent::viewer::kMeshVertexLayout);
  EXPECT_EQ(declaredInputs("mesh.vert"), mesh);
  EXPECT_EQ(declaredInputs("lines.vert"), tableInputs(tangent::viewer::kLineVertexLayout));
  const auto shadow = declaredInputs("shadow_depth.vert");
  EXPECT_FALSE(shadow.empty());
  for (const auto& [name, value] : shadow) {
    ASSERT_TRUE(mesh.count(name)) << name;
    EXPECT_EQ(mesh.at(name), value) << name;
  }
}

}  // namespace
