// SPDX-License-Identifier: MIT
// Included before every source of the web build (cmake/web.cmake): what emscripten 3.1.6's
// libc++ lacks of C++20. std::bit_cast is the compiler's builtin.
#pragma once
#ifdef __cplusplus
#include <bit>
#include <type_traits>
#if !defined(__cpp_lib_bit_cast)
namespace std {
template <class To, class From>
  requires(sizeof(To) == sizeof(From) && is_trivially_copyable_v<To> && is_trivially_copyable_v<From>)
constexpr To bit_cast(const From& from) noexcept {
  return __builtin_bit_cast(To, from);
}
}  // namespace std
#endif
#endif
