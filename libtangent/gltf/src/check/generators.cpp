// SPDX-License-Identifier: MIT
// Fresh frames by one generator, and check --identify (check/generators.hpp).
#include "check/generators.hpp"

#include <algorithm>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include "check/tangent_rules.hpp"

namespace tangent::gltf::detail {
namespace {

// Memory the heap holds free, given back to the system (glibc; elsewhere nothing). Between
// identify's generators: each takes 0.5-1 GB of scratch at 10^6 triangles and frees it, and
// the heap, which the tangent command keeps from returning large blocks (large_pages.cpp), grew
// by 0.2 GB with every generator over the holes the one before left (1.74 GB at the end, where
// the largest generator alone takes 1.16 GB).
void releaseFreeHeap() {
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
}

}  // namespace

void computeFrames(const PrimitiveGeometry& frames, Method method, Weighting weighting, TangentWorkspace& workspace,
                   std::vector<float>& computed, std::vector<FrameSource>& sources) {
  Options core;
  core.method = method;
  core.weighting = weighting;
  core.uvOrigin = kGltfUvOrigin;
  core.threads = threadsFor(frames.corners.size(), core.threads);
  computed.assign(frames.corners.size() * 4, 0.0f);
  sources.assign(frames.corners.size(), FrameSource{});
  computeCornerTangents({frames.positions, frames.normals, frames.uvs, frames.corners}, CornerOutputs{computed, sources}, core, workspace);
}

void identifyGenerator(const PrimitiveGeometry& frames, const PrimitiveGeometry& part, const UsedVertices& used,
                       const std::vector<float>& tangents, TangentWorkspace& workspace, PrimitiveCheck& result) {
  for (const Generator& candidate : kGenerators) {
    std::vector<float> computed;
    std::vector<FrameSource> sources;
    computeFrames(frames, candidate.method, candidate.weighting, workspace, computed, sources);
    std::vector<double> angles;
    std::size_t wAgree = 0;
    for (std::size_t c = 0; c < frames.corners.size(); ++c) {
      if (sources[c] == FrameSource::neighbour || sources[c] == FrameSource::fixed) continue;
      const float* stored = &tangents[4 * used.vertices[part.corners[c]]];
      if (!finite4(stored)) continue;
      angles.push_back(angleBetweenDegrees(stored, &computed[4 * c]));
      wAgree += (stored[3] < 0) == (computed[4 * c + 3] < 0);
    }
    GeneratorMatch match;
    match.name = toString(candidate);
    if (angles.empty()) {
      match.medianDegrees = match.maxDegrees = 180;
    } else {
      // The median by selection, not a sort: a sort of 6 million angles per generator took 8%
      // of identify's time at 10^6 triangles.
      const auto middle = angles.begin() + static_cast<std::ptrdiff_t>(angles.size() / 2);
      std::nth_element(angles.begin(), middle, angles.end());
      match.medianDegrees = *middle;
      match.maxDegrees = *std::max_element(middle, angles.end());
      match.wAgreement = double(wAgree) / double(angles.size());
    }
    result.generators.push_back(std::move(match));
    releaseFreeHeap();
  }
  std::stable_sort(result.generators.begin(), result.generators.end(),
                   [](const GeneratorMatch& a, const GeneratorMatch& b) { return a.medianDegrees < b.medianDegrees; });
  const GeneratorMatch& best = result.generators.front();
  result.generator = best.medianDegrees <= kIdentifyMedianDegrees && best.wAgreement >= kIdentifyWAgreement
                         ? best.name
                         : "none of these (nearest: " + best.name + ")";
}

}  // namespace tangent::gltf::detail
