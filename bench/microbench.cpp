// Google Benchmark micro-benchmarks: single-ray closest hit on the cat with
// each accelerator, on the diffuse (incoherent) ray set (ray_bench.h), and
// the denoiser on a 512 x 512 frame.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include <glm/geometric.hpp>

#include "geometry/bvh.h"
#include "geometry/object_bvh.h"
#include "render/denoise.h"
#include "ray_bench.h"

namespace {

using namespace whisker;

const std::vector<Ray>& rays() {
  static const std::vector<Ray> r = bench::make_diffuse_rays(
      bench::load_cat(WHISKER_ASSETS_DIR "/cat.obj"), bench::make_primary_rays(), 1);
  return r;
}

void trace(benchmark::State& state, BvhMethod kind) {
  const Bvh bvh = Bvh::build(bench::load_cat(WHISKER_ASSETS_DIR "/cat.obj"), kind);
  const std::vector<Ray>& rs = rays();
  std::size_t i = 0;
  for (auto _ : state) {
    Hit h;
    benchmark::DoNotOptimize(bvh.intersect(rs[i], h));
    if (++i == rs.size()) i = 0;
  }
  state.SetItemsProcessed(state.iterations());
}

BENCHMARK_CAPTURE(trace, sah, BvhMethod::Sah);
BENCHMARK_CAPTURE(trace, midpoint, BvhMethod::Midpoint);

// Closest hit among N random spheres (radius 0.5-2 in a 200-unit cube), rays
// from random points in random directions: the object-level BVH against one
// flat 8-wide list, to show how each grows with N.
struct SphereField {
  std::vector<Sphere> spheres;
  std::vector<Ray> rays;
  explicit SphereField(int n) {
    std::mt19937 g(3);
    std::uniform_real_distribution<float> pos(-100.0f, 100.0f), rad(0.5f, 2.0f);
    std::normal_distribution<float> dir;
    for (int k = 0; k < n; ++k) spheres.push_back({vec3(pos(g), pos(g), pos(g)), rad(g)});
    for (int k = 0; k < 4096; ++k)
      rays.push_back(Ray{vec3(pos(g), pos(g), pos(g)), glm::normalize(vec3(dir(g), dir(g), dir(g)))});
  }
};

void spheres_object_bvh(benchmark::State& state) {
  const SphereField f(static_cast<int>(state.range(0)));
  const ObjectBvh bvh(f.spheres, Box3{});
  std::size_t i = 0;
  for (auto _ : state) {
    Hit h;
    benchmark::DoNotOptimize(bvh.intersect(f.rays[i], h, nullptr));
    if (++i == f.rays.size()) i = 0;
  }
  state.SetItemsProcessed(state.iterations());
}

void spheres_flat_list(benchmark::State& state) {
  const SphereField f(static_cast<int>(state.range(0)));
  const SphereSet set(f.spheres);
  std::size_t i = 0;
  for (auto _ : state) {
    float t;
    std::uint32_t id;
    benchmark::DoNotOptimize(set.intersect(f.rays[i], kInf, t, id));
    if (++i == f.rays.size()) i = 0;
  }
  state.SetItemsProcessed(state.iterations());
}

BENCHMARK(spheres_object_bvh)->RangeMultiplier(10)->Range(10, 100000);
BENCHMARK(spheres_flat_list)->RangeMultiplier(10)->Range(10, 100000);

// The denoiser on a 512 x 512 frame (render/denoise.h) on 2 threads: two
// noisy half images of a gradient with an albedo step, flat features.
void denoise_512(benchmark::State& state, DenoiseFilter filter) {
  constexpr int kSize = 512;
  const std::size_t values = std::size_t(kSize) * kSize * 3;
  std::vector<float> a(values), b(values), albedo(values), normal(values, 0.0f), depth(values / 3, 40.0f);
  std::mt19937 rng(7);
  std::normal_distribution<float> noise(0.0f, 0.3f);
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x)
      for (int c = 0; c < 3; ++c) {
        const std::size_t k = (std::size_t(y) * kSize + std::size_t(x)) * 3 + std::size_t(c);
        albedo[k] = x < kSize / 2 ? 0.8f : 0.3f;
        const float truth = albedo[k] * (0.2f + float(y) / kSize);
        a[k] = truth * (1.0f + noise(rng));
        b[k] = truth * (1.0f + noise(rng));
        if (c == 2) normal[k] = 1.0f;
      }
  const DenoiseInput in{kSize, kSize, a, b, albedo, albedo, normal, normal, depth, depth};
  const DenoiseOptions options{filter, 2};
  for (auto _ : state) benchmark::DoNotOptimize(denoise(in, options).rgb.data());
}

BENCHMARK_CAPTURE(denoise_512, fast, DenoiseFilter::Fast)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(denoise_512, quality, DenoiseFilter::Quality)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
