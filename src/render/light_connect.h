// Light connections: a second way to make the paths camera ... x -> y ->
// light, where x and y are diffuse and the point light shines on y. The
// cosine bounce from x finds y and samples y's direct light; a light path
// instead leaves the light in a direction uniform on the sphere, meets y
// first, and is connected to x by a visibility ray. The light paths are
// traced once per sample and shared by the image's vertices (light_cache.h),
// which scales their density by M / M_c (B below); without a cache (the
// viewer's quick passes) no connection is made and the bounces weigh 1.
// The two are combined by
// the balance heuristic with sample counts (Veach, "Robust Monte Carlo
// Methods for Light Transport Simulation", PhD thesis 1997, section 9.2):
// n cosine bounces leave x (the split factor) and one light path.
//
// Densities per unit area at y, for distance r from x to y, d from the light
// to y, and cosines cos_x (x's facing shading normal, x to y), cos_y (y's
// geometric normal, y to x), cos_l (y's geometric normal, y to the light):
//   a bounce:     p_b = cos_x/pi * cos_y / r^2   (cosine sampling, report section 3)
//   a light path: p_l = 1/(4 pi) * cos_l / d^2   (uniform directions from a point)
// With A = pi p_b and B = pi p_l, each bounce's direct light at y is weighted
// n A / (n A + B); the light path brings beta_x rho_y W_y A / (n A + B), W_y
// the light's weight at y (direct_light.h): its contribution f/p_l = beta_x
// rho_y W_y A / B times its weight B / (n A + B). With the cache, B is
// taken M / M_c times larger and the pick weighed M_c / M (light_cache.h):
// the light path still brings beta_x rho_y W_y A / (n A + B). The weights of a path sum
// to 1, so the sum of both is unbiased (Veach 9.2.2) whatever n is.
#pragma once

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "render/direct_light.h"
#include "render/integrator.h"
#include "render/light_cache.h"

namespace whisker {

// Light paths start this far from the light, a relative 1e-5 of its
// coordinates (far above their rounding): a light on a surface then never
// finds that surface at a distance of rounding error. No light path reaches
// a point closer than this, so bounces' weights there are 1.
inline float light_path_start(const World::Light& light) {
  const vec3 p = glm::abs(light.position);
  return 1e-5f * std::max({p.x, p.y, p.z});
}

// Where a cosine bounce that left a diffuse vertex with `count` bounces can
// also be made by a light path (both its normals in front of the direction).
inline Departure departure(const FacingNormals& n, const vec3& d, int count,
                           float light_scale = 1.0f) {
  if (!(glm::dot(n.ng, d) > 0.0f)) return {};
  return {glm::dot(n.ns, d), float(count), light_scale};
}

// The balance heuristic's weight of a bounce (see above), for the n A and B
// of one path.
inline float bounce_share(float nA, float B) {
  const float w = nA / (nA + B);
  return w == w ? w : 1.0f;  // NaN: nA infinite (y at x), where the bounce takes all
}
// The light path's factor A / (n A + B): its contribution f / p_l = beta
// rho W A / B times its weight B / (n A + B), formed without the difference
// 1 - bounce_share, which loses every digit where B << n A (y near x).
inline float light_path_factor(float n, float A, float B) { return 1.0f / (n + B / A); }

// The weight of the direct light `a` at y, reached by the bounce `in` from
// the vertex it departed: n A / (n A + B), 1 if no light path was sent
// there or none can reach y.
inline float bounce_weight(const Departure& from, const Ray& in, const SurfaceHit& y,
                           const LightArrival& a, float light_start) {
  if (!(from.cos > 0.0f) || a.d2 < light_start * light_start) return 1.0f;
  const float nA = from.count * from.cos * std::fabs(glm::dot(y.ng, in.d)) / (y.t * y.t);
  return bounce_share(nA, from.light_scale * a.cos_g / (4.0f * a.d2));
}

// A vertex's light path, chosen before the vertex's other work (it draws
// one 2D request): with the sample's light cache (light_cache.h), the entry
// picked, already on its way into the processor's cache (prefetched:
// it is read after the direct light's shadow ray and the bounces), and the
// light paths' density factor M / M_c for the vertex's channels (0 without
// a cache or a matching entry: no light path makes the vertex's paths).
struct LightPick {
  const CachedLightVertex* entry = nullptr;
  float scale = 0.0f;
};
// Draws two numbers for the vertex of throughput beta (its albedo in it);
// `exclude` is the sphere the vertex lies on if the ray came from outside
// it (kNoSkip otherwise), whose entries it cannot see (light_cache.h).
LightPick pick_light_path(const PathContext& ctx, const vec3& beta, Sampler& sampler,
                          std::uint32_t exclude = kNoSkip);
// That sphere for the recorded hit h of the ray `in`.
inline std::uint32_t hidden_sphere(const Ray& in, const SurfaceHit& h) {
  return h.sphere != kNoSkip && glm::dot(in.d, h.outward) < 0.0f ? h.sphere : kNoSkip;
}

// The light path `pick` connected to the diffuse vertex x (its hit, facing
// normals and throughput, the albedo in it, with `bounces` cosine bounces
// leaving it): the light it brings there, weighted (see above; the
// throughput applied). Counts its rays.
vec3 light_connection(const PathContext& ctx, const SurfaceHit& x, const FacingNormals& n,
                      const vec3& beta, int bounces, const LightPick& pick);

}  // namespace whisker
