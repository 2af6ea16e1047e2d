// Google Benchmark micro-benchmark: single-ray closest hit on the cat with
// each accelerator, on the diffuse (incoherent) ray set (ray_bench.h).
#include <benchmark/benchmark.h>

#include <random>

#include <glm/geometric.hpp>

#include "geometry/bvh.h"
#include "geometry/object_bvh.h"
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

}  // namespace

BENCHMARK_MAIN();
