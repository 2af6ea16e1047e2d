// Ray/sphere intersection, stable for the report's huge wall spheres.
#pragma once

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

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

// The float test above picks the closest sphere; for that one sphere the
// distance is solved again in double, because at grazing angles on the
// radius-990 floor float loses up to ~1e-4 of t, which would shift shading
// positions.
//
// First one Newton step from the float root on g(t) = |f + t d|^2 - r^2
// (f = o - c), in double: g'(t) = 2 (f + t d).d, and since g'' = 2 |d|^2 the
// error after the step is e^2 |d|^2 / |g'| for a start e away from the root,
// about step^2 |d|^2 / |g'|. When that bound is below 1e-9 of t (float rounds
// at 6e-8) the step is the answer: one division where the quadratic takes
// two and a square root. Otherwise (grazing rays, where g' is small, or a
// poor start) the stable quadratic below decides.
inline double solve_sphere_t(const Sphere& s, const Ray& r, float t_float);
// x as a float and the float of its remainder: hi + lo is x to about 2^-48
// of it (a hit point refined in double, kept as Ray::o and Ray::o_lo).
// The empty asm keeps the compiler from treating double(float(x)) as x:
// GCC 12 at -O3 -march=native folds it so in vectorised code (lo became 0).
inline void split_double(const glm::dvec3& x, vec3& hi, vec3& lo) {
  for (int k = 0; k < 3; ++k) {
    float h = static_cast<float>(x[k]);
    asm("" : "+x"(h));
    hi[k] = h;
    lo[k] = static_cast<float>(x[k] - static_cast<double>(h));
  }
}

inline glm::dvec3 exact_origin(const Ray& r) { return glm::dvec3(r.o) + glm::dvec3(r.o_lo); }
inline double refine_sphere_t(const Sphere& s, const Ray& r, float t_float) {
  const glm::dvec3 f = exact_origin(r) - glm::dvec3(s.center);
  const glm::dvec3 d(r.d);
  const double t = t_float;
  const glm::dvec3 p = f + t * d;
  const double r2 = double(s.radius) * double(s.radius);
  const double g = glm::dot(p, p) - r2;
  const double gp = 2.0 * glm::dot(p, d);
  const double step = g / gp;
  const double t1 = t - step;
  if (step * step * glm::dot(d, d) <= 1e-9 * std::fabs(gp) * std::fabs(t1)) return t1;
  return solve_sphere_t(s, r, t_float);
}

// The double-precision root nearest t_float by the stable quadratic (same
// form as intersect_sphere()).
inline double solve_sphere_t(const Sphere& s, const Ray& r, float t_float) {
  const glm::dvec3 f = exact_origin(r) - glm::dvec3(s.center);
  const glm::dvec3 d(r.d);
  const double inv_len2 = 1.0 / glm::dot(d, d);  // d is unit in float, not in double
  const double b = -glm::dot(f, d) * inv_len2;
  const glm::dvec3 perp = f + b * d;
  const double r2 = double(s.radius) * double(s.radius);
  const double disc = std::max(0.0, (r2 - glm::dot(perp, perp)) * inv_len2);
  const double c = (glm::dot(f, f) - r2) * inv_len2;
  const double q = b + std::copysign(std::sqrt(disc), b);
  const double t0 = q != 0.0 ? c / q : 0.0, t1 = q;
  return std::fabs(t0 - t_float) < std::fabs(t1 - t_float) ? t0 : t1;
}

}  // namespace whisker
