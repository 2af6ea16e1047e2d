#include "viewer/camera_control.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/trigonometric.hpp>

namespace whisker {

// In double, as the scene keeps positions (scene.h).
void orbit(Camera& cam, float dx, float dy) {
  const glm::dvec3 up = glm::normalize(glm::dvec3(cam.up));
  glm::dvec3 offset = cam.position - cam.look_at;
  const double r = glm::length(offset);
  if (r <= 0.0) return;
  offset = glm::angleAxis(double(dx), up) * offset;
  // Keep the polar angle inside [1, 179] degrees from up.
  const double polar = std::acos(std::clamp(glm::dot(offset / r, up), -1.0, 1.0));
  const double lo = glm::radians(1.0), hi = glm::radians(179.0);
  const double turn = std::clamp(polar + double(dy), lo, hi) - polar;
  const glm::dvec3 right = glm::cross(up, offset);
  if (glm::length(right) > 0.0)
    offset = glm::angleAxis(turn, glm::normalize(right)) * offset;
  cam.position = cam.look_at + offset;
}

void pan(Camera& cam, float dx_pixels, float dy_pixels) {
  const glm::dvec3 forward = cam.look_at - cam.position;
  const double r = glm::length(forward);
  if (r <= 0.0 || cam.width <= 0) return;
  const glm::dvec3 right = glm::normalize(glm::cross(forward, glm::dvec3(cam.up)));
  const glm::dvec3 up = glm::normalize(glm::cross(right, forward));
  // World size of one image pixel at the look-at distance (fov across width).
  const double per_pixel = 2.0 * r * std::tan(glm::radians(double(cam.fov_deg)) * 0.5) / cam.width;
  const glm::dvec3 move = (-double(dx_pixels) * right + double(dy_pixels) * up) * per_pixel;
  cam.position += move;
  cam.look_at += move;
}

void dolly(Camera& cam, float factor) {
  const glm::dvec3 offset = cam.position - cam.look_at;
  const double r = glm::length(offset);
  if (r <= 0.0) return;
  const double r2 = std::max(r * double(factor), 1e-3);
  cam.position = cam.look_at + offset * (r2 / r);
}

}  // namespace whisker
