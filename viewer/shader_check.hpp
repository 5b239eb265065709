// SPDX-License-Identifier: MIT
// `tangent-view --check-shaders`: links the mesh program in a spread of its variants, the
// shadow and the line programs, and compares what GL reports of their vertex inputs with the
// layout tables (viewer/vertex_layout.hpp). The viewer tests run it under Xvfb.
#pragma once

#include <string>
#include <vector>

#include "shader_library.hpp"

namespace tangent::viewer {

// Problems found (empty: all agree); `checked` counts the programs linked and compared.
std::vector<std::string> checkShaderInputs(ShaderLibrary& shaders, int& checked);

}  // namespace tangent::viewer
