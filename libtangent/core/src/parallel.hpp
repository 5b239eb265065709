// SPDX-License-Identifier: MIT
// Splits [0, count) into one contiguous chunk per thread. Each item's result depends only on
// the item, so the output is the same for any thread count.
#pragma once

#include <algorithm>
#include <cstddef>
#include <thread>
#include <vector>

namespace tangent::detail {

template <typename Body>
void parallelFor(std::size_t count, unsigned threads, const Body& body) {
  constexpr std::size_t kMinimumPerThread = 4096;
  const std::size_t workers = std::max<std::size_t>(1, std::min<std::size_t>(threads, count / kMinimumPerThread));
  if (workers <= 1) {
    body(std::size_t(0), count);
    return;
  }
  std::vector<std::thread> pool;
  pool.reserve(workers - 1);
  const std::size_t chunk = (count + workers - 1) / workers;
  for (std::size_t w = 1; w < workers; ++w) {
    const std::size_t begin = std::min(count, w * chunk), end = std::min(count, begin + chunk);
    pool.emplace_back([&body, begin, end] { body(begin, end); });
  }
  body(std::size_t(0), std::min(count, chunk));
  for (auto& thread : pool) thread.join();
}

}  // namespace tangent::detail
