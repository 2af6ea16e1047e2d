// Hit records: what a ray's hit on a sphere or a triangle is once the
// closest one is known (the point, its normals, and how a ray leaves it),
// from the distance the intersector found (sphere.h) or the barycentric
// weights (triangle.h). The World adds the material (scene/world.h).
#pragma once

#include <array>
#include <cstdint>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "geometry/offset.h"
#include "geometry/ray.h"
#include "geometry/sphere.h"
#include "geometry/triangle.h"

namespace whisker {

struct SurfacePoint {
  float t = kInf;
  vec3 p{0.0f};   // hit point
  vec3 ng{0.0f};  // unit geometric normal (outward; inward for inverted shells)
  vec3 ns{0.0f};  // unit shading normal (== ng unless vertex normals are on)
  // How rays leave this point (geometry/offset.h): a sphere's hit is left
  // from p itself, excluding that sphere (`sphere`, `outward` its outward
  // normal; `err` then holds the low part of the double hit, p + err); a
  // triangle's from p moved off the plane past `err`, a per-coordinate bound
  // on the rounding error of p.
  std::uint32_t sphere = kNoSkip;
  vec3 outward{0.0f};
  vec3 err{0.0f};
};

// A ray leaving the hit in direction d, and a shadow ray from it to the
// point `target` (geometry/offset.h).
inline Ray spawn_ray(const SurfacePoint& h, const vec3& d) {
  return spawn_from(h.p, h.ng, h.err, h.sphere, h.outward, d);
}
inline Ray spawn_shadow_ray(const SurfacePoint& h, const vec3& target) {
  return spawn_shadow_from(h.p, h.ng, h.err, h.sphere, h.outward, target);
}
// The same given the unit direction wi and distance from h.p to target.
inline Ray spawn_shadow_ray(const SurfacePoint& h, const vec3& target, const vec3& wi, float dist) {
  return spawn_shadow_from(h.p, h.ng, h.err, h.sphere, h.outward, target, wi, dist);
}

// The hit of `ray` on sphere number `index`, s, whose float distance the
// intersector found as t_float. The distance is refined in double
// (refine_sphere_t), the point and the normal taken from that double hit:
// the normal of a point rounded to float would be off by an ULP of the
// coordinates over the radius (0.4 % for a 1e-3 ball at 50).
inline SurfacePoint sphere_surface_point(const Sphere& s, std::uint32_t index, const Ray& ray,
                                         float t_float) {
  SurfacePoint out;
  const double t = refine_sphere_t(s, ray, t_float);
  const glm::dvec3 pd = exact_origin(ray) + t * glm::dvec3(ray.d);
  const glm::dvec3 nd = pd - glm::dvec3(s.center);
  out.t = float(t);
  split_double(pd, out.p, out.err);  // the low part in err (offset.h)
  // pd lies on the sphere to double rounding: dividing by the radius gives
  // a unit vector to far below float's precision, without a square root.
  out.outward = vec3(nd * (1.0 / double(s.radius)));
  out.ng = s.inverted ? -out.outward : out.outward;
  out.ns = out.ng;
  out.sphere = index;
  return out;
}

// The hit on `tri` (unit geometric normal ng) at distance t with the
// barycentric weights u (of v1) and v (of v2) that intersect_triangle()
// found. The point from the weights, not o + t d: a convex combination
// of the vertices lies on their plane but for its own rounding, whatever the
// error of the weights (they move it within the plane), so its distance from
// the plane is bounded by err below, while o + t d carries the error of t
// times |d| off the plane. The bound: b0 = 1 - u - v (two roundings, its
// error e|b| makes the weights sum to 1 + e, moving p by e|p|), three
// products and two sums, each rounding by at most 2^-24 of its magnitude: at
// most 7 roundings of terms bounded by sum |b_i v_i|, pbrt-v4's gamma(7)
// (Pharr, Jakob, Humphreys, "Physically Based Rendering" 4th ed. 6.8.5),
// doubled for the terms a first-order bound leaves out.
inline SurfacePoint triangle_surface_point(const Triangle& tri, const vec3& ng, float t, float u,
                                           float v) {
  SurfacePoint out;
  const float b0 = 1.0f - u - v;
  const vec3 a = b0 * tri.v0, b = u * tri.v1, c = v * tri.v2;
  out.t = t;
  out.p = a + b + c;
  constexpr float kGamma7x2 = 2.0f * 7.0f * 0x1p-24f / (1.0f - 7.0f * 0x1p-24f);
  out.err = (glm::abs(a) + glm::abs(b) + glm::abs(c)) * kGamma7x2;
  out.ng = ng;
  out.ns = ng;
  out.sphere = kNoSkip;
  out.outward = ng;
  return out;
}

// The shading normal at weights u, v from the unit normals of the corners
// v0, v1, v2: their interpolation, normalised. Corners whose normals cancel
// (or are zero) leave no direction: `ng` then, not the NaN of normalising
// zero.
inline vec3 interpolated_normal(const std::array<vec3, 3>& corner, float u, float v,
                                const vec3& ng) {
  const float b0 = 1.0f - u - v;
  const vec3 ns = b0 * corner[0] + u * corner[1] + v * corner[2];
  const float len2 = glm::dot(ns, ns);
  return len2 > 0.0f && len2 < kInf ? glm::normalize(ns) : ng;
}

}  // namespace whisker
