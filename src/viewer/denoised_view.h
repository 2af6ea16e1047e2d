// The viewer's denoised image (the panel's Denoised box, key D): a copy of
// the latest image with feature buffers, filtered by the fast filter
// (render/denoise.h) on a thread of its own, so the window and the render
// workers never wait for it. The raw film is never touched: what this
// returns is a separate image, labelled as such wherever it is shown or
// saved.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "render/denoise.h"
#include "render/film.h"

namespace whisker {

// The estimated error of a denoised image and of its raw image
// (estimate_error), at pixel scale and in 8 px blocks.
struct DenoisedFigures {
  bool valid = false;  // the halves are independent (not Sobol): the figures mean something
  ScaleError pixel, block;
  double seconds = 0.0;  // the filter's time
  std::uint64_t source_version = 0;  // the version of the snapshot it came from
  bool from_quick = false;           // of the quick passes' film
};

class DenoisedView {
 public:
  // `on_done` runs on the filter's thread after each image (a window wakes
  // its event loop with it).
  explicit DenoisedView(std::function<void()> on_done);
  ~DenoisedView();
  DenoisedView(const DenoisedView&) = delete;
  DenoisedView& operator=(const DenoisedView&) = delete;

  // Filters `s` (which must have feature buffers and at least two samples)
  // when the thread is free; a newer request replaces one not yet begun.
  // `independent`: its halves are independent (the estimate is valid).
  void request(const Snapshot& s, bool independent);
  // The latest denoised image (an image as a snapshot: sum / spp is the
  // denoised mean, no sums of squares), copied if its version differs from
  // out.version. Never waits.
  bool latest(Snapshot& out, DenoisedFigures& figures) const;

 private:
  void run();

  mutable std::mutex mutex_;
  std::condition_variable cv_;
  bool quit_ = false;
  bool pending_ = false;
  bool independent_ = false;
  Snapshot input_;
  std::uint64_t input_version_ = 0;  // of the last request taken
  Snapshot output_;
  DenoisedFigures figures_;
  std::function<void()> on_done_;
  std::thread thread_;
};

}  // namespace whisker
