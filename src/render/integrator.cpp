#include "render/integrator.h"

#include <cassert>
#include <cmath>

#include "render/direct_light.h"
#include "render/light_connect.h"
#include "render/sampling.h"
#include "render/scattering.h"
#include "render/splitting.h"

namespace whisker {

namespace {

// One hit of a path: `hit`, the closest hit of state.ray. Adds what the hit
// gives to state.L; returns whether the path goes on, along state.ray.
// Inlined: a call here measured 1-2 % on the defaults.
[[gnu::always_inline]] inline bool path_step(const PathContext& ctx, PathState& state,
                                             const Hit& hit, Sampler& sampler) {
  const RenderSettings& settings = ctx.settings;
  Ray& ray = state.ray;
  vec3& beta = state.beta;
  const Material& m = ctx.world.material(hit);
  if (m.kind == MaterialKind::Diffuse) {
    // A path that can carry no more light ends here (the walls' albedos
    // are pure primaries): its light and bounce would both be multiplied
    // by zero. It changes the time, not the estimate, and is decided
    // before the hit record is made.
    beta *= m.albedo;
    if (ends_dark(settings, beta)) return false;
  }
  SurfaceHit h;
  ctx.world.record(ray, hit, h);
  if (m.kind != MaterialKind::Diffuse) state.from = {};  // no light path passes a mirror
  if (m.kind == MaterialKind::Mirror) {
    ray = sample_mirror(ray, h);
    return true;
  }
  if (m.kind != MaterialKind::Diffuse) {  // glass, or a hollow ball's shells
    ray = sample_glass(ray, h, m.ior, settings.fresnel, sampler);
    return true;
  }
  return diffuse_vertex(ctx, ray, h, state, sampler);
}

}  // namespace

// One path is a group of one: a single loop for both (the defaults' split
// branches measured the same time as with a loop of their own).
vec3 trace_path(const PathContext& ctx, PathState& state, Sampler& sampler) {
  trace_paths(ctx, &state, &sampler, 1);
  return state.L;
}

void trace_paths(const PathContext& ctx, PathState* paths, Sampler* samplers, int count) {
  assert(count <= kLanes);
  const int max_depth = ctx.settings.max_depth;
  // depth counts hits: the camera hit plus up to max_depth more (getColor(ray, 5)).
  unsigned live = 0;  // bit k: path k goes on
  for (int k = 0; k < count; ++k)
    if (paths[k].depth <= max_depth) live |= 1u << k;
  while (live) {
    // All the closest hits first, then all the shading: a path's hit and
    // its shading depend on each other, the paths do not. (Shading each
    // path right after its hit measured 3.5 % slower.)
    Hit hits[kLanes];
    const Ray* rays[kLanes];
    unsigned trace = 0;  // the lanes whose hit is not known yet
    for (unsigned a = live; a; a &= a - 1) {
      const int k = __builtin_ctz(a);
      PathState& p = paths[k];
      if (p.first_hit) {
        hits[k] = *p.first_hit;
        p.first_hit = nullptr;
        continue;
      }
      rays[k] = &p.ray;
      trace |= 1u << k;
    }
    // Five or more side by side: a batch tests every sphere of the scene
    // once for all its lanes (six for the cat's room), which pays against
    // one call per ray from four or five rays on (fig 8's settings: batches
    // from 2, 4, 5, 6 and 7 rays up, and none, 64 spp, 7 interleaved pairs
    // each: 5 took 0.978 of the time of 2 and 0.959 of none, 7 0.993 of 5,
    // 6 0.999 of 4).
    constexpr int kMinBatch = 5;
    if (__builtin_popcount(trace) >= kMinBatch) {
      ctx.stats.rays += std::uint64_t(__builtin_popcount(trace));
      live &= ~trace | ctx.world.closest_batch(rays, trace, hits);
    } else {
      for (unsigned a = trace; a; a &= a - 1) {
        const int k = __builtin_ctz(a);
        ++ctx.stats.rays;
        if (!ctx.world.closest(paths[k].ray, hits[k])) live &= ~(1u << k);
      }
    }
    for (unsigned a = live; a; a &= a - 1) {
      const int k = __builtin_ctz(a);
      if (!path_step(ctx, paths[k], hits[k], samplers[k]) || ++paths[k].depth > max_depth)
        live &= ~(1u << k);
    }
  }
}

DirectLight add_direct_light(const PathContext& ctx, const Ray& in, const SurfaceHit& h,
                             const vec3& beta, const Departure& from) {
  DirectLight out{vec3(0.0f), FacingNormals(h, in.d)};
  const LightArrival a = direct_light(ctx.world, h, out.n, ctx.stats.rays);
  if (!a.lit) return out;
  if (from.cos > 0.0f)
    out.L = beta * (a.weight * bounce_weight(from, in, h, a, light_path_start(ctx.world.light())));
  else
    out.L = beta * a.weight;
  return out;
}

bool diffuse_vertex(const PathContext& ctx, const Ray& in, const SurfaceHit& h, PathState& state,
                    Sampler& sampler) {
  const RenderSettings& settings = ctx.settings;
  const bool bounces = settings.indirect && state.depth != settings.max_depth;
  // The light path is chosen first, so that a cached one is read from
  // memory while the shadow ray and the bounces run.
  const bool connect = settings.connect && bounces;
  const LightPick pick =
      connect ? pick_light_path(ctx, state.beta, sampler, hidden_sphere(in, h)) : LightPick{};
  const DirectLight direct = add_direct_light(ctx, in, h, state.beta, state.from);
  state.L += direct.L;
  if (!bounces) return false;
  const int split = split_factor(settings, state.diffuse_hits++, state.beta);
  const Frame frame(direct.n.ns);
  if (split > 1) {
    vec3 sum(0.0f);
    for (int k = 0; k < split; ++k) {
      Sampler branch = sampler.branch(std::uint32_t(k), std::uint32_t(split));
      PathState b{sample_diffuse(h, frame, branch), state.beta, state.depth + 1,
                  state.diffuse_hits};
      if (connect) b.from = departure(direct.n, b.ray.d, split, pick.scale);
      sum += trace_path(ctx, b, branch);
    }
    state.L = state.L + sum / float(split);
    if (connect) state.L += light_connection(ctx, {h, direct.n, state.beta, split}, pick);
    return false;
  }
  const vec3 d = sample_cosine(frame, sampler);
  if (connect) {
    state.from = departure(direct.n, d, 1, pick.scale);
    state.L += light_connection(ctx, {h, direct.n, state.beta, 1}, pick);
  }
  // Last, once `in` (which may be state.ray) is read no more, and straight
  // into the path's ray: returned in a std::optional it was copied twice,
  // the first copy's wide loads waiting on the narrow stores that built it
  // (0.981 of fig 8's time, 7 pairs).
  state.ray = spawn_ray(h, d);
  return true;
}

void camera_paths(const PathContext& ctx, const CameraFrame& cam, std::span<const Pixel> px,
                  Sampler* samplers, PathState* out) {
  assert(px.size() <= 8);
  CameraFrame::Lanes lanes;
  lanes.n = int(px.size());
  const bool aa = ctx.settings.aa;
  for (int l = 0; l < lanes.n; ++l) {
    lanes.i[l] = float(px[std::size_t(l)].i);
    lanes.j[l] = float(px[std::size_t(l)].j);
    if (aa) samplers[l].get2d(lanes.u1[l], lanes.u2[l]);
  }
  vec3 d[8];
  cam.directions(lanes, aa, d);
  // Every camera ray starts at the camera: one origin, split once, in one
  // path state copied to each (a state built anew for each lane was read
  // back by wide loads that waited on its narrow stores).
  const PathState start{ctx.world.to_render(cam.origin, vec3(0.0f, 0.0f, -1.0f))};
  for (int l = 0; l < lanes.n; ++l) {
    out[l] = start;
    out[l].ray.d = d[l];
  }
}

Ray camera_ray(const PathContext& ctx, const CameraFrame& cam, Pixel px, Sampler& sampler) {
  PathState path;
  camera_paths(ctx, cam, {&px, 1}, &sampler, &path);
  return path.ray;
}

vec3 sample_pixel(const PathContext& ctx, const CameraFrame& cam, Pixel px, Sampler& sampler) {
  PathState state{camera_ray(ctx, cam, px, sampler)};
  return trace_path(ctx, state, sampler);
}

}  // namespace whisker
