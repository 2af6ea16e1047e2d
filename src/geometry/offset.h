// Spawning rays off a surface without re-hitting it.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>

#include <glm/geometric.hpp>

#include "geometry/ray.h"

namespace whisker {

// Moves p off the surface along the geometric normal n (pointing to the side
// the new ray leaves on) by a number of float ULPs that grows with |p|, and by
// a fixed epsilon near the origin where ULPs are tiny.
// Waechter and Binder, "A Fast and Robust Method for Avoiding
// Self-Intersection", Ray Tracing Gems ch. 6 (2019): origin = 1/32,
// float_scale = 1/65536, int_scale = 256.
inline vec3 offset_ray_origin(const vec3& p, const vec3& n) {
  constexpr float kOrigin = 1.0f / 32.0f;
  constexpr float kFloatScale = 1.0f / 65536.0f;
  constexpr float kIntScale = 256.0f;
  vec3 out;
  for (int i = 0; i < 3; ++i) {
    const auto of = static_cast<std::int32_t>(kIntScale * n[i]);
    const auto bits = std::bit_cast<std::int32_t>(p[i]);
    const float pi = std::bit_cast<float>(bits + (p[i] < 0.0f ? -of : of));
    out[i] = std::fabs(p[i]) < kOrigin ? p[i] + kFloatScale * n[i] : pi;
  }
  return out;
}

// A ray leaving point p (geometric normal ng) in direction d: the origin is
// offset to the side d points to.
inline Ray spawn_ray(const vec3& p, const vec3& ng, const vec3& d) {
  const vec3 n = glm::dot(ng, d) >= 0.0f ? ng : -ng;
  return Ray{offset_ray_origin(p, n), d, 0.0f, kInf};
}

// A shadow ray from p towards the point light at `target`, d the unit
// direction from p to it; it stops just short of the light (a light is never
// an occluder): at the point of the line nearest the light, which the offset
// origin moves by a few ULPs at most.
inline Ray spawn_shadow_ray(const vec3& p, const vec3& ng, const vec3& target, const vec3& d) {
  const vec3 n = glm::dot(ng, d) >= 0.0f ? ng : -ng;
  const vec3 o = offset_ray_origin(p, n);
  return Ray{o, d, 0.0f, glm::dot(target - o, d) * (1.0f - 1e-5f)};
}

inline Ray spawn_shadow_ray(const vec3& p, const vec3& ng, const vec3& target) {
  return spawn_shadow_ray(p, ng, target, glm::normalize(target - p));
}

}  // namespace whisker
