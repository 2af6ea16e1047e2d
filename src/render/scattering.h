// The materials' scattering: the laws of reflection and refraction,
// Schlick's Fresnel term, and one `sample_*` per material kind that turns an
// incoming ray at a hit into the next ray of the path. Diffuse throughput
// (the albedo) is applied by the caller before the hit record is made.
#pragma once

#include <cmath>
#include <utility>

#include <glm/geometric.hpp>

#include "geometry/offset.h"
#include "render/sampler.h"
#include "render/sampling.h"
#include "scene/world.h"

namespace whisker {

inline vec3 reflect(const vec3& d, const vec3& n) { return d - 2.0f * glm::dot(n, d) * n; }

// Refracts unit d through the interface with unit normal n (facing against
// d) and relative index eta = n1/n2; false on total internal reflection.
// Out of line (scattering.cpp): inlined, the compiler may fuse its products
// with the caller's into other multiply-adds, and images change in the last bit.
bool refract(const vec3& d, const vec3& n, float eta, vec3& out);

// Schlick's approximation of the Fresnel reflectance.
inline float schlick(float cos_i, float n1, float n2) {
  // R = R0 + (1 - R0)(1 - |cos|)^5, R0 = ((n1 - n2)/(n1 + n2))^2 (docs/SCENES.md).
  const float r0 = (n1 - n2) / (n1 + n2);
  const float R0 = r0 * r0;
  const float c = 1.0f - std::fabs(cos_i);
  return R0 + (1.0f - R0) * c * c * c * c * c;
}

// A diffuse hit's normals turned to the side the ray `d` arrived from (the
// shading normal to the geometric one's side).
struct FacingNormals {
  vec3 ng, ns;
  FacingNormals(const SurfaceHit& h, const vec3& d)
      : ng(glm::dot(h.ng, d) < 0.0f ? h.ng : -h.ng),
        ns(glm::dot(h.ns, ng) >= 0.0f ? h.ns : -h.ns) {}
  FacingNormals(const vec3& geometric, const vec3& shading) : ng(geometric), ns(shading) {}
};

// Diffuse, report section 3: a cosine-distributed direction in `frame`
// (built on the facing shading normal); the estimator is then rho * L_in.
[[gnu::always_inline]] inline vec3 sample_cosine(const Frame& frame, Sampler& sampler) {
  float u1, u2;
  sampler.get2d(u1, u2);
  return cosine_direction(frame, u1, u2);
}
// The same as a bounce leaving from the hit h.
[[gnu::always_inline]] inline Ray sample_diffuse(const SurfaceHit& h, const Frame& frame,
                                              Sampler& sampler) {
  return spawn_ray(h, sample_cosine(frame, sampler));
}

// A perfect mirror about the shading normal.
inline Ray sample_mirror(const Ray& ray, const SurfaceHit& h) {
  return spawn_ray(h, reflect(ray.d, h.ns));
}

// Glass of index `ior` in air: refraction, or reflection on total internal
// reflection and, with `fresnel`, with Schlick's probability.
inline Ray sample_glass(const Ray& ray, const SurfaceHit& h, float ior, bool fresnel,
                        Sampler& sampler) {
  // Entering or leaving: the normal is flipped to face the ray and the
  // indices swapped (an inverted inner shell thus reads glass -> air).
  vec3 n = h.ng;
  float n1 = 1.0f, n2 = ior;
  if (glm::dot(ray.d, n) > 0.0f) {
    n = -n;
    std::swap(n1, n2);
  }
  vec3 t;
  bool reflected = !refract(ray.d, n, n1 / n2, t);  // total internal reflection
  if (!reflected && fresnel) reflected = sampler.get1d() < schlick(glm::dot(ray.d, n), n1, n2);
  return spawn_ray(h, reflected ? reflect(ray.d, n) : t);
}

}  // namespace whisker
