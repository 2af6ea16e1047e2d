// Direct light from the scene's point light (owned by the World) at a
// diffuse point, with its shadow ray.
#pragma once

#include <cmath>
#include <cstdint>

#include <glm/geometric.hpp>

#include "geometry/offset.h"
#include "render/scattering.h"
#include "scene/world.h"

namespace whisker {

// The point light's contribution at a point: whether it arrives (in front
// of the surface and visible) and its weight; with the cosine between the
// facing geometric normal and the direction to the light, and the squared
// distance to it (the light path's density there, light_connect.h).
struct LightArrival {
  bool lit = false;
  float weight = 0.0f;  // everything but rho (the caller's throughput holds it)
  float cos_g = 0.0f;
  float d2 = 0.0f;
};

// Report section 2: I/(4 pi d^2) * cos/pi, the light's weight at a point
// `to_light` away from it (inv_d its inverse length) where the facing
// shading normal makes cosine cos_s with the direction to the light.
inline float light_weight(float intensity, float cos_s, const vec3& to_light, float inv_d) {
  constexpr float kPi = 3.14159265358979323846f;
  float weight = intensity * cos_s * (inv_d * inv_d) * (1.0f / (4.0f * kPi * kPi));
  // I cos / d^2 can leave float's range before the 1/(4 pi^2) brings the term
  // back (a light 1e-5 from the surface at the scene reader's 1e30): then in
  // double, so that the term is infinite only where float cannot hold it.
  if (!(weight < kInf)) {
    const glm::dvec3 to(to_light);
    const double dd2 = glm::dot(to, to);
    weight = float(double(intensity) * cos_s / (dd2 * (4.0 * double(kPi) * double(kPi))));
  }
  return weight;
}

// Report section 2: L_d = I/(4 pi d^2) * rho/pi * <N, w_i> * V at the hit h
// with facing normals n; counts the shadow ray it traces in `rays`.
// The shadow ray leaves h by the spawn rule, aimed at the light from there.
inline LightArrival direct_light(const World& world, const SurfaceHit& h, const FacingNormals& n,
                                 std::uint64_t& rays) {
  const World::Light& light = world.light();
  const vec3 to_light = light.position - h.p;
  const float d2 = glm::dot(to_light, to_light);
  const float inv_d = 1.0f / std::sqrt(d2);
  const vec3 wi = to_light * inv_d;
  const float cos_s = glm::dot(n.ns, wi);
  const float cos_g = glm::dot(n.ng, wi);
  // The geometric test keeps vertex normals from lighting the far side.
  if (!(cos_s > 0.0f && cos_g > 0.0f)) return {};
  ++rays;
  const Ray shadow = spawn_shadow_ray(h, light.position, wi, d2 * inv_d);
  if (world.occluded_to_light(shadow, d2, -to_light)) return {};
  return {true, light_weight(light.intensity, cos_s, to_light, inv_d), cos_g, d2};
}

}  // namespace whisker
