// SPDX-License-Identifier: MIT
// The hot path's contract: the same bits for any thread count and any triangle order, the
// vertex split it returns, a workspace that repeated calls reuse, and the OpenMesh call on
// the same kernel.
#include <gtest/gtest.h>

#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <cstdlib>
#include <iostream>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <thread>

#include "support/random_meshes.hpp"
#include "support/test_assets.hpp"
#include "tangent/bulk_buffer.hpp"
#include "tangent/openmesh.hpp"
#include "tangent/tangent.hpp"
#include "lengyel.hpp"
#include "parallel.hpp"

namespace {

using tangent::testing::GridMesh;
using tangent::testing::hardMesh;

using Output = tangent::testing::CornerRun;

Output compute(const tangent::MeshArrays& mesh, unsigned threads, tangent::TangentWorkspace& workspace,
               tangent::Method method = tangent::Method::mikktspace) {
  return tangent::testing::runCorners(mesh, threads, workspace, method);
}

Output compute(const tangent::MeshArrays& mesh, unsigned threads,
               tangent::Method method = tangent::Method::mikktspace) {
  tangent::TangentWorkspace workspace;
  return compute(mesh, threads, workspace, method);
}

constexpr tangent::Method kEveryMethod[] = {tangent::Method::mikktspace, tangent::Method::lengyel, tangent::Method::meshopt,
                                            tangent::Method::flat};

// A closed fan of four triangles around vertex 0 whose UVs fold: two triangles of each UV
// orientation, with every dP/du and every dP/dv (signed by the orientation) inside one half
// plane, so that only the orientation keeps the fan shortcut from taking the four as one
// group (the full grouping makes two, with opposite w).
GridMesh foldedFan() {
  GridMesh m;
  m.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, -1, 0, 0, 0, -1, 0};
  m.normals = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
  m.uvs = {0.5f, 0.5f, 0.85f, 1.43f, 0.0f, 0.41f, 0.69f, 0.14f, 0.23f, 0.13f};
  m.indices = {0, 1, 2, 0, 2, 3, 0, 3, 4, 0, 4, 1};
  return m;
}

tangent::MeshArrays arraysOf(const GridMesh& m) { return {m.positions, m.normals, m.uvs, m.indices}; }

TEST(Workspace, SameBitsForOneTwoThreeAndEightThreadsAndShuffledInput) {
  const GridMesh meshes[] = {hardMesh(), tangent::testing::makeTorus(256, 128)};
  for (const tangent::Method method : kEveryMethod) {
    SCOPED_TRACE(std::string(tangent::toString(method)));
    for (const GridMesh& m : meshes) {
      const Output one = compute(arraysOf(m), 1, method);
      for (unsigned threads : {2u, 3u, 8u, 0u}) {
        const Output other = compute(arraysOf(m), threads, method);
        ASSERT_EQ(0, std::memcmp(one.tangents.data(), other.tangents.data(), one.tangents.size() * sizeof(float))) << threads;
        ASSERT_EQ(one.cornerVertex, other.cornerVertex) << threads;
        ASSERT_EQ(one.report.splitVertices, other.report.splitVertices);
        ASSERT_EQ(one.report.nonManifoldFaces, other.report.nonManifoldFaces);
      }
      for (unsigned seed : {3u, 4u, 5u}) {
        const auto shuffled = tangent::testing::shuffleFacesAndRotateCorners(m, seed);
        const Output s = compute(arraysOf(shuffled.mesh), 8, method);
        for (std::size_t c = 0; c < shuffled.originalCorner.size(); ++c)
          ASSERT_EQ(0, std::memcmp(&s.tangents[4 * c], &one.tangents[4 * shuffled.originalCorner[c]], 16)) << "corner " << c;
        EXPECT_EQ(s.report.splitVertices, one.report.splitVertices);
      }
    }
  }
}

// Sets TANGENT_MAX_CPU_ISA for its lifetime, then puts back what was there.
class ScopedVectorIsa {
 public:
  explicit ScopedVectorIsa(const char* isa) {
    if (const char* old = std::getenv(kName)) saved_ = old;
    if (isa) {
      setenv(kName, isa, 1);
    } else {
      unsetenv(kName);
    }
  }
  ~ScopedVectorIsa() {
    if (saved_) {
      setenv(kName, saved_->c_str(), 1);
    } else {
      unsetenv(kName);
    }
  }
  ScopedVectorIsa(const ScopedVectorIsa&) = delete;
  ScopedVectorIsa& operator=(const ScopedVectorIsa&) = delete;

 private:
  static constexpr const char* kName = "TANGENT_MAX_CPU_ISA";
  std::optional<std::string> saved_;
};

// The triangle pass in AVX2 (eight triangles a step), SSE2 (four) and scalar code: every width
// this build and processor have gives the scalar code's bits.
TEST(Workspace, SameBitsForEveryVectorWidth) {
  std::string widest;
  {
    const ScopedVectorIsa uncapped(nullptr);
    widest = tangent::vectorIsa();
  }
#if defined(__SSE2__) && defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
  EXPECT_EQ(widest, __builtin_cpu_supports("avx2") ? "avx2" : "sse2") << "the widest this processor has";
#endif
  // A torus with values the float formulas do not resolve: NaN, infinite, huge, tiny.
  GridMesh extreme = tangent::testing::makeTorus(128, 64);
  for (std::size_t v = 0; v < extreme.positions.size() / 3; ++v) {
    float* p = &extreme.positions[3 * v];
    if (v % 97 == 0) p[0] = std::numeric_limits<float>::quiet_NaN();
    if (v % 89 == 0) extreme.uvs[2 * v + 1] = std::numeric_limits<float>::infinity();
    if (v % 83 == 0) p[1] *= 1e30f;
    if (v % 79 == 0) p[2] *= 1e-30f;
    if (v % 73 == 0) extreme.uvs[2 * v] *= 1e-25f;
  }
  const GridMesh meshes[] = {hardMesh(), tangent::testing::makeTorus(256, 128), extreme};
  for (const tangent::Method method : kEveryMethod) {
    SCOPED_TRACE(std::string(tangent::toString(method)));
    for (const GridMesh& m : meshes) {
      Output scalar;
      {
        const ScopedVectorIsa cap("scalar");
        ASSERT_EQ(tangent::vectorIsa(), "scalar");
        scalar = compute(arraysOf(m), 2, method);
      }
      int compared = 0;
      for (const char* isa : {"sse2", "avx2"}) {
        const ScopedVectorIsa cap(isa);
        if (tangent::vectorIsa() != isa) {
          if (method == tangent::Method::mikktspace)
            std::cout << "[ NOTE     ] " << isa << " not compared: this build and processor run " << tangent::vectorIsa()
                      << " at most\n";
          continue;
        }
        const Output wide = compute(arraysOf(m), 2, method);
        const std::size_t bytes = scalar.tangents.size() * sizeof(float);
        ASSERT_EQ(0, std::memcmp(scalar.tangents.data(), wide.tangents.data(), bytes)) << isa;
        ASSERT_EQ(scalar.cornerVertex, wide.cornerVertex) << isa;
        ASSERT_EQ(scalar.report.degenerateTriangles, wide.report.degenerateTriangles) << isa;
        ASSERT_EQ(scalar.report.zeroUvAreaTriangles, wide.report.zeroUvAreaTriangles) << isa;
        ASSERT_EQ(scalar.report.nonFiniteTriangles, wide.report.nonFiniteTriangles) << isa;
        ++compared;
      }
      EXPECT_EQ(compared, widest == "avx2" ? 2 : widest == "sse2" ? 1 : 0);
    }
  }
  // Lanes that leave to the scalar code: not vacuous.
  const Output hard = compute(arraysOf(meshes[0]), 2), odd = compute(arraysOf(meshes[2]), 2);
  EXPECT_GT(hard.report.zeroUvAreaTriangles, 0u);
  EXPECT_GT(hard.report.degenerateTriangles, 0u);
  EXPECT_GT(odd.report.nonFiniteTriangles, 0u);
}

// The triangle pass's zero-area test (kFlat) takes a float test first and double only where
// float is not sure: slivers from sine 0.3 down to 1e-20 (double's bound is 1e-14, float's
// about 0.0155), at scales from 2^-40 to 2^126 (float's squared lengths out of range there;
// at 2^126 the sum of a triangle's values overflows, which sends it the scalar way)
// and far from the origin, give the scalar code's flags and bits on every vector width.
TEST(Workspace, SameFlatTrianglesForEveryVectorWidth) {
  GridMesh slivers;
  const float scales[] = {0x1p-40f, 0x1p-20f, 1.0f, 0x1p20f, 0x1p40f, 0x1p70f, 0x1p126f};
  const float offsets[] = {0.0f, 1000.0f};
  for (float scale : scales) {
    for (float offset : offsets) {
      for (int e = 2; e <= 80; ++e) {  // sine 10^(-e / 4)
        const double sine = std::pow(10.0, -e / 4.0), cosine = std::sqrt(1.0 - sine * sine);
        const auto first = static_cast<std::uint32_t>(slivers.positions.size() / 3);
        const float x = static_cast<float>(cosine * scale), y = static_cast<float>(sine * scale);
        const float corner[3][3] = {
            {offset, offset, offset}, {offset + scale, offset, offset}, {offset + x, offset + y, offset}};
        const float uv[3][2] = {{0, 0}, {1, 0}, {0, 1}};
        for (int k = 0; k < 3; ++k) {
          slivers.positions.insert(slivers.positions.end(), corner[k], corner[k] + 3);
          slivers.normals.insert(slivers.normals.end(), {0.0f, 0.0f, 1.0f});
          slivers.uvs.insert(slivers.uvs.end(), uv[k], uv[k] + 2);
          slivers.indices.push_back(first + k);
        }
      }
    }
  }
  // One vertex more, so that no triangle has the last vertex (the rows' loads leave those to
  // the scalar code).
  slivers.positions.insert(slivers.positions.end(), {0.0f, 0.0f, 0.0f});
  slivers.normals.insert(slivers.normals.end(), {0.0f, 0.0f, 1.0f});
  slivers.uvs.insert(slivers.uvs.end(), {0.0f, 0.0f});
  Output scalar;
  {
    const ScopedVectorIsa cap("scalar");
    scalar = compute(arraysOf(slivers), 1);
  }
  const std::size_t triangles = slivers.indices.size() / 3;
  EXPECT_GT(scalar.report.degenerateTriangles, triangles / 10);
  EXPECT_LT(scalar.report.degenerateTriangles, triangles / 2);
  for (const char* isa : {"sse2", "avx2"}) {
    const ScopedVectorIsa cap(isa);
    if (tangent::vectorIsa() != isa) continue;
    const Output wide = compute(arraysOf(slivers), 1);
    EXPECT_EQ(scalar.report.degenerateTriangles, wide.report.degenerateTriangles) << isa;
    const std::size_t bytes = scalar.tangents.size() * sizeof(float);
    EXPECT_EQ(0, std::memcmp(scalar.tangents.data(), wide.tangents.data(), bytes)) << isa;
  }
}

// The kernel's shortcut for a plain fan of one orientation (one frame for the whole bucket, its
// group weight kept once per bucket) against the full grouping of every bucket. The shortcut
// sums the bucket's terms rounded to a fixed grid (exact in any order), the full grouping sums
// them as they are, so the two may differ in the last bits of a frame, never more: w the same,
// xyz within a few float steps, the same vertex split and counts.
TEST(Workspace, FanShortcutAgreesWithTheFullGrouping) {
  const GridMesh meshes[] = {hardMesh(), tangent::testing::makeTorus(256, 128), foldedFan()};
  for (const GridMesh& m : meshes) {
    tangent::TangentWorkspace shortcut, full;
    full.data().fastBuckets = false;
    for (unsigned threads : {1u, 3u}) {
      const Output a = compute(arraysOf(m), threads, shortcut), b = compute(arraysOf(m), threads, full);
      std::size_t differing = 0;
      for (std::size_t c = 0; c < a.tangents.size() / 4; ++c) {
        const float* x = &a.tangents[4 * c];
        const float* y = &b.tangents[4 * c];
        ASSERT_EQ(x[3], y[3]) << "corner " << c;
        for (int i = 0; i < 3; ++i) ASSERT_NEAR(x[i], y[i], 1e-6f) << "corner " << c << " component " << i;
        differing += std::memcmp(x, y, 16) != 0;
      }
      ASSERT_EQ(a.cornerVertex, b.cornerVertex) << threads;
      ASSERT_EQ(a.report.splitVertices, b.report.splitVertices);
      ASSERT_EQ(a.report.mirroredCorners, b.report.mirroredCorners);
      std::cout << "[ NOTE     ] " << differing << " of " << a.tangents.size() / 4 << " corners differ in their last bits\n";
    }
  }
}

TEST(Workspace, VertexSplitKeepsEveryVertexAndAddsOnePerExtraTangent) {
  const GridMesh m = hardMesh();
  const Output out = compute(arraysOf(m), 0);
  const std::size_t vertexCount = m.positions.size() / 3;
  ASSERT_EQ(out.report.outputVertices, vertexCount + out.report.splitVertices);
  // Distinct (input vertex, tangent bits) pairs, counted independently of the core.
  std::map<std::uint32_t, std::set<std::array<std::uint32_t, 4>>> tangentsOfVertex;
  std::map<std::uint32_t, std::pair<std::uint32_t, std::array<std::uint32_t, 4>>> outputVertex;  // output -> (input, bits)
  for (std::size_t c = 0; c < m.indices.size(); ++c) {
    std::array<std::uint32_t, 4> bits;
    std::memcpy(bits.data(), &out.tangents[4 * c], 16);
    tangentsOfVertex[m.indices[c]].insert(bits);
    const std::uint32_t o = out.cornerVertex[c];
    ASSERT_LT(o, out.report.outputVertices) << "corner " << c;
    auto [it, inserted] = outputVertex.try_emplace(o, m.indices[c], bits);
    if (!inserted) {
      ASSERT_EQ(it->second.first, m.indices[c]) << "output vertex " << o << " mixes input vertices";
      ASSERT_EQ(it->second.second, bits) << "output vertex " << o << " mixes tangents";
    }
    if (o < vertexCount) {
      ASSERT_EQ(o, m.indices[c]) << "an input vertex keeps its index";
    }
  }
  std::size_t extra = 0;
  for (const auto& [vertex, tangents] : tangentsOfVertex) extra += tangents.size() - 1;
  EXPECT_EQ(out.report.splitVertices, extra);
  EXPECT_GT(extra, 1000u);  // the hard cases split many vertices: the check is not vacuous
  // Corners with one input vertex and one tangent share one output vertex.
  std::map<std::pair<std::uint32_t, std::array<std::uint32_t, 4>>, std::uint32_t> byValue;
  for (const auto& [o, key] : outputVertex) ASSERT_TRUE(byValue.try_emplace(key, o).second) << "two output vertices for one tangent";
}

TEST(Workspace, RepeatedCallsReuseTheirMemory) {
  const GridMesh big = tangent::testing::makeTorus(200, 100), small = tangent::testing::makeTorus(40, 20);
  tangent::TangentWorkspace workspace;
  const Output first = compute(arraysOf(big), 1, workspace);
  const std::size_t reserved = workspace.bytesReserved();
  EXPECT_GT(reserved, big.indices.size() * 16);  // it holds the per-corner scratch
  const Output again = compute(arraysOf(big), 1, workspace);
  EXPECT_EQ(workspace.bytesReserved(), reserved);
  EXPECT_EQ(first.tangents, again.tangents);
  const Output smaller = compute(arraysOf(small), 1, workspace);
  EXPECT_EQ(workspace.bytesReserved(), reserved);
  EXPECT_EQ(smaller.tangents, compute(arraysOf(small), 1).tangents);  // a reused workspace changes nothing
}

// The plain call (no workspace of the caller's) runs on its thread's cached workspace: every
// method, thread count and vector width gives the bits of a fresh workspace, whatever the
// cache held before (a larger mesh, another method) and after it was released.
// One call of `method` on `threads`: the plain call (the thread's cached workspace) or, with
// `fresh`, a call on a new TangentWorkspace; `sources`, where given, gets each corner's source.
std::vector<float> callWith(bool fresh, const tangent::MeshArrays& mesh, tangent::Method method, unsigned threads,
                            std::vector<tangent::FrameSource>* sources) {
  std::vector<float> tangents(mesh.indices.size() * 4, std::numeric_limits<float>::quiet_NaN());
  tangent::Options options;
  options.method = method;
  options.threads = threads;
  if (sources) sources->assign(mesh.indices.size(), tangent::FrameSource{});
  const std::span<tangent::FrameSource> sourceSpan = sources ? std::span(*sources) : std::span<tangent::FrameSource>();
  if (fresh) {
    tangent::TangentWorkspace workspace;
    tangent::computeCornerTangents(mesh, tangent::CornerOutputs{tangents, sourceSpan}, options, workspace);
  } else {
    tangent::computeCornerTangents(mesh, tangents, options, sourceSpan);
  }
  return tangents;
}

std::vector<float> plainCall(const tangent::MeshArrays& mesh, tangent::Method method, unsigned threads,
                             std::vector<tangent::FrameSource>* sources = nullptr) {
  return callWith(false, mesh, method, threads, sources);
}

std::vector<float> freshCall(const tangent::MeshArrays& mesh, tangent::Method method, unsigned threads,
                             std::vector<tangent::FrameSource>* sources = nullptr) {
  return callWith(true, mesh, method, threads, sources);
}

bool sameBits(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

// TangentWorkspace::setReleaseAsItGoes frees each large array (2 MiB and more) once the call
// has read it for the last time: the same tangents, vertex split and counts for every method on
// one and two threads, a workspace that holds less after the call, and a next call on it (its
// arrays taken again) that gives the same bits again.
TEST(Workspace, ReleasingAsItGoesGivesTheSameBitsAndHoldsLess) {
  const GridMesh big = hardMesh(200000);  // every hard case; per-corner arrays of 2.4 MB
  const std::size_t corners = big.indices.size();
  for (const tangent::Method method : kEveryMethod) {
    for (const unsigned threads : {1u, 2u}) {
      SCOPED_TRACE(std::string(tangent::toString(method)) + " on " + std::to_string(threads) + " thread(s)");
      tangent::TangentWorkspace keeping, releasing;
      releasing.setReleaseAsItGoes(true);
      EXPECT_FALSE(keeping.releasesAsItGoes());
      EXPECT_TRUE(releasing.releasesAsItGoes());
      const Output kept = compute(arraysOf(big), threads, keeping, method);
      const Output released = compute(arraysOf(big), threads, releasing, method);
      EXPECT_TRUE(sameBits(kept.tangents, released.tangents));
      EXPECT_EQ(kept.cornerVertex, released.cornerVertex);
      EXPECT_EQ(kept.report.outputVertices, released.report.outputVertices);
      EXPECT_EQ(kept.report.nonManifoldFaces, released.report.nonManifoldFaces);
      EXPECT_EQ(kept.report.mirroredCorners, released.report.mirroredCorners);
      EXPECT_EQ(kept.report.fallbackFromNeighbours, released.report.fallbackFromNeighbours);
      EXPECT_EQ(kept.report.fallbackFixed, released.report.fallbackFixed);
      // At least two per-corner arrays of 4 bytes fewer (mikktspace: the pairing's two id
      // arrays and the corner links; the others: the triangle pass's results as well).
      EXPECT_LE(releasing.bytesReserved() + 8 * corners, keeping.bytesReserved())
          << releasing.bytesReserved() << " bytes held against " << keeping.bytesReserved();
      EXPECT_TRUE(sameBits(compute(arraysOf(big), threads, releasing, method).tangents, kept.tangents));
    }
  }
}

TEST(CachedWorkspace, PlainCallsGiveTheBitsOfAFreshWorkspaceForEveryMethodThreadCountAndOrder) {
  tangent::releaseCachedWorkspaces();
  ASSERT_EQ(tangent::cachedWorkspaceBytes(), 0u);
  const GridMesh big = hardMesh(), small = tangent::testing::makeTorus(64, 32);
  const auto shuffled = tangent::testing::shuffleFacesAndRotateCorners(big, 7);
  const tangent::Method methods[] = {tangent::Method::mikktspace, tangent::Method::lengyel, tangent::Method::flat,
                                     tangent::Method::meshopt};
  for (const tangent::Method method : methods) {
    for (const unsigned threads : {1u, 2u, 8u}) {
      // Big, then small on the big one's memory, then the big one shuffled, then big again.
      for (const GridMesh* m : {&big, &small, &shuffled.mesh, &big}) {
        std::vector<tangent::FrameSource> cachedSources, freshSources;
        const std::vector<float> cached = plainCall(arraysOf(*m), method, threads, &cachedSources);
        ASSERT_TRUE(sameBits(cached, freshCall(arraysOf(*m), method, threads, &freshSources)))
            << tangent::toString(method) << " threads " << threads << " corners " << m->indices.size();
        ASSERT_EQ(cachedSources, freshSources);
      }
      EXPECT_GT(tangent::cachedWorkspaceBytes(), 0u) << "the plain call keeps its workspace";
    }
  }
  // The shuffled mesh's corners carry the original corners' bits, as for a fresh workspace.
  const std::vector<float> one = plainCall(arraysOf(big), tangent::Method::mikktspace, 1);
  const std::vector<float> s = plainCall(arraysOf(shuffled.mesh), tangent::Method::mikktspace, 2);
  for (std::size_t c = 0; c < shuffled.originalCorner.size(); ++c)
    ASSERT_EQ(0, std::memcmp(&s[4 * c], &one[4 * shuffled.originalCorner[c]], 16)) << "corner " << c;
  // Released: nothing held, and the next call allocates again with the same bits.
  tangent::releaseCachedWorkspaces();
  EXPECT_EQ(tangent::cachedWorkspaceBytes(), 0u);
  EXPECT_TRUE(sameBits(plainCall(arraysOf(big), tangent::Method::mikktspace, 2), one));
  tangent::releaseCachedWorkspaces();
}

TEST(CachedWorkspace, EveryVectorWidthGivesTheSameBitsOnTheCachedWorkspace) {
  const GridMesh m = hardMesh();
  const std::vector<float> scalar = [&] {
    ScopedVectorIsa isa("scalar");
    return freshCall(arraysOf(m), tangent::Method::mikktspace, 1);
  }();
  for (const char* width : {"scalar", "sse2", "avx2", "simd128"}) {
    ScopedVectorIsa isa(width);  // capped at what this build and processor have
    for (const unsigned threads : {1u, 2u})
      ASSERT_TRUE(sameBits(plainCall(arraysOf(m), tangent::Method::mikktspace, threads), scalar)) << width << " " << threads;
  }
  tangent::releaseCachedWorkspaces();
}

TEST(CachedWorkspace, TheLimitFreesWhatIsOverItAndZeroKeepsNothing) {
  const GridMesh m = tangent::testing::makeTorus(200, 100);
  const std::vector<float> expected = freshCall(arraysOf(m), tangent::Method::mikktspace, 1);
  tangent::releaseCachedWorkspaces();
  EXPECT_EQ(tangent::workspaceCacheLimit(), tangent::kDefaultWorkspaceCacheLimit);
  EXPECT_TRUE(sameBits(plainCall(arraysOf(m), tangent::Method::mikktspace, 1), expected));
  const std::size_t held = tangent::cachedWorkspaceBytes();
  EXPECT_GT(held, m.indices.size() * 16);
  tangent::setWorkspaceCacheLimit(held - 1);  // this mesh's workspace is over it
  EXPECT_TRUE(sameBits(plainCall(arraysOf(m), tangent::Method::mikktspace, 1), expected));
  EXPECT_EQ(tangent::cachedWorkspaceBytes(), 0u);
  tangent::setWorkspaceCacheLimit(held);  // exactly at the limit: kept
  EXPECT_TRUE(sameBits(plainCall(arraysOf(m), tangent::Method::mikktspace, 1), expected));
  EXPECT_EQ(tangent::cachedWorkspaceBytes(), held);
  tangent::setWorkspaceCacheLimit(0);  // off: the call uses a workspace of its own
  tangent::releaseCachedWorkspaces();
  EXPECT_TRUE(sameBits(plainCall(arraysOf(m), tangent::Method::mikktspace, 1), expected));
  EXPECT_EQ(tangent::cachedWorkspaceBytes(), 0u);
  tangent::setWorkspaceCacheLimit(tangent::kDefaultWorkspaceCacheLimit);
}

TEST(CachedWorkspace, ANestedCallTakesAWorkspaceOfItsOwnAndThreadsKeepTheirOwn) {
  const GridMesh m = tangent::testing::makeTorus(64, 32);
  const std::vector<float> expected = freshCall(arraysOf(m), tangent::Method::mikktspace, 1);
  tangent::releaseCachedWorkspaces();
  {
    tangent::CachedWorkspace outer;
    tangent::CachedWorkspace inner;  // a call nested in another on this thread
    EXPECT_NE(&outer.get(), &inner.get());
    EXPECT_TRUE(sameBits(plainCall(arraysOf(m), tangent::Method::mikktspace, 1), expected));
    tangent::releaseCachedWorkspaces();  // the leased one stays
  }
  {
    tangent::CachedWorkspace again;  // the thread's cached one, kept through the release above
    EXPECT_EQ(tangent::cachedWorkspaceBytes(), again.get().bytesReserved());
  }
  tangent::releaseCachedWorkspaces();
  // Another thread's call keeps its own workspace, freed by a release from this thread or at its end.
  std::atomic<bool> called{false}, released{false};
  std::thread other([&] {
    EXPECT_TRUE(sameBits(plainCall(arraysOf(m), tangent::Method::mikktspace, 1), expected));
    called = true;
    while (!released) std::this_thread::yield();
  });
  while (!called) std::this_thread::yield();
  EXPECT_GT(tangent::cachedWorkspaceBytes(), 0u);
  tangent::releaseCachedWorkspaces();
  EXPECT_EQ(tangent::cachedWorkspaceBytes(), 0u);
  released = true;
  other.join();
  std::thread ending([&] { plainCall(arraysOf(m), tangent::Method::mikktspace, 1); });
  ending.join();
  EXPECT_EQ(tangent::cachedWorkspaceBytes(), 0u) << "a thread's cache ends with it";
}

// The workspace's large arrays: blocks of 2 MiB and more are mapped fresh on 2 MiB
// boundaries (Linux), keep their elements when the vector grows, and are given back whole.
TEST(BulkVector, LargeBlocksAreAlignedAndKeepTheirElementsWhenGrown) {
  tangent::BulkVector<std::uint32_t> v;
  v.resize(3 << 19);  // 6 MiB
#if defined(__linux__)
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(v.data()) % tangent::kHugePage, 0u);
#endif
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = static_cast<std::uint32_t>(i * 2654435761u);
  v.resize(v.size() + (5 << 18) + 3);  // grows past the block: moved into a new one
  bool kept = true;
  for (std::size_t i = 0; i < (3 << 19); ++i) kept = kept && v[i] == static_cast<std::uint32_t>(i * 2654435761u);
  EXPECT_TRUE(kept);
  v.back() = 7;  // the whole new block is usable
  EXPECT_EQ(v.back(), 7u);
  tangent::BulkVector<std::uint32_t> small(100, 5);  // under 2 MiB: the heap
  EXPECT_EQ(small[99], 5u);
  v.clear();
  v.shrink_to_fit();
  EXPECT_EQ(v.capacity(), 0u);
}

TEST(Workspace, OpenMeshCallGivesTheArrayCallsBitsOnHardCases) {
  const GridMesh m = hardMesh();
  const Output arrays = compute(arraysOf(m), 0);
  tangent::CornerMesh cornerMesh = tangent::buildCornerMesh(arraysOf(m));
  const tangent::Report report = tangent::computeTangents(cornerMesh);
  EXPECT_EQ(report.corners, m.indices.size());
  for (std::size_t c = 0; c < m.indices.size(); ++c) {
    const auto& t = cornerMesh.mesh.property(cornerMesh.tangent, cornerMesh.cornerHalfedge[c]);
    for (int i = 0; i < 4; ++i)
      ASSERT_EQ(std::bit_cast<std::uint32_t>(static_cast<float>(t[i])), std::bit_cast<std::uint32_t>(arrays.tangents[4 * c + i]))
          << "corner " << c;
  }
}

// The OpenMesh call lets corners of one mesh vertex share an array vertex where their values
// are equal; -0 against +0 and NaN must keep them apart exactly as the array call's weld does.
TEST(Workspace, OpenMeshCallKeepsSignedZerosAndNaNsApart) {
  const GridMesh torus = tangent::testing::makeTorus(12, 8);
  GridMesh m;  // one array vertex per corner, so each corner's values can differ
  for (std::size_t c = 0; c < torus.indices.size(); ++c) {
    const std::uint32_t v = torus.indices[c];
    m.positions.insert(m.positions.end(), &torus.positions[3 * v], &torus.positions[3 * v] + 3);
    m.normals.insert(m.normals.end(), &torus.normals[3 * v], &torus.normals[3 * v] + 3);
    m.uvs.insert(m.uvs.end(), &torus.uvs[2 * v], &torus.uvs[2 * v] + 2);
    m.indices.push_back(static_cast<std::uint32_t>(c));
  }
  std::size_t signedZeros = 0, nans = 0;
  for (std::size_t c = 0; c < m.indices.size(); ++c) {
    if (c % 5 == 1 && m.uvs[2 * c] == 0.0f) m.uvs[2 * c] = -0.0f, ++signedZeros;
    // The same NaN bits at every corner of a vertex: equal bits, yet never the same vertex.
    if (torus.indices[c] % 13 == 3) m.normals[3 * c + 1] = std::numeric_limits<float>::quiet_NaN(), ++nans;
    if (torus.indices[c] % 17 == 5) m.uvs[2 * c + 1] = std::numeric_limits<float>::quiet_NaN(), ++nans;
  }
  ASSERT_GT(signedZeros, 0u);
  ASSERT_GT(nans, 0u);
  const Output arrays = compute(arraysOf(m), 1);
  tangent::CornerMesh cornerMesh = tangent::buildCornerMesh(arraysOf(m));
  for (unsigned threads : {1u, 3u}) {
    tangent::Options options;
    options.threads = threads;
    tangent::computeTangents(cornerMesh, options);
    for (std::size_t c = 0; c < m.indices.size(); ++c) {
      const auto& t = cornerMesh.mesh.property(cornerMesh.tangent, cornerMesh.cornerHalfedge[c]);
      for (int i = 0; i < 4; ++i)
        ASSERT_EQ(std::bit_cast<std::uint32_t>(static_cast<float>(t[i])), std::bit_cast<std::uint32_t>(arrays.tangents[4 * c + i]))
            << "corner " << c << ", " << threads << " threads";
    }
  }
}

// Input as a vertex buffer holds it: the attributes interleaved in one buffer (in another
// order, with padding, at an odd byte offset), indices 16-bit or unaligned 32-bit. Every
// method gives the bits, the vertex split and the report of the packed 32-bit call.
TEST(Workspace, StridedAnd16BitInputGiveThePackedBits) {
  const GridMesh m = hardMesh(6000);
  const std::size_t vertexCount = m.positions.size() / 3, cornerCount = m.indices.size();
  ASSERT_LT(vertexCount, 65536u);
  constexpr std::size_t kStride = 40, kUv = 4, kPosition = 12, kNormal = 24;  // bytes; 36..40 padding
  std::vector<std::byte> buffer(2 + vertexCount * kStride, std::byte{0x7f});
  std::byte* vertices = buffer.data() + 2;  // not aligned for float
  for (std::size_t v = 0; v < vertexCount; ++v) {
    std::memcpy(vertices + v * kStride + kUv, &m.uvs[2 * v], 8);
    std::memcpy(vertices + v * kStride + kPosition, &m.positions[3 * v], 12);
    std::memcpy(vertices + v * kStride + kNormal, &m.normals[3 * v], 12);
  }
  std::vector<std::uint16_t> narrow(m.indices.begin(), m.indices.end());
  std::vector<std::byte> unaligned(2 + 4 * cornerCount);
  std::memcpy(unaligned.data() + 2, m.indices.data(), 4 * cornerCount);
  struct Case {
    tangent::Method method;
    tangent::Weighting weighting;
  };
  for (const Case& c : {Case{tangent::Method::mikktspace, tangent::Weighting::angle}, Case{tangent::Method::lengyel, tangent::Weighting::angle},
                        Case{tangent::Method::lengyel, tangent::Weighting::area}, Case{tangent::Method::lengyel, tangent::Weighting::uniform},
                        Case{tangent::Method::flat, tangent::Weighting::angle}}) {
    tangent::Options options;
    options.method = c.method;
    options.weighting = c.weighting;
    options.threads = 2;
    tangent::TangentWorkspace workspace;
    auto run = [&](auto&& input) {
      Output out;
      out.tangents.assign(cornerCount * 4, std::numeric_limits<float>::quiet_NaN());
      out.cornerVertex.assign(cornerCount, ~0u);
      out.report = tangent::computeCornerTangents(input, tangent::CornerOutputs{out.tangents, {}, out.cornerVertex}, options, workspace);
      return out;
    };
    const Output packed = run(arraysOf(m));
    tangent::StridedMesh strided;
    strided.vertexCount = vertexCount;
    strided.positions = vertices + kPosition;
    strided.normals = vertices + kNormal;
    strided.uvs = vertices + kUv;
    strided.positionStride = strided.normalStride = strided.uvStride = kStride;
    strided.indices = narrow.data();
    strided.indexCount = cornerCount;
    strided.indexType = tangent::IndexType::uint16;
    tangent::StridedMesh packedFloatsUnalignedIndices;
    packedFloatsUnalignedIndices.vertexCount = vertexCount;
    packedFloatsUnalignedIndices.positions = m.positions.data();
    packedFloatsUnalignedIndices.normals = m.normals.data();
    packedFloatsUnalignedIndices.uvs = m.uvs.data();
    packedFloatsUnalignedIndices.indices = unaligned.data() + 2;
    packedFloatsUnalignedIndices.indexCount = cornerCount;
    for (const tangent::StridedMesh& input : {strided, packedFloatsUnalignedIndices}) {
      const Output other = run(input);
      const std::string method(tangent::toString(c.method));
      ASSERT_EQ(0, std::memcmp(packed.tangents.data(), other.tangents.data(), packed.tangents.size() * sizeof(float))) << method;
      ASSERT_EQ(packed.cornerVertex, other.cornerVertex) << method;
      EXPECT_EQ(packed.report.splitVertices, other.report.splitVertices) << method;
      EXPECT_EQ(packed.report.mirroredCorners, other.report.mirroredCorners) << method;
      EXPECT_EQ(packed.report.fallbackFixed, other.report.fallbackFixed) << method;
      EXPECT_EQ(packed.report.nonManifoldFaces, other.report.nonManifoldFaces) << method;
    }
  }
}

TEST(WorkspaceErrors, StridedInputIsChecked) {
  const GridMesh m = tangent::testing::makeGrid(2, 2, false);
  std::vector<std::uint16_t> indices(m.indices.begin(), m.indices.end());
  indices[4] = static_cast<std::uint16_t>(m.positions.size() / 3);  // one past the last vertex
  std::vector<float> tangents(m.indices.size() * 4);
  tangent::TangentWorkspace workspace;
  tangent::StridedMesh mesh;
  mesh.vertexCount = m.positions.size() / 3;
  mesh.positions = m.positions.data();
  mesh.normals = m.normals.data();
  mesh.uvs = m.uvs.data();
  mesh.indices = indices.data();
  mesh.indexCount = indices.size();
  mesh.indexType = tangent::IndexType::uint16;
  auto message = [&](const tangent::StridedMesh& input) {
    try {
      tangent::computeCornerTangents(input, tangent::CornerOutputs{tangents}, {}, workspace);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message(mesh), "indices[4] = " + std::to_string(mesh.vertexCount) + " is out of range (vertex count " +
                               std::to_string(mesh.vertexCount) + ")");
  tangent::StridedMesh narrowStride = mesh;
  narrowStride.normalStride = 8;
  EXPECT_EQ(message(narrowStride), "normals: stride 8 is less than 12 bytes");
  tangent::StridedMesh noUvs = mesh;
  noUvs.uvs = nullptr;
  EXPECT_EQ(message(noUvs), "uvs: null");
}

TEST(WorkspaceErrors, CornerVertexOfTheWrongSize) {
  const GridMesh m = tangent::testing::makeGrid(2, 2, false);
  std::vector<float> tangents(m.indices.size() * 4);
  std::vector<std::uint32_t> cornerVertex(m.indices.size() - 1);
  tangent::TangentWorkspace workspace;
  EXPECT_THROW(tangent::computeCornerTangents(arraysOf(m), tangent::CornerOutputs{tangents, {}, cornerVertex}, {}, workspace),
               std::invalid_argument);
}


// One pool and one rule for every method: threads = 0 is every hardware thread this process may
// use, for lengyel and flat as for mikktspace; the pass each method starts with runs on the
// pool the call resolved, even where the caller sits in an arena of one; and no thread count
// moves a bit, on the array call or the OpenMesh call.
TEST(Workspace, ZeroThreadsIsEveryHardwareThreadForEveryMethod) {
  tangent::Options automatic;
  const unsigned hardware = static_cast<unsigned>(std::max(1, tbb::info::default_concurrency()));
  EXPECT_EQ(tangent::threadCount(automatic), hardware);
  tangent::Options three;
  three.threads = 3;
  EXPECT_EQ(tangent::threadCount(three), 3u);

  const GridMesh sphere = tangent::testing::makeSphere(160, 80);  // 25,000 triangles
  // Every method's parallel passes are forRange inside the call's onThreads (entry.cpp).
  tangent::detail::WorkspaceData ws;
  ws.threads = tangent::threadCount(automatic);
  std::atomic<int> widestArena{0};
  tbb::task_arena(1).execute([&] {
    tangent::detail::onThreads(ws, [&] {
      tangent::detail::forRange(ws, sphere.indices.size() / 3, 1024, [&](std::size_t, std::size_t) {
        int seen = widestArena.load();
        const int here = tbb::this_task_arena::max_concurrency();
        while (here > seen && !widestArena.compare_exchange_weak(seen, here)) {
        }
      });
    });
  });
  const auto allowed = tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
  EXPECT_EQ(static_cast<std::size_t>(widestArena.load()), std::min<std::size_t>(hardware, allowed));

  for (auto method : {tangent::Method::lengyel, tangent::Method::flat}) {
    for (auto weighting : {tangent::Weighting::angle, tangent::Weighting::area, tangent::Weighting::uniform}) {
      auto arrayCall = [&](unsigned threads) {
        tangent::Options options;
        options.method = method;
        options.weighting = weighting;
        options.threads = threads;
        std::vector<float> tangents(4 * sphere.indices.size(), std::numeric_limits<float>::quiet_NaN());
        tangent::computeCornerTangents(arraysOf(sphere), tangents, options);
        return tangents;
      };
      auto meshCall = [&](unsigned threads) {
        tangent::Options options;
        options.method = method;
        options.weighting = weighting;
        options.threads = threads;
        tangent::CornerMesh m = tangent::buildCornerMesh(arraysOf(sphere));
        tangent::computeTangents(m, options);
        std::vector<float> tangents;
        for (auto halfedge : m.cornerHalfedge) {
          const auto& t = m.mesh.property(m.tangent, halfedge);
          for (int i = 0; i < 4; ++i) tangents.push_back(static_cast<float>(t[i]));
        }
        return tangents;
      };
      const std::vector<float> one = arrayCall(1), oneMesh = meshCall(1);
      for (unsigned threads : {0u, 2u, 5u}) {
        const std::vector<float> many = arrayCall(threads), manyMesh = meshCall(threads);
        ASSERT_EQ(0, std::memcmp(one.data(), many.data(), one.size() * sizeof(float))) << threads;
        ASSERT_EQ(0, std::memcmp(oneMesh.data(), manyMesh.data(), oneMesh.size() * sizeof(float))) << threads;
      }
    }
  }
}

}  // namespace

namespace {

// The weld's ids and the buckets, recomputed the slow way: a vertex's id is the smallest
// vertex with equal values (+0 == -0, NaN never equal), each bucket holds its corners in
// corner order, and beside each bucketed corner lie its next and previous identities.
void expectWeldAndBuckets(const tangent::MeshArrays& mesh, unsigned threads, const std::string& name, bool edges = true) {
  SCOPED_TRACE(name + ", " + std::to_string(threads) + " threads" + (edges ? "" : ", no identities"));
  tangent::detail::WorkspaceData ws;
  ws.threads = threads;
  tangent::detail::onThreads(ws, [&] {
    tangent::detail::beginCall(ws, mesh);
    tangent::detail::weldAndBucket(ws, mesh, threads, edges);
  });
  const std::size_t vertices = mesh.positions.size() / 3, corners = mesh.indices.size();
  auto same = [&](std::size_t a, std::size_t b) {
    for (int i = 0; i < 3; ++i) {
      if (mesh.positions[3 * a + i] != mesh.positions[3 * b + i] || mesh.normals[3 * a + i] != mesh.normals[3 * b + i])
        return false;
    }
    return mesh.uvs[2 * a] == mesh.uvs[2 * b] && mesh.uvs[2 * a + 1] == mesh.uvs[2 * b + 1];
  };
  std::vector<std::uint32_t> id(vertices);
  std::map<std::array<std::uint32_t, 8>, std::uint32_t> first;  // by canonical bits; NaN apart below
  for (std::size_t v = 0; v < vertices; ++v) {
    std::array<std::uint32_t, 8> key;
    const float values[8] = {mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2],
                             mesh.normals[3 * v],   mesh.normals[3 * v + 1],   mesh.normals[3 * v + 2],
                             mesh.uvs[2 * v],       mesh.uvs[2 * v + 1]};
    for (int i = 0; i < 8; ++i) key[i] = values[i] == 0 ? 0u : std::bit_cast<std::uint32_t>(values[i]);
    const auto [at, inserted] = first.emplace(key, static_cast<std::uint32_t>(v));
    id[v] = !inserted && same(at->second, v) ? at->second : static_cast<std::uint32_t>(v);
  }
  for (std::size_t v = 0; v < vertices; ++v) ASSERT_EQ(ws.vertexId[v], id[v]) << "vertex " << v;
  auto idOf = [&](std::size_t c) { return id[mesh.indices[c]]; };
  for (std::size_t bucket = 0; bucket < vertices; ++bucket) {
    for (std::uint32_t slot = ws.bucketStart[bucket]; slot < ws.bucketStart[bucket + 1]; ++slot) {
      const std::uint32_t c = ws.bucketCorners[slot];
      ASSERT_EQ(idOf(c), bucket) << "slot " << slot;
      if (slot > ws.bucketStart[bucket]) {
        ASSERT_LT(ws.bucketCorners[slot - 1], c) << "slot " << slot;
      }
      if (!edges) continue;
      const std::size_t next = c % 3 == 2 ? c - 2 : c + 1, previous = c % 3 == 0 ? c + 2 : c - 1;
      ASSERT_EQ(ws.bucketNextId[slot], idOf(next)) << "slot " << slot;
      ASSERT_EQ(ws.bucketPreviousId[slot], idOf(previous)) << "slot " << slot;
    }
  }
  ASSERT_EQ(ws.bucketStart[vertices], corners);
}

}  // namespace

// Both ways of bucketing (one counting sort below four threads, by ranges of ids from four,
// whose ranges and chunks shrink with more threads) on a mesh that welds copies and on one
// that welds nothing, with and without the identities beside the corners, and vertices whose
// values differ in sign only (which share the weld's hash): never welded, while +0 and -0 are.
TEST(Workspace, WeldIdsAndBucketsWithEachCornersNeighbourIdentities) {
  const GridMesh hard = hardMesh(20000);
  const GridMesh sphere = tangent::testing::makeSphere(160, 80);
  GridMesh signs;
  // Vertex 0 and its copies: 1 with every value negated, 2 with -0 for +0, 3 with one sign
  // flipped; two triangles over them and two more vertices.
  const float base[8] = {0.5f, 0.0f, -2.0f, 0.0f, 0.0f, 1.0f, 0.25f, 0.75f};
  auto add = [&](const float (&values)[8]) {
    signs.positions.insert(signs.positions.end(), values, values + 3);
    signs.normals.insert(signs.normals.end(), values + 3, values + 6);
    signs.uvs.insert(signs.uvs.end(), values + 6, values + 8);
  };
  float negated[8], zeros[8], oneFlipped[8];
  for (int i = 0; i < 8; ++i) negated[i] = -base[i], zeros[i] = base[i] == 0 ? -0.0f : base[i], oneFlipped[i] = base[i];
  oneFlipped[6] = -base[6];
  add(base), add(negated), add(zeros), add(oneFlipped);
  add({1.0f, 0.0f, 0.0f, 0.0f, 0.0f, 1.0f, 1.0f, 0.0f});
  add({0.0f, 1.0f, 0.0f, 0.0f, 0.0f, 1.0f, 0.0f, 1.0f});
  signs.indices = {0, 4, 5, 1, 4, 5, 2, 5, 4, 3, 4, 5};
  for (unsigned threads : {1u, 2u, 4u, 8u, 16u}) {
    for (bool edges : {true, false}) {
      expectWeldAndBuckets(arraysOf(hard), threads, "hard mesh", edges);
      expectWeldAndBuckets(arraysOf(sphere), threads, "sphere", edges);
      expectWeldAndBuckets(arraysOf(signs), threads, "signs", edges);
    }
  }
  tangent::detail::WorkspaceData ws;
  tangent::detail::beginCall(ws, arraysOf(signs));
  tangent::detail::weldAndBucket(ws, arraysOf(signs), 1, true);
  EXPECT_EQ((std::vector<std::uint32_t>(ws.vertexId.begin(), ws.vertexId.begin() + 6)),
            (std::vector<std::uint32_t>{0, 1, 0, 3, 4, 5}));
}
