// SPDX-License-Identifier: MIT
// The threads of builds without oneTBB that still run in parallel (TANGENT_STD_THREADS: the
// threaded WebAssembly package, on emscripten's pthreads, where oneTBB is not available): a
// pool of std::threads that parallel.hpp and workspace.hpp use in oneTBB's place. A call's
// tasks are taken one at a time from a shared counter by the calling thread and by the pool's
// idle threads, so a call nested in a task runs even when every worker is busy (its caller
// does all of it then); a caller whose own tasks are all taken helps other calls until its
// helpers are done. The core gives the same bits for any split of its work, so this pool
// gives oneTBB's bits.
#pragma once

#if defined(TANGENT_STD_THREADS)

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <new>

namespace tangent::detail {

// The most threads one call runs on (the caller and kMaxPoolThreads - 1 workers): the per-thread
// slots of Combinable are a fixed array of this many.
constexpr unsigned kMaxPoolThreads = 64;

// The slot of the running thread: 0 outside the pool (a call's own thread), 1 .. kMaxPoolThreads - 1
// for the pool's workers.
unsigned poolSlot();

// Runs task(context, i) for every i in [0, tasks) on at most `threads` threads (the caller one
// of them) and returns when all have run. The first exception a task throws is thrown here,
// after every task that started has ended; the tasks not started by then are skipped.
void runOnPool(unsigned threads, std::size_t tasks, void (*task)(const void* context, std::size_t i),
               const void* context);

// The same for a callable: body(i).
template <typename Body>
void runOnPool(unsigned threads, std::size_t tasks, const Body& body) {
  runOnPool(threads, tasks, [](const void* context, std::size_t i) { (*static_cast<const Body*>(context))(i); }, &body);
}

// Threads of the machine as the standard library reports them (at least 1).
unsigned poolHardwareThreads();

// One value per thread of a call, for sums that threads add to without sharing a cache line
// (oneTBB's combinable, the operations the core uses).
template <typename T>
class Combinable {
 public:
  T& local() {
    Slot& slot = slots_[poolSlot()];
    slot.used = true;
    return slot.value;
  }
  template <typename F>
  void combine_each(F f) const {
    for (const Slot& slot : slots_) {
      if (slot.used) f(slot.value);
    }
  }
  template <typename F>
  T combine(F f) const {
    T total{};
    bool first = true;
    for (const Slot& slot : slots_) {
      if (!slot.used) continue;
      total = first ? slot.value : f(total, slot.value);
      first = false;
    }
    return total;
  }

 private:
  struct alignas(64) Slot {
    T value{};
    bool used = false;
  };
  Slot slots_[kMaxPoolThreads];
};

// Blocks on their own cache lines (oneTBB's cache_aligned_allocator).
template <typename T>
struct CacheAlignedAllocator {
  using value_type = T;
  static constexpr std::align_val_t kAlign{64};
  CacheAlignedAllocator() = default;
  template <typename U>
  CacheAlignedAllocator(const CacheAlignedAllocator<U>&) {}
  T* allocate(std::size_t n) { return static_cast<T*>(::operator new(n * sizeof(T), kAlign)); }
  void deallocate(T* p, std::size_t) { ::operator delete(p, kAlign); }
  template <typename U>
  bool operator==(const CacheAlignedAllocator<U>&) const {
    return true;
  }
};

// std::atomic_ref's operations the core uses, on the compiler's atomic built-ins (emscripten's
// C++ library has no atomic_ref).
template <typename T>
class BuiltinAtomicRef {
 public:
  explicit BuiltinAtomicRef(T& value) : value_(&value) {}
  T load(std::memory_order order) const { return __atomic_load_n(value_, builtin(order)); }
  void store(T desired, std::memory_order order) { __atomic_store_n(value_, desired, builtin(order)); }
  bool compare_exchange_weak(T& expected, T desired, std::memory_order order) {
    return __atomic_compare_exchange_n(value_, &expected, desired, true, builtin(order), failureOrder(order));
  }
  T fetch_add(T add, std::memory_order order) { return __atomic_fetch_add(value_, add, builtin(order)); }

 private:
  static constexpr int builtin(std::memory_order order) {
    switch (order) {
      case std::memory_order_relaxed: return __ATOMIC_RELAXED;
      case std::memory_order_consume: return __ATOMIC_CONSUME;
      case std::memory_order_acquire: return __ATOMIC_ACQUIRE;
      case std::memory_order_release: return __ATOMIC_RELEASE;
      case std::memory_order_acq_rel: return __ATOMIC_ACQ_REL;
      default: return __ATOMIC_SEQ_CST;
    }
  }
  // A failed exchange only loads: no release in its order.
  static constexpr int failureOrder(std::memory_order order) {
    switch (order) {
      case std::memory_order_release: return __ATOMIC_RELAXED;
      case std::memory_order_acq_rel: return __ATOMIC_ACQUIRE;
      default: return builtin(order);
    }
  }
  T* value_;
};

}  // namespace tangent::detail

#endif  // TANGENT_STD_THREADS
