// SPDX-License-Identifier: MIT
// libFuzzer target: the core on arbitrary arrays. The bytes choose a vertex count, a
// triangle list and every float (raw bits or a table of awkward values: zeros, signed zeros,
// denormals, huge, NaN, infinities), the method and the thread count. The core must answer
// every input with a finite unit tangent and w = +-1 on every corner (tangent.hpp); anything
// else aborts.
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "fuzz_support.hpp"
#include "tangent/tangent.hpp"

namespace {

class Bytes {
 public:
  Bytes(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  std::uint8_t byte() { return at_ < size_ ? data_[at_++] : 0; }
  float value(bool raw) {
    if (raw) {
      std::uint32_t bits = 0;
      for (int i = 0; i < 4; ++i) bits = bits << 8 | byte();
      float f;
      std::memcpy(&f, &bits, 4);
      return f;
    }
    static const float table[] = {0.0f, -0.0f, 1.0f, -1.0f, 0.5f, 2.0f, 1e-30f, -1e-30f, 1e30f,
                                  1e-45f, 3.0f, 0.25f, 1.0f + 1e-7f, std::numeric_limits<float>::quiet_NaN(),
                                  std::numeric_limits<float>::infinity(), 0.1f};
    return table[byte() % 16];
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t at_ = 0;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Bytes in(data, size);
  const std::size_t vertices = 1 + in.byte() % 32;
  const std::size_t triangles = 1 + in.byte() % 48;
  const std::uint8_t flags = in.byte();
  const bool raw = flags & 1;
  const tangent::Method method = static_cast<tangent::Method>((flags >> 1) % 4);  // every Method
  std::vector<float> positions(3 * vertices), normals(3 * vertices), uvs(2 * vertices);
  for (float& v : positions) v = in.value(raw);
  for (float& v : normals) v = in.value(raw);
  for (float& v : uvs) v = in.value(raw);
  std::vector<std::uint32_t> corners(3 * triangles);
  for (auto& c : corners) c = in.byte() % vertices;
  tangent::fuzz::computeAndCheck(positions, normals, uvs, corners, method, 1 + (flags >> 3) % 3);
  return 0;
}
