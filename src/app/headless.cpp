#include "app/headless.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include <unistd.h>

#include "app/denoised_output.h"
#include "app/shards.h"
#include "app/signals.h"
#include "io/accumulation_io.h"
#include "io/image_io.h"
#include "io/render_record.h"
#include "io/stats_io.h"
#include "render/progressive.h"
#include "scene/quote.h"
#include "scene/scene_io.h"
#include "scene/settings_json.h"

namespace whisker {

namespace {

// The outputs, in the order written.
std::vector<std::string> output_names(const HeadlessOptions& o) {
  std::vector<std::string> names;
  for (const std::string* out : {&o.out_png, &o.out_float, &o.out_sum, &o.out_denoised, &o.stats_json})
    if (!out->empty()) names.push_back(printable(*out));
  return names;
}

// What a second signal's message says (set_stop_note) once the first
// `written` outputs are: "wrote a.png; not written: b.pfm, s.json". An
// accumulation file kept up to date by --checkpoint keeps its last one.
void note_written(const HeadlessOptions& o, std::size_t written) {
  const std::vector<std::string> names = output_names(o);
  std::string wrote, not_written;
  for (std::size_t i = 0; i < names.size(); ++i) {
    std::string& list = i < written ? wrote : not_written;
    list += (list.empty() ? "" : ", ") + names[i];
    if (i >= written && o.checkpoint >= 0 && names[i] == printable(o.out_sum))
      list += " (its last checkpoint, if any, stays)";
  }
  if (wrote.empty() && not_written.empty()) return set_stop_note("nothing written");
  set_stop_note((wrote.empty() ? "" : "wrote " + wrote) +
                (wrote.empty() || not_written.empty() ? "" : "; ") +
                (not_written.empty() ? "" : "not written: " + not_written));
}

// The denoised copy of `snap` (app/denoised_output.h) as this render's.
std::string write_denoised(const HeadlessOptions& o, const Scene& scene, const Snapshot& snap,
                           const Image& raw, int threads) {
  const DenoisedOutput out{o.out_denoised,
                           o.denoise_fast,
                           threads,
                           deterministic_estimate(scene),
                           scene.settings.sampler == SamplerKind::Independent,
                           o.display_units,
                           render_record(scene, snap, o.display_units)};
  return write_denoised(out, snap, raw);
}

// --out-float: an EXR also holds the feature buffers when the render kept them.
void write_float_output(const HeadlessOptions& o, const Scene& scene, const Snapshot& snap, const Image& img) {
  ImageAttributes a = render_record(scene, snap, o.display_units);
  ImageLayers layers;
  if (lower_extension(o.out_float) == ".exr") layers = feature_layers(snap, o.display_units);
  if (!layers.empty()) add_feature_note(a);
  write_float_image(o.out_float, o.display_units ? display_referred(img) : img, a, layers);
}

// The images, the summary line and the stats of a finished render.
int write_outputs(const HeadlessOptions& o, const Scene& scene, const Snapshot& snap, int threads) {
  const bool exact = deterministic_estimate(scene);
  const double secs = snap.counters.seconds;
  const double pixels = double(snap.width) * snap.height;
  const double samples = pixels * double(snap.spp);
  const Image img = mean_image(snap);
  std::size_t written = 0;
  note_written(o, written);
  if (!o.out_png.empty()) {
    write_png(o.out_png, img);
    note_written(o, ++written);
  }
  if (!o.out_float.empty()) {
    write_float_output(o, scene, snap, img);
    note_written(o, ++written);
  }
  if (!o.out_sum.empty()) {
    write_accumulation(o.out_sum, accumulation_of(snap, o.plan.start.first_sample, o.plan.id));
    note_written(o, ++written);
  }
  std::string denoised;
  if (!o.out_denoised.empty()) {
    denoised = write_denoised(o, scene, snap, img, threads);
    note_written(o, ++written);
  }

  // A sample is one camera ray's estimate (with --split it continues as
  // several paths); rays/s counts every ray traced.
  std::printf(
      "%s %dx%d: %llu spp in %.3f s, %.3g samples/s, %.3g rays/s, %llu NaN/Inf dropped, %d "
      "threads",
      printable(scene.name).c_str(), snap.width, snap.height, (unsigned long long)snap.spp, secs,
      secs > 0 ? samples / secs : 0.0, secs > 0 ? double(snap.counters.rays) / secs : 0.0,
      (unsigned long long)snap.counters.nan_count, threads);
  if (exact) std::printf(", exact (deterministic estimate: every pass is the same)");
  for (const std::string* out : {&o.out_png, &o.out_float, &o.out_sum, &o.stats_json})
    if (!out->empty()) std::printf(" -> %s", printable(*out).c_str());
  std::printf("\n");
  std::fflush(stdout);  // the summary out when the images are, not at the exit

  if (!o.stats_json.empty()) {
    RenderStats st{scene.name, &snap, threads, &scene.settings, {}};
    st.extra.emplace_back("camera", RenderStats::JsonText{camera_json(scene.camera).dump()});
    st.extra.emplace_back("exact", RenderStats::JsonText{exact ? "true" : "false"});
    if (exact)
      st.extra.emplace_back("stands_for_spp",
                            RenderStats::JsonText{std::to_string(stands_for_spp(scene, snap))});
    if (!o.out_float.empty())
      st.extra.emplace_back("float_units", std::string(o.display_units ? "display" : "scene"));
    if (!denoised.empty()) st.extra.emplace_back("denoised", RenderStats::JsonText{denoised});
    write_stats_json(o.stats_json, st);
    note_written(o, ++written);
  }
  return 0;
}

// Waits until the render reaches its target or a signal asks to stop. It
// polls: a signal handler cannot wake the renderer's condition variable.
void wait_for_target(const ProgressiveRenderer& renderer, std::uint64_t gen,
                     std::uint64_t target) {
  Snapshot s;
  while (!interrupt_signal() && renderer.failure().empty()) {
    renderer.snapshot(s);  // copies only when a new pass was published
    if (s.generation == gen && !s.quick && (s.spp >= target || s.done)) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

// After Ctrl-C or SIGTERM: the outputs from the passes completed (if any),
// a line saying what was written, and 128 + the signal's number.
int finish_interrupted(const HeadlessOptions& o, const Scene& scene, const Snapshot& snap,
                       std::uint64_t gen, int threads) {
  const int sig = interrupt_signal();
  if (snap.generation != gen || snap.quick || snap.spp == 0) {
    std::fprintf(stderr, "whisker: interrupted before the first pass ended; nothing written\n");
    return interrupted_exit_code(sig);
  }
  write_outputs(o, scene, snap, threads);
  std::fprintf(stderr, "whisker: interrupted: wrote the %llu passes completed (%llu spp)\n",
               (unsigned long long)snap.counters.passes, (unsigned long long)snap.spp);
  return interrupted_exit_code(sig);
}

// "4m 05s", "12.3 s": a duration for the progress line.
std::string duration(double s) {
  char buf[32];
  if (s < 60)
    std::snprintf(buf, sizeof buf, "%.1f s", s);
  else if (s < 3600)
    std::snprintf(buf, sizeof buf, "%dm %02ds", int(s) / 60, int(s) % 60);
  else
    std::snprintf(buf, sizeof buf, "%dh %02dm", int(s) / 3600, int(s) / 60 % 60);
  return buf;
}

// Progress on stderr. On a terminal one line redrawn in place (from 2 s on);
// otherwise a plain line every `period` seconds, for logs. The time left is
// from the rate measured since the first sample arrived, so setup (loading,
// the BVH) does not inflate it; samples of the pass in flight count by tiles.
class Progress {
 public:
  Progress(std::string name, std::uint64_t target, bool tty, double period)
      : name_(printable(name)), target_(target), tty_(tty), period_(period) {}

  void update(double elapsed, const Snapshot& snap, std::uint64_t gen,
              const ProgressiveRenderer::PassProgress& pass) {
    double done = snap.generation == gen ? double(snap.spp) : 0.0;
    if (pass.generation == gen && pass.rendering && pass.tiles_total > 0)
      done += double(pass.pass_spp) * pass.tiles_done / pass.tiles_total;
    if (done > 0 && first_time_ < 0) {
      first_time_ = elapsed;
      first_done_ = done;
    }
    const double dt = elapsed - first_time_;
    const bool have_rate = first_time_ >= 0 && dt > 0.2 && done > first_done_;
    const std::string eta =
        have_rate ? duration((double(target_) - done) * dt / (done - first_done_)) : "--";
    if (tty_) {
      if (elapsed < 2.0) return;
      std::fprintf(stderr, "\r%s: %.1f/%llu spp  %s  eta %s   ", name_.c_str(), done,
                   (unsigned long long)target_, duration(elapsed).c_str(), eta.c_str());
      shown_ = true;
    } else if (elapsed >= next_line_) {
      next_line_ = elapsed + period_;
      if (elapsed < period_) return;  // nothing to say for short renders
      std::fprintf(stderr, "%s: %.1f/%llu spp (%.0f%%), %s elapsed, eta %s\n", name_.c_str(),
                   done, (unsigned long long)target_, 100.0 * done / double(target_),
                   duration(elapsed).c_str(), eta.c_str());
    }
  }

  void finish() const {
    if (shown_) std::fprintf(stderr, "\r%*s\r", 78, "");
  }

 private:
  std::string name_;
  std::uint64_t target_;
  bool tty_;
  double period_;
  double first_time_ = -1, first_done_ = 0;
  double next_line_ = 0;
  bool shown_ = false;
};

}  // namespace

int run_headless(const HeadlessOptions& o) {
  Scene scene = o.scene;
  scene.name = cut_for_message(scene.name);  // as echoed in the progress, the summary, the stats
  const std::uint64_t asked =
      o.plan.target ? o.plan.target : std::uint64_t(o.frames) * std::uint64_t(scene.settings.spp);
  scene.settings.target_spp = int(asked);
  // A deterministic estimate is exact after one pass: more add nothing. The
  // target stays in the settings, as what that pass stands for.
  const bool exact = o.one_pass_if_exact && deterministic_estimate(scene);
  const std::uint64_t target =
      exact ? std::min(asked, std::uint64_t(std::max(1, scene.settings.spp))) : asked;
  if (exact && o.target_spp_given && target < asked)
    std::fprintf(stderr,
                 "whisker: --target-spp %llu: the estimate is deterministic (no indirect light, no "
                 "anti-aliasing, no Fresnel choice), so one pass of %llu spp is exact and stands "
                 "for it; rendering that one pass\n",
                 (unsigned long long)asked, (unsigned long long)target);
  note_written(o, 0);
  if (o.plan.complete()) return write_outputs(o, scene, snapshot_of(*o.plan.start.resume), o.threads);

  if (!o.out_denoised.empty() && !exact && target < 2) {
    std::fprintf(stderr, "whisker: --out-denoised needs at least 2 samples per pixel (two half "
                         "images), got %llu\n", (unsigned long long)target);
    return 2;
  }
  ProgressiveRenderer renderer(o.threads);
  renderer.set_stop_when_exact(exact);
  renderer.set_features(o.features);
  const auto gen = renderer.set_scene(scene, o.plan.start);
  renderer.start();
  Checkpointer checkpoints(renderer, gen, o.out_sum, o.checkpoint, o.plan);

  const auto t0 = std::chrono::steady_clock::now();
  Snapshot snap;
  Progress progress(scene.name, target, ::isatty(2), o.progress_every);
  for (;;) {
    if (!o.progress) {  // nothing to print: wait for the target or a signal
      wait_for_target(renderer, gen, target);
      break;
    }
    renderer.snapshot(snap);
    if (snap.generation == gen && (snap.spp >= target || snap.done)) break;
    if (interrupt_signal() || !renderer.failure().empty()) break;
    const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    progress.update(el, snap, gen, renderer.pass_progress());
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  renderer.stop();
  checkpoints.stop();
  progress.finish();
  renderer.take_snapshot(snap);  // the last pass completed before the stop

  if (const std::string why = renderer.failure(); !why.empty()) {
    const std::uint64_t bytes = render_memory(scene, !o.out_sum.empty(), bool(o.plan.start.resume), o.features);
    std::fprintf(stderr, "whisker: %s: needs about %llu MB; nothing written\n", why.c_str(),
                 (unsigned long long)((bytes >> 20) + 1));
    return 2;
  }
  if (interrupt_signal()) {
    return finish_interrupted(o, scene, snap, gen, renderer.threads());
  }
  const int code = write_outputs(o, scene, snap, renderer.threads());
  if (!interrupt_signal()) return code;
  // A signal during the writes: they were finished, each whole.
  std::fprintf(stderr, "whisker: interrupted while writing; the outputs were finished\n");
  return interrupted_exit_code(interrupt_signal());
}

}  // namespace whisker
