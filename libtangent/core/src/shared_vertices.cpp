// SPDX-License-Identifier: MIT
// De-indexed corners made indexed by their bits (tangent/shared_vertices.hpp): one pass, an
// open-addressing table of (vertex + 1, hash), a small table of recent finds before it.
#include "tangent/shared_vertices.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <vector>

#include "parallel.hpp"
#include "tangent/tangent.hpp"
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

// The output arrays sized for `cornerCount` corners (grown only) and emptied: what both ways
// of sharing start from.
void sizeOutputs(SharedVertices& out, std::size_t cornerCount) {
  if (out.positions.size() < 3 * cornerCount) {
    out.positions.resize(3 * cornerCount);
    out.normals.resize(3 * cornerCount);
    out.uvs.resize(2 * cornerCount);
  }
  out.indices.resize(cornerCount);
  out.vertexCount = 0;
  out.zeroVertices.clear();
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
  sizeOutputs(out, cornerCount);
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

namespace {

// shareVertices on several threads, in passes that give VertexSharer's numbering:
//  1. per chunk of corners in order, each corner's hash, and the corner it repeats where a small
//     table of the chunk's recent corners finds one (most repeats are a few rows back); a
//     corner with a NaN is its own first corner (never shared);
//  2. the corners left (first of their bits in their chunk, or not found there), grouped by the
//     top bits of their hash (a stable counting sort: in corner order within a group), and in
//     each group every corner's first corner of the same bits;
//  3. per chunk in order, each repeat's first corner from the one it repeats (earlier, so done);
//  4. the first corners numbered in corner order (a scan), the vertices filled from them.
class ParallelSharer {
 public:
  ParallelSharer(const float* P, const float* N, const float* T, std::size_t count, SharedVertices& out, unsigned threads)
      : P_(P), N_(N), T_(T), count_(count), out_(out) {
    ws_.threads = threads;
  }

  void run() {
    out_.cornerHash.resize(count_);
    out_.firstCorner.resize(count_);
    out_.cornerVertex.resize(count_);
    sizeOutputs(out_, count_);  // table and recent are VertexSharer's only: left as they are
    detail::onThreads(ws_, [&] {
      findRecentRepeats();
      groupTheRest();
      followRepeats();
      numberAndFill();
    });
  }

 private:
  static constexpr std::size_t kChunk = std::size_t(1) << 16;
  static constexpr int kKeyBits = 12;
  // Each chunk's table of recent corners: 16,384 entries (128 KiB), four times VertexSharer's,
  // since a repeat it misses costs a random access in groupTheRest.
  static constexpr int kChunkRecentBits = 14;
  static constexpr std::uint32_t kUnknown = ~std::uint32_t(0);

  bool same(std::size_t a, std::size_t b) const {
    return sameBits(P_ + 3 * a, P_ + 3 * b, 3) && sameBits(N_ + 3 * a, N_ + 3 * b, 3) && sameBits(T_ + 2 * a, T_ + 2 * b, 2);
  }
  bool nan(std::size_t c) const { return hasNaN(P_ + 3 * c, N_ + 3 * c, T_ + 2 * c); }
  std::size_t chunks() const { return (count_ + kChunk - 1) / kChunk; }

  void findRecentRepeats() {
    std::uint32_t* hash = out_.cornerHash.data();
    std::uint32_t* first = out_.firstCorner.data();
    detail::forRange(ws_, chunks(), 1, [&](std::size_t begin, std::size_t end) {
      std::vector<std::uint32_t> recent(std::size_t(2) << kChunkRecentBits);  // (corner + 1, hash)
      for (std::size_t k = begin; k < end; ++k) {
        std::fill(recent.begin(), recent.end(), 0u);
        for (std::size_t c = k * kChunk; c < std::min(count_, (k + 1) * kChunk); ++c) {
          const std::uint32_t h = cornerHash(P_ + 3 * c, N_ + 3 * c, T_ + 2 * c);
          hash[c] = h;
          std::uint32_t* near = recent.data() + 2 * (h >> (32 - kChunkRecentBits));
          if (nan(c)) {
            first[c] = static_cast<std::uint32_t>(c);  // never shared: its own first corner
            continue;
          }
          first[c] = kUnknown;
          if (near[1] == h && near[0] != 0 && same(near[0] - 1, c)) {
            first[c] = near[0] - 1;  // a repeat; its first corner in followRepeats
            continue;
          }
          near[0] = static_cast<std::uint32_t>(c + 1);
          near[1] = h;
        }
      }
    });
  }

  void groupTheRest() {
    const std::uint32_t* hash = out_.cornerHash.data();
    std::uint32_t* first = out_.firstCorner.data();
    const std::vector<std::uint32_t> left =
        detail::collectIf(ws_, count_, [&](std::size_t c) { return first[c] == kUnknown; });
    constexpr std::size_t keys = std::size_t(1) << kKeyBits;
    const std::size_t sortChunks = std::max<std::size_t>(1, std::min<std::size_t>(4 * ws_.threads, left.size() / keys + 1));
    std::vector<std::uint32_t> counters(sortChunks * keys), groupStart(keys + 1), grouped(left.size());
    auto key = [&](std::uint32_t c) { return hash[c] >> (32 - kKeyBits); };
    detail::countingSortInChunks(
        ws_, left.size(), keys, sortChunks,
        [&](std::size_t begin, std::size_t end, std::uint32_t* counter) {
          for (std::size_t i = begin; i < end; ++i) ++counter[key(left[i])];
        },
        counters.data(), groupStart.data(),
        [&](std::size_t begin, std::size_t end, std::uint32_t* next) {
          for (std::size_t i = begin; i < end; ++i) grouped[next[key(left[i])]++] = left[i];
        });
    detail::forRange(ws_, keys, 16, [&](std::size_t begin, std::size_t end) {
      std::vector<std::uint32_t> table;  // (corner + 1, hash) per slot
      for (std::size_t g = begin; g < end; ++g) {
        const std::uint32_t* items = grouped.data() + groupStart[g];
        const std::size_t n = groupStart[g + 1] - groupStart[g];
        std::size_t slots = 16;
        while (slots < 2 * n) slots *= 2;
        table.assign(2 * slots, 0u);
        for (std::size_t i = 0; i < n; ++i) {
          const std::uint32_t c = items[i], h = hash[c];
          std::uint32_t found = c;
          for (std::size_t slot = h & (slots - 1);; slot = (slot + 1) & (slots - 1)) {
            std::uint32_t* entry = table.data() + 2 * slot;
            if (entry[0] == 0) {
              entry[0] = c + 1;
              entry[1] = h;
              break;
            }
            if (entry[1] == h && same(entry[0] - 1, c)) {
              found = entry[0] - 1;  // the smaller: the group is in corner order
              break;
            }
          }
          first[c] = found;
        }
      }
    });
  }

  void followRepeats() {
    std::uint32_t* first = out_.firstCorner.data();
    detail::forRange(ws_, chunks(), 1, [&](std::size_t begin, std::size_t end) {
      for (std::size_t c = begin * kChunk; c < std::min(count_, end * kChunk); ++c) {
        // A repeat found in the recent table names an earlier corner of its chunk, whose first
        // corner is known by now; a corner grouped names itself or its first already.
        const std::uint32_t earlier = first[c];
        if (earlier != c && first[earlier] != earlier) first[c] = first[earlier];
      }
    });
  }

  void numberAndFill() {
    const std::uint32_t* first = out_.firstCorner.data();
    std::uint32_t* vertex = out_.cornerVertex.data();
    detail::forRange(ws_, count_, 1 << 14, [&](std::size_t begin, std::size_t end) {
      for (std::size_t c = begin; c < end; ++c) vertex[c] = first[c] == c ? 1u : 0u;
    });
    const std::uint64_t vertices = detail::exclusiveScan(ws_, vertex, count_);
    float* P = out_.positions.data();
    float* N = out_.normals.data();
    float* T = out_.uvs.data();
    std::uint32_t* indices = out_.indices.data();
    detail::forRange(ws_, count_, 1 << 14, [&](std::size_t begin, std::size_t end) {
      for (std::size_t c = begin; c < end; ++c) {
        const std::uint32_t v = vertex[first[c]];
        indices[c] = v;
        if (first[c] != c) continue;
        std::memcpy(P + 3 * std::size_t(v), P_ + 3 * c, 12);
        std::memcpy(N + 3 * std::size_t(v), N_ + 3 * c, 12);
        std::memcpy(T + 2 * std::size_t(v), T_ + 2 * c, 8);
      }
    });
    out_.vertexCount = static_cast<std::size_t>(vertices);
    out_.zeroVertices = detail::collectIf(ws_, out_.vertexCount, [&](std::size_t v) {
      return hasZero(P + 3 * v, N + 3 * v, T + 2 * v);
    });
  }

  const float *P_, *N_, *T_;
  std::size_t count_;
  SharedVertices& out_;
  detail::WorkspaceData ws_;
};

}  // namespace

// Natively on the benchmark's de-indexed sphere of 1e6 triangles (3e6 corners, 22% of them
// left for the groups, nearly all first corners), on this project's 2-core machine: VertexSharer
// 80 ms, two threads 65-75 ms; the passes are bound by memory, and the groups' pass reads the
// corners it is left at random. Below 2 chunks, one thread's VertexSharer.
unsigned threadsToShareOn(std::size_t cornerCount, unsigned threads) {
  Options options;
  options.threads = threads;
  const unsigned count = threadCount(options);
  return count > 1 && cornerCount > 2 * (std::size_t(1) << 16) ? count : 1;
}

void shareVertices(const float* positions, const float* normals, const float* uvs, std::size_t cornerCount,
                   SharedVertices& out, unsigned threads) {
  if (const unsigned count = threadsToShareOn(cornerCount, threads); count > 1) {
    ParallelSharer(positions, normals, uvs, cornerCount, out, count).run();
    return;
  }
  VertexSharer sharer;
  sharer.begin(cornerCount, out);
  sharer.add(positions, normals, uvs, cornerCount);
}

}  // namespace tangent
