// SPDX-License-Identifier: MIT
// The vertex layouts of the viewer's programs: one table each, from which the renderer packs
// the vertices and sets up the vertex arrays. The GLSL's `layout(location = N) in` lines
// must agree with them; tests check that in the text (tests/viewer/shader_defines_test.cpp)
// and in every linked variant (tangent-view --check-shaders, run by the viewer tests).
#pragma once

#include <cstddef>
#include <span>

namespace tangent::viewer {

// Where a mesh vertex attribute's values come from in a gltf::DrawItem.
enum class VertexSource : unsigned char { position, normal, tangent, uvNormal, uv0, uv1, tangentError, cornerProblems, compareTangent, color };

struct VertexAttribute {
  const char* name;      // the GLSL input
  unsigned location;     // its layout location
  int components;        // floats
  int offset;            // in floats from the start of the vertex
  VertexSource source;   // for mesh vertices; unused by the glyph layout
};

// mesh.vert, and shadow_depth.vert, which reads a subset of it from the same vertex arrays.
inline constexpr VertexAttribute kMeshVertexLayout[] = {
    {"a_position", 0, 3, 0, VertexSource::position},
    {"a_normal", 1, 3, 3, VertexSource::normal},
    {"a_tangent", 2, 4, 6, VertexSource::tangent},  // xyz, w = handedness
    {"a_uvNormal", 3, 2, 10, VertexSource::uvNormal},
    {"a_uv0", 4, 2, 12, VertexSource::uv0},
    {"a_uv1", 5, 2, 14, VertexSource::uv1},
    {"a_tangentError", 6, 1, 16, VertexSource::tangentError},
    {"a_cornerProblems", 7, 1, 17, VertexSource::cornerProblems},
    {"a_tangentCompare", 8, 4, 18, VertexSource::compareTangent},  // the set compared with the file's
    {"a_color", 9, 4, 22, VertexSource::color},  // COLOR_0 as RGBA, white where the primitive has none
};

// lines.vert: tangent-frame glyphs.
inline constexpr VertexAttribute kLineVertexLayout[] = {
    {"a_position", 0, 3, 0, VertexSource::position},
    {"a_color", 1, 3, 3, VertexSource::position},
};

// Floats per vertex: the end of the last attribute. The offsets must be packed in order.
constexpr int floatsPerVertex(std::span<const VertexAttribute> layout) {
  int end = 0;
  for (const auto& attribute : layout) {
    if (attribute.offset != end) return -1;
    end += attribute.components;
  }
  return end;
}

inline constexpr int kMeshFloatsPerVertex = floatsPerVertex(kMeshVertexLayout);
inline constexpr int kLineFloatsPerVertex = floatsPerVertex(kLineVertexLayout);
static_assert(kMeshFloatsPerVertex == 26 && kLineFloatsPerVertex == 6, "offsets must follow each other");

}  // namespace tangent::viewer
