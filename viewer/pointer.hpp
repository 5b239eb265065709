// SPDX-License-Identifier: MIT
// Mouse drags in the view, as the desktop and the web viewer take them: a left drag orbits the
// camera, or, when it begins on the split view's divider, moves the divider; a right or middle
// drag pans. Fed with the window's events in the order they came (press, every move, release),
// not with the pointer's state polled once a frame: under a software rasteriser a frame takes
// 50-150 ms, and a quick drag begun and ended between two frames would otherwise be lost or
// begin somewhere else.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "camera.hpp"
#include "renderer.hpp"

namespace tangent::viewer {

// How far from the divider (in window pixels, either side) a left press grabs it.
inline constexpr double kDividerGrabPixels = 6;

// Whether a press at window x grabs the divider.
inline bool onDivider(double x, const RenderSettings& settings, int windowWidth) {
  return dividerShown(settings) && windowWidth > 0 && std::abs(x - settings.splitPosition * windowWidth) <= kDividerGrabPixels;
}

// The divider's place (a fraction of the width) for the pointer at window x, kept inside the window.
inline float dividerAt(double x, int windowWidth) { return std::clamp(static_cast<float>(x / std::max(windowWidth, 1)), 0.0f, 1.0f); }

class PointerDrags {
 public:
  enum class Button : std::uint8_t { left, right, middle };

  // A button went down (`down`) or up at the pointer's last position. A press the panel takes
  // (`panelTakesIt`) starts nothing; a release always ends what its button began.
  void button(Button which, bool down, bool panelTakesIt, const RenderSettings& settings, int windowWidth) {
    if (!down) {
      if (which == Button::left) left_ = LeftDrag::none;
      else panning_ &= ~bit(which);
      return;
    }
    if (panelTakesIt) return;
    if (which == Button::left) left_ = onDivider(x_, settings, windowWidth) ? LeftDrag::divider : LeftDrag::orbit;
    else panning_ |= bit(which);
  }

  // The pointer moved to window (x, y): what the drags under way do with the step.
  void move(double x, double y, OrbitCamera& camera, RenderSettings& settings, int windowWidth) {
    const float dx = static_cast<float>(x - x_), dy = static_cast<float>(y - y_);
    x_ = x;
    y_ = y;
    if (left_ == LeftDrag::divider) settings.splitPosition = dividerAt(x, windowWidth);
    else if (left_ == LeftDrag::orbit) camera.orbit(dx, dy);
    if (panning_) camera.pan(dx, dy, camera.matrices(1.0f).view);
  }

  bool movingDivider() const { return left_ == LeftDrag::divider; }

 private:
  enum class LeftDrag : std::uint8_t { none, orbit, divider };
  static std::uint8_t bit(Button which) { return static_cast<std::uint8_t>(1u << static_cast<unsigned>(which)); }
  double x_ = 0, y_ = 0;  // the pointer's last position, window pixels from the top left
  LeftDrag left_ = LeftDrag::none;
  std::uint8_t panning_ = 0;  // bits of the right and middle buttons held since a press outside the panel
};

}  // namespace tangent::viewer
