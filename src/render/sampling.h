// Sampling helpers of the estimator: sin/cos of a turn, an orthonormal frame
// around a normal, and cosine-weighted directions in it.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

#include <immintrin.h>

#include <glm/vec3.hpp>

namespace whisker {

using glm::vec3;

// The formulas below are written once for one float or for eight side by
// side (__m256, GCC's vector type: its arithmetic operators work lane by
// lane, a float operand is broadcast, and ?: selects lane by lane). These
// are the few operations they need that are spelt differently for the two.
using v8i = std::int32_t __attribute__((vector_size(32)));
using v8u = std::uint32_t __attribute__((vector_size(32)));
inline float round_even(float x) { return std::nearbyint(x); }
inline __m256 round_even(__m256 x) {
  return _mm256_round_ps(x, _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC);
}
inline float sqrt_lanes(float x) { return std::sqrt(x); }
inline __m256 sqrt_lanes(__m256 x) { return _mm256_sqrt_ps(x); }
inline std::uint32_t bits_of(float x) { return std::bit_cast<std::uint32_t>(x); }
inline v8u bits_of(__m256 x) { return std::bit_cast<v8u>(x); }
inline float float_of(std::uint32_t b) { return std::bit_cast<float>(b); }
inline __m256 float_of(v8u b) { return std::bit_cast<__m256>(b); }
inline float to_float(std::int32_t k) { return float(k); }
inline __m256 to_float(v8i k) { return __builtin_convertvector(k, __m256); }
inline std::uint32_t to_unsigned(float x) { return std::uint32_t(std::int32_t(x)); }
inline v8u to_unsigned(__m256 x) { return std::bit_cast<v8u>(__builtin_convertvector(x, v8i)); }
inline std::int32_t to_signed(std::uint32_t x) { return std::int32_t(x); }
inline v8i to_signed(v8u x) { return std::bit_cast<v8i>(x); }

// sin and cos of 2 pi u, for u in [0, 1], to within 1e-7.
template <class F>
inline void sincos_turn(F u, F& s, F& c) {
  // 2 pi u = q pi/2 + x with q = round(4u), |x| <= pi/4, where the Taylor
  // series to x^9 (sin) and x^8 (cos) are within 3e-8 of the truth
  // (remainders x^11/11! and x^10/10!).
  const F q = round_even(4.0f * u);
  const F x = (4.0f * u - q) * (0.5f * 3.14159265358979323846f);
  const F x2 = x * x;
  const F sx = x * (1.0f + x2 * (-1.0f / 6 + x2 * (1.0f / 120 + x2 * (-1.0f / 5040 + x2 * (1.0f / 362880)))));
  const F cx = 1.0f + x2 * (-0.5f + x2 * (1.0f / 24 + x2 * (-1.0f / 720 + x2 * (1.0f / 40320))));
  // Rotate by q quarter turns without branches (q is random: a switch
  // would mispredict most of the time): swap for odd q, then signs.
  const auto k = to_unsigned(q);
  const auto odd = (k & 1u) != 0u;
  const F a = odd ? cx : sx, b = odd ? sx : cx;
  s = float_of(bits_of(a) ^ ((k & 2u) << 30));
  c = float_of(bits_of(b) ^ (((k + 1u) & 2u) << 30));
}

// The natural logarithm of a positive normal float, to within 2e-7 of it
// relative. u = 2^e m with m in [sqrt(1/2), sqrt(2)) (the exponent taken
// from the bits, offset by those of sqrt(1/2)), and ln m = 2 atanh(s) with
// s = (m - 1) / (m + 1), |s| <= 0.1716: the series 2 (s + s^3/3 + ... + s^9/9)
// (Abramowitz and Stegun 4.1.27) leaves out less than 2 s^11/11, below 1e-9
// of ln m. m - 1 is exact, so the error stays relative as u nears 1.
template <class F>
inline F log_positive(F u) {
  constexpr std::uint32_t kSqrtHalf = 0x3f3504f3u;  // the bits of sqrt(1/2)
  const auto d = bits_of(u) - kSqrtHalf;
  const F e = to_float(to_signed(d) >> 23);
  const F m = float_of((d & 0x007fffffu) + kSqrtHalf);
  const F s = (m - 1.0f) / (m + 1.0f);
  const F s2 = s * s;
  const F series = s2 * (2.0f / 3 + s2 * (2.0f / 5 + s2 * (2.0f / 7 + s2 * (2.0f / 9))));
  return e * 0.693147180559945309f + (2.0f * s + s * series);
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
