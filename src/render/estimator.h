// The render side's one entry to the estimator: a tile of a pass, rendered
// into the film by per-pixel paths (integrator.h) or, with path reuse, by
// blocks of pixels sharing their bounces (path_reuse.h). The renderer
// (progressive.h) knows tiles, passes and the film, not which estimator.
#pragma once

#include <cstdint>

#include "render/camera.h"
#include "render/film.h"
#include "render/integrator.h"
#include "render/path_reuse.h"

namespace whisker {

// A tile's pixels and the pass's samples of each: numbers first_sample to
// first_sample + spp - 1.
struct TileWork {
  PixelBlock pixels;
  std::uint64_t first_sample = 0;
  int spp = 0;
};

// Adds the tile's samples to the film. With path reuse the blocks start at
// the tile's corner (tiles never split a block, so an image is the same
// whatever the thread count). Returns the samples dropped (not finite).
std::uint64_t render_tile(const PathContext& ctx, const CameraFrame& cam, const TileWork& tile,
                          Film& film);

}  // namespace whisker
