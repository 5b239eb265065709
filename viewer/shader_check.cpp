// SPDX-License-Identifier: MIT
#include "shader_check.hpp"

#include <algorithm>
#include <set>
#include <span>

#include "vertex_layout.hpp"

namespace tangent::viewer {
namespace {

int componentsOf(GLenum type) {
  switch (type) {
    case GL_FLOAT: return 1;
    case GL_FLOAT_VEC2: return 2;
    case GL_FLOAT_VEC3: return 3;
    case GL_FLOAT_VEC4: return 4;
    default: return -1;
  }
}

// Every active input of `program` is in `layout` at its location with its component count;
// every entry GL knows (location >= 0) is where the table says. Entries seen active are added
// to `used`.
void compare(GLuint program, const std::string& label, std::span<const VertexAttribute> layout, std::set<std::string>& used,
             std::vector<std::string>& problems) {
  GLint active = 0, longest = 0;
  glGetProgramiv(program, GL_ACTIVE_ATTRIBUTES, &active);
  glGetProgramiv(program, GL_ACTIVE_ATTRIBUTE_MAX_LENGTH, &longest);
  for (GLint i = 0; i < active; ++i) {
    std::string name(static_cast<std::size_t>(std::max(longest, 1)), '\0');
    GLsizei length = 0;
    GLint size = 0;
    GLenum type = 0;
    glGetActiveAttrib(program, static_cast<GLuint>(i), longest, &length, &size, &type, name.data());
    name.resize(static_cast<std::size_t>(length));
    if (name.rfind("gl_", 0) == 0) continue;  // built-ins such as gl_VertexID
    const VertexAttribute* entry = nullptr;
    for (const auto& attribute : layout)
      if (name == attribute.name) entry = &attribute;
    if (!entry) {
      problems.push_back(label + ": active input " + name + " is not in the layout table");
      continue;
    }
    used.insert(name);
    if (componentsOf(type) != entry->components || size != 1)
      problems.push_back(label + ": " + name + " has " + std::to_string(componentsOf(type)) + " components, the table " +
                         std::to_string(entry->components));
  }
  for (const auto& attribute : layout) {
    const GLint location = glGetAttribLocation(program, attribute.name);
    if (location >= 0 && location != static_cast<GLint>(attribute.location))
      problems.push_back(label + ": " + attribute.name + " at location " + std::to_string(location) + ", the table says " +
                         std::to_string(attribute.location));
  }
}

}  // namespace

std::vector<std::string> checkShaderInputs(ShaderLibrary& shaders, int& checked) {
  std::vector<std::string> problems;
  checked = 0;
  // Mesh variants: none, each feature alone, all features, every view and every tone mapping
  // with all features.
  FeatureSet all = 0;
  for (const auto& entry : kFeatureDefines) all |= static_cast<FeatureSet>(entry.feature);
  struct Variant {
    FeatureSet features;
    DebugView view;
    ToneMapping toneMapping;
  };
  std::vector<Variant> variants{{0, DebugView::lit, ToneMapping::none}};
  for (const auto& entry : kFeatureDefines) variants.push_back({static_cast<FeatureSet>(entry.feature), DebugView::lit, ToneMapping::none});
  for (const auto& view : kDebugViews) variants.push_back({all, view.view, ToneMapping::khrPbrNeutral});
  for (const auto& entry : kToneMappings) variants.push_back({all, DebugView::lit, entry.toneMapping});
  std::set<std::string> meshUsed, lineUsed;
  for (const auto& variant : variants) {
    const std::string label = "mesh program with\n" + definesFor(variant.features, variant.view, variant.toneMapping);
    try {
      compare(shaders.mesh(variant.features, variant.view, variant.toneMapping), label, kMeshVertexLayout, meshUsed, problems);
      ++checked;
    } catch (const std::exception& e) {
      problems.push_back(e.what());
    }
  }
  try {
    const auto alphaMask = static_cast<FeatureSet>(Feature::alphaMask);
    for (const FeatureSet features : {FeatureSet{0}, alphaMask, alphaMask | static_cast<FeatureSet>(Feature::baseColorMap)}) {
      compare(shaders.depthOnly(features), "depth-only program with\n" + definesFor(features, DebugView::lit), kMeshVertexLayout, meshUsed,
              problems);
      ++checked;
    }
    compare(shaders.lines(), "lines program", kLineVertexLayout, lineUsed, problems);
    ++checked;
  } catch (const std::exception& e) {
    problems.push_back(e.what());
  }
  // A table entry no variant reads is a stale entry.
  for (const auto& attribute : kMeshVertexLayout)
    if (!meshUsed.count(attribute.name)) problems.push_back(std::string("mesh layout entry ") + attribute.name + " is read by no variant");
  for (const auto& attribute : kLineVertexLayout)
    if (!lineUsed.count(attribute.name)) problems.push_back(std::string("line layout entry ") + attribute.name + " is read by no program");
  return problems;
}

}  // namespace tangent::viewer
