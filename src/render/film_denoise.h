// The film's two half images and their features (Snapshot::odd_rgb and
// features) as the denoiser's input (render/denoise.h): the even-indexed
// samples' means as half a, the odd ones' as half b.
#pragma once

#include <string>
#include <vector>

#include "render/denoise.h"
#include "render/film.h"

namespace whisker {

struct FilmHalves {
  int width = 0, height = 0;
  std::vector<float> colour[2], albedo[2], normal[2], depth[2];  // [0]: even samples, [1]: odd
  DenoiseInput input() const;
};

// The halves of `s`; "" if it has them, else why not (no feature buffers, or
// fewer than one even and one odd sample).
std::string film_halves(const Snapshot& s, FilmHalves& out);

}  // namespace whisker
