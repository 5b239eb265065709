// SPDX-License-Identifier: MIT
// SHA-256 of bytes in memory, as 64 lowercase hex digits: the digest the batch manifest records
// for files, here for short texts (the fingerprints of `tangent check --format codeclimate`).
#pragma once

#include <string>
#include <string_view>

namespace tangent::gltf {

std::string sha256Hex(std::string_view bytes);

}  // namespace tangent::gltf
