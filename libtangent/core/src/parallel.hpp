// SPDX-License-Identifier: MIT
// The parallel helpers every method shares, on the workspace's threads (oneTBB; the core's own
// pool of standard threads where built with TANGENT_STD_THREADS; one thread, in order, where
// built without threads: TANGENT_SERIAL; thread_backend.hpp). Each gives the same result for
// any thread count.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <vector>

#include "workspace.hpp"

namespace tangent::detail {

// Runs body(begin, end) over [0, count) on the workspace's threads.
template <typename Body>
void forRange(const WorkspaceData& ws, std::size_t count, std::size_t grain, const Body& body);

// Runs body() in an arena of ws.threads worker threads (inline for one).
template <typename Body>
void onThreads(const WorkspaceData& ws, const Body& body);

// Sorts [begin, end) by less on the workspace's threads (a total order gives the same result
// for any count).
template <typename Iterator, typename Less>
void sortInParallel(const WorkspaceData& ws, Iterator begin, Iterator end, const Less& less);

// Runs first() and second() side by side on the workspace's threads (one after the other on
// one); they must write no common data.
template <typename First, typename Second>
void invokeBoth(const WorkspaceData& ws, const First& first, const Second& second);

// Where each of `blocks` blocks starts when they are laid out one after another: start[b] is
// the sum of total(b') for b' < b, start[blocks] the sum of all; the totals are worked out in
// parallel (the first half of a two-pass parallel scan; the caller fills each block from its
// start).
template <typename Count, typename Total>
std::vector<Count> blockStarts(const WorkspaceData& ws, std::size_t blocks, const Total& total);

// A stable counting sort in parallel: the items [0, count), cut into `chunks` equal runs, each
// counted and scattered by one task with its own counters (counters: chunks * keys), so that
// the items come out grouped by key, each group in item order; groupStart (keys + 1) gets
// the groups' starts. countChunk(begin, end, counter) adds the items [begin, end) of one
// chunk to counter[key]; fill(begin, end, next) places them, next[key] being where the next
// item of that key goes; `align`: chunks start at multiples of it.
template <typename CountChunk, typename Fill>
void countingSortInChunks(const WorkspaceData& ws, std::size_t count, std::size_t keys, std::size_t chunks,
                          const CountChunk& countChunk, std::uint32_t* counters, std::uint32_t* groupStart,
                          const Fill& fill, std::size_t align = 1);

// Replaces values[i] by the sum of values[0, i), block by block in parallel; returns the sum
// of all (which the caller checks against its own limit: each value is stored as it comes).
inline std::uint64_t exclusiveScan(const WorkspaceData& ws, std::uint32_t* values, std::size_t count);

// The indices in [0, count) where keep(i) holds, in increasing order, gathered in parallel
// (fixed chunks: counted, then filled at their offsets).
template <typename Keep>
std::vector<std::uint32_t> collectIf(const WorkspaceData& ws, std::size_t count, const Keep& keep);
// The same where keep(i) can hold only if flags[i] has `flag`: runs of eight bytes without it
// are skipped (these lists are rare corners of large arrays).
template <typename Keep>
std::vector<std::uint32_t> collectFlagged(const WorkspaceData& ws, const std::uint8_t* flags, std::uint8_t flag,
                                          std::size_t count, const Keep& keep);


}  // namespace tangent::detail

#if defined(TANGENT_ONETBB)
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_sort.h>
#include <tbb/task_arena.h>
#endif

namespace tangent::detail {

template <typename Body>
void forRange(const WorkspaceData& ws, std::size_t count, std::size_t grain, const Body& body) {
  if (ws.threads <= 1 || count <= grain) {
    if (count > 0) body(std::size_t(0), count);
    return;
  }
#if defined(TANGENT_SERIAL)
  body(std::size_t(0), count);
#elif defined(TANGENT_STD_THREADS)
  // Pieces of at least `grain`, four a thread, taken one at a time by the threads free.
  const std::size_t pieces = std::min((count + grain - 1) / grain, std::size_t(ws.threads) * 4);
  runOnPool(ws.threads, pieces, [&](std::size_t piece) {
    body(count * piece / pieces, count * (piece + 1) / pieces);
  });
#else
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, grain),
                    [&](const tbb::blocked_range<std::size_t>& range) { body(range.begin(), range.end()); });
#endif
}

template <typename Iterator, typename Less>
void sortInParallel(const WorkspaceData& ws, Iterator begin, Iterator end, const Less& less) {
#if defined(TANGENT_ONETBB)
  if (ws.threads > 1) {
    tbb::parallel_sort(begin, end, less);
    return;
  }
#else
  (void)ws;
#endif
  std::sort(begin, end, less);
}

template <typename First, typename Second>
void invokeBoth(const WorkspaceData& ws, const First& first, const Second& second) {
#if defined(TANGENT_ONETBB)
  if (ws.threads > 1) {
    tbb::parallel_invoke(first, second);
    return;
  }
#elif defined(TANGENT_STD_THREADS)
  if (ws.threads > 1) {
    runOnPool(ws.threads, 2, [&](std::size_t i) { i == 0 ? first() : second(); });
    return;
  }
#else
  (void)ws;
#endif
  first();
  second();
}

template <typename Count, typename Total>
std::vector<Count> blockStarts(const WorkspaceData& ws, std::size_t blocks, const Total& total) {
  std::vector<Count> start(blocks + 1, 0);
  forRange(ws, blocks, 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t b = begin; b < end; ++b) start[b + 1] = total(b);
  });
  for (std::size_t b = 0; b < blocks; ++b) start[b + 1] += start[b];
  return start;
}

// Calls each(i) for the i in [begin, end) where keep(i) holds, in increasing order.
template <typename Keep, typename Each>
void scanKept(const std::uint8_t* flags, std::uint8_t flag, std::size_t begin, std::size_t end, const Keep& keep,
              const Each& each) {
  std::size_t i = begin;
  if (flags != nullptr) {
    const std::uint64_t any = 0x0101010101010101ull * flag;
    for (; i + 8 <= end; i += 8) {
      std::uint64_t eight;
      std::memcpy(&eight, flags + i, sizeof eight);
      if (!(eight & any)) continue;
      for (std::size_t j = i; j < i + 8; ++j) {
        if (keep(j)) each(j);
      }
    }
  }
  for (; i < end; ++i) {
    if (keep(i)) each(i);
  }
}

template <typename Keep>
std::vector<std::uint32_t> collectFlagged(const WorkspaceData& ws, const std::uint8_t* flags, std::uint8_t flag,
                                          std::size_t count, const Keep& keep) {
  constexpr std::size_t kChunk = 1 << 16;
  const std::size_t chunkCount = (count + kChunk - 1) / kChunk;
  auto chunkEnd = [&](std::size_t k) { return std::min(count, (k + 1) * kChunk); };
  const std::vector<std::size_t> offset = blockStarts<std::size_t>(ws, chunkCount, [&](std::size_t k) {
    std::size_t n = 0;
    scanKept(flags, flag, k * kChunk, chunkEnd(k), keep, [&](std::size_t) { ++n; });
    return n;
  });
  std::vector<std::uint32_t> kept(offset[chunkCount]);
  forRange(ws, chunkCount, 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) {
      std::size_t at = offset[k];
      scanKept(flags, flag, k * kChunk, chunkEnd(k), keep,
               [&](std::size_t i) { kept[at++] = static_cast<std::uint32_t>(i); });
    }
  });
  return kept;
}

template <typename Keep>
std::vector<std::uint32_t> collectIf(const WorkspaceData& ws, std::size_t count, const Keep& keep) {
  return collectFlagged(ws, nullptr, 0, count, keep);
}

template <typename CountChunk, typename Fill>
void countingSortInChunks(const WorkspaceData& ws, std::size_t count, std::size_t keys, std::size_t chunks,
                          const CountChunk& countChunk, std::uint32_t* counters, std::uint32_t* groupStart,
                          const Fill& fill, std::size_t align) {
  const std::size_t length = chunks == 0 ? 0 : (count / align + chunks - 1) / chunks * align;
  forRange(ws, chunks, 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) {
      std::uint32_t* counter = counters + k * keys;
      std::fill(counter, counter + keys, 0u);
      countChunk(std::min(count, k * length), std::min(count, (k + 1) * length), counter);
    }
  });
  // Key-major offsets: each group's items chunk by chunk. In blocks of keys, so that the
  // scan runs in parallel too (one thread scanning a vertex's worth of keys per corner bucket
  // was most of the bucketing's serial time): each block's total, the blocks' starts, then
  // each block's offsets from its start.
  constexpr std::size_t kKeyBlock = 1 << 14;
  const std::size_t blocks = (keys + kKeyBlock - 1) / kKeyBlock;
  const std::vector<std::uint32_t> blockStart = blockStarts<std::uint32_t>(ws, blocks, [&](std::size_t b) {
    std::uint32_t n = 0;
    for (std::size_t k = 0; k < chunks; ++k) {
      const std::uint32_t* counter = counters + k * keys;
      for (std::size_t g = b * kKeyBlock; g < std::min(keys, (b + 1) * kKeyBlock); ++g) n += counter[g];
    }
    return n;
  });
  forRange(ws, blocks, 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t b = begin; b < end; ++b) {
      std::uint32_t total = blockStart[b];
      for (std::size_t g = b * kKeyBlock; g < std::min(keys, (b + 1) * kKeyBlock); ++g) {
        groupStart[g] = total;
        for (std::size_t k = 0; k < chunks; ++k) {
          const std::uint32_t n = counters[k * keys + g];
          counters[k * keys + g] = total;
          total += n;
        }
      }
    }
  });
  groupStart[keys] = blockStart[blocks];
  forRange(ws, chunks, 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) {
      fill(std::min(count, k * length), std::min(count, (k + 1) * length), counters + k * keys);
    }
  });
}

inline std::uint64_t exclusiveScan(const WorkspaceData& ws, std::uint32_t* values, std::size_t count) {
  constexpr std::size_t kBlock = 1 << 14;
  const std::size_t blocks = (count + kBlock - 1) / kBlock;
  auto blockEnd = [&](std::size_t k) { return std::min(count, (k + 1) * kBlock); };
  const std::vector<std::uint64_t> start = blockStarts<std::uint64_t>(ws, blocks, [&](std::size_t k) {
    std::uint64_t n = 0;
    for (std::size_t i = k * kBlock; i < blockEnd(k); ++i) n += values[i];
    return n;
  });
  forRange(ws, blocks, 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) {
      std::uint64_t sum = start[k];
      for (std::size_t i = k * kBlock; i < blockEnd(k); ++i) {
        const std::uint32_t n = values[i];
        values[i] = static_cast<std::uint32_t>(sum);
        sum += n;
      }
    }
  });
  return start[blocks];
}

template <typename Body>
void onThreads(const WorkspaceData& ws, const Body& body) {
#if !defined(TANGENT_ONETBB)
  (void)ws;  // the pool's calls take ws.threads themselves
  body();
#else
  if (ws.threads <= 1) {
    body();
    return;
  }
  // No more slots than the process may run threads: the pool never grants the extra workers,
  // only warns on standard error that it will not. ws.threads still picks the methods (the
  // same bits for any count).
  const std::size_t limit = tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
  const auto slots = static_cast<int>(std::min<std::size_t>(ws.threads, std::max<std::size_t>(limit, 1)));
  tbb::task_arena arena(slots);
  arena.execute(body);
#endif
}

}  // namespace tangent::detail
