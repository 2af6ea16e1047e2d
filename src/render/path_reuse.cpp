#include "render/path_reuse.h"

#include <cmath>
#include <vector>

#include <glm/geometric.hpp>

#include "render/sampler.h"
#include "render/sampling.h"
#include "render/scattering.h"
#include "render/splitting.h"

namespace whisker {

namespace {

constexpr int kMaxPixels = kMaxReuse * kMaxReuse;

// A pixel's first hit: a sampling technique of the block when diffuse.
struct FirstHit {
  SurfaceHit h;
  vec3 ns{0.0f};     // facing shading normal: the bounces' cosine frame
  vec3 beta{0.0f};   // the albedo (the camera ray carries 1)
  int bounces = 0;   // n: bounces it sends; 0 = not a technique
};

// A bounce from a technique that met a diffuse point y.
struct Bounce {
  vec3 p{0.0f};   // y
  vec3 ng{0.0f};  // y's geometric normal, turned to the side the bounce came from
  vec3 Lo{0.0f};  // L_o(y), in the channels some pixel of the block carries
  std::uint32_t sphere = kNoSkip;  // y's sphere (kNoSkip: a triangle)
  int owner = 0;  // the pixel that sent it
};

// The camera hit of pixel px: when it is a technique, `first` (with the hit's
// direct light in `L`); otherwise (no diffuse hit, or nothing to carry) the
// whole sample as sample_pixel traces it, in `L`.
struct CameraHit {
  FirstHit first;
  vec3 L{0.0f};
};
CameraHit first_hit(const PathContext& ctx, const CameraFrame& cam, Pixel px, Sampler& sampler) {
  const RenderSettings& s = ctx.settings;
  CameraHit out;
  const Ray ray = camera_ray(ctx, cam, px, sampler);
  Hit hit;
  ++ctx.stats.rays;
  if (!ctx.world.closest(ray, hit)) return out;
  const Material& m = ctx.world.material(hit);
  if (m.kind != MaterialKind::Diffuse) {
    PathState state{ray};
    state.first_hit = &hit;
    out.L = trace_path(ctx, state, sampler);
    return out;
  }
  FirstHit& first = out.first;
  first.beta = m.albedo;
  if (ends_dark(s, first.beta)) return out;
  ctx.world.record(ray, hit, first.h);
  const DirectLight direct = add_direct_light(ctx, ray, first.h, first.beta);
  out.L += direct.L;
  first.ns = direct.n.ns;
  first.bounces = split_factor(s, 0, first.beta);
  return out;
}

// A technique of the block: pixel `pixel`'s first hit, and the channels
// some pixel of the block carries (the bounces' light is traced in those).
struct Technique {
  const FirstHit& x;
  int pixel = 0;
  vec3 carried{0.0f};
};

// The technique's bounces: those meeting a diffuse point go to `out` with
// L_o traced in the carried channels; the others are finished for its pixel
// alone, their light added to its light L so far, which is returned.
vec3 send_bounces(const PathContext& ctx, const Technique& t, Sampler& sampler,
                  std::vector<Bounce>& out, vec3 L) {
  const FirstHit& x = t.x;
  const Frame frame(x.ns);
  const float inv_n = 1.0f / float(x.bounces);
  for (int b = 0; b < x.bounces; ++b) {
    Sampler branch = sampler.branch(std::uint32_t(b), std::uint32_t(x.bounces));
    const Ray ray = sample_diffuse(x.h, frame, branch);
    Hit hit;
    ++ctx.stats.rays;
    if (!ctx.world.closest(ray, hit)) continue;
    const Material& m = ctx.world.material(hit);
    if (m.kind != MaterialKind::Diffuse) {  // glass or mirror: its light depends on the way in
      PathState state{ray, x.beta, 1, 1};
      state.first_hit = &hit;
      L += trace_path(ctx, state, branch) * inv_n;
      continue;
    }
    const vec3 beta = t.carried * m.albedo;
    if (ends_dark(ctx.settings, beta)) continue;
    SurfaceHit h;
    ctx.world.record(ray, hit, h);
    Bounce y;
    y.p = h.p;
    y.ng = glm::dot(h.ng, ray.d) < 0.0f ? h.ng : -h.ng;
    y.owner = t.pixel;
    y.sphere = h.sphere;
    PathState state{ray, beta, 1, 1};
    if (diffuse_vertex(ctx, ray, h, state, branch)) {
      y.Lo = state.L;
      PathState rest{state.ray, beta, 2, state.diffuse_hits};
      rest.from = state.from;  // the light connection's weight at the next vertex
      y.Lo += trace_path(ctx, rest, branch);
    } else {
      y.Lo = state.L;
    }
    out.push_back(y);
  }
  return L;
}

// g = cos_x cos_y / d^2 between technique x and the bounce y (pi cancels
// in the weights), 0 where x does not face y or sees its other side.
float geometry(const FirstHit& x, const Bounce& y) {
  const vec3 v = y.p - x.h.p;
  const float d2 = glm::dot(v, v);
  const float cos_x = glm::dot(x.ns, v);
  const float cos_y = -glm::dot(y.ng, v);
  if (!(d2 > 0.0f && cos_x > 0.0f && cos_y > 0.0f)) return 0.0f;
  return (cos_x / d2) * (cos_y / d2);
}

// Shares bounce y among the techniques: the balance heuristic's weight
// n_j g_j / sum_m n_m g_m over the bounce count of j, i.e. g_j / sum.
// x: the block's pixels' first hits (`pixels` of them).
struct BlockHits {
  const FirstHit* x;
  int pixels;
};
void share(const PathContext& ctx, BlockHits block, const Bounce& y, vec3* L) {
  const FirstHit* x = block.x;
  const int pixels = block.pixels;
  float g[kMaxPixels] = {};
  float sum = 0.0f;
  for (int m = 0; m < pixels; ++m) {
    if (x[m].bounces == 0) continue;  // not a technique: g stays 0
    g[m] = geometry(x[m], y);
    if (g[m] > 0.0f && m != y.owner) {
      ++ctx.stats.rays;
      // y's own sphere cannot block: geometry() checked that x sees its outer side.
      if (ctx.world.occluded(spawn_shadow_ray(x[m].h, y.p), y.sphere)) g[m] = 0.0f;
    }
    sum += float(x[m].bounces) * g[m];
  }
  const int o = y.owner;
  if (!(g[o] > 0.0f && sum < kInf)) {  // a grazing bounce: its own pixel's, as unshared
    L[o] += x[o].beta * y.Lo * (1.0f / float(x[o].bounces));
    return;
  }
  const float inv_sum = 1.0f / sum;
  for (int m = 0; m < pixels; ++m)
    if (g[m] > 0.0f) L[m] += x[m].beta * y.Lo * (g[m] * inv_sum);
}

}  // namespace

void sample_block(const PathContext& ctx, const CameraFrame& cam, const PixelBlock& block,
                  std::uint64_t sample, vec3* out) {
  const RenderSettings& s = ctx.settings;
  const int cols = block.j1 - block.j0, pixels = (block.i1 - block.i0) * cols;
  FirstHit x[kMaxPixels];
  thread_local std::vector<Bounce> bounces;
  bounces.clear();
  {
    Sampler samplers[kMaxPixels];
    vec3 carried(0.0f);
    for (int p = 0; p < pixels; ++p) {
      const Pixel px{block.i0 + p / cols, block.j0 + p % cols};
      samplers[p] = pixel_sampler(s, cam, px, sample);
      CameraHit c = first_hit(ctx, cam, px, samplers[p]);
      x[p] = c.first;
      out[p] = c.L;
      if (!reuses_paths(s)) x[p].bounces = 0;  // nothing leaves the first hit
      for (int ch = 0; ch < 3; ++ch)
        if (x[p].bounces > 0 && x[p].beta[ch] != 0.0f) carried[ch] = 1.0f;
    }
    for (int p = 0; p < pixels; ++p)
      if (x[p].bounces > 0)
        out[p] = send_bounces(ctx, Technique{x[p], p, carried}, samplers[p], bounces, out[p]);
  }
  // The sharing keeps gradual underflow: a bounce's light times a small
  // weight can fall below float's normal range where the pixel's own light
  // does not (a light of intensity 1e-30), and flushed to zero it would
  // bias the pixel.
  for (const Bounce& y : bounces) share(ctx, BlockHits{x, pixels}, y, out);
}

}  // namespace whisker
