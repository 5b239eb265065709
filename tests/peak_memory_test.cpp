// SPDX-License-Identifier: MIT
// The peak-memory measure of `tangent bench` (tools/bench/peak_memory.hpp): that it sees a
// peak that is already gone when the work returns, that memory an earlier piece of work freed
// counts as new, and that on the library's call it agrees with the workspace's own count of its
// scratch (TangentWorkspace::bytesReserved), an independent measure of the same arrays.
// Skips, saying why, where the system does not report a peak (not Linux) or an AddressSanitizer
// build measures its own allocator instead.
#include "peak_memory.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <vector>

#include "analytic_surfaces.hpp"
#include "tangent/bulk_buffer.hpp"
#include "tangent/tangent.hpp"

namespace {

constexpr std::size_t kMiB = std::size_t(1) << 20;

// Touches every page of `bytes` new bytes and keeps them until the returned owner goes.
std::unique_ptr<char[]> touched(std::size_t bytes) {
  std::unique_ptr<char[]> block(new char[bytes]);
  std::memset(block.get(), 1, bytes);
  // The block escapes: no compiler may drop the stores, or the allocation, as unread.
  asm volatile("" : : "r"(block.get()) : "memory");
  return block;
}

#define REQUIRE_PEAK(growth)                                                                            \
  if (!(growth))                                                                                        \
  GTEST_SKIP() << "no resident-set peak here (/proc/self/clear_refs and VmHWM are Linux's; none under " \
                  "AddressSanitizer)"

TEST(PeakMemory, SeesAPeakGoneBeforeTheWorkReturns) {
  volatile char last = 0;
  const auto growth = tangent::bench::peakResidentGrowth([&] {
    auto block = touched(64 * kMiB);
    last = block[64 * kMiB - 1];
  });  // freed inside the work: only the peak shows it
  REQUIRE_PEAK(growth);
  EXPECT_EQ(last, 1);
  EXPECT_GE(*growth, 63 * kMiB);
  EXPECT_LE(*growth, 72 * kMiB);
}

TEST(PeakMemory, WorkThatTakesNothingAddsNothing) {
  auto block = touched(32 * kMiB);  // resident before the work: not the work's
  const auto growth = tangent::bench::peakResidentGrowth([&] { std::memset(block.get(), 2, 32 * kMiB); });
  REQUIRE_PEAK(growth);
  EXPECT_LE(*growth, 2 * kMiB);
}

TEST(PeakMemory, PagesTheHeapKeptFromEarlierWorkCountAsNew) {
  // 64 MiB in blocks small enough to come from the heap (not mapped apart), freed: the heap
  // keeps them resident unless given back, and the next work would reuse them for free.
  std::vector<std::unique_ptr<char[]>> blocks;
  for (int i = 0; i < 1024; ++i) blocks.push_back(touched(64 * 1024));
  blocks.clear();
  const auto growth = tangent::bench::peakResidentGrowth([&] {
    for (int i = 0; i < 1024; ++i) blocks.push_back(touched(64 * 1024));
  });
  blocks.clear();
  REQUIRE_PEAK(growth);
  EXPECT_GE(*growth, 60 * kMiB);
}

TEST(PeakMemory, LibraryCallAgreesWithItsWorkspacesOwnCount) {
  const tangent::bench::AnalyticMesh mesh = tangent::bench::makeSurface("sphere", 400000);
  std::vector<float> tangents(mesh.indices.size() * 4, 0.0f);  // the caller's, resident before
  std::size_t reserved = 0;
  const auto growth = tangent::bench::peakResidentGrowth([&] {
    tangent::TangentWorkspace workspace;
    tangent::Options options;
    options.threads = 1;
    tangent::computeCornerTangents(mesh.arrays(), tangent::CornerOutputs{tangents}, options, workspace);
    reserved = workspace.bytesReserved();
  });
  REQUIRE_PEAK(growth);
  ASSERT_GT(reserved, 0u);
  // mikktspace writes every array it reserves. The peak holds a little more: arrays of 2 MiB
  // and more are mapped in whole 2 MiB pages where transparent huge pages are on
  // (tangent/bulk_buffer.hpp), and the count leaves out the per-thread bucket scratch;
  // measured 1.14-1.17 times the count on this sphere (Linux 6.18, glibc 2.36, transparent
  // huge pages on request). Twice the count, or none of it, would mean a broken measure.
  const double ratio = static_cast<double>(*growth) / static_cast<double>(reserved);
  EXPECT_GT(ratio, 0.9) << *growth << " bytes at the peak, " << reserved << " reserved";
  EXPECT_LT(ratio, 1.5) << *growth << " bytes at the peak, " << reserved << " reserved";
}

// TangentWorkspace::setReleaseAsItGoes lowers a one-off call's peak, measured as bake's call
// is made: the caller's tangents and vertex split new (untouched until the call writes them),
// a new workspace. mikktspace: the weld's table and the pairing's ids are gone before the split
// writes cornerVertex (4 bytes a corner); lengyel: also the count's edges and the tables before
// the frames, the triangle pass's results (over 60 bytes a triangle) before the split.
TEST(PeakMemory, ReleasingAsItGoesLowersTheCallsPeak) {
  const tangent::bench::AnalyticMesh mesh = tangent::bench::makeSurface("sphere", 400000);
  const std::size_t corners = mesh.indices.size();
  auto peak = [&](tangent::Method method, bool release) {
    return tangent::bench::peakResidentGrowth([&] {
      tangent::BulkVector<float> tangents(corners * 4);
      tangent::BulkVector<std::uint32_t> cornerVertex(corners);
      tangent::TangentWorkspace workspace;
      workspace.setReleaseAsItGoes(release);
      tangent::Options options;
      options.method = method;
      options.threads = 1;
      tangent::computeCornerTangents(mesh.arrays(), tangent::CornerOutputs{tangents, {}, cornerVertex}, options, workspace);
    });
  };
  for (const auto& [method, least] : {std::pair{tangent::Method::mikktspace, std::size_t(3)}, {tangent::Method::lengyel, std::size_t(12)}}) {
    const auto kept = peak(method, false), released = peak(method, true);
    REQUIRE_PEAK(kept && released);
    // At least `least` bytes a corner lower (2 MiB pages make the measure coarse).
    EXPECT_LE(*released + least * corners, *kept)
        << tangent::toString(method) << ": peak " << *released << " bytes releasing, " << *kept << " keeping";
  }
}

}  // namespace
