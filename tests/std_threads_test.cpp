// SPDX-License-Identifier: MIT
// The core built on its own pool of standard threads (TANGENT_STD_THREADS, thread_pool.hpp:
// what the threaded WebAssembly package runs on) gives one thread's bits for every method,
// thread count and face order, on meshes with every hard case; and the pool itself runs every
// task once, nested calls included, and hands back a task's exception. This binary links that
// build of the core alone (tangent_core_std_threads), never oneTBB's.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "support/random_meshes.hpp"
#include "support/test_assets.hpp"
#include "tangent/tangent.hpp"
#include "thread_pool.hpp"

#if !defined(TANGENT_STD_THREADS)
#error "std_threads_test.cpp tests the TANGENT_STD_THREADS build of the core"
#endif

namespace {

using tangent::testing::GridMesh;
using tangent::testing::hardMesh;

using Output = tangent::testing::CornerRun;

Output compute(const GridMesh& m, unsigned threads, tangent::Method method) {
  tangent::TangentWorkspace workspace;
  return tangent::testing::runCorners({m.positions, m.normals, m.uvs, m.indices}, threads, workspace, method);
}

void expectSameBits(const Output& one, const Output& other, const std::string& what) {
  ASSERT_EQ(0, std::memcmp(one.tangents.data(), other.tangents.data(), one.tangents.size() * sizeof(float))) << what;
  ASSERT_EQ(one.cornerVertex, other.cornerVertex) << what;
  ASSERT_EQ(one.report.splitVertices, other.report.splitVertices) << what;
  ASSERT_EQ(one.report.nonManifoldFaces, other.report.nonManifoldFaces) << what;
  ASSERT_EQ(one.report.mirroredCorners, other.report.mirroredCorners) << what;
}

TEST(StdThreads, EveryMethodGivesOneThreadsBitsOnEveryThreadCountAndOrder) {
  const GridMesh meshes[] = {hardMesh(60000), tangent::testing::makeTorus(256, 128)};
  for (const tangent::Method method :
       {tangent::Method::mikktspace, tangent::Method::lengyel, tangent::Method::meshopt, tangent::Method::flat}) {
    for (const GridMesh& m : meshes) {
      const Output one = compute(m, 1, method);
      for (unsigned threads : {2u, 3u, 8u, 0u}) {
        expectSameBits(one, compute(m, threads, method), std::string(tangent::toString(method)) + " on " + std::to_string(threads) + " threads");
      }
      const auto shuffled = tangent::testing::shuffleFacesAndRotateCorners(m, 7);
      const Output s = compute(shuffled.mesh, 3, method);
      for (std::size_t c = 0; c < shuffled.originalCorner.size(); ++c)
        ASSERT_EQ(0, std::memcmp(&s.tangents[4 * c], &one.tangents[4 * shuffled.originalCorner[c]], 16)) << "corner " << c;
    }
  }
}

TEST(StdThreads, ThePoolRunsEveryTaskOnceNestedCallsIncluded) {
  constexpr std::size_t kOuter = 37, kInner = 101;
  std::vector<std::atomic<int>> runs(kOuter * kInner);
  tangent::detail::runOnPool(4, kOuter, [&](std::size_t i) {
    tangent::detail::runOnPool(3, kInner, [&](std::size_t j) { runs[i * kInner + j].fetch_add(1); });
  });
  for (std::size_t k = 0; k < runs.size(); ++k) ASSERT_EQ(1, runs[k].load()) << k;
}

TEST(StdThreads, TwoThreadsRunTwoTasksAtOnce) {
  // Each task waits (up to 20 s) for the other to start: only two threads at once end both.
  std::atomic<int> started{0};
  std::atomic<bool> together{true};
  tangent::detail::runOnPool(2, 2, [&](std::size_t) {
    started.fetch_add(1);
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (started.load() < 2) {
      if (std::chrono::steady_clock::now() > until) {
        together = false;
        return;
      }
      std::this_thread::yield();
    }
  });
  EXPECT_TRUE(together.load()) << "the second task did not start while the first ran";
}

TEST(StdThreads, ATasksExceptionReachesTheCallerAfterTheOthersEnd) {
  std::atomic<int> running{0}, maxAfter{0};
  EXPECT_THROW(tangent::detail::runOnPool(4, 1000,
                                          [&](std::size_t i) {
                                            running.fetch_add(1);
                                            if (i == 17) {
                                              running.fetch_sub(1);
                                              throw std::runtime_error("task 17");
                                            }
                                            running.fetch_sub(1);
                                          }),
               std::runtime_error);
  maxAfter = running.load();
  EXPECT_EQ(0, maxAfter.load()) << "a task still ran after the call returned";
  // The pool is still whole: the next call runs every task.
  std::atomic<int> count{0};
  tangent::detail::runOnPool(4, 500, [&](std::size_t) { count.fetch_add(1); });
  EXPECT_EQ(500, count.load());
}

}  // namespace
