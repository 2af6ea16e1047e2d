// The progressive renderer: worker threads add path-traced samples into a
// film (render/film.h), pass after pass; readers (the viewer, the headless
// mode) take consistent snapshots of it.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "render/accumulation.h"
#include "render/film.h"
#include "scene/scene.h"

namespace whisker {

class World;

// Where a generation starts: its first sample index (a sample range's start)
// and, to resume, the accumulation it continues (one contiguous range ending
// where this generation's samples begin).
struct RenderStart {
  std::uint64_t first_sample = 0;
  std::shared_ptr<const Accumulation> resume;
};

class ProgressiveRenderer {
 public:
  // threads <= 0: all hardware threads.
  explicit ProgressiveRenderer(int threads = 0);
  ~ProgressiveRenderer();
  ProgressiveRenderer(const ProgressiveRenderer&) = delete;
  ProgressiveRenderer& operator=(const ProgressiveRenderer&) = delete;

  // Adopt a scene and its settings at the next pass boundary: the buffer is
  // cleared and samples of older generations are thrown away. Returns the new
  // generation number. Thread-safe.
  // With `start`, from there instead of sample 0 with an empty film.
  std::uint64_t set_scene(const Scene& scene, RenderStart start = {});
  // Same, for settings-only edits. (A scene whose meshes are the same
  // objects, and the same accel kind, reuses the BVH either way.)
  std::uint64_t set_settings(const RenderSettings& settings);
  // Changes only the target samples per pixel of the current generation: the
  // accumulation goes on from where it is (a finished render resumes). Meant
  // for raising the target; a target below the samples already taken just
  // stops. Thread-safe.
  void set_target_spp(int target_spp);

  // How far the pass in flight is: tiles finished out of all, for a progress
  // display (a long pass shows no new image for a while).
  struct PassProgress {
    std::uint64_t generation = 0;
    int tiles_done = 0, tiles_total = 0;
    int pass_spp = 0;            // samples per pixel this pass adds
    double pass_seconds = 0.0;   // time since the pass began
    bool rendering = false;      // false between passes (paused, done)
  };
  PassProgress pass_progress() const;

  // Launches the workers; with fewer threads if not all can be created (a
  // warning on stderr; threads() says how many), throws std::runtime_error
  // naming the cause if none can.
  void start();
  void stop();                  // join them (a running pass is abandoned)
  void set_paused(bool paused);
  bool paused() const { return paused_.load(); }
  void set_threads(int threads);  // restarts the pool if running
  // Quick passes (the viewer's, render/quick_passes.h): for the first
  // moments of every new generation (QuickPasses::kSeconds of them, before
  // its first full pass) run quick passes of one path per sample, no
  // splitting, no path reuse and one sample per pass, into a film of their
  // own published by quick_snapshot(), so an edit shows at full resolution
  // at once. They never touch the generation's own accumulation (snapshot()
  // stays what headless renders), and a quick pass is not abandoned by a
  // newer edit, so a drag shows images as fast as quick passes land. Off by
  // default.
  void set_quick_passes(bool on) { quick_enabled_ = on; }
  // While the user drags (a camera orbit, a slider), edits come faster than
  // full-resolution quick passes: the quick passes then render one path per
  // stride x stride pixels (Snapshot::stride; QuickPasses::drag_stride). A
  // coarse pass is shown alone, never combined with full-resolution ones;
  // when the drag ends the quick passes go back to full resolution.
  // Thread-safe.
  void set_dragging(bool on) { dragging_ = on; }
  // Growing passes (the viewer's): a generation's own passes start at one
  // sample per pixel and double up to its settings' spp (1, 1, 2, 4, ...),
  // so that with many samples per pass its first image comes after one
  // sample, not a whole pass of them, and the image keeps refining. The
  // samples are the same ones; only the order of the double additions of
  // their float values differs (as it does for any pass size). Off by
  // default: headless passes are exactly --spp.
  void set_growing_passes(bool on) { growing_ = on; }
  // Called by a worker after each pass it publishes (own or quick), outside
  // the renderer's locks: a window wakes its event loop with it. Set before
  // start().
  void set_on_publish(std::function<void()> f) { on_publish_ = std::move(f); }
  // The latest quick pass's film (its generation, spp = quick samples),
  // copied if its version differs from out.version. Never waits.
  bool quick_snapshot(Snapshot& out) const;
  // Run the workers at a lower scheduling priority (nice +5), so that an
  // interactive UI thread on the same cores stays responsive. Takes effect
  // at the next start().
  void set_low_priority(bool on) { low_priority_ = on; }
  int threads() const { return threads_; }
  // A generation whose estimate is deterministic (deterministic_estimate)
  // is done after its first pass, whatever its target. Off by default.
  void set_stop_when_exact(bool on) { stop_when_exact_ = on; }
  // The generation's film also keeps the denoiser's feature buffers and
  // the odd samples' RGB (Snapshot::features, odd_rgb), from the next
  // generation on. Off by default: they cost a camera ray's features a
  // sample. Set before set_scene().
  void set_features(bool on) { features_ = on; }

  // Copies the latest published pass into `out` if its version differs from
  // out.version; returns whether it copied. Never waits for a pass.
  bool snapshot(Snapshot& out) const;
  // After stop(): moves the latest published pass into `out`, no copy (a
  // render's double sums are tens of megabytes, and a fresh copy's page
  // faults cost more than the copy); the renderer keeps an empty one.
  void take_snapshot(Snapshot& out);

  // Blocks until generation `gen` has at least `spp` samples per pixel (or
  // reached its target). Returns false if the renderer was stopped first.
  bool wait_for(std::uint64_t gen, std::uint64_t spp);

  // Why the workers stopped on their own ("out of memory while ..."), or "".
  std::string failure() const;

 private:
  struct Job;
  void worker_main(int index);
  bool begin_pass();   // thread 0 only: adopt settings, pause; false = quit
  void adopt_generation(const RenderStart& start);  // thread 0: a new scene or settings
  void plan_pass();    // thread 0: the pass's camera, samples, chunks and counters
  void build_light_caches(int chunk);     // all threads: the chunk's light caches
  void run_tiles(int chunk);
  // Set when the pass in flight is to be dropped (a stop, or an edit).
  const std::atomic<bool>& cancel_flag() const;
  void end_pass();     // thread 0 only: merge and publish
  std::uint64_t new_generation();  // pending_mutex_ held: after an edit

  int threads_ = 1;
  std::vector<std::thread> pool_;
  std::unique_ptr<Job> job_;
  std::atomic<bool> paused_{false};
  std::atomic<bool> running_{false};
  std::atomic<bool> quick_enabled_{false};
  std::atomic<bool> dragging_{false};
  std::atomic<bool> growing_{false};
  std::function<void()> on_publish_;
  std::atomic<bool> stop_when_exact_{false};
  std::atomic<bool> features_{false};
  bool low_priority_ = false;
  // pending state, guarded by pending_mutex_
  mutable std::mutex pending_mutex_;
  std::condition_variable pending_cv_;
  Scene pending_scene_;
  RenderStart pending_start_;
  // Written under pending_mutex_; atomic so that workers can check them
  // between tiles without taking the lock.
  std::atomic<std::uint64_t> pending_generation_{0};
  std::atomic<bool> quit_{false};
  // Set by an edit (set_scene, set_settings) and by stop(), cleared when a
  // pass adopts the newest generation: the generation's own passes stop at
  // it; quick passes read quit_ alone.
  std::atomic<bool> cancel_{false};
  std::string failure_;  // guarded by pending_mutex_
  // published snapshot, guarded by publish_mutex_
  mutable std::mutex publish_mutex_;
  std::condition_variable publish_cv_;
  Snapshot published_;
  Snapshot quick_published_;  // the quick passes' film, same mutex
  bool job_exact_published_ = false;  // published_ is of a deterministic estimate
  // The pass in flight, for pass_progress(); written by the workers.
  std::atomic<std::uint64_t> progress_generation_{0};
  std::atomic<int> progress_tiles_done_{0}, progress_tiles_total_{0}, progress_spp_{0};
  std::atomic<std::int64_t> progress_start_ns_{0};
  std::atomic<bool> progress_running_{false};
};

}  // namespace whisker
