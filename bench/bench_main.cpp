// whisker-bench rays FILE [--accel brute|bbox|midpoint|sah] [--threads T] [--json]
//
// Traces a ray file (ray_bench.h) against the cat alone and prints rays,
// hits, the sum of hit distances and Mrays/s on one thread and on all
// threads (median of --reps runs), with Embree 3's rtcIntersect1 on the
// same rays in the same run when it is built in. Also the build time and
// bytes per triangle.
//
// whisker-bench make-rays DIR [--seed S]
//
// Writes the cat's two ray sets, DIR/cat_primary.rays and
// DIR/cat_diffuse.rays (ray_bench.h), and prints their counts.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <iostream>
#include <string>
#include <thread>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "geometry/bvh.h"
#include "scene/mesh_io.h"
#include "scene/world.h"
#include "ray_bench.h"
#ifdef WHISKER_HAVE_EMBREE
#include "embree_tracer.h"
#endif

namespace {

using namespace whisker;


struct Options {
  std::string file;
  std::string mesh = WHISKER_ASSETS_DIR "/cat.obj";
  std::string accel = "sah";
  int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  int reps = 5;
  std::size_t limit = 0;
  bool json = false;
  bool no_embree = false;
  bool use_min = false;
  int subdivide = 0;
};

// Splits every triangle into four at its edge midpoints, `levels` times: the
// surface stays the same (so do the ray files' hits), the count grows 4x per
// level, 3954 -> 1.01M triangles at 4 levels. For the scaling figures.
std::vector<Triangle> subdivide(std::vector<Triangle> tris, int levels) {
  for (int l = 0; l < levels; ++l) {
    std::vector<Triangle> out;
    out.reserve(tris.size() * 4);
    for (const Triangle& t : tris) {
      const vec3 a = 0.5f * (t.v0 + t.v1), b = 0.5f * (t.v1 + t.v2), c = 0.5f * (t.v2 + t.v0);
      out.push_back({t.v0, a, c});
      out.push_back({a, t.v1, b});
      out.push_back({c, b, t.v2});
      out.push_back({a, b, c});
    }
    tris = std::move(out);
  }
  return tris;
}

int run_rays(const Options& opt) {
  std::vector<Ray> rays = bench::read_rays(opt.file);
  if (opt.limit > 0 && opt.limit < rays.size()) rays.resize(opt.limit);
  const std::vector<Triangle> tris = subdivide(bench::load_cat(opt.mesh), opt.subdivide);
  BvhMethod kind = BvhMethod::Sah;
  parse(opt.accel, kind);  // CLI11 has checked the name
  const Bvh bvh = Bvh::build(tris, kind);
  auto trace = [&](const Ray& r, float& t) {
    Hit h;
    if (!bvh.intersect(r, h)) return false;
    t = h.t;
    return true;
  };
#ifdef WHISKER_HAVE_EMBREE
  double embree_build = 0.0;
  bench::EmbreeScene* es = opt.no_embree ? nullptr : bench::embree_build(tris, embree_build);
#endif
  // One thread: Whisker and Embree repetitions alternate, so a change in
  // the machine's load hits both alike; then the median (or fastest) each.
  std::vector<double> wt, et;
  bench::Timing one, emb;
  for (int rep = 0; rep < opt.reps; ++rep) {
    one = bench::time_trace(rays, 1, 1, trace, opt.use_min);
    wt.push_back(one.seconds);
#ifdef WHISKER_HAVE_EMBREE
    if (es) {
      emb = bench::time_trace(rays, 1, 1, [&](const Ray& r, float& t) {
        return bench::embree_intersect(es, r, t);
      }, opt.use_min);
      et.push_back(emb.seconds);
    }
#endif
  }
  auto pick = [&](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return opt.use_min ? v.front() : v[v.size() / 2];
  };
  one.seconds = pick(wt);
  const bench::Timing all = bench::time_trace(rays, opt.threads, opt.reps, trace, opt.use_min);

  nlohmann::json j;
  j["rays"] = rays.size();
  j["hits"] = one.result.hits;
  j["distance_sum"] = one.result.distance_sum;
  j["mrays_per_s_1thread"] = one.mrays_per_s(rays.size());
  j["mrays_per_s_all"] = all.mrays_per_s(rays.size());
  j["threads"] = opt.threads;
  j["accel"] = opt.accel;
  j["triangles"] = bvh.triangle_count();
  j["nodes"] = bvh.node_count();
  j["build_ms"] = bvh.build_seconds() * 1e3;
  j["bytes_per_triangle"] = double(bvh.bytes()) / double(std::max<std::size_t>(1, tris.size()));
#ifdef WHISKER_HAVE_EMBREE
  if (es) {
    bench::embree_release(es);
    emb.seconds = pick(et);
    j["embree_mrays_per_s_1thread"] = emb.mrays_per_s(rays.size());
    j["embree_hits"] = emb.result.hits;
    j["embree_distance_sum"] = emb.result.distance_sum;
    j["embree_build_ms"] = embree_build * 1e3;
    j["ratio"] = j["mrays_per_s_1thread"].get<double>() / emb.mrays_per_s(rays.size());
  }
#endif
  if (opt.json) {
    std::cout << j.dump() << "\n";
    return 0;
  }
  std::printf("file          %s\n", opt.file.c_str());
  std::printf("accel         %s: %zu triangles, %zu nodes, built in %.2f ms, %.1f bytes/triangle\n",
              opt.accel.c_str(), bvh.triangle_count(), bvh.node_count(), bvh.build_seconds() * 1e3,
              j["bytes_per_triangle"].get<double>());
  std::printf("rays          %zu\n", rays.size());
  std::printf("hits          %zu\n", one.result.hits);
  std::printf("distance sum  %.6f\n", one.result.distance_sum);
  std::printf("Mrays/s       %.3f on 1 thread, %.3f on %d threads (%s of %d)\n",
              one.mrays_per_s(rays.size()), all.mrays_per_s(rays.size()), opt.threads, opt.use_min ? "fastest" : "median", opt.reps);
  if (j.contains("embree_mrays_per_s_1thread")) {
    std::printf("embree        %.3f Mrays/s on 1 thread, %zu hits, distance sum %.6f, built in %.2f ms\n",
                j["embree_mrays_per_s_1thread"].get<double>(), j["embree_hits"].get<std::size_t>(),
                j["embree_distance_sum"].get<double>(), j["embree_build_ms"].get<double>());
    std::printf("ratio         %.3f (whisker / embree, 1 thread)\n", j["ratio"].get<double>());
  }
  return 0;
}

int make_rays(const Options& opt, const std::string& dir, std::uint64_t seed) {
  const std::vector<Ray> primary = bench::make_primary_rays();
  const std::vector<Ray> diffuse = bench::make_diffuse_rays(bench::load_cat(opt.mesh), primary, seed);
  bench::write_rays(dir + "/cat_primary.rays", primary);
  bench::write_rays(dir + "/cat_diffuse.rays", diffuse);
  std::printf("%s/cat_primary.rays: %zu rays\n%s/cat_diffuse.rays: %zu rays\n", dir.c_str(),
              primary.size(), dir.c_str(), diffuse.size());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Whisker benchmarks"};
  app.require_subcommand(1);
  Options opt;
  CLI::App* rays = app.add_subcommand("rays", "trace a ray file against the cat");
  rays->add_option("FILE", opt.file, "ray file (bench/ray_bench.h; make-rays writes the cat's two)")->required();
  rays->add_option("--accel", opt.accel, "brute|bbox|midpoint|sah")
      ->check(CLI::IsMember({"brute", "bbox", "midpoint", "sah"}));
  rays->add_option("--threads", opt.threads, "threads for the all-threads figure")
      ->check(CLI::PositiveNumber);
  rays->add_option("--mesh", opt.mesh, "OBJ mesh (scaled 0.6, moved by (0,-10,0))");
  rays->add_option("--reps", opt.reps, "repetitions; the median is reported")
      ->check(CLI::PositiveNumber);
  rays->add_option("--limit", opt.limit, "trace only the first N rays (for brute force)");
  rays->add_flag("--json", opt.json, "one JSON object on stdout");
  rays->add_option("--subdivide", opt.subdivide, "split each triangle in 4, this many times")
      ->check(CLI::Range(0, 5));
  rays->add_flag("--no-embree", opt.no_embree, "skip the Embree comparison");
  rays->add_flag("--min", opt.use_min, "fastest repetition (1 thread: its CPU time) instead of the median");
  std::string dir;
  std::uint64_t seed = 1;
  CLI::App* make = app.add_subcommand("make-rays", "write the cat's primary and diffuse ray sets");
  make->add_option("DIR", dir, "an existing folder for cat_primary.rays and cat_diffuse.rays")
      ->required()->check(CLI::ExistingDirectory);
  make->add_option("--mesh", opt.mesh, "OBJ mesh (scaled 0.6, moved by (0,-10,0))");
  make->add_option("--seed", seed, "the diffuse directions' seed");
  CLI11_PARSE(app, argc, argv);
  try {
    if (make->parsed()) return make_rays(opt, dir, seed);
    return run_rays(opt);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "whisker-bench: %s\n", e.what());
    return 1;
  }
}
