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
#include "render/quick_passes.h"
#include "render/sampler.h"

namespace whisker {

namespace {
constexpr int kTile = 32;
constexpr int kCachedSamples = 16;
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
  int width = 0, height = 0;
  Film film;
  bool film_stale = false;  // film holds an older generation's sums
  bool quick_pass = false;
  QuickPasses quick;  // set_quick_passes
  bool exact = false;  // deterministic_estimate(scene)
  std::uint64_t spp_done = 0;
  RenderCounters counters;
  std::uint64_t first_sample = 0;  // sample index of the generation's first sample

  // this pass
  const CameraFrame* pass_cam = nullptr;
  int pass_tiles_x = 0, pass_tiles_y = 0;  // of the pass camera's image
  std::uint64_t sample_base = 0;
  int pass_spp = 0;
  Clock::time_point pass_start;
  std::atomic<int> next_tile{0};
  // With light connections a pass runs in chunks of at most kCachedSamples
  // samples, each with its samples' caches (light_cache.h); the pixels'
  // sums carry from chunk to chunk (TileWork::carry): the same sums as one.
  std::vector<LightCache> light_caches;  // one per sample of a chunk
  std::atomic<int> next_cache{0};
  int chunks = 1, chunk_spp = 0;
  std::vector<PixelSum> carry;
  int chunk_samples(int chunk) const { return std::min(chunk_spp, pass_spp - chunk * chunk_spp); }
  std::atomic<std::uint64_t> pass_nans{0}, pass_rays{0};
  std::atomic<bool> aborted{false};
};

ProgressiveRenderer::ProgressiveRenderer(int threads) {
  threads_ = threads > 0 ? threads : int(std::max(1u, std::thread::hardware_concurrency()));
}

ProgressiveRenderer::~ProgressiveRenderer() { stop(); }

std::uint64_t ProgressiveRenderer::set_scene(const Scene& scene, RenderStart start) {
  std::lock_guard lock(pending_mutex_);
  pending_scene_ = scene;
  pending_start_ = std::move(start);
  return new_generation();
}

std::uint64_t ProgressiveRenderer::set_settings(const RenderSettings& settings) {
  std::lock_guard lock(pending_mutex_);
  pending_scene_.settings = settings;
  return new_generation();
}

std::uint64_t ProgressiveRenderer::new_generation() {
  cancel_ = true;
  pending_cv_.notify_all();
  return ++pending_generation_;
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
  if (published_.generation == gen && !published_.quick && !(stop_when_exact_ && job_exact_published_))
    published_.done = target > 0 && published_.spp >= std::uint64_t(target);
}

ProgressiveRenderer::PassProgress ProgressiveRenderer::pass_progress() const {
  PassProgress p{progress_generation_.load(), progress_tiles_done_.load(), progress_tiles_total_.load(),
                 progress_spp_.load(), 0.0, progress_running_.load()};
  const std::int64_t now = std::chrono::duration_cast<std::chrono::nanoseconds>(
                               Clock::now().time_since_epoch()).count();
  p.pass_seconds = p.rendering ? double(now - progress_start_ns_.load()) * 1e-9 : 0.0;
  return p;
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
    cancel_ = true;
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

void ProgressiveRenderer::take_snapshot(Snapshot& out) {
  std::lock_guard lock(publish_mutex_);
  out = std::move(published_);
  published_ = Snapshot{};
}

bool ProgressiveRenderer::quick_snapshot(Snapshot& out) const {
  std::lock_guard lock(publish_mutex_);
  if (quick_published_.version == out.version) return false;
  out = quick_published_;
  return true;
}

bool ProgressiveRenderer::wait_for(std::uint64_t gen, std::uint64_t spp) {
  std::unique_lock lock(publish_mutex_);
  publish_cv_.wait(lock, [&] {
    if (!running_) return true;
    return published_.generation > gen ||
           (published_.generation == gen && !published_.quick &&
            (published_.spp >= spp || published_.done));
  });
  return published_.generation == gen && !published_.quick &&
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
  const auto guarded = [&](const char* doing, auto&& step) {
    try {
      step();
    } catch (const std::bad_alloc&) {
      std::lock_guard lock(pending_mutex_);
      if (failure_.empty()) failure_ = std::string("out of memory while ") + doing;
      quit_ = true;
      job.aborted = true;
    }
  };
  for (;;) {
    if (index == 0) job.keep_going = false;  // and so it stays if begin_pass fails
    if (index == 0) guarded("preparing the scene (its BVH and image buffers)", [&] { job.keep_going = begin_pass(); });
    job.sync.arrive_and_wait();
    if (!job.keep_going) return;
    const int chunks = job.chunks;  // read now: after the last barrier thread 0 starts the next pass
    const bool caches = !job.light_caches.empty();
    for (int chunk = 0; chunk < chunks; ++chunk) {  // every thread, every barrier
      if (caches) {
        guarded("tracing light paths", [&] { build_light_caches(chunk); });
        job.sync.arrive_and_wait();
        if (index == 0) job.next_cache = 0;  // next read after the tiles' barrier
      }
      guarded("rendering", [&] { run_tiles(chunk); });
      job.sync.arrive_and_wait();
      if (index == 0) job.next_tile = 0;  // next read after the caches' barrier
    }
    if (index == 0) {
      guarded("publishing a pass", [&] { end_pass(); });
      if (on_publish_ && !job.aborted) on_publish_();
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
    const bool exact_done = stop_when_exact_ && job.spp_done > 0 && job.exact;
    const bool done = !fresh && ((target > 0 && job.spp_done >= std::uint64_t(target)) || exact_done);
    if (!paused_ && pending_generation_ != 0 && (fresh || !done)) break;
    pending_cv_.wait(lock);
  }
  if (pending_generation_ != job.generation) {
    job.scene = pending_scene_;
    job.generation = pending_generation_;
    cancel_ = false;  // set again by the next edit or stop
    const RenderStart start = pending_start_;
    lock.unlock();
    adopt_generation(start);
  } else {
    lock.unlock();
  }
  plan_pass();
  return true;
}

void ProgressiveRenderer::adopt_generation(const RenderStart& start) {
  // Everything accumulated so far is thrown away. Spheres and materials are
  // rebuilt (cheap); the BVH is reused when the meshes and the accel kind
  // are the same.
  Job& job = *job_;
  job.world = World(job.scene, &job.world);
  job.cam = std::make_unique<CameraFrame>(job.scene.camera);
  job.width = job.scene.camera.width;
  job.height = job.scene.camera.height;
  job.spp_done = 0;
  job.counters = {};
  job.quick_pass = false;
  job.exact = deterministic_estimate(job.scene);
  // The film is cleared when the generation's own first pass begins: a
  // drag adopts a generation per quick pass and may never reach one.
  job.film_stale = true;
  job.quick.begin_generation(job.scene, quick_enabled_ && !start.resume);
  job.first_sample = start.first_sample;
  if (!start.resume) return;
  // The resumed part's sums, counters and samples, as if its passes had
  // just run here: the next pass adds onto them exactly as it would have.
  const Accumulation& a = *start.resume;
  job.film.reset(job.width, job.height, features_ && a.with_features);
  job.film_stale = false;
  job.film.load(a.sum, a.sum_sq, a.odd_rgb, a.features);
  job.spp_done = a.samples();
  job.counters = a.counters;
}

void ProgressiveRenderer::plan_pass() {
  Job& job = *job_;
  // Quick passes first, then the generation's own.
  job.quick_pass = job.quick.next_is_quick(job.spp_done);
  if (job.quick_pass) job.quick.set_up(dragging_, features_);
  if (!job.quick_pass && job.film_stale) {
    job.film.reset(job.width, job.height, features_);
    job.film_stale = false;
  }
  job.pass_cam = job.quick_pass ? &job.quick.camera(*job.cam) : job.cam.get();
  job.pass_tiles_x = (job.pass_cam->width + kTile - 1) / kTile;
  job.pass_tiles_y = (job.pass_cam->height + kTile - 1) / kTile;
  const RenderSettings& s = job.scene.settings;
  int spp = job.quick_pass ? 1 : std::max(1, s.spp);
  if (growing_ && !job.quick_pass) spp = int(std::min<std::uint64_t>(spp, std::max<std::uint64_t>(1, job.spp_done)));
  if (s.target_spp > 0 && !job.quick_pass)
    spp = int(std::min<std::uint64_t>(spp, std::uint64_t(s.target_spp) - job.spp_done));
  // At most kCachedSamples light caches at a time: bounded whatever --spp.
  const bool cached = !job.quick_pass && s.connect && s.indirect;
  job.chunk_spp = cached ? std::min(spp, kCachedSamples) : spp;
  job.chunks = (spp + job.chunk_spp - 1) / job.chunk_spp;
  job.light_caches.resize(cached ? std::size_t(job.chunk_spp) : 0);
  if (job.chunks > 1) job.carry.resize(std::size_t(job.pass_cam->width) * std::size_t(job.pass_cam->height));
  job.next_cache = 0;
  job.pass_spp = spp;
  job.sample_base = job.quick_pass ? job.quick.next_sample() : job.first_sample + job.spp_done;
  job.next_tile = 0;
  job.pass_nans = 0;
  job.pass_rays = 0;
  job.aborted = false;
  job.pass_start = Clock::now();
  progress_generation_ = job.generation;
  progress_tiles_done_ = 0;
  progress_tiles_total_ = job.pass_tiles_x * job.pass_tiles_y * job.chunks;
  progress_spp_ = job.quick_pass ? 0 : spp;
  progress_start_ns_ = std::chrono::duration_cast<std::chrono::nanoseconds>(
                           job.pass_start.time_since_epoch()).count();
  progress_running_ = true;
}

const std::atomic<bool>& ProgressiveRenderer::cancel_flag() const {
  // A quick pass runs to its end (a drag shows each one), but a stop ends it.
  return job_->quick_pass ? quit_ : cancel_;
}

void ProgressiveRenderer::build_light_caches(int chunk) {
  Job& job = *job_;
  std::uint64_t rays = 0;
  const std::uint64_t first = job.sample_base + std::uint64_t(chunk * job.chunk_spp);
  for (;;) {
    const int k = job.next_cache.fetch_add(1, std::memory_order_relaxed);
    if (k >= job.chunk_samples(chunk)) break;
    if (cancel_flag().load(std::memory_order_relaxed)) job.aborted = true;  // no tile may run on a cache never built
    if (job.aborted) break;
    job.light_caches[std::size_t(k)].build(job.world, job.scene.settings, first + std::uint64_t(k), rays);
  }
  job.pass_rays.fetch_add(rays, std::memory_order_relaxed);
}

void ProgressiveRenderer::run_tiles(int chunk) {
  Job& job = *job_;
  const int tiles = job.pass_tiles_x * job.pass_tiles_y;
  for (;;) {
    const int tile = job.next_tile.fetch_add(1, std::memory_order_relaxed);
    if (tile >= tiles) break;
    // An edit or a stop abandons the pass; its partial sums are discarded.
    if (cancel_flag().load(std::memory_order_relaxed)) job.aborted = true;
    if (job.aborted) break;
    const int ty = tile / job.pass_tiles_x, tx = tile % job.pass_tiles_x;
    const int i0 = ty * kTile, j0 = tx * kTile;
    const CameraFrame& cam = *job.pass_cam;
    const int i1 = std::min(cam.height, i0 + kTile), j1 = std::min(cam.width, j0 + kTile);
    PathStats stats;
    const Scene& scene = job.quick_pass ? job.quick.scene() : job.scene;
    Film& film = job.quick_pass ? job.quick.film() : job.film;
    const PathContext ctx{job.world, scene.settings, stats};
    TileWork work{{i0, i1, j0, j1}, job.sample_base + std::uint64_t(chunk * job.chunk_spp),
                  job.chunk_samples(chunk), &cancel_flag(),
                  job.light_caches.empty() ? nullptr : job.light_caches.data(), {}, film.has_features()};
    if (job.chunks > 1) work.carry = {job.carry.data(), chunk > 0, chunk + 1 < job.chunks};
    const TileResult r = render_tile(ctx, cam, work, film);
    if (r.abandoned) {  // the pass is dropped as a whole, never published
      job.aborted = true;
      break;
    }
    job.pass_rays.fetch_add(stats.rays, std::memory_order_relaxed);
    job.pass_nans.fetch_add(r.dropped, std::memory_order_relaxed);
    progress_tiles_done_.fetch_add(1, std::memory_order_relaxed);
  }
}

void ProgressiveRenderer::end_pass() {
  Job& job = *job_;
  if (job.aborted) return;
  if (job.quick_pass) {
    // A quick pass: its own film and counts, published beside the real ones.
    const double seconds = std::chrono::duration<double>(Clock::now() - job.pass_start).count();
    std::lock_guard lock(publish_mutex_);
    job.quick.publish(seconds, job.generation, quick_published_);
    publish_cv_.notify_all();
    return;
  }
  job.spp_done += std::uint64_t(job.pass_spp);
  job.counters += {.passes = 1, .nan_count = job.pass_nans, .rays = job.pass_rays,
                   .seconds = std::chrono::duration<double>(Clock::now() - job.pass_start).count()};
  const int target = job.scene.settings.target_spp;

  std::lock_guard lock(publish_mutex_);
  Snapshot& s = published_;
  job.film.publish(s);
  s.spp = job.spp_done;
  s.first_sample = job.first_sample;
  s.generation = job.generation;
  s.version += 1;
  s.counters = job.counters;
  s.done = (target > 0 && job.spp_done >= std::uint64_t(target)) || (stop_when_exact_ && job.exact);
  s.quick = false;
  job_exact_published_ = job.exact;
  s.triangles = job.world.triangle_count();
  s.bvh_nodes = job.world.bvh() ? job.world.bvh()->node_count() : 0;
  publish_cv_.notify_all();
}

}  // namespace whisker
