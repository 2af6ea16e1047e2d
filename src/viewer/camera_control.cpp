#include "viewer/camera_control.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/trigonometric.hpp>

namespace whisker {

void orbit(Camera& cam, float dx, float dy) {
  const vec3 up = glm::normalize(cam.up);
  vec3 offset = cam.position - cam.look_at;
  const float r = glm::length(offset);
  if (r <= 0.0f) return;
  offset = glm::angleAxis(dx, up) * offset;
  // Keep the polar angle inside [1, 179] degrees from up.
  const float polar = std::acos(std::clamp(glm::dot(offset / r, up), -1.0f, 1.0f));
  const float lo = glm::radians(1.0f), hi = glm::radians(179.0f);
  const float turn = std::clamp(polar + dy, lo, hi) - polar;
  const vec3 right = glm::cross(up, offset);
  if (glm::length(right) > 0.0f)
    offset = glm::angleAxis(turn, glm::normalize(right)) * offset;
  cam.position = cam.look_at + offset;
}

void pan(Camera& cam, float dx_pixels, float dy_pixels) {
  const vec3 forward = cam.look_at - cam.position;
  const float r = glm::length(forward);
  if (r <= 0.0f || cam.width <= 0) return;
  const vec3 right = glm::normalize(glm::cross(forward, cam.up));
  const vec3 up = glm::normalize(glm::cross(right, forward));
  // World size of one image pixel at the look-at distance (fov across width).
  const float per_pixel = 2.0f * r * std::tan(glm::radians(cam.fov_deg) * 0.5f) / cam.width;
  const vec3 move = (-dx_pixels * right + dy_pixels * up) * per_pixel;
  cam.position += move;
  cam.look_at += move;
}

void dolly(Camera& cam, float factor) {
  const vec3 offset = cam.position - cam.look_at;
  const float r = glm::length(offset);
  if (r <= 0.0f) return;
  const float r2 = std::max(r * factor, 1e-3f);
  cam.position = cam.look_at + offset * (r2 / r);
}

}  // namespace whisker
