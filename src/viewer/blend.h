// What the window shows of a generation: its own passes (the snapshot the
// headless mode would write), the viewer's quick passes
// (ProgressiveRenderer::set_quick_passes), or both combined.
//
// Both are unbiased estimates of the same pixel values, so any combination of
// their per-pixel means with weights fixed in advance is unbiased too. The
// weights here are each estimator's sample count times a constant per
// estimator (own_sample_weight), the same for every pixel and never read
// from the pixels' values. Once the generation's own samples weigh
// kDropQuickRatio times the quick ones, the quick samples are left out (a
// rule on the counts alone, so still unbiased): from then on the window
// shows exactly the headless image.
#pragma once

#include <cstdint>

#include "render/film.h"
#include "scene/settings.h"

namespace whisker {

inline constexpr double kDropQuickRatio = 16.0;

// The weight of one sample of the settings' own estimator against one quick
// sample (one path, no splitting): its paths per sample, a fixed
// guess at how much less it varies.
double own_sample_weight(const RenderSettings& s);

struct Shown {
  Snapshot image;             // what to draw and save: sum / spp = mean
  std::uint64_t quick_spp = 0;  // quick samples in it (0: the own passes alone)
  std::uint64_t own_spp = 0;    // the generation's own samples in it
};

// Fills `out` from the latest own snapshot `own` and quick snapshot `quick`:
// the newer generation wins; in the same generation both are combined until
// the quick ones are dropped.
void blend_for_display(const Snapshot& own, const Snapshot& quick, const RenderSettings& own_settings,
                       Shown& out);

}  // namespace whisker
