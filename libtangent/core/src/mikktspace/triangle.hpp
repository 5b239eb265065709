// SPDX-License-Identifier: MIT
// The triangle pass: each triangle's dP/du, dP/dv, UV orientation and flags (the reference's
// float formulas, eq. 18 and 19 of its source), and each corner's angle-weighted term parked
// in its output slot for the fan shortcut (fan.cpp). Scalar here (triangle.cpp); four and eight
// lanes at a time in lanes4.cpp (SSE2 or SIMD128) and lanes8.cpp (AVX2), which share
// lanes.inc and triangle_lanes.inc and give the same bits.
#pragma once

#include <cstddef>
#include <cstdint>

#include "angles.hpp"
#include "arrays.hpp"

// Four lanes where the target has SSE2 or WebAssembly SIMD128; GCC on x86-64 also builds the
// triangle pass for AVX2, chosen at run time (isa.cpp).
#if defined(__SSE2__) || defined(__wasm_simd128__)
#define TANGENT_LANES4 1
#endif
#if defined(__SSE2__) && defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define TANGENT_LANES8 1
#endif

namespace tangent::detail::mikk {

// The group pass's common case, prepared in corner order by the triangle pass: each corner's
// angle-weighted term, parked in its own output slot until the group pass replaces it with
// the frame. Float arithmetic, eight triangles at a time where AVX2 is there, four where SSE2
// or SIMD128 is (triangle_lanes.inc); the scalar function does the same operations in the same order, so
// every width gives the same bits.
//
// Slot of corner c: {S.x * angle, S.y * angle, S.z * angle, angle}, S the reference's
// projection of the triangle's dP/du on the corner's raw normal N, angle the corner's angle
// between its edges e1, e2 projected on the plane of N: atan2(|N.A| |N|, |N|^2 (e1.e2) -
// (N.e1)(N.e2)), A = e1 x e2 (from the corner's own edges, so that a rotation of the
// triangle's corners moves no bit). The low kConeBits of the angle's bits say on which side
// of +-kConeMargin each component of S and of the projected dP/dv (as a direction) lies; 0
// where the corner is not the common case (then its bucket takes the full path). Its sign bit
// (the angle is never negative) is set where the triangle's orientation is not positive, so
// that the fan shortcut sees one orientation in the terms it sums, without the triangles.
constexpr std::uint32_t kConeBits = 0xFFF;
constexpr std::uint32_t kNotPositiveBit = 0x80000000u;
constexpr float kConeMargin = 1.0f / 64, kConeMargin2 = kConeMargin * kConeMargin;
constexpr float kSmallestAngle = 0.1f;      // below (or within this of pi) the full path's rules apply
constexpr float kSmallestProduct = 1e-30f;  // below, float products lose digits
constexpr float kSmallestNormal2 = 1e-20f;  // |N|^2 below: the full path

// Which side of +-kConeMargin each component of v / |v| lies on (two bits per component),
// without the division: v.i^2 against kConeMargin^2 |v|^2.
inline std::uint32_t coneBits(F3 v) {
  const float bound = kConeMargin2 * fdot(v, v);
  auto side = [&](float x) { return x * x > bound ? (x > 0 ? 1u : 2u) : 0u; };
  return side(v.x) | side(v.y) << 2 | side(v.z) << 4;
}

// Three floats of p at vertex v (a position or a normal), as the reference reads them.
inline F3 floatsAt(const float* p, std::uint32_t v) {
  return F3{p[3 * std::size_t(v)], p[3 * std::size_t(v) + 1], p[3 * std::size_t(v) + 2]};
}

// Unit dP/du and dP/dv of triangle t (signed by the UV orientation), its orientation and
// flags (triangle.cpp).
void evaluateTriangle(const Arrays& a, std::size_t t, float* frame, std::int8_t& orientation, std::uint8_t& flags);
// The parked terms of triangle t's three corners (frame: its dP/du, dP/dv; orientation and
// flags: what evaluateTriangle gave).
void cornerTermsOne(const Arrays& a, std::size_t t, const float* frame, std::int8_t orientation, std::uint8_t flags,
                    float* tangents);
// One triangle the scalar way: its orientation, flags and its corners' parked terms.
void evaluateAndParkOne(const Arrays& a, std::size_t t, std::int8_t& orientation, std::uint8_t& flags, float* tangents);

#if defined(TANGENT_LANES4)
// Triangles t .. t + 3 (lanes4.cpp).
void evaluateLanes4(const Arrays& a, std::size_t t, std::int8_t* orientation, std::uint8_t* flags, float* tangents);
#endif
#if defined(TANGENT_LANES8)
// Triangles t .. t + 7, where the processor has AVX2 (lanes8.cpp).
void evaluateLanes8(const Arrays& a, std::size_t t, std::int8_t* orientation, std::uint8_t* flags, float* tangents);
#endif

}  // namespace tangent::detail::mikk
