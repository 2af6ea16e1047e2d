// The report's estimator: one path per sample, direct light from the point
// light at every diffuse hit, mirror, glass with optional Fresnel, and
// cosine-sampled indirect light.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>

#include "geometry/world.h"
#include "render/camera.h"
#include "render/sampler.h"
#include "scene/scene.h"

namespace whisker {

struct PathStats {
  std::uint64_t rays = 0;  // intersection and shadow rays traced
};

// Radiance arriving along `ray` (light intensity applied), with at most
// settings.max_depth hits after the first. The ray is unbounded: only its
// origin and direction are used.
vec3 radiance(const World& world, const PointLight& light, const RenderSettings& settings,
              Ray ray, Sampler& sampler, PathStats& stats);

// One sample of pixel (i, j): camera ray (with Gaussian jitter when AA is on)
// and its radiance.
vec3 sample_pixel(const World& world, const Scene& scene, const CameraFrame& cam, int i,
                  int j, Sampler& sampler, PathStats& stats);

// Directions, exposed for tests.
vec3 reflect(const vec3& d, const vec3& n);
// Refracts unit d through the interface with unit normal n (facing against
// d) and relative index eta = n1/n2; false on total internal reflection.
bool refract(const vec3& d, const vec3& n, float eta, vec3& out);
// Schlick's approximation of the Fresnel reflectance.
float schlick(float cos_i, float n1, float n2);
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

// Cosine-distributed direction around unit n from two uniforms.
vec3 cosine_direction(const vec3& n, float u1, float u2);

}  // namespace whisker
