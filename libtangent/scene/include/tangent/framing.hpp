// SPDX-License-Identifier: MIT
// Where to point a camera to show what `tangent check` flags on a primitive: the thumbnails of
// `tangent check --format html` (through tangent-view --frame-box) and the web viewer's list of
// findings (clicking one frames its triangles) use the same rule.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "tangent/check.hpp"
#include "tangent/scene.hpp"

namespace tangent::gltf {

// One flag per triangle of `item` (1: flagged): the triangles with a corner that fails `check`
// (DrawItem::cornerProblems; w-uniform: the triangles whose corners' stored w differ), or with a
// corner that fails any check for std::nullopt. present and format flag no triangle: they are
// about the whole primitive.
std::vector<std::uint8_t> flaggedTriangles(const DrawItem& item, std::optional<CheckId> check);

// A camera's target: a world-space box and the named side (tangent-view --camera) to look from.
struct Framing {
  std::array<float, 3> lo{}, hi{};
  std::string camera = "iso";
  std::size_t flaggedTriangles = 0;  // 0: nothing flagged, the whole primitive is framed
};

// The world-space box (`world`: the column-major node transform) of the flagged triangles, grown
// to at least kMinFrameShare of the primitive's so that a sliver shows with its surroundings,
// and the side whose view direction best faces their mean normal (iso when the normals cancel
// out). The whole primitive when no triangle is flagged; std::nullopt when it has no finite
// position.
inline constexpr float kMinFrameShare = 0.4f;
std::optional<Framing> frameTriangles(const DrawItem& item, const std::array<float, 16>& world,
                                      std::span<const std::uint8_t> flagged);

}  // namespace tangent::gltf
