// SPDX-License-Identifier: MIT
// A cube shadow map for a point light: six 90-degree perspective depth views from the light,
// one per face of a GL depth cube map, read in shadows.glsl (POINT_SHADOWS) by a
// samplerCubeShadow with the fragment's depth in the face its direction falls in: the face's
// eye-space depth is the largest component of the light-to-fragment vector.
#pragma once

#include <glm/glm.hpp>

#include "gl_objects.hpp"

namespace tangent::viewer {

// The view-projection of face `face` (GL's order: +X, -X, +Y, -Y, +Z, -Z) from `light`: the
// image it draws is the face as GL's cube map lookup reads it (OpenGL 4.6 table 8.19).
glm::mat4 cubeFaceViewProjection(const glm::vec3& light, int face, float nearPlane, float farPlane);

// A depth cube map of size x size faces, compared in hardware (GL_LEQUAL) and filtered
// bilinearly, as the 2D shadow map is.
Texture makeShadowCube(int size);

}  // namespace tangent::viewer
