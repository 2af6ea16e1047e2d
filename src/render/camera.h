// Camera rays, as in docs/SCENES.md "Conventions".
#pragma once

#include <cmath>
#include <cstdint>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/trigonometric.hpp>

#include "geometry/ray.h"
#include "render/sampling.h"
#include "scene/scene.h"

namespace whisker {

// Anti-aliasing, report section 3: a Gaussian offset of the pixel position,
// two independent N(0, 0.5^2) pixels from two uniform numbers in [0, 1)
// by Box-Muller; for one sample or eight side by side (sampling.h).
template <class F>
inline void aa_offset(F u1, F u2, F& dx, F& dy) {
  u1 = 1.0f - u1;  // (0, 1]: the logarithm stays finite
  const F r = 0.5f * sqrt_lanes(-2.0f * log_positive(u1));
  F s, c;
  sincos_turn(u2, s, c);
  dx = r * c;
  dy = r * s;
}

struct CameraFrame {
  glm::dvec3 origin;  // world space, as the scene gives it
  int width, height;  // the image, pixels
  vec3 right, up, forward;
  float half_w, half_h, focal;  // focal = W / (2 tan(fov/2)), in pixels

  explicit CameraFrame(const Camera& c)
      : origin(c.position),
        width(c.width),
        height(c.height),
        forward(view_direction(c)),
        half_w(0.5f * float(c.width)),
        half_h(0.5f * float(c.height)),
        focal(float(c.width) / (2.0f * std::tan(glm::radians(c.fov_deg) * 0.5f))) {
    right = camera_right(c, forward);
    up = glm::cross(right, forward);
  }

  // Pixel (row i, column j)'s place in the film and the sampler's pixel number.
  std::uint32_t pixel_index(int i, int j) const {
    return std::uint32_t(i) * std::uint32_t(width) + std::uint32_t(j);
  }

  // The direction through the centre of pixel (row i from the top, column
  // j), world space: directions() of one lane without AA (below).
  vec3 centre_direction(int i, int j) const {
    Lanes s;
    s.n = 1;
    s.i[0] = float(i);
    s.j[0] = float(j);
    vec3 d;
    directions(s, false, &d);
    return d;
  }
  // Up to eight samples side by side: pixel (i[l], j[l]) and the two
  // uniforms of its AA offset (aa_offset()), for l < n.
  struct Lanes {
    int n = 0;
    alignas(32) float i[8] = {}, j[8] = {}, u1[8] = {}, u2[8] = {};
  };
  // The direction of each of them, world space, written to out[l]: pixel
  // (i, j) with offset (dx, dy) in pixels (none without `aa`) is direction
  // (j - W/2 + 0.5 + dx, H/2 - i - 0.5 - dy, -focal) in camera space,
  // normalised. Every camera ray is made here: camera_paths() (integrator.h),
  // for one sample or more, and centre_direction().
  void directions(const Lanes& s, bool aa, vec3* out) const {
    __m256 dx = _mm256_setzero_ps(), dy = _mm256_setzero_ps();
    if (aa) aa_offset(_mm256_load_ps(s.u1), _mm256_load_ps(s.u2), dx, dy);
    const __m256 x = _mm256_load_ps(s.j) - half_w + 0.5f + dx;
    const __m256 y = half_h - _mm256_load_ps(s.i) - 0.5f - dy;
    const __m256 vx = x * right.x + y * up.x + focal * forward.x;
    const __m256 vy = x * right.y + y * up.y + focal * forward.y;
    const __m256 vz = x * right.z + y * up.z + focal * forward.z;
    const __m256 inv = 1.0f / sqrt_lanes(vx * vx + vy * vy + vz * vz);
    alignas(32) float ox[8], oy[8], oz[8];
    _mm256_store_ps(ox, vx * inv);
    _mm256_store_ps(oy, vy * inv);
    _mm256_store_ps(oz, vz * inv);
    for (int l = 0; l < s.n; ++l) out[l] = vec3(ox[l], oy[l], oz[l]);
  }
};

}  // namespace whisker
