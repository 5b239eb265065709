// SPDX-License-Identifier: MIT
// The one place the viewer's two targets differ in GL: desktop OpenGL 3.3 core through libepoxy,
// or WebGL2 (OpenGL ES 3.0) under emscripten. kDesktopGl is the capability check: what WebGL2
// lacks (seamless cube-map filtering as a switch, the debug-output extension, GL_MULTISAMPLE as
// a switch) runs only where it is true; README.md lists what the web viewer leaves out.
#pragma once

#ifdef __EMSCRIPTEN__
#include <GLES3/gl3.h>
// Enums of desktop-only calls, so that code guarded by kDesktopGl compiles on both targets.
#ifndef GL_TEXTURE_CUBE_MAP_SEAMLESS
#define GL_TEXTURE_CUBE_MAP_SEAMLESS 0x884F
#endif
#ifndef GL_MULTISAMPLE
#define GL_MULTISAMPLE 0x809D
#endif
#else
#include <epoxy/gl.h>
#endif

namespace tangent::viewer {
#ifdef __EMSCRIPTEN__
inline constexpr bool kDesktopGl = false;
#else
inline constexpr bool kDesktopGl = true;
#endif
}  // namespace tangent::viewer
