// Headless mode: the same progressive renderer, N passes, images and stats.
#pragma once

#include <string>

#include "app/shards.h"
#include "scene/scene.h"

namespace whisker {

struct HeadlessOptions {
  Scene scene;
  int frames = 1;     // passes of scene.settings.spp samples per pixel
  int threads = 0;    // 0 = all hardware threads
  std::string out_png;
  std::string out_float;  // .pfm or .exr
  std::string stats_json;
  // Progress on stderr: on a terminal a line redrawn in place; otherwise (a
  // pipe, a CI log) a plain line every progress_every seconds.
  bool progress = true;
  double progress_every = 5.0;
  bool display_units = false;  // --out-float: 1.0 = the report's white (kReportWhite)
  // Which samples, from what start (--samples, --resume); unset: plan.target
  // = 0, the frames x spp samples of a render from sample 0.
  ShardPlan plan;
  std::string out_sum;  // accumulation file (.exr)
  // A denoised copy of the image (.png, .pfm or .exr; render/denoise.h),
  // and its filter: the raw outputs stay as they are.
  std::string out_denoised;
  bool denoise_fast = false;
  // Keep the denoiser's feature buffers (--features, or --out-denoised):
  // in --out-sum, --out-float's EXR and the checkpoints too.
  bool features = false;
  // No --frames, --samples or --resume on the command line: a scene whose
  // estimate is deterministic (deterministic_estimate) renders one pass,
  // whatever its target (--target-spp, else its file's), and records the
  // target as what that pass stands for. --frames N renders its N passes, as
  // the viewer's does: a pass count, as for timing, not a quality target.
  bool one_pass_if_exact = false;
  bool target_spp_given = false;  // --target-spp: say on stderr it was cut to one pass
  double checkpoint = -1;  // seconds between --out-sum writes while rendering (< 0: off)
};

// Renders and writes the outputs; returns the process exit code.
int run_headless(const HeadlessOptions& options);

}  // namespace whisker
