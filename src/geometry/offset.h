// Spawning rays off a surface without re-hitting it, at every scale.
//
// The rule (docs/NUMERICS.md): a ray leaving a sphere starts at the hit point
// itself and excludes that sphere exactly (Ray::skip: ignored when leaving it
// outwards, only its far root when entering); a ray leaving a triangle starts
// at the hit point moved off the plane, along the geometric normal, by the
// bound on the point's rounding error, each coordinate then rounded away
// from the surface (pbrt-v4's OffsetRayOrigin, "Physically Based Rendering"
// 4th ed. 6.8.6). Neither has an absolute floor: both scale with the
// coordinates, which render space (scene/world.h) keeps small near the camera.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>

#include <glm/geometric.hpp>

#include "geometry/ray.h"

namespace whisker {

// The float next to x in the direction of the sign of `dir` (x itself for
// dir == 0): one step of the integer bit pattern, as pbrt-v4's NextFloatUp/
// NextFloatDown, without the library call of std::nextafter.
inline float float_step(float x, float dir) {
  if (dir == 0.0f || std::isinf(x)) return x;
  if (x == 0.0f) x = dir > 0.0f ? 0.0f : -0.0f;  // step off the zero of the right sign
  const std::uint32_t b = std::bit_cast<std::uint32_t>(x);
  const bool away = (dir > 0.0f) == (x >= 0.0f && !std::signbit(x));  // magnitude grows
  return std::bit_cast<float>(away ? b + 1u : b - 1u);
}

// p moved along unit n by the distance the error box `err` (per-coordinate
// bounds on |p - exact|) reaches along n, to the side `side` points to; each
// coordinate rounded one float further away, so the rounding of the sum
// cannot bring it back inside the box.
inline vec3 offset_ray_origin(const vec3& p, const vec3& err, const vec3& n, const vec3& side) {
  const float dist = glm::dot(glm::abs(n), err);
  vec3 off = dist * n;
  if (glm::dot(side, n) < 0.0f) off = -off;
  vec3 o = p + off;
  for (int i = 0; i < 3; ++i) o[i] = float_step(o[i], off[i]);
  return o;
}

// The origin of a ray leaving a surface point in direction d: see the rule
// above. `sphere` is kNoSkip for a triangle; `outward` the sphere's outward
// normal; `err` the triangle point's error bound, ng its geometric normal.
// For a sphere, `err` holds the point's low part instead (Ray::o_lo).
[[gnu::always_inline]] inline Ray spawn_from(const vec3& p, const vec3& ng, const vec3& err, std::uint32_t sphere,
                      const vec3& outward, const vec3& d) {
  // One named result on both paths, built in place in the caller's Ray
  // (two different return objects would be built here and then copied).
  Ray r;
  r.d = d;
  if (sphere != kNoSkip) {
    r.o = p;
    r.o_lo = err;
    r.skip = sphere;
    r.far_only = glm::dot(d, outward) < 0.0f;
  } else {
    r.o = offset_ray_origin(p, err, ng, d);
  }
  return r;
}

// A shadow ray from a surface point towards the point light at `target`,
// aimed from its spawned origin (the direction from p itself, followed from
// the moved origin, can miss the light and meet the surface it sits on). It
// stops just short of the light: a light is never an occluder. wi and dist:
// the unit direction and distance from p to target, which a sphere's ray
// (leaving from p itself) keeps.
inline Ray spawn_shadow_from(const vec3& p, const vec3& ng, const vec3& err, std::uint32_t sphere,
                             const vec3& outward, const vec3& target, const vec3& wi,
                             float dist) {
  Ray r = spawn_from(p, ng, err, sphere, outward, wi);
  if (sphere == kNoSkip) {
    const vec3 to = target - r.o;
    dist = std::sqrt(glm::dot(to, to));
    r.d = to * (1.0f / dist);
  }
  r.tmax = dist * (1.0f - 1e-5f);
  return r;
}

inline Ray spawn_shadow_from(const vec3& p, const vec3& ng, const vec3& err, std::uint32_t sphere,
                             const vec3& outward, const vec3& target) {
  const vec3 to = target - p;
  const float dist = std::sqrt(glm::dot(to, to));
  return spawn_shadow_from(p, ng, err, sphere, outward, target, to * (1.0f / dist), dist);
}

}  // namespace whisker
