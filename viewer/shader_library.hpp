// SPDX-License-Identifier: MIT
// Shader programs from the files in shaders/: `#include "x.glsl"` resolved at load, feature
// defines inserted after #version, each variant compiled once and cached until reload().
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "gl_objects.hpp"
#include "shader_features.hpp"

namespace tangent::viewer {

// A shader file's text for this build's GL (GLSL 3.30 core, or GLSL ES 3.00 with precisions on
// the web, kDesktopGl) with a variant's defines after the #version line.
std::string forTarget(std::string text, const std::string& defines);

class ShaderLibrary {
 public:
  explicit ShaderLibrary(std::filesystem::path directory) : directory_(std::move(directory)) {}

  // The mesh program for a feature set, debug view and number of lights (0 to kMaxLights, the
  // light loop's trip count); throws std::runtime_error with the compiler's log on failure.
  GLuint mesh(FeatureSet features, DebugView view, ToneMapping toneMapping = ToneMapping::none, int lightCount = kMaxLights);
  // Depth only (the shadow map, the depth pre-pass); of the features, only alphaMask and
  // baseColorMap make a difference (an alpha test reads any UV set and transform).
  GLuint depthOnly(FeatureSet features = 0);
  GLuint lines();
  // Forgets every compiled program; the next request reads the files again ('r').
  void reload() { programs_.clear(); }
  std::size_t variantsCompiled() const { return programs_.size(); }

 private:
  GLuint program(const std::string& vertexFile, const std::string& fragmentFile, const std::string& defines);
  std::string source(const std::string& file, int depth = 0) const;

  std::filesystem::path directory_;
  std::map<std::tuple<std::string, std::string, std::string>, Program> programs_;
};

}  // namespace tangent::viewer
