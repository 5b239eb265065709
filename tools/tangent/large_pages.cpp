// SPDX-License-Identifier: MIT
// The command's allocation policy: blocks of 2 MiB and more (a primitive's arrays, buffers,
// the file read whole) are placed on 2 MiB boundaries and asked for transparent huge pages,
// so that first touching them costs one page fault per 2 MiB instead of one per 4 KiB. On
// virtual machines a page fault costs microseconds; profiled at a million triangles, faults
// and zero fills were 40% of `tangent bake`. Everything still works where the kernel declines.
// Replaces the global operator new/delete of this program only (never of the libraries).
#include <cstdlib>
#include <new>

#include "tangent/bulk_buffer.hpp"

#if defined(__linux__)
#include <malloc.h>
#endif

namespace {

void* allocate(std::size_t bytes) noexcept {
  if (bytes < tangent::kHugePage) return std::malloc(bytes == 0 ? 1 : bytes);
  return tangent::allocateHugePages(bytes);
}

#if defined(__linux__) && defined(M_MMAP_MAX)
// Freed blocks stay in the heap for the next ones: memory the kernel hands out again is
// zeroed again, page by page (measured: clearing pages was a third of a bake).
const bool kHeapKept = [] {
  mallopt(M_MMAP_MAX, 0);
  mallopt(M_TRIM_THRESHOLD, 256 << 20);
  return true;
}();
#endif

}  // namespace

void* operator new(std::size_t bytes) {
  if (void* p = allocate(bytes)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t bytes) { return operator new(bytes); }
void* operator new(std::size_t bytes, const std::nothrow_t&) noexcept { return allocate(bytes); }
void* operator new[](std::size_t bytes, const std::nothrow_t&) noexcept { return allocate(bytes); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
