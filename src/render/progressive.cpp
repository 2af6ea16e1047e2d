#include "render/progressive.h"

#include <algorithm>
#include <barrier>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <new>
#include <stdexcept>
#include <string>
#include <system_error>

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include "scene/world.h"
#include "render/camera.h"
#include "render/integrator.h"
#include "render/path_reuse.h"
#include "render/sampler.h"

namespace whisker {

namespace {
constexpr int kTile = 32;
constexpr int kPreviewBlock = 4;  // the preview renders one sample per 4x4 block
using Clock = std::chrono::steady_clock;
}  // namespace

// The state of the generation being rendered; touched by workers during a
// pass and by thread 0 between passes only.
struct ProgressiveRenderer::Job {
  explicit Job(int threads) : sync(threads) {}

  std::barrier<> sync;
  bool keep_going = true;

  Scene scene;
  World world;
  std::unique_ptr<CameraFrame> cam;
  std::uint64_t generation = 0;  // 0: nothing adopted yet
  int width = 0, height = 0, tiles_x = 0, tiles_y = 0;
  Film film;
  bool preview_pass = false;
  std::uint64_t spp_done = 0, passes = 0, nan_count = 0, rays = 0;
  std::uint64_t first_sample = 0;  // sample index of the generation's first sample
  double seconds = 0.0;

  // this pass
  std::uint64_t sample_base = 0;
  int pass_spp = 0;
  Clock::time_point pass_start;
  std::atomic<int> next_tile{0};
  std::atomic<std::uint64_t> pass_nans{0}, pass_rays{0};
  std::atomic<bool> aborted{false};
};

ProgressiveRenderer::ProgressiveRenderer(int threads) {
  threads_ = threads > 0 ? threads : int(std::max(1u, std::thread::hardware_concurrency()));
}

ProgressiveRenderer::~ProgressiveRenderer() { stop(); }

std::uint64_t ProgressiveRenderer::set_scene(const Scene& scene) {
  return set_scene(scene, RenderStart{});
}

std::uint64_t ProgressiveRenderer::set_scene(const Scene& scene, RenderStart start) {
  std::lock_guard lock(pending_mutex_);
  pending_scene_ = scene;
  pending_start_ = std::move(start);
  ++pending_generation_;
  pending_cv_.notify_all();
  return pending_generation_;
}

std::uint64_t ProgressiveRenderer::set_settings(const RenderSettings& settings) {
  std::lock_guard lock(pending_mutex_);
  pending_scene_.settings = settings;
  ++pending_generation_;
  pending_cv_.notify_all();
  return pending_generation_;
}

void ProgressiveRenderer::set_target_spp(int target_spp) {
  const int target = std::max(0, target_spp);
  std::uint64_t gen = 0;
  {
    std::lock_guard lock(pending_mutex_);
    pending_scene_.settings.target_spp = target;
    gen = pending_generation_;
    pending_cv_.notify_all();
  }
  // The published image is no longer "done" if the target went up.
  std::lock_guard lock(publish_mutex_);
  if (published_.generation == gen && !published_.preview)
    published_.done = target > 0 && published_.spp >= std::uint64_t(target);
}

ProgressiveRenderer::PassProgress ProgressiveRenderer::pass_progress() const {
  PassProgress p;
  p.generation = progress_generation_.load();
  p.tiles_done = progress_tiles_done_.load();
  p.tiles_total = progress_tiles_total_.load();
  p.pass_spp = progress_spp_.load();
  p.rendering = progress_running_.load();
  const std::int64_t now = std::chrono::duration_cast<std::chrono::nanoseconds>(
                               Clock::now().time_since_epoch()).count();
  p.pass_seconds = p.rendering ? double(now - progress_start_ns_.load()) * 1e-9 : 0.0;
  return p;
}

Scene ProgressiveRenderer::current_scene() const {
  std::lock_guard lock(pending_mutex_);
  return pending_scene_;
}

void ProgressiveRenderer::start() {
  if (!pool_.empty()) return;
  {
    std::lock_guard lock(pending_mutex_);
    quit_ = false;
  }
  job_ = std::make_unique<Job>(threads_);
  running_ = true;
  pool_.reserve(std::size_t(threads_));
  for (int i = 0; i < threads_; ++i) {
    try {
      pool_.emplace_back([this, i] { worker_main(i); });
    } catch (const std::system_error& e) {
      // EAGAIN under ulimit -u, or a stack past ulimit -v (pthread_create(3)).
      // The threads not created leave the barrier (arrive_and_drop,
      // [thread.barrier.class]), else the others wait there for ever.
      const std::string why = e.code().message();
      if (i == 0) {
        job_.reset();
        running_ = false;
        throw std::runtime_error("cannot create a render thread: " + why + " (limit of processes, ulimit -u, or of memory, ulimit -v)");
      }
      for (int k = i; k < threads_; ++k) job_->sync.arrive_and_drop();
      std::fprintf(stderr, "whisker: warning: created %d of %d render threads (%s); rendering with %d\n",
                   i, threads_, why.c_str(), i);
      threads_ = i;
      break;
    }
  }
}

void ProgressiveRenderer::stop() {
  if (pool_.empty()) return;
  {
    std::lock_guard lock(pending_mutex_);
    quit_ = true;
    pending_cv_.notify_all();
  }
  for (auto& t : pool_) t.join();
  pool_.clear();
  job_.reset();
  // Wake waiters: the renderer is stopped.
  std::lock_guard lock(publish_mutex_);
  running_ = false;
  publish_cv_.notify_all();
}

void ProgressiveRenderer::set_paused(bool paused) {
  std::lock_guard lock(pending_mutex_);
  paused_ = paused;
  pending_cv_.notify_all();
}

void ProgressiveRenderer::set_threads(int threads) {
  const int n = threads > 0 ? threads : int(std::max(1u, std::thread::hardware_concurrency()));
  if (n == threads_) return;
  const bool running = !pool_.empty();
  stop();
  threads_ = n;
  if (running) {
    // A fresh job adopts the pending scene again, from scratch.
    std::lock_guard lock(pending_mutex_);
    ++pending_generation_;
  }
  if (running) start();
}

bool ProgressiveRenderer::snapshot(Snapshot& out) const {
  std::lock_guard lock(publish_mutex_);
  if (published_.version == out.version) return false;
  out = published_;
  return true;
}

bool ProgressiveRenderer::wait_for(std::uint64_t gen, std::uint64_t spp) {
  std::unique_lock lock(publish_mutex_);
  publish_cv_.wait(lock, [&] {
    if (!running_) return true;
    return published_.generation > gen ||
           (published_.generation == gen && !published_.preview &&
            (published_.spp >= spp || published_.done));
  });
  return published_.generation == gen && !published_.preview &&
         (published_.spp >= spp || published_.done);
}

void ProgressiveRenderer::worker_main(int index) {
  if (low_priority_) {
    // On Linux a thread id names one thread for setpriority.
    const auto tid = static_cast<id_t>(::syscall(SYS_gettid));
    ::setpriority(PRIO_PROCESS, tid, ::getpriority(PRIO_PROCESS, tid) + 5);
  }
  Job& job = *job_;
  // Out of memory in a worker (the BVH, the film, a snapshot) ended the
  // process in std::terminate: it stops the render instead, for failure().
  const auto out_of_memory = [&](const char* doing) {
    {
      std::lock_guard lock(pending_mutex_);
      if (failure_.empty()) failure_ = std::string("out of memory while ") + doing;
      quit_ = true;
    }
    job.aborted = true;
  };
  for (;;) {
    if (index == 0) {
      try {
        job.keep_going = begin_pass();
      } catch (const std::bad_alloc&) {
        out_of_memory("preparing the scene (its BVH and image buffers)");
        job.keep_going = false;
      }
    }
    job.sync.arrive_and_wait();
    if (!job.keep_going) return;
    try {
      run_tiles();
    } catch (const std::bad_alloc&) {
      out_of_memory("rendering");
    }
    job.sync.arrive_and_wait();
    if (index == 0) {
      try {
        end_pass();
      } catch (const std::bad_alloc&) {
        out_of_memory("publishing a pass");
      }
    }
  }
}

std::string ProgressiveRenderer::failure() const {
  std::lock_guard lock(pending_mutex_);
  return failure_;
}

bool ProgressiveRenderer::begin_pass() {
  Job& job = *job_;
  std::unique_lock lock(pending_mutex_);
  progress_running_ = false;
  for (;;) {
    if (quit_) return false;
    const bool fresh = pending_generation_ != job.generation;
    // A raised target (set_target_spp) carries on with the same generation.
    if (!fresh) job.scene.settings.target_spp = pending_scene_.settings.target_spp;
    const int target = fresh ? pending_scene_.settings.target_spp : job.scene.settings.target_spp;
    const bool done = !fresh && target > 0 && job.spp_done >= std::uint64_t(target);
    if (!paused_ && pending_generation_ != 0 && (fresh || !done)) break;
    pending_cv_.wait(lock);
  }
  if (pending_generation_ != job.generation) {
    // Adopt the new generation: everything accumulated so far is thrown away.
    job.scene = pending_scene_;
    job.generation = pending_generation_;
    const RenderStart start = pending_start_;
    lock.unlock();
    // Spheres and materials are rebuilt (cheap); the BVH is reused when the
    // meshes and the accel kind are the same.
    job.world = World(job.scene, &job.world);
    job.cam = std::make_unique<CameraFrame>(job.scene.camera);
    job.width = job.scene.camera.width;
    job.height = job.scene.camera.height;
    job.tiles_x = (job.width + kTile - 1) / kTile;
    job.tiles_y = (job.height + kTile - 1) / kTile;
    job.spp_done = job.passes = job.nan_count = job.rays = 0;
    job.seconds = 0.0;
    job.preview_pass = preview_enabled_;
    job.film.reset(job.width, job.height, job.preview_pass);
    adopt_start(start);
  } else {
    lock.unlock();
  }
  const RenderSettings& s = job.scene.settings;
  int spp = job.preview_pass ? 1 : std::max(1, s.spp);
  if (s.target_spp > 0)
    spp = int(std::min<std::uint64_t>(spp, std::uint64_t(s.target_spp) - job.spp_done));
  job.pass_spp = spp;
  job.sample_base = job.first_sample + job.spp_done;
  job.next_tile = 0;
  job.pass_nans = 0;
  job.pass_rays = 0;
  job.aborted = false;
  job.pass_start = Clock::now();
  progress_generation_ = job.generation;
  progress_tiles_done_ = 0;
  progress_tiles_total_ = job.tiles_x * job.tiles_y;
  progress_spp_ = job.preview_pass ? 0 : spp;
  progress_start_ns_ = std::chrono::duration_cast<std::chrono::nanoseconds>(
                           job.pass_start.time_since_epoch()).count();
  progress_running_ = true;
  return true;
}

void ProgressiveRenderer::adopt_start(const RenderStart& start) {
  Job& job = *job_;
  job.first_sample = start.first_sample;
  if (!start.resume) return;
  // The resumed part's sums, counters and samples, as if its passes had
  // just run here: the next pass adds onto them exactly as it would have.
  const Accumulation& a = *start.resume;
  job.film.load(a.sum, a.sum_sq);
  job.spp_done = a.samples();
  job.passes = a.passes;
  job.nan_count = a.nan_count;
  job.rays = a.rays;
  job.seconds = a.seconds;
}

bool ProgressiveRenderer::abandoning() const {
  return quit_.load(std::memory_order_relaxed) ||
         pending_generation_.load(std::memory_order_relaxed) != job_->generation;
}

void ProgressiveRenderer::run_tiles() {
  Job& job = *job_;
  const int tiles = job.tiles_x * job.tiles_y;
  const Scene& scene = job.scene;
  const std::uint64_t seed = scene.settings.seed;
  for (;;) {
    const int tile = job.next_tile.fetch_add(1, std::memory_order_relaxed);
    if (tile >= tiles) break;
    // An edit or a stop abandons the pass; its partial sums are discarded.
    if (abandoning()) job.aborted = true;
    if (job.aborted) break;
    const int ty = tile / job.tiles_x, tx = tile % job.tiles_x;
    const int i0 = ty * kTile, j0 = tx * kTile;
    const int i1 = std::min(job.height, i0 + kTile), j1 = std::min(job.width, j0 + kTile);
    PathStats stats;
    std::uint64_t nans = 0;
    if (job.preview_pass) {
      // One sample at each block's first pixel, copied over the block. Its
      // sample index lies far beyond any real one, so no sample repeats.
      for (int i = i0; i < i1; i += kPreviewBlock) {
        for (int j = j0; j < j1; j += kPreviewBlock) {
          const std::uint32_t pixel = std::uint32_t(i) * std::uint32_t(job.width) + std::uint32_t(j);
          Sampler sampler(scene.settings.sampler, pixel, ~std::uint64_t(0), seed);
          const vec3 c = sample_pixel(job.world, scene, *job.cam, i, j, sampler, stats);
          job.film.fill_preview(j, i, std::min(j1, j + kPreviewBlock),
                                std::min(i1, i + kPreviewBlock), c);
        }
      }
      job.pass_rays.fetch_add(stats.rays, std::memory_order_relaxed);
      continue;
    }
    nans = run_blocks(i0, i1, j0, j1, stats);
    job.pass_rays.fetch_add(stats.rays, std::memory_order_relaxed);
    job.pass_nans.fetch_add(nans, std::memory_order_relaxed);
    progress_tiles_done_.fetch_add(1, std::memory_order_relaxed);
  }
}

// The tile's pixels [i0, i1) x [j0, j1), this pass's samples of each: with
// path reuse in blocks of settings.reuse on a side, from the tile's corner
// (tiles never split a block, so an image is the same whatever the thread
// count), otherwise pixel by pixel. Returns the samples dropped.
std::uint64_t ProgressiveRenderer::run_blocks(int i0, int i1, int j0, int j1, PathStats& stats) {
  Job& job = *job_;
  const Scene& scene = job.scene;
  const bool reuse = reuses_paths(scene.settings);
  const int side = reuse ? std::min(scene.settings.reuse, kMaxReuseBlock) : 1;
  std::uint64_t nans = 0;
  // Once per tile, not per block: a pixel by itself clears one sum, not 64.
  PixelSum sums[kMaxReuseBlock * kMaxReuseBlock];
  vec3 out[kMaxReuseBlock * kMaxReuseBlock];
  for (int bi = i0; bi < i1; bi += side) {
    for (int bj = j0; bj < j1; bj += side) {
      const int bi1 = std::min(i1, bi + side), bj1 = std::min(j1, bj + side);
      const int cols = bj1 - bj, pixels = (bi1 - bi) * cols;
      std::fill_n(sums, pixels, PixelSum{});
      for (int k = 0; k < job.pass_spp; ++k) {
        // A stop or an edit is seen within one sample of a block, not at
        // the next tile: a tile of a 65536-sample pass takes minutes. The
        // pass is abandoned; the film's sums of it are never published.
        if (abandoning()) {
          job.aborted = true;
          return nans;
        }
        const std::uint64_t sample = job.sample_base + std::uint64_t(k);
        if (reuse) {
          sample_block(job.world, scene, *job.cam, bi, bi1, bj, bj1, sample, out, stats);
        } else {  // one pixel
          const std::uint32_t pixel = std::uint32_t(bi) * std::uint32_t(job.width) + std::uint32_t(bj);
          Sampler sampler(scene.settings.sampler, pixel, sample, scene.settings.seed);
          out[0] = sample_pixel(job.world, scene, *job.cam, bi, bj, sampler, stats);
        }
        for (int p = 0; p < pixels; ++p) sums[p].add(out[p]);
      }
      for (int p = 0; p < pixels; ++p) {
        const int i = bi + p / cols, j = bj + p % cols;
        job.film.add(std::uint32_t(i) * std::uint32_t(job.width) + std::uint32_t(j), sums[p]);
        nans += sums[p].dropped;
      }
    }
  }
  return nans;
}

void ProgressiveRenderer::end_pass() {
  Job& job = *job_;
  if (job.aborted) return;
  // A preview publishes its coarse image in a generation's first snapshot
  // (every counter still zero) and leaves the accumulation alone.
  const bool preview = job.preview_pass;
  job.preview_pass = false;
  if (!preview) {
    job.spp_done += std::uint64_t(job.pass_spp);
    job.passes += 1;
    job.nan_count += job.pass_nans;
    job.rays += job.pass_rays;
    job.seconds += std::chrono::duration<double>(Clock::now() - job.pass_start).count();
  }
  const int target = job.scene.settings.target_spp;

  std::lock_guard lock(publish_mutex_);
  Snapshot& s = published_;
  job.film.publish(s, preview);
  if (publish_exact_ && !preview) job.film.publish_exact(s);
  s.spp = preview ? 1 : job.spp_done;  // the preview shows as one sample
  s.generation = job.generation;
  s.version += 1;
  s.passes = job.passes;
  s.nan_count = job.nan_count;
  s.rays = job.rays;
  s.seconds = job.seconds;
  s.done = !preview && target > 0 && job.spp_done >= std::uint64_t(target);
  s.preview = preview;
  s.triangles = job.world.triangle_count();
  s.bvh_nodes = job.world.bvh() ? job.world.bvh()->node_count() : 0;
  publish_cv_.notify_all();
}

}  // namespace whisker
