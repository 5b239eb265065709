// SPDX-License-Identifier: MIT
// Bounded, checked loading of untrusted glTF (README "Security and limits"): the JSON's
// nesting depth is measured before any parser recurses into it, and every index, offset,
// count and stride the tools read is checked against the document (64-bit arithmetic) before
// anything is allocated or read from it. Errors name the file and a JSON pointer to the element.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

namespace tangent::gltf::detail {

// Deepest nesting of arrays and objects a glTF's JSON may have. glTF's own structure nests
// about 8 deep; the rest is room for extras and extensions.
inline constexpr std::size_t kMaxJsonDepth = 256;
// Largest glTF JSON text accepted (a JSON chunk or .gltf file).
inline constexpr std::size_t kMaxJsonBytes = std::size_t(512) << 20;

// Throws InputError when `text` is longer than kMaxJsonBytes or nests deeper than kMaxJsonDepth
// (strings are skipped). `what` names the text in the message: a glTF, a check configuration.
void checkJsonDepth(std::string_view text, const std::string& label, const char* what = "glTF JSON");

// Types, references and declared sizes of the whole document (glTF 2.0 schema rules the tools
// depend on); throws InputError "<label>: /pointer/to/element: what is wrong".
void validateDocument(const nlohmann::ordered_json& doc, const std::string& label);

}  // namespace tangent::gltf::detail
