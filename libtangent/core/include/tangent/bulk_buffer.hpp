// SPDX-License-Identifier: MIT
// Large arrays without the cost of their first touch: elements are default-initialized (no
// zero fill that is overwritten anyway) and, on Linux, blocks of 2 MiB or more are asked for
// transparent huge pages, so that one page fault maps 2 MiB instead of 4 KiB. On virtual
// machines a page fault costs microseconds: at a million triangles the zero fills and faults
// of plain std::vector took more time than computing the tangents.
#pragma once

#include <cstddef>
#include <cstdint>
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

// At least `bytes` of memory fresh from the kernel, on 2 MiB boundaries, rounded up to whole
// 2 MiB, with transparent huge pages asked for; null when out of memory. Free with
// unmapHugePages(p, bytes). Unlike allocateHugePages, never memory the heap hands out again:
// that was first touched in 4 KiB pages, which advice no longer changes. Measured on the
// kernel benchmark at 4e6 triangles: a third of the workspace came back from the heap in
// small pages (the input's temporaries, freed), and the call ran 25% slower for it.
inline void* mapHugePages(std::size_t bytes) noexcept {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  const std::size_t rounded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
  void* raw = mmap(nullptr, rounded + kHugePage, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (raw == MAP_FAILED) return nullptr;
  // Keep the 2 MiB-aligned part, give back the rest on either side.
  const auto start = reinterpret_cast<std::uintptr_t>(raw);
  const std::uintptr_t aligned = (start + kHugePage - 1) & ~(kHugePage - 1), end = start + rounded + kHugePage;
  if (aligned > start) munmap(raw, aligned - start);
  if (end > aligned + rounded) munmap(reinterpret_cast<void*>(aligned + rounded), end - (aligned + rounded));
  madvise(reinterpret_cast<void*>(aligned), rounded, MADV_HUGEPAGE);
  return reinterpret_cast<void*>(aligned);
#else
  return allocateHugePages(bytes);
#endif
}
inline void unmapHugePages(void* p, std::size_t bytes) noexcept {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  munmap(p, (bytes + kHugePage - 1) / kHugePage * kHugePage);
#else
  (void)bytes;
  std::free(p);
#endif
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
    void* p = mapHugePages(bytes);
    if (!p) throw std::bad_alloc();
    return static_cast<T*>(p);
  }
  void deallocate(T* p, std::size_t n) noexcept {
    if (n * sizeof(T) < kHugePage) ::operator delete(p);
    else unmapHugePages(p, n * sizeof(T));
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
