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

constexpr int kMaxPixels = kMaxReuseBlock * kMaxReuseBlock;

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

// The camera hit of pixel (i, j): its direct light into L and, when it is a
// technique, `first`; otherwise (no diffuse hit, or nothing to carry) the
// whole sample as sample_pixel traces it.
void first_hit(const World& world, const Scene& scene, const CameraFrame& cam, int i, int j,
               Sampler& sampler, PathStats& stats, FirstHit& first, vec3& L) {
  const RenderSettings& s = scene.settings;
  const Ray ray = camera_ray(world, scene, cam, i, j, sampler);
  Hit hit;
  ++stats.rays;
  if (!world.closest(ray, hit)) return;
  const Material& m = world.material(hit);
  if (m.kind != MaterialKind::Diffuse) {
    L = trace_path(world, s, ray, vec3(1.0f), 0, 0, sampler, stats, &hit);
    return;
  }
  first.beta = m.albedo;
  if (ends_dark(s, first.beta)) return;
  world.record(ray, hit, first.h);
  first.ns = add_direct_light(world, ray, first.h, first.beta, stats, L).ns;
  first.bounces = split_factor(s, 0, first.beta);
}

// Pixel p's bounces: those meeting a diffuse point go to `out` with L_o
// traced in the channels `carried`; the others are finished for p alone.
void send_bounces(const World& world, const RenderSettings& s, const FirstHit& x, int p,
                  Sampler& sampler, const vec3& carried, PathStats& stats,
                  std::vector<Bounce>& out, vec3& L) {
  const Frame frame(x.ns);
  const float inv_n = 1.0f / float(x.bounces);
  for (int b = 0; b < x.bounces; ++b) {
    Sampler branch = sampler.branch(std::uint32_t(b), std::uint32_t(x.bounces));
    const Ray ray = sample_diffuse(x.h, frame, branch);
    Hit hit;
    ++stats.rays;
    if (!world.closest(ray, hit)) continue;
    const Material& m = world.material(hit);
    if (m.kind != MaterialKind::Diffuse) {  // glass or mirror: its light depends on the way in
      L += trace_path(world, s, ray, x.beta, 1, 1, branch, stats, &hit) * inv_n;
      continue;
    }
    const vec3 beta = carried * m.albedo;
    if (ends_dark(s, beta)) continue;
    SurfaceHit h;
    world.record(ray, hit, h);
    Bounce y;
    y.p = h.p;
    y.ng = glm::dot(h.ng, ray.d) < 0.0f ? h.ng : -h.ng;
    y.owner = p;
    y.sphere = h.sphere;
    int diffuse_hits = 1;
    Ray next;
    if (diffuse_vertex(world, s, ray, h, beta, 1, diffuse_hits, branch, stats, y.Lo, next))
      y.Lo += trace_path(world, s, next, beta, 2, diffuse_hits, branch, stats);
    out.push_back(y);
  }
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
void share(const World& world, const FirstHit* x, int pixels, const Bounce& y,
           PathStats& stats, vec3* L) {
  float g[kMaxPixels] = {};
  float sum = 0.0f;
  for (int m = 0; m < pixels; ++m) {
    if (x[m].bounces == 0) continue;  // not a technique: g stays 0
    g[m] = geometry(x[m], y);
    if (g[m] > 0.0f && m != y.owner) {
      ++stats.rays;
      // y's own sphere cannot block: geometry() checked that x sees its outer side.
      if (world.occluded(spawn_shadow_ray(x[m].h, y.p), y.sphere)) g[m] = 0.0f;
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

void sample_block(const World& world, const Scene& scene, const CameraFrame& cam, int i0,
                  int i1, int j0, int j1, std::uint64_t sample, vec3* out, PathStats& stats) {
  const RenderSettings& s = scene.settings;
  const int cols = j1 - j0, pixels = (i1 - i0) * cols;
  FirstHit x[kMaxPixels];
  thread_local std::vector<Bounce> bounces;
  bounces.clear();
  {
    // The paths, with denormals flushed as sample_pixel traces them.
    const FlushDenormals ftz;
    Sampler samplers[kMaxPixels];
    vec3 carried(0.0f);
    for (int p = 0; p < pixels; ++p) {
      const int i = i0 + p / cols, j = j0 + p % cols;
      const std::uint32_t pixel = std::uint32_t(i) * std::uint32_t(scene.camera.width) + std::uint32_t(j);
      samplers[p] = Sampler(s.sampler, pixel, sample, s.seed);
      out[p] = vec3(0.0f);
      first_hit(world, scene, cam, i, j, samplers[p], stats, x[p], out[p]);
      if (!reuses_paths(s)) x[p].bounces = 0;  // nothing leaves the first hit
      for (int c = 0; c < 3; ++c)
        if (x[p].bounces > 0 && x[p].beta[c] != 0.0f) carried[c] = 1.0f;
    }
    for (int p = 0; p < pixels; ++p)
      if (x[p].bounces > 0)
        send_bounces(world, s, x[p], p, samplers[p], carried, stats, bounces, out[p]);
  }
  // The sharing keeps gradual underflow: a bounce's light times a small
  // weight can fall below float's normal range where the pixel's own light
  // does not (a light of intensity 1e-30), and flushed to zero it would
  // bias the pixel.
  for (const Bounce& y : bounces) share(world, x, pixels, y, stats, out);
}

}  // namespace whisker
