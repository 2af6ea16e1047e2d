#include "viewer/camera_control.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/trigonometric.hpp>

#include "scene/world.h"

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

namespace {

// The closest surface along the segment from `from` towards `to` (world
// space), or a negative distance if none lies within its length.
double surface_along(const World& world, const glm::dvec3& from, const glm::dvec3& to) {
  const glm::dvec3 d = to - from;
  const double len = glm::length(d);
  if (!(len > 0.0)) return -1.0;
  Ray ray = world.to_render(from, vec3(d / len));
  ray.tmax = float(len) * 1.0001f + 1e-6f;
  SurfaceHit hit;
  if (!world.intersect(ray, hit) || double(hit.t) > len) return -1.0;
  return double(hit.t);
}

}  // namespace

bool stop_at_surfaces(const Camera& before, Camera& cam, const World& world) {
  const glm::dvec3 from = before.position, to = cam.position;
  const double len = glm::length(to - from);
  if (!(len > 0.0)) return false;
  const double margin = std::max(1e-3, 0.01 * glm::length(before.look_at - before.position));
  // The eye must stay `margin` away: look a margin past the end as well.
  const glm::dvec3 dir = (to - from) / len;
  const double hit = surface_along(world, from, to + dir * margin);
  if (hit < 0.0) return false;
  const double keep = std::max(0.0, hit - margin);
  const glm::dvec3 moved = dir * keep;
  const glm::dvec3 look_shift = (cam.look_at - before.look_at);
  cam.position = from + moved;
  // A pan moves both points together; keep them together.
  if (glm::length(look_shift) > 0.0) cam.look_at = before.look_at + look_shift * (keep / len);
  // The eye must not sit on the look-at point.
  if (glm::length(cam.look_at - cam.position) < 1e-6) cam = before;
  return true;
}

bool eye_inside_room(const Camera& cam, const World& world, std::string* why) {
  return inside_room(cam.position, cam.look_at - cam.position, world, "the eye", why);
}

bool inside_room(const glm::dvec3& p, const glm::dvec3& view, const World& world, const char* who,
                 std::string* why) {
  const glm::dvec3 dirs[7] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1},
                              glm::length(view) > 0.0 ? glm::normalize(view) : glm::dvec3(0, 0, -1)};
  const char* names[7] = {"+x", "-x", "+y", "-y", "+z", "-z", "the view direction"};
  for (int k = 0; k < 7; ++k) {
    const vec3 d = vec3(dirs[k]);
    Ray ray = world.to_render(p, d);
    // Glass is looked through (a glass cat, a glass ball): follow the ray on.
    for (int step = 0; step < 8; ++step) {
      SurfaceHit hit;
      if (!world.intersect(ray, hit)) {
        if (why) *why = std::string(who) + " sees nothing along " + names[k] + ": it is outside the room";
        return false;
      }
      const MaterialKind kind = hit.material ? hit.material->kind : MaterialKind::Diffuse;
      if (is_glass(kind)) {
        ray.tmin = hit.t * 1.0001f + 1e-4f;
        continue;
      }
      if (glm::dot(hit.ng, d) > 0.0f) {
        if (why) *why = std::string(who) + " is behind a surface (seen along " + names[k] + ")";
        return false;
      }
      break;
    }
  }
  return true;
}

}  // namespace whisker
