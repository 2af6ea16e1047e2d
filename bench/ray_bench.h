// Ray-file benchmark helpers: reading and writing ray files, making the two
// ray sets of the cat, loading the cat, and timing a closest-hit tracer over
// the rays on one or several threads.
//
// A ray file is binary, little-endian, no header: records of 7 float32,
// ox oy oz dx dy dz tmax (28 bytes; tmin is 0; tmax may be +inf; unit
// directions), traced against the cat mesh alone (scaled by 0.6, then moved
// by (0, -10, 0)) in world space. The two sets (make_primary_rays,
// make_diffuse_rays) are those of the course's ray files of the same names:
//   cat_primary.rays  the report's camera, one ray through each pixel
//                     centre of 512 x 512 (coherent);
//   cat_diffuse.rays  8 cosine-distributed bounce rays from each camera-ray
//                     hit on the cat, origins moved 1e-3 off the surface
//                     (incoherent; the directions depend on the seed).
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <ctime>
#include <cstddef>
#include <cstdint>
#include <string>
#include <thread>
#include <vector>

#include "geometry/ray.h"
#include "geometry/triangle.h"

namespace whisker::bench {

// Records of 7 little-endian float32: ox oy oz dx dy dz tmax; tmin is 0.
std::vector<Ray> read_rays(const std::string& path);

// Writes rays in that format (a temporary file renamed into place).
void write_rays(const std::string& path, const std::vector<Ray>& rays);

// The cat as the ray files expect it: scaled by 0.6, then moved by (0,-10,0).
std::vector<Triangle> load_cat(const std::string& path);

// The report's camera at (0, 0, 55), 60 degrees across 512 pixels, one ray
// through each pixel centre (CameraFrame::centre_direction), rows from the top.
std::vector<Ray> make_primary_rays();
// Per primary ray that hits `tris`, 8 directions cosine-distributed about the
// hit triangle's normal on the ray's side, from the hit moved 1e-3 along it.
std::vector<Ray> make_diffuse_rays(const std::vector<Triangle>& tris,
                                   const std::vector<Ray>& primary, std::uint64_t seed);

struct TraceResult {
  std::size_t hits = 0;
  double distance_sum = 0.0;  // sum of hit distances: the checksum
};

struct Timing {
  TraceResult result;
  double seconds = 0.0;  // median over the repetitions
  double mrays_per_s(std::size_t rays) const { return rays / seconds * 1e-6; }
};

inline double thread_cpu_seconds() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

// Runs `trace(ray, t) -> bool` over all rays `reps` times on `threads`
// threads (work taken in chunks from an atomic counter); the median wall
// time, or with use_min the fastest run, measured on one thread as that
// thread's CPU time (for tuning while other processes share the cores).
template <class Trace>
Timing time_trace(const std::vector<Ray>& rays, int threads, int reps, const Trace& trace,
                  bool use_min = false) {
  constexpr std::size_t kChunk = 1024;
  std::vector<double> times;
  Timing out;
  for (int rep = 0; rep < reps; ++rep) {
    std::atomic<std::size_t> next{0};
    std::vector<TraceResult> part(static_cast<std::size_t>(threads));
    auto work = [&](int id) {
      TraceResult r;
      for (;;) {
        const std::size_t b = next.fetch_add(kChunk, std::memory_order_relaxed);
        if (b >= rays.size()) break;
        const std::size_t e = std::min(rays.size(), b + kChunk);
        for (std::size_t i = b; i < e; ++i) {
          float t;
          if (trace(rays[i], t)) {
            ++r.hits;
            r.distance_sum += t;
          }
        }
      }
      part[static_cast<std::size_t>(id)] = r;
    };
    const auto start = std::chrono::steady_clock::now();
    if (threads == 1) {
      const double cpu0 = thread_cpu_seconds();
      work(0);
      if (use_min) {  // tuning on a shared machine: this thread's CPU time
        times.push_back(thread_cpu_seconds() - cpu0);
        out.result = part[0];
        continue;
      }
    } else {
      std::vector<std::thread> pool;
      for (int i = 0; i < threads; ++i) pool.emplace_back(work, i);
      for (std::thread& th : pool) th.join();
    }
    times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    TraceResult total;
    for (const TraceResult& p : part) {
      total.hits += p.hits;
      total.distance_sum += p.distance_sum;
    }
    out.result = total;
  }
  std::sort(times.begin(), times.end());
  out.seconds = use_min ? times.front() : times[times.size() / 2];
  return out;
}

}  // namespace whisker::bench
