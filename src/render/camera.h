// Camera rays, as in docs/SCENES.md "Conventions".
#pragma once

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/trigonometric.hpp>

#include "geometry/ray.h"
#include "render/sampling.h"
#include "scene/scene.h"

namespace whisker {

// Anti-aliasing, report section 3: a Gaussian offset of the pixel position,
// two independent N(0, 0.5^2) pixels from two uniform numbers in [0, 1)
// by Box-Muller.
inline glm::vec2 aa_offset(float u1, float u2) {
  u1 = 1.0f - u1;  // (0, 1]: log stays finite
  const float r = 0.5f * std::sqrt(-2.0f * std::log(u1));
  float s, c;
  sincos_turn(u2, s, c);
  return {r * c, r * s};
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
