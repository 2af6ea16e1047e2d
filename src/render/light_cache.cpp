#include "render/light_cache.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "render/direct_light.h"
#include "render/light_connect.h"
#include "render/sampling.h"
#include "render/sampler.h"

namespace whisker {

void LightCache::build(const World& world, const RenderSettings& settings, std::uint64_t sample,
                       std::uint64_t& rays) {
  entries_.clear();
  for (auto& l : lists_) l.clear();
  entries_.reserve(kPaths / 2);
  const World::Light& light = world.light();
  // The light's own numbers, apart from every pixel's (Rng's pixel argument
  // is the stratum; the seed is changed so no pixel stream is repeated).
  const std::uint64_t seed = settings.seed ^ 0x6c1b3f5e2d4a9087ull;
  for (int m = 0; m < kPaths; ++m) {
    Rng rng(std::uint32_t(m), sample, seed);
    const float u1 = (float(m % kSide) + rng.uniform()) * (1.0f / kSide);
    const float u2 = (float(m / kSide) + rng.uniform()) * (1.0f / kSide);
    Ray ray;
    ray.o = light.position;
    ray.d = uniform_sphere(std::min(u1, 0x1.fffffep-1f), std::min(u2, 0x1.fffffep-1f));
    ray.tmin = light_path_start(light);
    ++rays;
    Hit hit;
    if (!world.closest(ray, hit)) continue;
    const Material& mat = world.material(hit);
    if (mat.kind != MaterialKind::Diffuse || channel_bits(mat.albedo) == 0) continue;
    SurfaceHit y;
    world.record(ray, hit, y);
    const vec3 to_light = light.position - y.p;
    const float d2 = glm::dot(to_light, to_light);
    const float inv_d = 1.0f / std::sqrt(d2);
    CachedLightVertex e;
    const bool flip = !(glm::dot(y.ng, to_light) > 0.0f);
    e.p = y.p;
    e.err = y.err;
    e.ng = flip ? -y.ng : y.ng;
    e.sphere = y.sphere;
    e.flags = (glm::dot(y.outward, e.ng) < 0.0f ? 1u : 0u) | (flip ? 2u : 0u);
    const vec3 ns = glm::dot(y.ns, e.ng) >= 0.0f ? y.ns : -y.ns;
    const float cos_l = glm::dot(e.ng, to_light) * inv_d;
    const float cos_s = glm::dot(ns, to_light) * inv_d;
    if (!(cos_l > 0.0f && cos_s > 0.0f)) continue;
    e.albedo = mat.albedo;
    e.weight = light_weight(light.intensity, cos_s, to_light, inv_d);
    e.B = cos_l / (4.0f * d2);
    if (!(e.weight > 0.0f && e.B > 0.0f && e.B < kInf)) continue;
    const unsigned bits = channel_bits(e.albedo);
    for (unsigned c = 1; c < 8; ++c)
      if (c & bits) lists_[c].push_back(std::uint32_t(entries_.size()));
    entries_.push_back(e);
  }
  // Each list grouped by sphere (a stable counting sort), and the runs of
  // the spheres: those numbered below kRunSpheres, so that a scene of
  // many spheres costs at most that many runs a list. Triangles, and the
  // spheres past them (picks never leave those out), sort last.
  std::uint32_t spheres = 0;
  for (const CachedLightVertex& e : entries_)
    if (e.sphere < kRunSpheres) spheres = std::max(spheres, e.sphere + 1);
  std::vector<std::uint32_t> sorted, next;
  for (unsigned c = 0; c < 8; ++c) {
    std::vector<std::uint32_t>& list = lists_[c];
    std::vector<Run>& runs = runs_[c];
    runs.clear();
    scale_[c] = list.empty() ? 0.0f : float(kPaths) / float(list.size());
    if (list.empty()) continue;  // no run: density_scale is scale_[c], 0
    runs.assign(spheres, Run{});
    for (std::uint32_t k : list)
      if (entries_[k].sphere < spheres) ++runs[entries_[k].sphere].count;
    std::uint32_t start = 0;
    for (Run& r : runs) {
      r.start = start;
      start += r.count;
      const std::size_t left = list.size() - r.count;
      r.scale = left == 0 ? 0.0f : float(kPaths) / float(left);
    }
    sorted.assign(list.size(), 0);
    std::uint32_t rest = start;
    next.resize(spheres);
    for (std::uint32_t s = 0; s < spheres; ++s) next[s] = runs[s].start;
    for (std::uint32_t k : list) {
      const std::uint32_t sphere = entries_[k].sphere;
      sorted[sphere < spheres ? next[sphere]++ : rest++] = k;
    }
    list.swap(sorted);
  }
}

}  // namespace whisker
