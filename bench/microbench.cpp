// Google Benchmark micro-benchmark: single-ray closest hit on the cat with
// each accelerator, on the diffuse (incoherent) ray file.
#include <benchmark/benchmark.h>

#include "geometry/bvh.h"
#include "ray_bench.h"

namespace {

using namespace whisker;

const std::vector<Ray>& rays() {
  static const std::vector<Ray> r = bench::read_rays(WHISKER_SHARED_DIR "/bench/rays/cat_diffuse.rays");
  return r;
}

void trace(benchmark::State& state, AccelKind kind) {
  const Bvh bvh = Bvh::build(bench::load_cat(WHISKER_SHARED_DIR "/assets/cat.obj"), kind);
  const std::vector<Ray>& rs = rays();
  std::size_t i = 0;
  for (auto _ : state) {
    Hit h;
    benchmark::DoNotOptimize(bvh.intersect(rs[i], h));
    if (++i == rs.size()) i = 0;
  }
  state.SetItemsProcessed(state.iterations());
}

BENCHMARK_CAPTURE(trace, sah, AccelKind::Sah);
BENCHMARK_CAPTURE(trace, midpoint, AccelKind::Midpoint);

}  // namespace

BENCHMARK_MAIN();
