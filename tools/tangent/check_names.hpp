// SPDX-License-Identifier: MIT
// How every `tangent check` report names a primitive and sums up a finding.
#pragma once

#include <string>

#include "tangent/check.hpp"
#include "tangent/text.hpp"

namespace tangent::cli {

inline std::string primitiveName(const gltf::PrimitiveCheck& p) {
  return "mesh " + std::to_string(p.mesh) + (p.meshName.empty() ? "" : " '" + text::quoted(p.meshName) + "'") +
         " primitive " + std::to_string(p.primitive);
}

// The primitive as a JSON pointer into the document (SARIF's logical location, the code quality
// report's element).
inline std::string primitivePointer(const gltf::PrimitiveCheck& p) {
  return "/meshes/" + std::to_string(p.mesh) + "/primitives/" + std::to_string(p.primitive);
}

inline std::string findingSummary(const gltf::CheckFinding& f) {
  return std::to_string(f.failed) + " of " + std::to_string(f.total) + " " + f.unit + ": " + f.message;
}

}  // namespace tangent::cli
