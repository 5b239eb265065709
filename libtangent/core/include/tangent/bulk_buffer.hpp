// SPDX-License-Identifier: MIT
// Large arrays without the cost of their first touch: elements are default-initialized (no
// zero fill that is overwritten anyway) and, on Linux, blocks of 2 MiB or more are asked for
// transparent huge pages, so that one page fault maps 2 MiB instead of 4 KiB. On virtual
// machines a page fault costs microseconds: at a million triangles the zero fills and faults
// of plain std::vector took more time than computing the tangents.
#pragma once

#include <cstddef>
#include <cstdlib>
#include <new>
#include <utility>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace tangent {

inline constexpr std::size_t kHugePage = std::size_t(2) << 20;

// At least `bytes` on 2 MiB boundaries, rounded up to whole 2 MiB, with transparent huge pages
// asked for (advice only: without them it still works); null when out of memory. Free with
// std::free. For blocks of kHugePage and more.
inline void* allocateHugePages(std::size_t bytes) noexcept {
  const std::size_t rounded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
  void* p = std::aligned_alloc(kHugePage, rounded);
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  if (p) madvise(p, rounded, MADV_HUGEPAGE);
#endif
  return p;
}

template <typename T>
struct BulkAllocator {
  using value_type = T;

  BulkAllocator() noexcept = default;
  template <typename U>
  BulkAllocator(const BulkAllocator<U>&) noexcept {}

  T* allocate(std::size_t n) {
    const std::size_t bytes = n * sizeof(T);
    if (bytes < kHugePage) return static_cast<T*>(::operator new(bytes));
    void* p = allocateHugePages(bytes);
    if (!p) throw std::bad_alloc();
    return static_cast<T*>(p);
  }
  void deallocate(T* p, std::size_t n) noexcept {
    if (n * sizeof(T) < kHugePage) ::operator delete(p);
    else std::free(p);
  }
  // Default-initialize: no zero fill for arithmetic types.
  template <typename U>
  void construct(U* p) noexcept {
    ::new (static_cast<void*>(p)) U;
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
  template <typename U>
  bool operator==(const BulkAllocator<U>&) const noexcept {
    return true;
  }
};

// A std::vector whose resize() leaves new arithmetic elements uninitialized.
template <typename T>
using BulkVector = std::vector<T, BulkAllocator<T>>;

}  // namespace tangent
