// Camera rays, as in SCENES.md "Conventions".
#pragma once

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
