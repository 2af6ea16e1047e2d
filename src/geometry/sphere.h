// Ray/sphere intersection, stable for the report's huge wall spheres.
#pragma once

#include <cmath>

#include <glm/geometric.hpp>

#include "geometry/ray.h"

namespace whisker {

struct Sphere {
  vec3 center{0.0f};
  float radius = 1.0f;
  bool inverted = false;  // inner shell of a hollow sphere: normal points in
};

// Smallest root t of |o + t d - c| = r inside (tmin, tmax), or kInf.
// The discriminant is formed from the perpendicular offset of the centre to
// the ray, and the near root from the far one through Vieta's formula, as in
// Haines, Guenther, Akenine-Moeller, "Precision Improvements for Ray/Sphere
// Intersection", Ray Tracing Gems ch. 7 (2019). d must be unit length.
inline float intersect_sphere(const Sphere& s, const Ray& r) {
  const vec3 f = r.o - s.center;
  const float b = -glm::dot(f, r.d);               // b' = -(f.d)
  const vec3 perp = f + b * r.d;                    // f - (f.d) d
  const float r2 = s.radius * s.radius;
  const float disc = r2 - glm::dot(perp, perp);     // eq. 7.5
  if (disc < 0.0f) return kInf;
  const float c = glm::dot(f, f) - r2;
  const float q = b + std::copysign(std::sqrt(disc), b);  // eq. 7.8
  // Roots are c/q and q; when q == 0 both are 0 (origin on the sphere).
  float t0 = q != 0.0f ? c / q : 0.0f;
  float t1 = q;
  if (t0 > t1) std::swap(t0, t1);
  if (t0 > r.tmin && t0 < r.tmax) return t0;
  if (t1 > r.tmin && t1 < r.tmax) return t1;
  return kInf;
}

// The hit point for a sphere hit at distance t, projected back onto the
// surface in double precision so its error is about one float ULP (the
// projection costs one square root per shaded hit, not per test).
inline vec3 sphere_hit_point(const Sphere& s, const Ray& r, float t) {
  const double px = double(r.o.x) + double(t) * r.d.x - s.center.x;
  const double py = double(r.o.y) + double(t) * r.d.y - s.center.y;
  const double pz = double(r.o.z) + double(t) * r.d.z - s.center.z;
  const double k = double(s.radius) / std::sqrt(px * px + py * py + pz * pz);
  return vec3(float(s.center.x + px * k), float(s.center.y + py * k),
              float(s.center.z + pz * k));
}

// Outward geometric normal (inward for an inverted shell).
inline vec3 sphere_normal(const Sphere& s, const vec3& p) {
  const vec3 n = glm::normalize(p - s.center);
  return s.inverted ? -n : n;
}

}  // namespace whisker
