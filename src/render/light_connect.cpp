#include "render/light_connect.h"

namespace whisker {

namespace {

// The end of a segment from x to the cached light vertex e, seen from
// direction `from_x`: a triangle's point moved off its plane towards x
// (geometry/offset.h), so the segment stops short of it; a sphere's point
// itself, that sphere then untested where it cannot block (the segment
// meets it at y only): x in front of its outer side, or x on the same
// sphere (a chord: x's cosine test has already refused the outer side).
// Elsewhere the sphere is tested, and the segment's end short of y
// (spawn_shadow_ray) keeps y from blocking itself: a light on a sphere sends
// light paths to its far inside, which x outside it must not see.
// Returns the sphere left untested (kNoSkip: none) and writes the point to
// `p`: a struct of both, built by three stores and read back by one 16-byte
// load, stalled every connection on the store-to-load forward.
std::uint32_t segment_end(const SurfaceHit& x, const CachedLightVertex& e, const vec3& from_x,
                          vec3& p) {
  if (e.sphere == kNoSkip) {
    p = offset_ray_origin(e.p, e.err, e.record_ng(), -from_x);
    return kNoSkip;
  }
  p = e.p;
  return x.sphere == e.sphere || glm::dot(e.outward(), from_x) < 0.0f ? e.sphere : kNoSkip;
}

}  // namespace

LightPick pick_light_path(const PathContext& ctx, const vec3& beta, Sampler& sampler,
                          std::uint32_t exclude) {
  LightPick pick;
  float u1, u2;  // one 2D request (a stratified pair); the first number picks
  sampler.get2d(u1, u2);
  if (!ctx.lights) return pick;
  const unsigned channels = channel_bits(beta);
  pick.scale = ctx.lights->density_scale(channels, exclude);
  pick.entry = ctx.lights->pick(channels, u1, exclude);
  if (pick.entry) __builtin_prefetch(pick.entry);
  return pick;
}

vec3 light_connection(const PathContext& ctx, const SurfaceHit& x, const FacingNormals& n,
                      const vec3& beta, int bounces, const LightPick& pick) {
  if (!pick.entry) return vec3(0.0f);
  const CachedLightVertex& e = *pick.entry;
  const vec3 to = e.p - x.p;
  const float r2 = glm::dot(to, to);
  const vec3 w = to * (1.0f / std::sqrt(r2));
  const float cos_x = glm::dot(n.ns, w);
  if (!(cos_x > 0.0f && glm::dot(n.ng, w) > 0.0f)) return vec3(0.0f);
  const float cos_y = -glm::dot(e.ng, w);  // x on the side the light shines on
  if (!(cos_y > 0.0f)) return vec3(0.0f);
  const float A = cos_x * cos_y / r2;
  const float weight = light_path_factor(float(bounces), A, e.B * pick.scale);
  if (!(weight > 0.0f)) return vec3(0.0f);
  vec3 end;
  const std::uint32_t untested = segment_end(x, e, w, end);
  ++ctx.stats.rays;
  if (ctx.world.occluded(spawn_shadow_ray(x, end), untested)) return vec3(0.0f);
  return beta * e.albedo * (e.weight * weight);
}

}  // namespace whisker
