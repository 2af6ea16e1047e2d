#include "viewer/denoised_view.h"

#include <chrono>
#include <utility>

#include "render/film_denoise.h"
#include "scene/scene.h"
#include "viewer/viewer_state.h"

namespace whisker {

DenoisedView::DenoisedView(std::function<void()> on_done)
    : on_done_(std::move(on_done)), thread_([this] { run(); }) {}

DenoisedView::~DenoisedView() {
  {
    std::lock_guard lock(mutex_);
    quit_ = true;
  }
  cv_.notify_all();
  thread_.join();
}

void DenoisedView::request(const Snapshot& s, bool independent) {
  std::lock_guard lock(mutex_);
  input_ = s;
  independent_ = independent;
  pending_ = true;
  cv_.notify_all();
}

bool DenoisedView::latest(Snapshot& out, DenoisedFigures& figures) const {
  std::lock_guard lock(mutex_);
  if (output_.version == out.version) return false;
  out = output_;
  figures = figures_;
  return true;
}

void DenoisedView::run() {
  std::unique_lock lock(mutex_);
  for (;;) {
    cv_.wait(lock, [&] { return quit_ || pending_; });
    if (quit_) return;
    Snapshot in = std::move(input_);
    input_ = Snapshot{};
    pending_ = false;
    const bool independent = independent_;
    lock.unlock();

    Snapshot out;
    DenoisedFigures fig;
    FilmHalves halves;
    bool ok = film_halves(in, halves).empty();
    if (ok) {
      const auto t0 = std::chrono::steady_clock::now();
      const DenoiseInput din = halves.input();
      try {
        const DenoiseResult r = denoise(din, {DenoiseFilter::Fast, 0});
        fig.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        fig.valid = independent;
        fig.source_version = in.version;
        fig.from_quick = in.quick;
        fig.pixel = estimate_error(din, r, 1);
        if (in.width >= 8 && in.height >= 8) fig.block = estimate_error(din, r, 8);
        // As a snapshot: sum / spp is the denoised mean.
        out.width = in.width;
        out.height = in.height;
        out.spp = in.spp;
        out.sum.resize(r.rgb.size());
        for (std::size_t k = 0; k < r.rgb.size(); ++k) out.sum[k] = double(r.rgb[k]) * double(in.spp);
      } catch (const DenoiseError&) {
        ok = false;  // a non-finite pixel: the raw image stays on screen
      }
    }
    out.generation = in.generation;
    out.first_sample = in.first_sample;
    out.counters = in.counters;
    out.quick = in.quick;
    out.stride = in.stride;
    out.triangles = in.triangles;
    out.bvh_nodes = in.bvh_nodes;
    lock.lock();
    if (!ok) continue;
    out.version = output_.version + 1;
    output_ = std::move(out);
    figures_ = fig;
    lock.unlock();
    if (on_done_) on_done_();
    lock.lock();
  }
}


const Snapshot* denoise_source(const ViewerState& s) {
  if (!s.denoised_view || deterministic_estimate(s.applied)) return nullptr;
  const auto usable = [&](const Snapshot& sn) {
    return sn.generation == s.generation && sn.spp >= 2 && sn.stride == 1 && !sn.features.empty();
  };
  return usable(s.snap) ? &s.snap : usable(s.quick) ? &s.quick : nullptr;
}

std::uint64_t denoise_key(const ViewerState& s, const Snapshot& source) {
  return source.version * 2 + (&source == &s.quick ? 1 : 0);  // the two films count apart
}

bool denoised_caught_up(const ViewerState& s) {
  return !s.denoised_view || deterministic_estimate(s.applied) ||
         (s.denoised.spp > 0 && !s.denoised_figures.from_quick &&
          s.denoised_figures.source_version == s.snap.version);
}

}  // namespace whisker
