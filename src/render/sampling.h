// Sampling helpers of the estimator: sin/cos of a turn, an orthonormal frame
// around a normal, and cosine-weighted directions in it.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

#include <glm/vec3.hpp>

namespace whisker {

using glm::vec3;

// sin and cos of 2 pi u, for u in [0, 1], to within 1e-7.
inline void sincos_turn(float u, float& s, float& c) {
  // 2 pi u = q pi/2 + x with q = round(4u), |x| <= pi/4, where the Taylor
  // series to x^9 (sin) and x^8 (cos) are within 3e-8 of the truth
  // (remainders x^11/11! and x^10/10!).
  const float q = std::nearbyint(4.0f * u);
  const float x = (4.0f * u - q) * (0.5f * 3.14159265358979323846f);
  const float x2 = x * x;
  const float sx = x * (1.0f + x2 * (-1.0f / 6 + x2 * (1.0f / 120 + x2 * (-1.0f / 5040 + x2 * (1.0f / 362880)))));
  const float cx = 1.0f + x2 * (-0.5f + x2 * (1.0f / 24 + x2 * (-1.0f / 720 + x2 * (1.0f / 40320))));
  // Rotate by q quarter turns without branches (q is random: a switch
  // would mispredict most of the time): swap for odd q, then signs.
  const unsigned k = unsigned(int(q));
  const bool odd = k & 1u;
  const float a = odd ? cx : sx, b = odd ? sx : cx;
  s = std::bit_cast<float>(std::bit_cast<std::uint32_t>(a) ^ ((k & 2u) << 30));
  c = std::bit_cast<float>(std::bit_cast<std::uint32_t>(b) ^ (((k + 1u) & 2u) << 30));
}

// An orthonormal basis (b1, b2, n) around unit n (Duff et al., "Building an
// Orthonormal Basis, Revisited", JCGT 2017). Built once per shading point:
// its division would otherwise be repeated for every split branch.
struct Frame {
  vec3 b1, b2, n;
  explicit Frame(const vec3& normal) : n(normal) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float b = n.x * n.y * a;
    b1 = vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
    b2 = vec3(b, sign + n.y * n.y * a, -n.y);
  }
};

// Cosine-weighted hemisphere (report section 3, Scene::random_cos):
// x = cos(2 pi u1) sqrt(1 - u2), y = sin(2 pi u1) sqrt(1 - u2), z = sqrt(u2).
// b1, b2, n are orthonormal, so the result is unit to rounding (a few ULP).
inline vec3 cosine_direction(const Frame& f, float u1, float u2) {
  const float r = std::sqrt(1.0f - u2);
  float s, c;
  sincos_turn(u1, s, c);
  return r * c * f.b1 + r * s * f.b2 + std::sqrt(u2) * f.n;
}

// A direction uniform on the unit sphere: z = 1 - 2 u2, the azimuth 2 pi u1
// (Archimedes: z is uniform on a sphere).
inline vec3 uniform_sphere(float u1, float u2) {
  const float z = 1.0f - 2.0f * u2;
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  float s, c;
  sincos_turn(u1, s, c);
  return vec3(r * c, r * s, z);
}

// The same around unit n, from two uniforms.
inline vec3 cosine_direction(const vec3& n, float u1, float u2) {
  return cosine_direction(Frame(n), u1, u2);
}

}  // namespace whisker
