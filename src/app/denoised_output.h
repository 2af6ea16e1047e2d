// The denoised copy of a render (--out-denoised of a headless render and of
// `whisker merge`), and the denoiser's inputs as layers of a float EXR: one
// writer for both, so that a merged render denoises as the render done whole.
#pragma once

#include <string>

#include "io/image_io.h"
#include "render/film.h"

namespace whisker {

struct DenoisedOutput {
  std::string path;  // .png, .pfm or .exr
  bool fast = false;  // the a-trous filter, else the regression (quality) one
  int threads = 0;
  // A deterministic estimate is exact: its copy is the raw image itself.
  bool exact = false;
  // The sampler's even and odd samples are independent halves (the
  // independent sampler): only then is the error estimate valid.
  bool independent = false;
  bool display_units = false;  // a float copy in display units (--float-units display)
  ImageAttributes attributes;  // a float copy's header: what was rendered how
};

// Writes the denoised copy of `snap` (whose mean image is `raw`), prints its
// estimated error against the raw image's, and returns the stats'
// "denoised" record (JSON text). Throws ImageError naming the option and
// the path when `snap` cannot be denoised (no feature buffers, fewer than 2
// samples).
std::string write_denoised(const DenoisedOutput& out, const Snapshot& snap, const Image& raw);

// The two half images of `snap` and their features as EXR layers (even.R
// ... odd.depth.Z, docs/SHARDS.md), and the header attribute that says so;
// none when `snap` kept no feature buffers. Display units scale the colours
// as the image's.
ImageLayers feature_layers(const Snapshot& snap, bool display_units);
void add_feature_note(ImageAttributes& attributes);

}  // namespace whisker
