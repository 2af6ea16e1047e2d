// Camera rays, as in SCENES.md "Conventions".
#pragma once

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "geometry/ray.h"
#include "scene/scene.h"

namespace whisker {

struct CameraFrame {
  glm::dvec3 origin;  // world space, as the scene gives it
  vec3 right, up, forward;
  float half_w, half_h, focal;  // focal = W / (2 tan(fov/2)), in pixels

  explicit CameraFrame(const Camera& c)
      : origin(c.position),
        forward(view_direction(c)),
        half_w(0.5f * float(c.width)),
        half_h(0.5f * float(c.height)),
        focal(float(c.width) / (2.0f * std::tan(glm::radians(c.fov_deg) * 0.5f))) {
    right = glm::normalize(pow2_scaled(glm::cross(forward, pow2_scaled(c.up))));
    up = glm::cross(right, forward);
  }

  // v times the power of two (exact) that puts its largest component in
  // [1, 2). glm::normalize squares its argument in float, and the scene file
  // takes an `up` of any length in [1e-30, 1e30] and any look_at: the side
  // vector of a view nearly along `up` may be 1e-32 long. Squared, such
  // vectors underflow to 0 (a NaN basis: a black image) or overflow (a zero
  // basis: one colour everywhere). A power of two changes no bit of the
  // normalised result where there was no underflow or overflow.
  static vec3 pow2_scaled(vec3 v) {
    const float m = std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
    if (m > 0.0f && std::isfinite(m)) v = vec3(std::ldexp(v.x, -std::ilogb(m)),
                                               std::ldexp(v.y, -std::ilogb(m)),
                                               std::ldexp(v.z, -std::ilogb(m)));
    return v;
  }

  // Pixel (row i from the top, column j) with offset (dx, dy) in pixels:
  // direction (j - W/2 + 0.5 + dx, H/2 - i - 0.5 - dy, -focal) in camera space.
  vec3 direction(int i, int j, float dx, float dy) const {
    const float x = float(j) - half_w + 0.5f + dx;
    const float y = half_h - float(i) - 0.5f - dy;
    return glm::normalize(x * right + y * up + focal * forward);
  }
  // The same as a world-space ray (its origin rounded to float).
  Ray ray(int i, int j, float dx, float dy) const {
    return Ray{vec3(origin), direction(i, j, dx, dy), 0.0f, kInf};
  }
};

}  // namespace whisker
