#include "app/headless.h"

#include <chrono>
#include <cstdio>
#include <thread>

#include <unistd.h>

#include "app/signals.h"
#include "render/accumulation_io.h"
#include "render/image_io.h"
#include "render/progressive.h"
#include "render/stats_io.h"
#include "scene/quote.h"

namespace whisker {

namespace {

// The images, the summary line and the stats of a finished render.
int write_outputs(const HeadlessOptions& o, const Scene& scene, const Snapshot& snap, int threads) {
  const double secs = snap.seconds;
  const double pixels = double(snap.width) * snap.height;
  const double paths = pixels * double(snap.spp);
  const Image img = mean_image(snap);
  if (!o.out_png.empty()) write_png(o.out_png, img);
  if (!o.out_float.empty()) write_float_image(o.out_float, img);
  if (!o.out_sum.empty())
    write_accumulation(o.out_sum, accumulation_of(snap, o.plan.start.first_sample, o.plan.id));

  std::printf(
      "%s %dx%d: %llu spp in %.3f s, %.3g paths/s, %.3g rays/s, %llu NaN/Inf dropped, %d threads",
      scene.name.c_str(), snap.width, snap.height, (unsigned long long)snap.spp, secs,
      secs > 0 ? paths / secs : 0.0, secs > 0 ? double(snap.rays) / secs : 0.0,
      (unsigned long long)snap.nan_count, threads);
  if (!o.out_png.empty()) std::printf(" -> %s", o.out_png.c_str());
  if (!o.out_float.empty()) std::printf(" -> %s", o.out_float.c_str());
  if (!o.out_sum.empty()) std::printf(" -> %s", o.out_sum.c_str());
  std::printf("\n");

  if (!o.stats_json.empty())
    write_stats_json(o.stats_json, {scene.name, &snap, threads, &scene.settings, {}});
  return 0;
}

// Waits until the render reaches its target or a signal asks to stop. It
// polls: a signal handler cannot wake the renderer's condition variable.
void wait_for_target(const ProgressiveRenderer& renderer, std::uint64_t gen,
                     std::uint64_t target) {
  Snapshot s;
  while (!interrupt_signal()) {
    renderer.snapshot(s);  // copies only when a new pass was published
    if (s.generation == gen && !s.preview && (s.spp >= target || s.done)) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

// After Ctrl-C or SIGTERM: the outputs from the passes completed (if any),
// a line saying what was written, and 128 + the signal's number.
int finish_interrupted(const HeadlessOptions& o, const Scene& scene, const Snapshot& snap,
                       std::uint64_t gen, int threads) {
  const int sig = interrupt_signal();
  if (snap.generation != gen || snap.preview || snap.spp == 0) {
    std::fprintf(stderr, "whisker: interrupted before the first pass ended; nothing written\n");
    return interrupted_exit_code(sig);
  }
  write_outputs(o, scene, snap, threads);
  std::fprintf(stderr, "whisker: interrupted: wrote the %llu passes completed (%llu spp)\n",
               (unsigned long long)snap.passes, (unsigned long long)snap.spp);
  return interrupted_exit_code(sig);
}

}  // namespace

int run_headless(const HeadlessOptions& o) {
  Scene scene = o.scene;
  scene.name = cut_for_message(scene.name);  // as echoed in the progress, the summary, the stats
  const std::uint64_t target =
      o.plan.target ? o.plan.target : std::uint64_t(o.frames) * std::uint64_t(scene.settings.spp);
  scene.settings.target_spp = int(target);
  if (o.plan.complete()) return write_outputs(o, scene, snapshot_of(*o.plan.start.resume), o.threads);

  ProgressiveRenderer renderer(o.threads);
  renderer.set_publish_exact(!o.out_sum.empty());
  const auto gen = renderer.set_scene(scene, o.plan.start);
  renderer.start();
  Checkpointer checkpoints(renderer, gen, o.out_sum, o.checkpoint, o.plan);

  const bool tty = o.progress && ::isatty(2);
  const auto t0 = std::chrono::steady_clock::now();
  Snapshot snap;
  bool shown = false;
  for (;;) {
    // Poll for progress; the wait itself is on the renderer's condition.
    if (!tty) {
      wait_for_target(renderer, gen, target);
      renderer.snapshot(snap);
      break;
    }
    renderer.snapshot(snap);
    if (snap.generation == gen && (snap.spp >= target || snap.done)) break;
    if (interrupt_signal()) break;
    const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (el > 2.0) {
      const double frac = double(snap.spp) / double(target);
      std::fprintf(stderr, "\r%s: %llu/%llu spp  %.1f s  eta %.1f s   ", scene.name.c_str(),
                   (unsigned long long)snap.spp, (unsigned long long)target, el,
                   frac > 0 ? el / frac - el : 0.0);
      shown = true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  renderer.stop();
  checkpoints.stop();
  if (shown) std::fprintf(stderr, "\r%*s\r", 70, "");

  if (interrupt_signal()) {
    renderer.snapshot(snap);  // the last pass completed before the stop
    return finish_interrupted(o, scene, snap, gen, renderer.threads());
  }
  const int code = write_outputs(o, scene, snap, renderer.threads());
  if (!interrupt_signal()) return code;
  // A signal during the writes: they were finished, each whole.
  std::fprintf(stderr, "whisker: interrupted while writing; the outputs were finished\n");
  return interrupted_exit_code(interrupt_signal());
}

}  // namespace whisker
