// Ray-file benchmark helpers: reading ../shared/bench/rays/*.rays (FORMAT.md
// there), loading the cat, and timing a closest-hit tracer over the rays on
// one or several threads.
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <ctime>
#include <cstddef>
#include <string>
#include <thread>
#include <vector>

#include "geometry/ray.h"
#include "geometry/triangle.h"

namespace whisker::bench {

// Records of 7 little-endian float32: ox oy oz dx dy dz tmax; tmin is 0.
std::vector<Ray> read_rays(const std::string& path);

// The cat as the ray files expect it: scaled by 0.6, then moved by (0,-10,0).
std::vector<Triangle> load_cat(const std::string& path);

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
