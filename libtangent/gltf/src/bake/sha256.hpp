// SPDX-License-Identifier: MIT
// SHA-256 (FIPS 180-4, section 6.2), for the batch manifest's input digests.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>

namespace tangent::gltf::detail {

class Sha256 {
 public:
  Sha256();
  void update(std::span<const std::uint8_t> bytes);
  std::string hexDigest();  // finishes; call once

 private:
  void block(const std::uint8_t* p);
  std::array<std::uint32_t, 8> state_;
  std::array<std::uint8_t, 64> buffer_{};
  std::size_t buffered_ = 0;
  std::uint64_t length_ = 0;  // bytes
};

}  // namespace tangent::gltf::detail
