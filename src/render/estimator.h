// The render side's one entry to the estimator: a tile of a pass, rendered
// into the film by per-pixel paths (integrator.h). The renderer
// (progressive.h) knows tiles, passes and the film, not the paths.
#pragma once

#include <cstdint>
#include <functional>

#include "render/camera.h"
#include "render/film.h"
#include "render/integrator.h"
#include "render/light_cache.h"

namespace whisker {

// Whether every pass of `scene` gives the same image: no indirect light, no
// anti-aliasing jitter, no Fresnel choice at glass (off, or no glass), and the
// one point light. Its render is exact after one pass.
bool deterministic_estimate(const Scene& scene);

// The cheap estimator, for the first moments after an edit: the same paths
// at one sample per pass, one path per sample (no splitting), with
// its own seed so its samples are independent of the settings' own.
RenderSettings cheap_settings(const RenderSettings& s);
// Whether the cheap estimator differs from the settings' own.
bool cheap_differs(const RenderSettings& s);

// A block of pixels: rows [i0, i1), columns [j0, j1).
struct PixelBlock {
  int i0 = 0, i1 = 0, j0 = 0, j1 = 0;
};

// A tile's pixels and the pass's samples of each: numbers first_sample to
// first_sample + spp - 1. `abandon`, asked before every group of kLanes
// paths, says the pass is being
// dropped (a stop or an edit): a tile of a pass of 65536 samples takes
// minutes, and a stop must not wait for it.
struct TileWork {
  PixelBlock pixels;
  std::uint64_t first_sample = 0;
  int spp = 0;
  std::function<bool()> abandon;
  // Light connections' caches of samples first_sample.. (light_cache.h), or
  // null: no connections are made.
  const LightCache* light_caches = nullptr;
  // A pass in chunks of samples: each pixel's sums (indexed by i * width +
  // j) start from `sums` when `in` (else from zero) and are left there when
  // `out` (else added to the film), so the film gets the pass's sums as if
  // its samples had run in one chunk, bit for bit.
  struct Carry {
    PixelSum* sums = nullptr;
    bool in = false, out = false;
  } carry;
  // The denoiser's features of each sample's camera ray (render/features.h)
  // added beside its light (PixelSum::add_features).
  bool features = false;
};

struct TileResult {
  std::uint64_t dropped = 0;  // samples not finite
  bool abandoned = false;     // stopped early: the film holds part of the tile
};

// Adds the tile's samples to the film.
TileResult render_tile(const PathContext& ctx, const CameraFrame& cam, const TileWork& tile,
                       Film& film);

}  // namespace whisker
