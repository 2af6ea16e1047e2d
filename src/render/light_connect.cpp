#include "render/light_connect.h"

#include "render/sampling.h"

namespace whisker {

namespace {

// A direction uniform on the unit sphere: z = 1 - 2 u2, the azimuth 2 pi u1
// (Archimedes: z is uniform on a sphere).
vec3 uniform_sphere(float u1, float u2) {
  const float z = 1.0f - 2.0f * u2;
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  float s, c;
  sincos_turn(u1, s, c);
  return vec3(r * c, r * s, z);
}

// The end of a segment from x to the surface point y, seen from direction
// `from_x`: a triangle's point moved off its plane towards x
// (geometry/offset.h), so the segment stops short of it; a sphere's point
// itself, that sphere then untested where it cannot block (the segment
// meets it at y only): x in front of its outer side, or x on the same
// sphere (a chord: x's cosine test has already refused the outer side).
// Elsewhere the sphere is tested, and the segment's end short of y
// (spawn_shadow_ray) keeps y from blocking itself: a light on a sphere sends
// light paths to its far inside, which x outside it must not see.
struct SegmentEnd {
  vec3 p;
  std::uint32_t sphere = kNoSkip;
};
SegmentEnd segment_end(const SurfaceHit& x, const SurfaceHit& y, const vec3& from_x) {
  if (y.sphere == kNoSkip) return {offset_ray_origin(y.p, y.err, y.ng, -from_x)};
  if (x.sphere == y.sphere || glm::dot(y.outward, from_x) < 0.0f) return {y.p, y.sphere};
  return {y.p};
}

}  // namespace

vec3 light_connection(const PathContext& ctx, const ConnectionVertex& x, Sampler& sampler) {
  float u1, u2;
  sampler.get2d(u1, u2);
  const World::Light& light = ctx.world.light();
  Ray ray;
  ray.o = light.position;
  ray.d = uniform_sphere(u1, u2);
  ray.tmin = light_path_start(light);
  ++ctx.stats.rays;
  Hit hit;
  if (!ctx.world.closest(ray, hit)) return vec3(0.0f);
  const Material& m = ctx.world.material(hit);
  const vec3 beta = x.beta * m.albedo;
  if (m.kind != MaterialKind::Diffuse || ends_dark(ctx.settings, beta)) return vec3(0.0f);
  SurfaceHit y;
  ctx.world.record(ray, hit, y);
  const vec3 to = y.p - x.h.p;
  const float r2 = glm::dot(to, to);
  const vec3 w = to * (1.0f / std::sqrt(r2));
  const float cos_x = glm::dot(x.n.ns, w);
  if (!(cos_x > 0.0f && glm::dot(x.n.ng, w) > 0.0f)) return vec3(0.0f);
  const FacingNormals ny(y, w);  // turned towards x
  const vec3 to_light = light.position - y.p;
  const float d2 = glm::dot(to_light, to_light);
  const float inv_d = 1.0f / std::sqrt(d2);
  const float cos_l = glm::dot(ny.ng, to_light) * inv_d;
  const float cos_s = glm::dot(ny.ns, to_light) * inv_d;
  if (!(cos_l > 0.0f && cos_s > 0.0f)) return vec3(0.0f);  // lit from x's side only
  const float A = cos_x * -glm::dot(ny.ng, w) / r2;
  const float B = cos_l / (4.0f * d2);
  const float weight = light_path_factor(float(x.bounces), A, B);
  if (!(weight > 0.0f)) return vec3(0.0f);
  const SegmentEnd end = segment_end(x.h, y, w);
  ++ctx.stats.rays;
  if (ctx.world.occluded(spawn_shadow_ray(x.h, end.p), end.sphere)) return vec3(0.0f);
  return beta * (light_weight(light.intensity, cos_s, to_light, inv_d) * weight);
}

}  // namespace whisker
