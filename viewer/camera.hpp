// SPDX-License-Identifier: MIT
// Orbit camera: yaw/pitch around a target, distance, pan; named views that frame the scene.
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <string_view>

#include "renderer.hpp"

namespace tangent::viewer {

// The sides OrbitCamera::frame looks from, as --camera names them.
inline constexpr std::string_view kCameraViews = "front|back|left|right|top|bottom|iso";

struct OrbitCamera {
  glm::vec3 target{0};
  float distance = 5;
  float yaw = 0, pitch = 0;  // radians; yaw 0, pitch 0 looks along -z (the front view)
  float radius = 1;          // of the framed scene
  bool orthographic = false;

  glm::vec3 eye() const {
    const glm::vec3 offset(std::sin(yaw) * std::cos(pitch), std::sin(pitch), std::cos(yaw) * std::cos(pitch));
    return target + offset * distance;
  }

  CameraMatrices matrices(float aspect) const {
    CameraMatrices m;
    m.eye = eye();
    const glm::vec3 up = std::abs(std::cos(pitch)) < 1e-4f ? glm::vec3(0, 0, -1) : glm::vec3(0, 1, 0);
    m.view = glm::lookAt(m.eye, target, up);
    const float nearPlane = std::max(distance - 3 * radius, distance * 1e-3f), farPlane = distance + 3 * radius;
    if (orthographic) {
      const float halfHeight = std::max(radius, radius / aspect) * 1.02f;
      m.projection = glm::ortho(-halfHeight * aspect, halfHeight * aspect, -halfHeight, halfHeight, nearPlane, farPlane);
    } else {
      m.projection = glm::perspective(glm::radians(kFieldOfViewY), aspect, nearPlane, farPlane);
    }
    return m;
  }

  static constexpr float kFieldOfViewY = 40.0f;  // degrees

  // Frames the bounds from a named side (kCameraViews). The
  // perspective view backs off just far enough that all eight corners of the box are inside
  // the frame of the given aspect (plus 5%); the orthographic one shows the bounding sphere.
  bool frame(glm::vec3 boundsMin, glm::vec3 boundsMax, const std::string& view, float aspect = 16.0f / 9.0f) {
    target = (boundsMin + boundsMax) * 0.5f;
    radius = std::max(glm::length(boundsMax - boundsMin) * 0.5f, 1e-3f);
    const float quarter = glm::half_pi<float>();
    if (view == "front") yaw = 0, pitch = 0;
    else if (view == "back") yaw = 2 * quarter, pitch = 0;
    else if (view == "right") yaw = quarter, pitch = 0;
    else if (view == "left") yaw = -quarter, pitch = 0;
    else if (view == "top") yaw = 0, pitch = quarter;
    else if (view == "bottom") yaw = 0, pitch = -quarter;
    else if (view == "iso") yaw = quarter / 2, pitch = 0.6f;
    else return false;
    distance = 1;
    const glm::mat4 view1 = matrices(aspect).view;  // orientation only: the eye at distance 1
    const float tanY = std::tan(glm::radians(kFieldOfViewY) * 0.5f), tanX = tanY * aspect;
    float needed = 0;
    for (int corner = 0; corner < 8; ++corner) {
      const glm::vec3 p((corner & 1) ? boundsMax.x : boundsMin.x, (corner & 2) ? boundsMax.y : boundsMin.y,
                        (corner & 4) ? boundsMax.z : boundsMin.z);
      // Camera-space offset from the target: x right, y up, z towards the eye.
      const glm::vec3 q = glm::mat3(view1) * (p - target);
      needed = std::max({needed, q.z + std::abs(q.x) / tanX, q.z + std::abs(q.y) / tanY});
    }
    distance = std::max(needed * 1.05f, radius * 0.05f);
    return true;
  }

  void orbit(float dx, float dy) {
    yaw -= dx * 0.008f;
    pitch = std::clamp(pitch + dy * 0.008f, -glm::half_pi<float>() + 1e-3f, glm::half_pi<float>() - 1e-3f);
  }
  void pan(float dx, float dy, const glm::mat4& view) {
    const glm::vec3 right(view[0][0], view[1][0], view[2][0]), up(view[0][1], view[1][1], view[2][1]);
    target += (-right * dx + up * dy) * (distance * 0.0015f);
  }
  void zoom(float steps) { distance = std::max(distance * std::pow(0.9f, steps), radius * 0.05f); }
};

}  // namespace tangent::viewer
