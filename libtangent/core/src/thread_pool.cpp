// SPDX-License-Identifier: MIT
// The pool of thread_pool.hpp (TANGENT_STD_THREADS builds only).
#if defined(TANGENT_STD_THREADS)

#include "thread_pool.hpp"

#include <algorithm>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace tangent::detail {

namespace {

thread_local unsigned tSlot = 0;

// One call's tasks: handed out by `next`; `helpers` workers are in it now.
struct Job {
  void (*task)(const void*, std::size_t);
  const void* context;
  std::size_t tasks;
  unsigned helperLimit;  // workers that may join (the call's threads less its caller)
  unsigned helpers = 0;  // workers in the job; guarded by the pool's mutex
  std::atomic<std::size_t> next{0};
  std::exception_ptr failure;  // guarded by the pool's mutex

  // Runs tasks until none is left; false once a task has thrown (its exception kept).
  void work(std::mutex& mutex) {
    for (std::size_t i = next.fetch_add(1, std::memory_order_relaxed); i < tasks;
         i = next.fetch_add(1, std::memory_order_relaxed)) {
      try {
        task(context, i);
      } catch (...) {
        next.store(tasks, std::memory_order_relaxed);  // skip the tasks not started
        std::lock_guard lock(mutex);
        if (!failure) failure = std::current_exception();
      }
    }
  }
  bool open() const { return helpers < helperLimit && next.load(std::memory_order_relaxed) < tasks; }
};

class Pool {
 public:
  static Pool& instance() {
    // Never destroyed: workers may still be waiting when static destructors run.
    static Pool* pool = new Pool;
    return *pool;
  }

  void run(unsigned threads, std::size_t tasks, void (*task)(const void*, std::size_t), const void* context) {
    threads = std::min({threads, kMaxPoolThreads, static_cast<unsigned>(std::min<std::size_t>(tasks, kMaxPoolThreads))});
    if (threads <= 1) {
      for (std::size_t i = 0; i < tasks; ++i) task(context, i);
      return;
    }
    Job job{task, context, tasks, threads - 1};
    {
      std::lock_guard lock(mutex_);
      growTo(threads - 1);
      jobs_.push_back(&job);
    }
    changed_.notify_all();
    job.work(mutex_);
    std::unique_lock lock(mutex_);
    jobs_.erase(std::find(jobs_.begin(), jobs_.end(), &job));
    // While its helpers end their last tasks the caller helps any other call: a pass nested in
    // one of the helpers' tasks (the triangle pass beside the weld, invokeBoth) would otherwise
    // run on that helper alone while the caller slept (measured in WebAssembly: the two-thread
    // core 1.4-1.6x one thread's where oneTBB's, which steals, gave 1.8-2.0x).
    while (job.helpers != 0) {
      if (Job* other = openJob()) {
        helpWith(*other, lock);
      } else {
        changed_.wait(lock);
      }
    }
    if (job.failure) std::rethrow_exception(job.failure);
  }

 private:
  // Starts workers until there are `count` (under the mutex).
  void growTo(unsigned count) {
    while (workers_ < count) {
      const unsigned slot = ++workers_;
      std::thread([this, slot] { serve(slot); }).detach();
    }
  }

  // A job with tasks left and room for a helper, the oldest first (under the mutex).
  Job* openJob() const {
    for (Job* candidate : jobs_) {
      if (candidate->open()) return candidate;
    }
    return nullptr;
  }

  // Runs tasks of `job` as one of its helpers (called and returning with `lock` held).
  void helpWith(Job& job, std::unique_lock<std::mutex>& lock) {
    ++job.helpers;
    lock.unlock();
    job.work(mutex_);
    lock.lock();
    if (--job.helpers == 0) changed_.notify_all();
  }

  void serve(unsigned slot) {
    tSlot = slot;
    std::unique_lock lock(mutex_);
    for (;;) {
      Job* job = nullptr;
      changed_.wait(lock, [&] { return (job = openJob()) != nullptr; });
      helpWith(*job, lock);
    }
  }

  std::mutex mutex_;
  // Notified when a job is posted and when a job's last helper leaves it.
  std::condition_variable changed_;
  std::vector<Job*> jobs_;  // calls with tasks, the newest last
  unsigned workers_ = 0;
};

}  // namespace

unsigned poolSlot() { return tSlot; }

void runOnPool(unsigned threads, std::size_t tasks, void (*task)(const void*, std::size_t), const void* context) {
  Pool::instance().run(threads, tasks, task, context);
}

unsigned poolHardwareThreads() { return std::max(1u, std::thread::hardware_concurrency()); }

}  // namespace tangent::detail

#endif  // TANGENT_STD_THREADS
