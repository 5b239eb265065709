// SPDX-License-Identifier: MIT
// referenceAllowance and allowanceBounds (tangent_rules.hpp): how far rounded positions and UVs
// (KHR_mesh_quantization, Draco) can turn the frame recomputed at each vertex, so that
// `reference` does not blame the stored tangents for it.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <utility>

#if !defined(TANGENT_SERIAL)
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#endif

#include "check/tangent_rules.hpp"
#include "read/primitive.hpp"

namespace tangent::gltf::detail {
namespace {

// One triangle's share of its corners' frames, as MikkTSpace sums them (and Lengyel's angle
// weighting): its tangent direction v = sign * (e1 * dv2 - e2 * dv1) (e: edges from corner 0,
// dv: their V deltas, sign: that of the UV area, held fixed), projected onto each corner's
// normal plane, unit length, times the corner's angle; zero where undefined.
// `weights`: the corners' angles, computed into it where `keepWeights` is false, else taken
// from it (a V moved: the positions, and so the angles, are the same).
constexpr double kHalfPi = 1.57079632679489661923;

inline double norm3(double x, double y, double z) { return std::sqrt(x * x + y * y + z * z); }

// A triangle's UV orientation (the sign of its UV area) and whether rounding UVs by up to eu
// leaves it decided: the area moves by at most 2 eu (|du1| + |du2| + |dv1| + |dv2|) + 8 eu^2.
struct UvOrientation {
  double sign = 1;
  bool decided = true;
};
UvOrientation uvOrientation(const PrimitiveGeometry& geometry, const std::uint32_t* c, double eu) {
  const float* uv[3] = {&geometry.uvs[2 * c[0]], &geometry.uvs[2 * c[1]], &geometry.uvs[2 * c[2]]};
  const double du1 = double(uv[1][0]) - uv[0][0], dv1 = double(uv[1][1]) - uv[0][1];
  const double du2 = double(uv[2][0]) - uv[0][0], dv2 = double(uv[2][1]) - uv[0][1];
  const double area = du1 * dv2 - du2 * dv1;
  const double areaChange = 2 * eu * (std::abs(du1) + std::abs(du2) + std::abs(dv1) + std::abs(dv2)) + 8 * eu * eu;
  return {area < 0 ? -1.0 : 1.0, std::abs(area) > areaChange && std::isfinite(area)};
}

// How far a sum of length `size` can turn when it moves by up to `moved`: asin(moved / size),
// or uncomparable where the movement reaches its length.
float turnDegrees(double moved, double size) {
  return moved < size ? static_cast<float>(std::asin(moved / size) * kDegreesPerRadian) : kUncomparableDegrees;
}

void cornerShares(const double p[3][3], const double v[3], double sign, const float* const normals[3], double weights[3], bool keepWeights,
                  double shares[3][3]) {
  double e1[3], e2[3], direction[3];
  for (int i = 0; i < 3; ++i) {
    e1[i] = p[1][i] - p[0][i];
    e2[i] = p[2][i] - p[0][i];
  }
  const double dv1 = v[1] - v[0], dv2 = v[2] - v[0];
  for (int i = 0; i < 3; ++i) direction[i] = sign * (e1[i] * dv2 - e2[i] * dv1);
  for (int k = 0; k < 3; ++k) {
    for (int i = 0; i < 3; ++i) shares[k][i] = 0;
    const float* n = normals[k];
    const double nLength = std::sqrt(double(n[0]) * n[0] + double(n[1]) * n[1] + double(n[2]) * n[2]);
    const bool hasNormal = nLength > 0 && std::isfinite(nLength);
    auto project = [&](double x[3]) {
      if (!hasNormal) return;
      const double dot = (x[0] * n[0] + x[1] * n[1] + x[2] * n[2]) / (nLength * nLength);
      for (int i = 0; i < 3; ++i) x[i] -= dot * n[i];
    };
    // The corner's angle between its edges projected onto the normal plane; 90 deg where one
    // is zero (MikkTSpace's rule: the dot product of a zero vector).
    if (!keepWeights) {
      const double* here = p[k];
      const double* next = p[(k + 1) % 3];
      const double* prev = p[(k + 2) % 3];
      double a[3] = {next[0] - here[0], next[1] - here[1], next[2] - here[2]};
      double b[3] = {prev[0] - here[0], prev[1] - here[1], prev[2] - here[2]};
      project(a);
      project(b);
      const double cross[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
      const bool zeroEdge = !(norm3(a[0], a[1], a[2]) > 0) || !(norm3(b[0], b[1], b[2]) > 0);
      weights[k] = zeroEdge ? kHalfPi : std::atan2(norm3(cross[0], cross[1], cross[2]), a[0] * b[0] + a[1] * b[1] + a[2] * b[2]);
    }
    const double weight = weights[k];
    double projected[3] = {direction[0], direction[1], direction[2]};
    project(projected);
    const double projectedLength = norm3(projected[0], projected[1], projected[2]);
    if (!(projectedLength > 0) || !std::isfinite(projectedLength) || !std::isfinite(weight)) continue;
    for (int i = 0; i < 3; ++i) shares[k][i] = weight * projected[i] / projectedLength;
  }
}

// Vertices whose `width` floats from `values` are equal, numbered: rounding gives equal values
// equal results, so such vertices (a UV seam's copies of a position, a hard edge's copies of
// a UV) moved together.
std::vector<std::uint32_t> equalValueGroups(const std::vector<float>& values, int width, std::size_t count, std::uint32_t& groups) {
  // Compared as bit patterns: a strict order even with NaN in the data.
  std::vector<std::uint32_t> bits(values.size()), order(count), group(count, 0);
  if (!values.empty()) std::memcpy(bits.data(), values.data(), values.size() * sizeof(float));
  for (std::size_t v = 0; v < count; ++v) order[v] = static_cast<std::uint32_t>(v);
  auto less = [&](std::uint32_t a, std::uint32_t b) {
    return std::lexicographical_compare(&bits[std::size_t(a) * width], &bits[std::size_t(a) * width] + width, &bits[std::size_t(b) * width],
                                        &bits[std::size_t(b) * width] + width);
  };
  std::sort(order.begin(), order.end(), less);
  groups = 0;
  for (std::size_t i = 0; i < count; ++i) {
    if (i > 0 && less(order[i - 1], order[i])) ++groups;
    group[order[i]] = groups;
  }
  if (count) ++groups;
  return group;
}

// The bound this file used first, triangle by triangle (5-8x too loose on gltfpack outputs, but
// cheap): a triangle's tangent direction v = e1 * dv2 - e2 * dv1 moves by at most
//   2 eu (|e1| + |e2|) + 2 sqrt(3) ep (|dv1| + |dv2|) + 8 sqrt(3) ep eu,
// and turns by at most asin(change / |v|); each triangle's unit tangent moves by at most the
// chord 2 sin(turn / 2) (2 when its orientation is undecided), so a vertex's angle-weighted sum
// S moves by at most E = sum a_i chord_i and turns by at most asin(E / |S|). Where it is below
// kCoarseEnoughDegrees, referenceAllowance keeps it and skips the finer computation.
std::vector<float> coarseVertexDegrees(const PrimitiveGeometry& geometry, const InputRounding& rounding) {
  const double eu = rounding.uv, ep = rounding.position, root3 = std::sqrt(3.0);
  const std::size_t triangles = geometry.corners.size() / 3;
  std::vector<double> sum(3 * geometry.vertexCount, 0.0), movement(geometry.vertexCount, 0.0);
  for (std::size_t t = 0; t < triangles; ++t) {
    const std::uint32_t* c = &geometry.corners[3 * t];
    const float* p[3] = {&geometry.positions[3 * c[0]], &geometry.positions[3 * c[1]], &geometry.positions[3 * c[2]]};
    const float* uv[3] = {&geometry.uvs[2 * c[0]], &geometry.uvs[2 * c[1]], &geometry.uvs[2 * c[2]]};
    double e1[3], e2[3];
    for (int i = 0; i < 3; ++i) {
      e1[i] = double(p[1][i]) - p[0][i];
      e2[i] = double(p[2][i]) - p[0][i];
    }
    const double dv1 = double(uv[1][1]) - uv[0][1], dv2 = double(uv[2][1]) - uv[0][1];
    const UvOrientation orientation = uvOrientation(geometry, c, eu);
    const double sign = orientation.sign;
    double v[3] = {sign * (e1[0] * dv2 - e2[0] * dv1), sign * (e1[1] * dv2 - e2[1] * dv1), sign * (e1[2] * dv2 - e2[2] * dv1)};
    const double vLength = std::hypot(v[0], v[1], v[2]);
    double chord = 2;
    if (orientation.decided) {
      const double e1Length = std::hypot(e1[0], e1[1], e1[2]), e2Length = std::hypot(e2[0], e2[1], e2[2]);
      const double change = 2 * eu * (e1Length + e2Length) + 2 * root3 * ep * (std::abs(dv1) + std::abs(dv2)) + 8 * root3 * ep * eu;
      if (change < vLength) chord = 2 * std::sin(std::asin(change / vLength) / 2);
    }
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t vertex = c[k];
      // Corner angle at this vertex: the weight MikkTSpace gives the triangle there.
      const float* here = p[k];
      const float* next = p[(k + 1) % 3];
      const float* prev = p[(k + 2) % 3];
      const float a[3] = {next[0] - here[0], next[1] - here[1], next[2] - here[2]};
      const float b[3] = {prev[0] - here[0], prev[1] - here[1], prev[2] - here[2]};
      const double weight = angleBetweenDegrees(a, b) / kDegreesPerRadian;
      if (!std::isfinite(weight)) continue;
      movement[vertex] += weight * chord;
      // The triangle's tangent projected onto the vertex's normal plane, unit length.
      const float* n = &geometry.normals[3 * vertex];
      const double nLength = length3(n);
      double projected[3] = {v[0], v[1], v[2]};
      if (nLength > 0 && std::isfinite(nLength)) {
        const double dot = (v[0] * n[0] + v[1] * n[1] + v[2] * n[2]) / (nLength * nLength);
        for (int i = 0; i < 3; ++i) projected[i] -= dot * n[i];
      }
      const double projectedLength = std::hypot(projected[0], projected[1], projected[2]);
      if (!(projectedLength > 0) || !std::isfinite(projectedLength)) continue;
      for (int i = 0; i < 3; ++i) sum[3 * vertex + i] += weight * projected[i] / projectedLength;
    }
  }
  std::vector<float> degrees(geometry.vertexCount);
  for (std::size_t v = 0; v < geometry.vertexCount; ++v)
    degrees[v] = turnDegrees(movement[v], std::hypot(sum[3 * v], sum[3 * v + 1], sum[3 * v + 2]));
  return degrees;
}


}  // namespace

// A vertex's frame is the direction of S, the sum of its triangles' shares (cornerShares).
// Rounding moved each position component by up to ep and each UV component by up to eu from
// what the tangents were baked from. U enters a triangle's share only through the sign of its
// UV area: where the rounding can change that sign (the area moves by at most
// 2 eu (|du1| + |du2| + |dv1| + |dv2|) + 8 eu^2), the triangle's orientation is undecided, it
// may join or leave the vertex's group, and its share counts as moving by twice its weight.
// Every other input x_j (a V, a position component; vertices with equal values move together,
// as rounding moves them) moves S by the vector dS_j when it alone moves by its half step,
// recomputed. To first order the joint movement is their sum, so |dS| <= E = sum |dS_j| (the
// inputs' effects on the same triangle added as vectors first: they partly cancel, which the
// triangle-by-triangle worst case (coarseVertexDegrees) does not see; it is 5-8x too loose on
// gltfpack outputs). kSecondOrderMargin covers the products of moves the first order leaves
// out, and S turns by at most asin(E / |S|); where E reaches |S| the vertex cannot be compared.
// Where the coarse bound is already small, it is kept (the finer one is not computed there).
namespace {

constexpr float kCoarseEnoughDegrees = 4.0f;  // a 10 deg turn is caught under it anyway

// Every triangle's UV orientation (and whether rounding leaves it decided) and its corners'
// shares; per vertex, S (the sum of its shares) and the movement that undecided triangles give.
struct BaseShares {
  std::vector<double> sum;       // S, 3 per vertex
  std::vector<double> movement;  // per vertex, added to by each phase
  std::vector<double> shares;    // 9 per triangle: a share per corner
  std::vector<double> weights;   // 3 per triangle: the corners' angles
  std::vector<double> signs;     // per triangle: the sign of its UV area
};

// A triangle's positions, V coordinates and normals, as cornerShares reads them.
void loadTriangle(const PrimitiveGeometry& geometry, std::size_t t, double p[3][3], double v[3], const float* normals[3]) {
  for (int k = 0; k < 3; ++k) {
    const std::uint32_t vertex = geometry.corners[3 * t + k];
    for (int i = 0; i < 3; ++i) p[k][i] = geometry.positions[3 * vertex + i];
    v[k] = geometry.uvs[2 * vertex + 1];
    normals[k] = &geometry.normals[3 * vertex];
  }
}

BaseShares baseShares(const PrimitiveGeometry& geometry, double eu, ReferenceAllowance& allowance) {
  const std::size_t triangles = geometry.corners.size() / 3, vertexCount = geometry.vertexCount;
  BaseShares base;
  base.sum.assign(3 * vertexCount, 0.0);
  base.movement.assign(vertexCount, 0.0);
  base.shares.assign(9 * triangles, 0.0);
  base.weights.assign(3 * triangles, 0.0);
  base.signs.assign(triangles, 1.0);
  for (std::size_t t = 0; t < triangles; ++t) {
    const std::uint32_t* c = &geometry.corners[3 * t];
    const UvOrientation orientation = uvOrientation(geometry, c, eu);
    base.signs[t] = orientation.sign;
    if (!orientation.decided) allowance.orientationDecided[t] = 0;
    double p[3][3], v[3];
    const float* normals[3];
    loadTriangle(geometry, t, p, v, normals);
    double share[3][3];
    cornerShares(p, v, base.signs[t], normals, &base.weights[3 * t], false, share);
    for (int k = 0; k < 3; ++k) {
      for (int i = 0; i < 3; ++i) {
        base.shares[9 * t + 3 * k + i] = share[k][i];
        base.sum[3 * c[k] + i] += share[k][i];
      }
      if (!allowance.orientationDecided[t]) base.movement[c[k]] += 2 * norm3(share[k][0], share[k][1], share[k][2]);
    }
  }
  return base;
}

// The decided triangles at each vertex that have a share, as offsets and a list. A triangle
// without one (its direction exactly zero: a pole's coincident vertices on one UV row) is left
// out: exact zeros come from exact data, which rounding keeps (tools map a range's ends exactly).
struct IncidentTriangles {
  std::vector<std::uint32_t> first;  // per vertex + 1: where its triangles start in `list`
  std::vector<std::uint32_t> list;
};

IncidentTriangles movingTriangles(const PrimitiveGeometry& geometry, const BaseShares& base, const ReferenceAllowance& allowance) {
  const std::size_t triangles = geometry.corners.size() / 3, vertexCount = geometry.vertexCount;
  const std::vector<double>& shares = base.shares;
  std::vector<char> moves(triangles, 0);
  for (std::size_t t = 0; t < triangles; ++t)
    moves[t] = allowance.orientationDecided[t] && std::any_of(&shares[9 * t], &shares[9 * t] + 9, [](double x) { return x != 0; });
  IncidentTriangles incident;
  std::vector<std::uint32_t>& firstTriangle = incident.first;
  firstTriangle.assign(vertexCount + 1, 0);
  for (std::size_t t = 0; t < triangles; ++t)
    if (moves[t])
      for (int k = 0; k < 3; ++k) ++firstTriangle[geometry.corners[3 * t + k] + 1];
  for (std::size_t v = 0; v < vertexCount; ++v) firstTriangle[v + 1] += firstTriangle[v];
  incident.list.resize(firstTriangle[vertexCount]);
  std::vector<std::uint32_t> next(firstTriangle.begin(), firstTriangle.end() - 1);
  for (std::size_t t = 0; t < triangles; ++t)
    if (moves[t])
      for (int k = 0; k < 3; ++k) incident.list[next[geometry.corners[3 * t + k]]++] = static_cast<std::uint32_t>(t);
  return incident;
}

// The vertices of equal values (equalValueGroups) as groups: each vertex's group, and each
// group's vertices as offsets and a list.
struct ValueGroups {
  std::vector<std::uint32_t> group;       // per vertex
  std::uint32_t count = 0;
  std::vector<std::uint32_t> members;     // per group + 1: where its vertices start in memberList
  std::vector<std::uint32_t> memberList;
};

ValueGroups valueGroups(const std::vector<float>& values, int width, std::size_t vertexCount) {
  ValueGroups groups;
  groups.group = equalValueGroups(values, width, vertexCount, groups.count);
  groups.members.assign(groups.count + 1, 0);
  for (std::size_t v = 0; v < vertexCount; ++v) ++groups.members[groups.group[v] + 1];
  for (std::uint32_t k = 0; k < groups.count; ++k) groups.members[k + 1] += groups.members[k];
  groups.memberList.resize(vertexCount);
  std::vector<std::uint32_t> next(groups.members.begin(), groups.members.end() - 1);
  for (std::size_t v = 0; v < vertexCount; ++v) groups.memberList[next[groups.group[v]]++] = static_cast<std::uint32_t>(v);
  return groups;
}

// dS_j per input: a group of equal values moved by its half step; |dS_j| for each vertex of the
// group's triangles, appended to `out` in vertex order. Only groups with a triangle at a vertex
// whose coarse bound exceeds `fineAbove` are moved.
class GroupMover {
 public:
  struct Scratch {
    std::vector<std::uint32_t> affected;
    std::vector<std::pair<std::uint32_t, std::array<double, 3>>> changes;
  };

  GroupMover(const PrimitiveGeometry& geometry, const BaseShares& base, const IncidentTriangles& incident,
             const std::vector<float>& coarse, float fineAbove)
      : geometry_(geometry), base_(base), incident_(incident), coarse_(coarse), fineAbove_(fineAbove) {}

  // `groups` until the next call: the groups of the input moved (0: V, 1-3: x, y, z).
  void moveGroup(const ValueGroups& groups, std::uint32_t k, int input, double step, Scratch& scratch,
                 std::vector<std::pair<std::uint32_t, double>>& out) const {
    const std::vector<std::uint32_t>& corners = geometry_.corners;
    std::vector<std::uint32_t>& affected = scratch.affected;
    affected.clear();
    for (std::uint32_t m = groups.members[k]; m < groups.members[k + 1]; ++m) {
      const std::uint32_t w = groups.memberList[m];
      affected.insert(affected.end(), incident_.list.begin() + incident_.first[w], incident_.list.begin() + incident_.first[w + 1]);
    }
    std::sort(affected.begin(), affected.end());
    affected.erase(std::unique(affected.begin(), affected.end()), affected.end());
    const bool needed = std::any_of(affected.begin(), affected.end(), [&](std::uint32_t t) {
      return coarse_[corners[3 * t]] > fineAbove_ || coarse_[corners[3 * t + 1]] > fineAbove_ || coarse_[corners[3 * t + 2]] > fineAbove_;
    });
    if (!needed) return;
    auto& changes = scratch.changes;
    changes.clear();
    for (const std::uint32_t t : affected) {
      double p[3][3], v[3];
      const float* normals[3];
      loadTriangle(geometry_, t, p, v, normals);
      for (int corner = 0; corner < 3; ++corner) {
        if (groups.group[corners[3 * t + corner]] != k) continue;
        if (input == 0) v[corner] += step; else p[corner][input - 1] += step;
      }
      const std::vector<double>& weights = base_.weights;
      double share[3][3], moved[3] = {weights[3 * t], weights[3 * t + 1], weights[3 * t + 2]};
      cornerShares(p, v, base_.signs[t], normals, moved, input == 0, share);
      for (int corner = 0; corner < 3; ++corner) {
        const double* before = &base_.shares[9 * t + 3 * corner];
        changes.push_back({corners[3 * t + corner], {share[corner][0] - before[0], share[corner][1] - before[1], share[corner][2] - before[2]}});
      }
    }
    std::stable_sort(changes.begin(), changes.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    for (std::size_t i = 0; i < changes.size();) {
      std::array<double, 3> total = {0, 0, 0};
      std::size_t j = i;
      for (; j < changes.size() && changes[j].first == changes[i].first; ++j)
        for (int c = 0; c < 3; ++c) total[c] += changes[j].second[c];
      out.push_back({changes[i].first, norm3(total[0], total[1], total[2])});
      i = j;
    }
  }

 private:
  const PrimitiveGeometry& geometry_;
  const BaseShares& base_;
  const IncidentTriangles& incident_;
  const std::vector<float>& coarse_;
  float fineAbove_;
};

// Every group of one input moved (GroupMover), its |dS_j| added to `movement`. Groups in
// chunks, a batch of chunks at a time on the oneTBB pool the core uses (its arena and global
// limits apply; one thread in the web build); the movements are added in group order, so the
// result does not depend on the thread count.
void addInputMovements(const GroupMover& mover, const ValueGroups& groups, int input, double step,
                       std::vector<GroupMover::Scratch>& scratch, std::vector<double>& movement) {
  constexpr std::uint32_t kChunk = 4096;
  const auto threads = static_cast<unsigned>(scratch.size());
  const std::uint32_t groupCount = groups.count;
  const std::uint32_t chunks = (groupCount + kChunk - 1) / kChunk;
  for (std::uint32_t firstChunk = 0; firstChunk < chunks; firstChunk += 4 * threads) {
    const std::uint32_t batch = std::min(chunks - firstChunk, 4 * threads);
    std::vector<std::vector<std::pair<std::uint32_t, double>>> results(batch);
    auto chunk = [&](std::uint32_t c, GroupMover::Scratch& mine) {
      const std::uint32_t first = (firstChunk + c) * kChunk, last = std::min(groupCount, first + kChunk);
      for (std::uint32_t k = first; k < last; ++k) mover.moveGroup(groups, k, input, step, mine, results[c]);
    };
#if defined(TANGENT_SERIAL)
    for (std::uint32_t c = 0; c < batch; ++c) chunk(c, scratch[0]);
#else
    if (threads == 1 || batch == 1) {
      for (std::uint32_t c = 0; c < batch; ++c) chunk(c, scratch[0]);
    } else {
      tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, batch, 1), [&](const tbb::blocked_range<std::uint32_t>& range) {
        // Each thread of the arena has its own scratch (its slot index is below max_concurrency).
        const int slot = tbb::this_task_arena::current_thread_index();
        GroupMover::Scratch& mine = scratch[slot >= 0 && static_cast<unsigned>(slot) < threads ? slot : 0];
        for (std::uint32_t c = range.begin(); c < range.end(); ++c) chunk(c, mine);
      });
    }
#endif
    for (const auto& result : results)
      for (const auto& [vertex, moved] : result) movement[vertex] += moved;
  }
}

// Both bounds per vertex (and `allowance`'s orientations). The finer one moves only the inputs
// of triangles with a vertex whose coarse bound exceeds `fineAbove` (-1: every triangle), so it
// holds at those vertices alone.
AllowanceBounds computeAllowanceBounds(const PrimitiveGeometry& geometry, const InputRounding& rounding, float fineAbove,
                                       ReferenceAllowance& allowance) {
  constexpr double kSecondOrderMargin = 1.25;
  AllowanceBounds bounds;
  if (!rounding.any()) return bounds;
  const std::vector<float> coarse = coarseVertexDegrees(geometry, rounding);
  const double eu = rounding.uv, ep = rounding.position;
  const std::size_t triangles = geometry.corners.size() / 3, vertexCount = geometry.vertexCount;
  allowance.vertexDegrees.assign(vertexCount, 0.0f);
  allowance.orientationDecided.assign(triangles, 1);
  BaseShares base = baseShares(geometry, eu, allowance);
  const IncidentTriangles incident = movingTriangles(geometry, base, allowance);
  const GroupMover mover(geometry, base, incident, coarse, fineAbove);
#if defined(TANGENT_SERIAL)
  const unsigned threads = 1;
#else
  const unsigned threads = static_cast<unsigned>(std::max(1, tbb::this_task_arena::max_concurrency()));
#endif
  std::vector<GroupMover::Scratch> scratch(threads);
  ValueGroups groups;
  for (int input = 0; input < 4; ++input) {  // V, then x, y, z
    const double step = input == 0 ? eu : ep;
    if (!(step > 0)) continue;
    if (input == 0) groups = valueGroups(geometry.uvs, 2, vertexCount);
    if (input == 1) groups = valueGroups(geometry.positions, 3, vertexCount);
    addInputMovements(mover, groups, input, step, scratch, base.movement);
  }
  bounds.coarseDegrees = coarse;
  bounds.fineDegrees.assign(vertexCount, kUncomparableDegrees);
  for (std::size_t v = 0; v < vertexCount; ++v) {
    const double size = std::hypot(base.sum[3 * v], base.sum[3 * v + 1], base.sum[3 * v + 2]);
    const double moved = kSecondOrderMargin * base.movement[v];
    bounds.fineDegrees[v] = turnDegrees(moved, size);
  }
  return bounds;
}

}  // namespace

ReferenceAllowance referenceAllowance(const PrimitiveGeometry& geometry, const InputRounding& rounding) {
  ReferenceAllowance allowance;
  const AllowanceBounds bounds = computeAllowanceBounds(geometry, rounding, kCoarseEnoughDegrees, allowance);
  for (std::size_t v = 0; v < allowance.vertexDegrees.size(); ++v) {
    const float coarse = bounds.coarseDegrees[v];
    allowance.vertexDegrees[v] = coarse <= kCoarseEnoughDegrees ? coarse : std::min(coarse, bounds.fineDegrees[v]);
  }
  return allowance;
}

AllowanceBounds allowanceBounds(const PrimitiveGeometry& geometry, const InputRounding& rounding) {
  ReferenceAllowance unused;
  return computeAllowanceBounds(geometry, rounding, -1.0f, unused);
}

}  // namespace tangent::gltf::detail
