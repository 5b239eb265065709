// SPDX-License-Identifier: MIT
// De-indexed corners made indexed by their bits (tangent/shared_vertices.hpp): one pass, an
// open-addressing table of (vertex + 1, hash), a small table of recent finds before it.
#include "tangent/shared_vertices.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <vector>

#include "vertex_hash.hpp"
#include "workspace.hpp"  // bitCast

namespace tangent {
namespace {

// A corner's vertex shared again within a few rows of a mesh is found here without a probe of
// the large table (on the benchmark's sphere 78% of corners): 4096 entries, 32 KiB.
constexpr int kRecentBits = 12;
// Corners hashed and their slots loaded ahead of the probes: WebAssembly has no prefetch, and
// a probe's branch on a slot that misses the cache waits for memory corner after corner; the
// loads of a batch wait together instead.
constexpr std::size_t kBatch = 64;

// Whether `count` floats have the same bits (no call to memcmp: WebAssembly has no inline one).
inline bool sameBits(const float* a, const float* b, int count) {
  using detail::bitCast;
  std::uint32_t differ = 0;
  for (int i = 0; i < count; ++i) differ |= bitCast<std::uint32_t>(a[i]) ^ bitCast<std::uint32_t>(b[i]);
  return differ == 0;
}

inline bool hasNaN(const float* p, const float* n, const float* t) {
  return p[0] != p[0] || p[1] != p[1] || p[2] != p[2] || n[0] != n[0] || n[1] != n[1] || n[2] != n[2] || t[0] != t[0] ||
         t[1] != t[1];
}

// Whether any of a corner's eight values is +0 or -0.
inline bool hasZero(const float* p, const float* n, const float* t) {
  using detail::bitCast;
  auto zero = [](float x) { return (bitCast<std::uint32_t>(x) << 1) == 0; };
  return zero(p[0]) | zero(p[1]) | zero(p[2]) | zero(n[0]) | zero(n[1]) | zero(n[2]) | zero(t[0]) | zero(t[1]);
}

// The core's vertex hash (vertex_hash.hpp), folded to 32 bits: equal bits, equal hashes.
inline std::uint32_t cornerHash(const float* p, const float* n, const float* t) {
  return static_cast<std::uint32_t>(detail::vertexHash(p, n, t));
}

}  // namespace

void VertexSharer::begin(std::size_t cornerCount, SharedVertices& out) {
  out_ = &out;
  cornerCount_ = cornerCount;
  added_ = 0;
  count_ = 0;
  // Sized for about a sixth as many vertices as corners, at most half full; grown (rehashed
  // from the stored hashes) where a mesh shares less.
  capacity_ = 64;
  while (capacity_ < cornerCount / 3) capacity_ *= 2;
  out.table.assign(2 * capacity_, 0u);
  out.recent.assign(std::size_t(2) << kRecentBits, 0u);
  if (out.positions.size() < 3 * cornerCount) {
    out.positions.resize(3 * cornerCount);
    out.normals.resize(3 * cornerCount);
    out.uvs.resize(2 * cornerCount);
  }
  out.indices.resize(cornerCount);
  out.vertexCount = 0;
  out.zeroVertices.clear();
}

bool VertexSharer::add(const float* positions, const float* normals, const float* uvs, std::size_t count) {
  if (count > cornerCount_ - added_) return false;
  SharedVertices& out = *out_;
  float* P = out.positions.data();
  float* N = out.normals.data();
  float* T = out.uvs.data();
  std::uint32_t* indices = out.indices.data() + added_;
  std::uint32_t* recent = out.recent.data();
  std::uint32_t sink = 0;
  auto recentEntry = [&](std::uint32_t hash) { return recent + 2 * (hash >> (32 - kRecentBits)); };
  std::uint32_t hashes[kBatch];
  for (std::size_t first = 0; first < count; first += kBatch) {
    const std::size_t last = std::min(count, first + kBatch);
    std::uint32_t* table = out.table.data();
    std::size_t mask = capacity_ - 1;
    // The batch's hashes, then a load of each large-table slot that the recent table will not
    // answer, in a loop of their own so that they are all in flight at once (their values
    // only summed: the probes below find the slots in cache).
    for (std::size_t c = first; c < last; ++c) hashes[c - first] = cornerHash(positions + 3 * c, normals + 3 * c, uvs + 2 * c);
    for (std::size_t i = 0; i < last - first; ++i) {
      if (recentEntry(hashes[i])[1] != hashes[i]) sink += table[2 * (hashes[i] & mask)];
    }
    for (std::size_t c = first; c < last; ++c) {
      const float* p = positions + 3 * c;
      const float* n = normals + 3 * c;
      const float* t = uvs + 2 * c;
      auto same = [&](std::uint32_t v) {
        return sameBits(P + 3 * v, p, 3) && sameBits(N + 3 * v, n, 3) && sameBits(T + 2 * v, t, 2);
      };
      // A corner with a NaN is looked up like any other but never stored in either table, so
      // that no vertex there has a NaN and no lookup can match one: its test waits for a miss.
      std::uint32_t vertex = static_cast<std::uint32_t>(count_);
      const std::uint32_t hash = hashes[c - first];
      std::uint32_t* near = recentEntry(hash);
      if (near[1] == hash && near[0] != 0 && same(near[0] - 1)) {
        vertex = near[0] - 1;
      } else {
        for (std::size_t slot = hash & mask;; slot = (slot + 1) & mask) {
          std::uint32_t* entry = table + 2 * slot;
          if (entry[0] == 0) {
            if (hasNaN(p, n, t)) break;
            entry[0] = vertex + 1;
            entry[1] = hash;
            near[0] = vertex + 1;
            near[1] = hash;
            break;
          }
          if (entry[1] == hash && same(entry[0] - 1)) {
            vertex = entry[0] - 1;
            near[0] = vertex + 1;
            near[1] = hash;
            break;
          }
        }
      }
      indices[c] = vertex;
      if (vertex != count_) continue;
      std::memcpy(P + 3 * count_, p, 12);
      std::memcpy(N + 3 * count_, n, 12);
      std::memcpy(T + 2 * count_, t, 8);
      if (hasZero(p, n, t)) out.zeroVertices.push_back(static_cast<std::uint32_t>(count_));
      ++count_;
      if (2 * count_ > capacity_) {
        grow();
        table = out.table.data();
        mask = capacity_ - 1;
      }
    }
  }
  added_ += count;
  out.vertexCount = count_;
  out.probeSink += sink;
  return true;
}

// More than half full: twice the slots, each entry moved to its slot by its stored hash.
void VertexSharer::grow() {
  SharedVertices& out = *out_;
  std::vector<std::uint32_t> old(std::move(out.table));
  capacity_ *= 2;
  const std::size_t mask = capacity_ - 1;
  out.table.assign(2 * capacity_, 0u);
  std::uint32_t* table = out.table.data();
  for (std::size_t s = 0; s < old.size(); s += 2) {
    if (old[s] == 0) continue;
    std::size_t slot = old[s + 1] & mask;
    while (table[2 * slot] != 0) slot = (slot + 1) & mask;
    table[2 * slot] = old[s];
    table[2 * slot + 1] = old[s + 1];
  }
}

// All of `cornerCount` corners at once.
void shareVertices(const float* positions, const float* normals, const float* uvs, std::size_t cornerCount,
                   SharedVertices& out) {
  VertexSharer sharer;
  sharer.begin(cornerCount, out);
  sharer.add(positions, normals, uvs, cornerCount);
}

}  // namespace tangent
