// SPDX-License-Identifier: MIT
#include "shader_library.hpp"

#include <algorithm>
#include <fstream>
#include <iterator>
#include <regex>
#include <stdexcept>

#include "debug_colours.hpp"
#include "tangent/input_file.hpp"
#include "tangent/tangent.hpp"

namespace tangent::viewer {
namespace {

std::string infoLog(GLuint object, bool isProgram) {
  GLint length = 0;
  isProgram ? glGetProgramiv(object, GL_INFO_LOG_LENGTH, &length) : glGetShaderiv(object, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
  isProgram ? glGetProgramInfoLog(object, length, nullptr, log.data()) : glGetShaderInfoLog(object, length, nullptr, log.data());
  return log;
}

GLuint compile(GLenum stage, const std::string& text, const std::string& name) {
  const GLuint shader = glCreateShader(stage);
  const char* source = text.c_str();
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    const std::string log = infoLog(shader, false);
    glDeleteShader(shader);
    throw std::runtime_error("shader " + name + " does not compile:\n" + log);
  }
  return shader;
}

}  // namespace

// The shaders are GLSL 3.30 core. WebGL2 compiles GLSL ES 3.00: the same language for what they
// use, with a different #version line and no default precision for floats in fragment shaders
// nor for the shadow, 3D and array samplers in either stage. Everything a target needs is put
// here, after the #version line, with the variant's defines.
std::string forTarget(std::string text, const std::string& defines) {
  const auto lineEnd = text.find('\n');  // after "#version ..."
  if (lineEnd == std::string::npos || text.compare(0, 9, "#version ") != 0) throw std::runtime_error("shader does not begin with #version");
  if (!kDesktopGl) {
    text.replace(0, lineEnd, "#version 300 es");
    return text.insert(std::string("#version 300 es").size() + 1,
                       "precision highp float;\nprecision highp int;\nprecision highp sampler2D;\nprecision highp samplerCube;\n"
                       "precision highp sampler2DShadow;\nprecision highp samplerCubeShadow;\nprecision highp sampler3D;\n"
                       "precision highp sampler2DArray;\n" + defines);
  }
  return text.insert(lineEnd + 1, defines);
}

std::string ShaderLibrary::source(const std::string& file, int depth) const {
  if (depth > 8) throw std::runtime_error("shader includes nest too deep at " + file);
  tangent::gltf::requireInputFile(directory_ / file, "a shader");  // the input rule: no FIFO, device or folder
  std::ifstream in(directory_ / file);
  if (!in) throw std::runtime_error("cannot read shader " + (directory_ / file).string());
  std::string text(std::istreambuf_iterator<char>(in), {});
  static const std::regex include(R"re(^[ \t]*#include[ \t]+"([^"]+)"[^\n]*)re", std::regex::multiline);
  std::string out;
  auto begin = text.cbegin();
  std::smatch match;
  while (std::regex_search(begin, text.cend(), match, include)) {
    out.append(begin, match[0].first);
    out += source(match[1].str(), depth + 1);
    begin = match[0].second;
  }
  out.append(begin, text.cend());
  return out;
}

GLuint ShaderLibrary::program(const std::string& vertexFile, const std::string& fragmentFile, const std::string& defines) {
  const auto key = std::make_tuple(vertexFile, fragmentFile, defines);
  if (auto it = programs_.find(key); it != programs_.end()) return it->second.get();
  auto withDefines = [&](std::string text) { return forTarget(std::move(text), defines); };
  const GLuint vertex = compile(GL_VERTEX_SHADER, withDefines(source(vertexFile)), vertexFile);
  GLuint fragment = 0;
  try {
    fragment = compile(GL_FRAGMENT_SHADER, withDefines(source(fragmentFile)), fragmentFile + " with\n" + defines);
  } catch (...) {
    glDeleteShader(vertex);
    throw;
  }
  Program program(glCreateProgram());
  glAttachShader(program.get(), vertex);
  glAttachShader(program.get(), fragment);
  glLinkProgram(program.get());
  glDeleteShader(vertex);
  glDeleteShader(fragment);
  GLint ok = 0;
  glGetProgramiv(program.get(), GL_LINK_STATUS, &ok);
  if (!ok) throw std::runtime_error("program " + vertexFile + " + " + fragmentFile + " does not link:\n" + infoLog(program.get(), true));
  const GLuint id = program.get();
  programs_.emplace(key, std::move(program));
  return id;
}

// glTF's handedness from the library's one rule: the w that counter-clockwise UVs get (-1).
// normal_mapping.glsl is written for it and refuses to compile under another.
static const std::string kHandednessDefine =
    "#define TANGENT_W_CCW_UV " + std::to_string(static_cast<int>(tangent::handedness(1.0f, tangent::kGltfUvOrigin))) + "\n";

GLuint ShaderLibrary::mesh(FeatureSet features, DebugView view, ToneMapping toneMapping, int lightCount) {
  static const std::string kColourDefines = debugColourDefines();
  const std::string lights = "#define LIGHT_COUNT " + std::to_string(std::clamp(lightCount, 0, kMaxLights)) + "\n";
  return program("mesh.vert", "mesh.frag", definesFor(features, view, toneMapping) + lights + kHandednessDefine + kColourDefines);
}
GLuint ShaderLibrary::depthOnly(FeatureSet features) {
  features &= static_cast<FeatureSet>(Feature::alphaMask) | static_cast<FeatureSet>(Feature::baseColorMap);
  if (!has(features, Feature::alphaMask)) features = 0;  // the texture matters only to the alpha test
  // Drawn once per light change, not per frame: one program for every UV set and transform.
  if (has(features, Feature::baseColorMap)) features |= static_cast<FeatureSet>(Feature::uvTransforms);
  return program("shadow_depth.vert", "shadow_depth.frag", definesFor(features, DebugView::lit));
}
GLuint ShaderLibrary::lines() { return program("lines.vert", "lines.frag", ""); }

}  // namespace tangent::viewer
