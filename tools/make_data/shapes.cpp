// SPDX-License-Identifier: MIT
#include "shapes.hpp"

#include <cmath>
#include <numbers>

namespace make_data {

MeshData uvSphere(int slices, int stacks, float radius) {
  MeshData mesh;
  for (int j = 0; j <= stacks; ++j) {
    const double v = double(j) / stacks, theta = v * std::numbers::pi;
    for (int i = 0; i <= slices; ++i) {
      const double u = double(i) / slices, phi = u * 2 * std::numbers::pi;
      const double n[3] = {std::sin(theta) * std::cos(phi), std::cos(theta), -std::sin(theta) * std::sin(phi)};
      for (int k = 0; k < 3; ++k) {
        mesh.positions.push_back(static_cast<float>(radius * n[k]));
        mesh.normals.push_back(static_cast<float>(n[k]));
      }
      mesh.uvs.push_back(static_cast<float>(u * 2));  // the map tiles twice around
      mesh.uvs.push_back(static_cast<float>(v));
    }
  }
  for (int j = 0; j < stacks; ++j) {
    for (int i = 0; i < slices; ++i) {
      const auto a = static_cast<std::uint16_t>(j * (slices + 1) + i), b = static_cast<std::uint16_t>(a + slices + 1);
      if (j != 0) mesh.indices.insert(mesh.indices.end(), {a, b, static_cast<std::uint16_t>(a + 1)});
      if (j != stacks - 1) mesh.indices.insert(mesh.indices.end(), {static_cast<std::uint16_t>(a + 1), b, static_cast<std::uint16_t>(b + 1)});
    }
  }
  return mesh;
}

MeshData mirroredQuads() {
  MeshData mesh;
  const float xs[3] = {-1, 0, 1};
  const float us[3] = {0, 1, 0};
  for (int row = 0; row < 2; ++row) {
    for (int col = 0; col < 3; ++col) {
      mesh.positions.insert(mesh.positions.end(), {xs[col], static_cast<float>(row) - 0.5f, 0});
      mesh.normals.insert(mesh.normals.end(), {0, 0, 1});
      mesh.uvs.insert(mesh.uvs.end(), {us[col], static_cast<float>(1 - row)});
    }
  }
  mesh.indices = {0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 4};
  return mesh;
}

MeshData plane(float halfSize, float y) {
  MeshData mesh;
  mesh.positions = {-halfSize, y, halfSize, halfSize, y, halfSize, halfSize, y, -halfSize, -halfSize, y, -halfSize};
  mesh.normals = {0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0};
  mesh.uvs = {0, 4, 4, 4, 4, 0, 0, 0};
  mesh.indices = {0, 1, 2, 0, 2, 3};
  return mesh;
}

MeshData cube(float half) {
  // 24 vertices: 4 per face, u along the face's first edge, outward winding.
  MeshData mesh;
  const int axes[6][3] = {{0, 1, 2}, {0, 1, 2}, {2, 1, 0}, {2, 1, 0}, {0, 2, 1}, {0, 2, 1}};
  const float sides[6] = {1, -1, -1, 1, -1, 1};
  for (int f = 0; f < 6; ++f) {
    const int ua = axes[f][0], va = axes[f][1], na = axes[f][2];
    const float side = sides[f];
    const auto base = static_cast<std::uint16_t>(mesh.positions.size() / 3);
    const float corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (const auto& c : corners) {
      float p[3] = {0, 0, 0}, n[3] = {0, 0, 0};
      p[ua] = c[0] * half * side * (f >= 4 ? -1.0f : 1.0f);
      p[va] = c[1] * half;
      p[na] = half * side;
      n[na] = side;
      mesh.positions.insert(mesh.positions.end(), p, p + 3);
      mesh.normals.insert(mesh.normals.end(), n, n + 3);
      mesh.uvs.insert(mesh.uvs.end(), {(c[0] + 1) / 2, (1 - c[1]) / 2});
    }
    // Wind counter-clockwise as seen from outside: flip when the (u, v, n) basis is left-handed.
    float pu[3] = {0, 0, 0}, pv[3] = {0, 0, 0}, pn[3] = {0, 0, 0};
    pu[ua] = side * (f >= 4 ? -1.0f : 1.0f);
    pv[va] = 1;
    pn[na] = side;
    const float handed = (pu[1] * pv[2] - pu[2] * pv[1]) * pn[0] + (pu[2] * pv[0] - pu[0] * pv[2]) * pn[1] + (pu[0] * pv[1] - pu[1] * pv[0]) * pn[2];
    if (handed > 0) mesh.indices.insert(mesh.indices.end(), {base, static_cast<std::uint16_t>(base + 1), static_cast<std::uint16_t>(base + 2), base, static_cast<std::uint16_t>(base + 2), static_cast<std::uint16_t>(base + 3)});
    else mesh.indices.insert(mesh.indices.end(), {base, static_cast<std::uint16_t>(base + 2), static_cast<std::uint16_t>(base + 1), base, static_cast<std::uint16_t>(base + 3), static_cast<std::uint16_t>(base + 2)});
  }
  return mesh;
}

MeshData torus(int rings, int sides, float major, float minor) {
  MeshData mesh;
  for (int i = 0; i <= rings; ++i) {
    for (int j = 0; j <= sides; ++j) {
      const double a = 2 * std::numbers::pi * i / rings, b = 2 * std::numbers::pi * j / sides;
      const double n[3] = {std::cos(a) * std::cos(b), std::sin(b), -std::sin(a) * std::cos(b)};
      mesh.positions.insert(mesh.positions.end(), {static_cast<float>(major * std::cos(a) + minor * n[0]), static_cast<float>(minor * n[1]),
                                                   static_cast<float>(-major * std::sin(a) + minor * n[2])});
      mesh.normals.insert(mesh.normals.end(), {static_cast<float>(n[0]), static_cast<float>(n[1]), static_cast<float>(n[2])});
      mesh.uvs.insert(mesh.uvs.end(), {static_cast<float>(3.0 * i / rings), static_cast<float>(1.0 * j / sides)});
    }
  }
  for (int i = 0; i < rings; ++i) {
    for (int j = 0; j < sides; ++j) {
      const auto a = static_cast<std::uint16_t>(i * (sides + 1) + j), b = static_cast<std::uint16_t>(a + sides + 1);
      // Counter-clockwise seen from outside, as the normals point (glTF: front faces CCW).
      mesh.indices.insert(mesh.indices.end(), {a, b, static_cast<std::uint16_t>(a + 1), static_cast<std::uint16_t>(a + 1), b, static_cast<std::uint16_t>(b + 1)});
    }
  }
  return mesh;
}

MeshData cylinder(int rings, int sides, float radius, float height) {
  MeshData mesh;
  for (int j = 0; j < rings; ++j) {
    const double y = height * (1.0 - double(j) / (rings - 1));
    for (int i = 0; i <= sides; ++i) {
      const double a = 2 * std::numbers::pi * i / sides;
      mesh.positions.insert(mesh.positions.end(), {static_cast<float>(radius * std::cos(a)), static_cast<float>(y), static_cast<float>(-radius * std::sin(a))});
      mesh.normals.insert(mesh.normals.end(), {static_cast<float>(std::cos(a)), 0.0f, static_cast<float>(-std::sin(a))});
      mesh.uvs.insert(mesh.uvs.end(), {static_cast<float>(2.0 * i / sides), static_cast<float>(height - y)});
    }
  }
  for (int j = 0; j + 1 < rings; ++j) {
    for (int i = 0; i < sides; ++i) {
      const auto a = static_cast<std::uint16_t>(j * (sides + 1) + i), b = static_cast<std::uint16_t>(a + sides + 1);
      mesh.indices.insert(mesh.indices.end(), {a, b, static_cast<std::uint16_t>(a + 1), static_cast<std::uint16_t>(a + 1), b, static_cast<std::uint16_t>(b + 1)});
    }
  }
  return mesh;
}

MeshData grid(int segments) {
  MeshData mesh;
  for (int j = 0; j <= segments; ++j) {
    for (int i = 0; i <= segments; ++i) {
      const float x = -1.0f + 2.0f * i / segments, y = 1.0f - 2.0f * j / segments;
      mesh.positions.insert(mesh.positions.end(), {x, y, 0.0f});
      mesh.normals.insert(mesh.normals.end(), {0.0f, 0.0f, 1.0f});
      mesh.uvs.insert(mesh.uvs.end(), {x + 1, 1 - y});
    }
  }
  for (int j = 0; j < segments; ++j) {
    for (int i = 0; i < segments; ++i) {
      const auto a = static_cast<std::uint16_t>(j * (segments + 1) + i), b = static_cast<std::uint16_t>(a + segments + 1);
      mesh.indices.insert(mesh.indices.end(), {a, b, static_cast<std::uint16_t>(a + 1), static_cast<std::uint16_t>(a + 1), b, static_cast<std::uint16_t>(b + 1)});
    }
  }
  return mesh;
}

MeshData quad(float half) {
  MeshData mesh;
  mesh.positions = {-half, -half, 0, half, -half, 0, half, half, 0, -half, half, 0};
  mesh.normals = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
  mesh.uvs = {0, 1, 1, 1, 1, 0, 0, 0};
  mesh.indices = {0, 1, 2, 0, 2, 3};
  return mesh;
}

MeshData disc(int rings, int segments, float radius) {
  MeshData mesh;
  auto vertex = [&](double x, double y) {
    mesh.positions.insert(mesh.positions.end(), {static_cast<float>(x), static_cast<float>(y), 0.0f});
    mesh.normals.insert(mesh.normals.end(), {0.0f, 0.0f, 1.0f});
    mesh.uvs.insert(mesh.uvs.end(), {static_cast<float>((x / radius + 1) / 2), static_cast<float>((1 - y / radius) / 2)});
    // T along +u (+x); B = cross(N, T) * w = +y, towards the image's top (-v): w = +1.
    mesh.tangents.insert(mesh.tangents.end(), {1.0f, 0.0f, 0.0f, 1.0f});
  };
  vertex(0, 0);
  for (int ring = 1; ring <= rings; ++ring)
    for (int i = 0; i < segments; ++i) {
      const double a = 2 * std::numbers::pi * i / segments, r = radius * ring / rings;
      vertex(r * std::cos(a), r * std::sin(a));
    }
  auto at = [&](int ring, int i) { return static_cast<std::uint16_t>(ring == 0 ? 0 : 1 + (ring - 1) * segments + (i % segments)); };
  for (int i = 0; i < segments; ++i) mesh.indices.insert(mesh.indices.end(), {at(0, 0), at(1, i), at(1, i + 1)});
  for (int ring = 1; ring < rings; ++ring)
    for (int i = 0; i < segments; ++i)
      mesh.indices.insert(mesh.indices.end(), {at(ring, i), at(ring + 1, i), at(ring + 1, i + 1), at(ring, i), at(ring + 1, i + 1), at(ring, i + 1)});
  return mesh;
}

}  // namespace make_data
