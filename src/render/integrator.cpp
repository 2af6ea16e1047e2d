#include "render/integrator.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <new>
#include <vector>

#include "render/direct_light.h"
#include "render/features.h"
#include "render/light_connect.h"
#include "render/sampling.h"
#include "render/scattering.h"

namespace whisker {

namespace {

// The closest hits of the paths in `live` (bit k: paths[k]); returns the
// paths that hit something. A batch tests each sphere once for all its
// lanes, which pays from five rays on; fewer go one by one. A path that
// leaves the scene before a diffuse hit has no features.
unsigned closest_hits(const PathContext& ctx, PathState* paths, unsigned live, Hit* hits) {
  const Ray* rays[kLanes];
  for (unsigned a = live; a; a &= a - 1) rays[__builtin_ctz(a)] = &paths[__builtin_ctz(a)].ray;
  unsigned hit = live;
  constexpr int kMinBatch = 5;
  if (__builtin_popcount(live) >= kMinBatch) {
    ctx.stats.rays += std::uint64_t(__builtin_popcount(live));
    hit &= ctx.world.closest_batch(rays, live, hits);
  } else {
    for (unsigned a = live; a; a &= a - 1) {
      const int k = __builtin_ctz(a);
      ++ctx.stats.rays;
      if (!ctx.world.closest(paths[k].ray, hits[k])) hit &= ~(1u << k);
    }
  }
  for (unsigned a = live & ~hit; a; a &= a - 1)
    if (Features* f = paths[__builtin_ctz(a)].features) *f = Features{};
  return hit;
}

// The denoiser's features at the path's hit h: the distance along the
// chain of mirrors and glass so far, the facing normal, and at the first
// diffuse hit its albedo, after which the path records no more.
void record_features(PathState& p, const SurfaceHit& h, const Material& m) {
  p.features->depth = (p.depth == 0 ? 0.0f : p.features->depth) + h.t;
  p.features->normal = FacingNormals(h, p.ray.d).ns;
  if (m.kind != MaterialKind::Diffuse) return;
  p.features->albedo = m.albedo;
  p.features = nullptr;
}

}  // namespace

vec3 trace_path(const PathContext& ctx, PathState& state, Sampler& sampler) {
  trace_paths(ctx, &state, &sampler, 1);
  return state.L;
}

// The path, report sections 2-3: at each hit the material decides; mirrors
// and glass turn the ray, a diffuse hit gathers the light's direct light,
// sends a light connection, and splits or bounces. Written for up to
// kLanes paths side by side: all the lanes' closest hits are found before
// any is shaded, since a path's hit and its shading depend on each other
// and the paths do not (docs/PERFORMANCE.md, "Paths side by side").
void trace_paths(const PathContext& ctx, PathState* paths, Sampler* samplers, int count) {
  assert(count <= kLanes);
  const RenderSettings& settings = ctx.settings;
  // depth counts hits: the camera hit plus up to max_depth more (getColor(ray, 5)).
  unsigned live = (1u << count) - 1;  // bit k: path k goes on
  for (int k = 0; k < count; ++k)
    if (paths[k].depth > settings.max_depth) live &= ~(1u << k);
  while (live) {
    Hit hits[kLanes];
    live = closest_hits(ctx, paths, live, hits);
    for (unsigned a = live; a; a &= a - 1) {
      const int k = __builtin_ctz(a);
      PathState& p = paths[k];
      Sampler& sampler = samplers[k];
      const Material& m = ctx.world.material(hits[k]);
      const bool diffuse = m.kind == MaterialKind::Diffuse;
      auto end = [&] { live &= ~(1u << k); };

      // ---- Throughput: a diffuse hit's albedo, before the hit is recorded.
      // A path of zero throughput (the walls are pure primaries) ends here:
      // a change of time, not of the estimate (RenderSettings::zero_cutoff).
      if (diffuse) p.beta *= m.albedo;
      const bool dark = diffuse && ends_dark(settings, p.beta);
      if (dark && !p.features) {
        end();
        continue;
      }
      SurfaceHit h;
      ctx.world.record(p.ray, hits[k], h);
      if (p.features) record_features(p, h, m);  // for the denoiser
      if (dark) {
        end();
        continue;
      }

      // ---- Mirror and glass: the ray turns; glass chooses reflection or
      // refraction by Schlick's Fresnel term when Fresnel is on. No light
      // path passes a specular surface, so no connection weighs the next hit.
      if (!diffuse) {
        p.from = {};
        p.ray = m.kind == MaterialKind::Mirror ? sample_mirror(p.ray, h)
                                               : sample_glass(p.ray, h, m.ior, settings.fresnel, sampler);
        if (++p.depth > settings.max_depth) end();
        continue;
      }

      // ---- Light connection, chosen first: the cached light vertex it
      // picks is read from memory while the shadow ray and the bounces run.
      const bool bounces = settings.indirect && p.depth != settings.max_depth;
      const bool connect = settings.connect && bounces;
      const LightPick pick =
          connect ? pick_light_path(ctx, p.beta, sampler, hidden_sphere(p.ray, h)) : LightPick{};

      // ---- Direct light from the point light (report section 2), weighed
      // against the light path that could have found this point.
      const FacingNormals n(h, p.ray.d);
      const LightArrival arrival = direct_light(ctx.world, h, n, ctx.stats.rays);
      if (arrival.lit) {
        const float w = p.from.cos > 0.0f ? arrival.weight * bounce_weight(p.from, p.ray, h, arrival,
                                                                           light_path_start(ctx.world.light()))
                                          : arrival.weight;
        p.L += p.beta * w;
      }
      if (!bounces) {
        end();
        continue;
      }

      // ---- Split: several cosine bounces leave the first diffuse hits, each
      // a path of its own from here, and their mean is this path's indirect
      // light (RenderSettings::split).
      const int split = split_factor(settings, p.diffuse_hits++, p.beta);
      const Frame frame(n.ns);
      if (split > 1) {
        vec3 sum(0.0f);
        for (int b = 0; b < split; ++b) {
          Sampler branch = sampler.branch(std::uint32_t(b), std::uint32_t(split));
          PathState q{sample_diffuse(h, frame, branch), p.beta, p.depth + 1, p.diffuse_hits};
          if (connect) q.from = departure(n, q.ray.d, split, pick.scale);
          sum += trace_path(ctx, q, branch);
        }
        p.L = p.L + sum / float(split);
        if (connect) p.L += light_connection(ctx, h, n, p.beta, split, pick);
        end();
        continue;
      }

      // ---- Bounce: one cosine-sampled direction (report section 3), the
      // light connection made from here, and the path goes on.
      const vec3 d = sample_cosine(frame, sampler);
      if (connect) {
        p.from = departure(n, d, 1, pick.scale);
        p.L += light_connection(ctx, h, n, p.beta, 1, pick);
      }
      p.ray = spawn_ray(h, d);
      if (++p.depth > settings.max_depth) end();
    }
  }
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

namespace {

// A pixel's sums at the start of the tile's samples: carried from the
// pass's earlier chunk, or zero.
// Without feature buffers only the radiance sums are read (Film::add), so
// only they are cleared: most of a PixelSum is feature sums, and clearing
// them all was a pass's largest memset.
void start_sum(const TileWork& tile, std::uint32_t pixel, bool features, PixelSum& out) {
  if (tile.carry.in) {
    out = tile.carry.sums[pixel];
  } else if (features) {
    out = PixelSum{};
  } else {
    out.sum = glm::dvec3(0.0);
    out.sum_sq = out.odd_sum = 0.0;
    out.dropped = 0;
  }
}

// A pixel's sums at the end: left for the pass's next chunk, or added to the
// film (its non-finite samples counted in `result` then).
void finish_sum(const TileWork& tile, std::uint32_t pixel, const PixelSum& sum, Film& film,
                TileResult& result) {
  if (tile.carry.out) {
    tile.carry.sums[pixel] = sum;
    return;
  }
  film.add(pixel, sum);
  result.dropped += sum.dropped;
}

// Whether the pass is being dropped (asked before each group of paths).
bool abandoned(const TileWork& tile, TileResult& result) {
  if (!(tile.cancel && tile.cancel->load(std::memory_order_relaxed))) return false;
  result.abandoned = true;
  return true;
}

}  // namespace

// The tile's (pixel, sample) pairs, kLanes at a time side by side
// (trace_paths), each pixel adding its samples in order. With light caches
// the samples are the outer loop and a group never straddles two of them, so
// a thread reads one sample's cache at a time (a pass's caches together
// outgrow the processor's caches); without, the pixels are, so a pixel's
// Sobol seeds are made once for all its samples. Both orders give the same
// sums bit for bit.
TileResult render_tile(const PathContext& ctx, const CameraFrame& cam, const TileWork& tile,
                       Film& film) {
  const PixelBlock& t = tile.pixels;
  const int cols = t.j1 - t.j0;
  const std::int64_t pixels = std::int64_t(t.i1 - t.i0) * cols, pairs = pixels * tile.spp;
  const bool by_sample = tile.light_caches != nullptr;
  TileResult result;
  const FlushDenormals ftz;
  std::vector<PixelSum> sums(static_cast<std::size_t>(pixels));
  auto index = [&](std::int64_t p) { return cam.pixel_index(t.i0 + int(p / cols), t.j0 + int(p % cols)); };
  const bool features = tile.features || film.has_features();
  for (std::int64_t p = 0; p < pixels; ++p) start_sum(tile, index(p), features, sums[std::size_t(p)]);
  for (std::int64_t q0 = 0; q0 < pairs;) {
    if (abandoned(tile, result)) return result;
    int n = int(std::min<std::int64_t>(kLanes, pairs - q0));
    if (by_sample) n = int(std::min<std::int64_t>(n, pixels - q0 % pixels));
    const std::int64_t k0 = by_sample ? q0 / pixels : 0;
    PathContext group_ctx = ctx;
    if (by_sample) group_ctx.lights = &tile.light_caches[k0];
    PathState path[kLanes];
    Sampler sampler[kLanes];
    Pixel px[kLanes];
    std::int64_t pixel[kLanes];
    std::uint64_t sample[kLanes];
    for (int l = 0; l < n; ++l) {
      const std::int64_t q = q0 + l;
      pixel[l] = by_sample ? q % pixels : q / tile.spp;
      sample[l] = tile.first_sample + std::uint64_t(by_sample ? k0 : q % tile.spp);
      px[l] = Pixel{t.i0 + int(pixel[l] / cols), t.j0 + int(pixel[l] % cols)};
      // Made in place: a copy of a sampler just built (its fields stored
      // one by one, read back by one wide load) waited on the stores.
      ::new (&sampler[l]) Sampler(pixel_sampler(ctx.settings, cam, px[l], sample[l]));
    }
    camera_paths(group_ctx, cam, {px, std::size_t(n)}, sampler, path);
    Features features[kLanes];
    if (tile.features)
      for (int l = 0; l < n; ++l) path[l].features = &features[l];
    trace_paths(group_ctx, path, sampler, n);
    for (int l = 0; l < n; ++l) {
      PixelSum& sum = sums[std::size_t(pixel[l])];
      if (tile.features) sum.add_features(features[l].albedo, features[l].normal, features[l].depth, sample[l]);
      sum.add(path[l].L, sample[l]);
    }
    q0 += n;
  }
  for (std::int64_t p = 0; p < pixels; ++p) finish_sum(tile, index(p), sums[std::size_t(p)], film, result);
  return result;
}

}  // namespace whisker
