// A feature-guided denoiser for two independent half images of a render
// (even and odd samples) and their features (render/features.h), with an
// estimate of its own error, bias included. Plain float images in, plain
// float images out: nothing here knows the film, so the film, snapshots,
// files and the viewer each hand it what they hold.
//
// Two filters:
// - Fast: edge-avoiding a-trous wavelets (Dammertz, Hanika, Keller,
//   "Edge-Avoiding A-Trous Wavelet Transform for fast Global Illumination
//   Filtering", HPG 2010), the colour weight guided by the estimated
//   variance as in SVGF (Schied et al., "Spatiotemporal Variance-Guided
//   Filtering", HPG 2017), on the colour divided by the albedo.
// - Quality: a first-order regression of the colour on the features in a
//   window around each pixel, weighted by the colour of the other half,
//   after NFOR (Bitterli et al., "Nonlinearly Weighted First-order
//   Regression for Denoising Monte Carlo Renderings", EGSR 2016), each
//   half guided by its own fast-filtered colour.
//
// After either, each filtered half's coarse band is replaced by that raw
// half's (f + G(raw - f), G a 1 px Gaussian; denoise.cpp): the filters'
// bias, which shows past their blur, leaves the coarse scales, which carry
// the raw image's unbiased low frequencies instead.
//
// Both filter each half alone, its weights from its own colour and the
// features, never from the other half; the output is the mean of the two
// filtered halves. So each filtered half can be compared with the other,
// independent half, which gives the error estimate (estimate_error) of the
// output against the true image, bias included, from the halves alone.
#pragma once

#include <span>
#include <stdexcept>
#include <vector>

namespace whisker {

// Two independent estimates a and b of one image, each the mean of half of
// the samples (e.g. even and odd sample indices), and the mean features of
// the same samples. Row 0 at the top; `colour_*`, `albedo_*` and `normal_*`
// hold 3 floats per pixel, `depth_*` one.
struct DenoiseInput {
  int width = 0, height = 0;
  std::span<const float> colour_a, colour_b;  // linear RGB, any scale
  std::span<const float> albedo_a, albedo_b;  // in [0, 1] per channel
  std::span<const float> normal_a, normal_b;  // world space, length at most 1
  std::span<const float> depth_a, depth_b;    // positive distances
};

// Refused input (sizes that do not match, values that are not finite): the
// message names the buffer and, for a value, the pixel.
struct DenoiseError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};
// Throws DenoiseError when `in` cannot be denoised.
void validate(const DenoiseInput& in);

enum class DenoiseFilter { Fast, Quality };

struct DenoiseOptions {
  DenoiseFilter filter = DenoiseFilter::Fast;
  int threads = 0;  // <= 0: all hardware threads
};

struct DenoiseResult {
  int width = 0, height = 0;
  std::vector<float> rgb;           // the denoised image: (rgb_a + rgb_b) / 2
  std::vector<float> rgb_a, rgb_b;  // the two halves filtered (coarse band restored)
  // Per pixel, the estimated mean squared error over the three channels of
  // `rgb` (bias included) and of the raw image (a + b) / 2 (its variance),
  // each from a 7 x 7 neighbourhood: a map to look at, noisy per pixel;
  // estimate_error() gives the figures over the image.
  std::vector<float> mse, raw_mse;
};

// Throws DenoiseError on bad input (validate()).
DenoiseResult denoise(const DenoiseInput& in, const DenoiseOptions& options = {});

// The estimated error of the denoised and the raw image after both are
// box-filtered by `scale` (the mean of each scale x scale block, blocks past
// the edge dropped): mean squared error per block and channel, in the
// input's units, as a comparison with a reference at that scale would give.
// From the halves alone, per block of the block means:
//   raw       ((a - b) / 2)^2                 (the variance of (a + b) / 2)
//   denoised  ((f_a - b)^2 + (f_b - a)^2) / 2 - (a - b)^2 / 2 - (f_a - f_b)^2 / 4
// Each filtered half is compared with the other, independent half (NFOR's
// other-half reference): the first two terms estimate the mean of the two
// halves' errors, bias included, and the last turns that into the error of
// their mean f = (f_a + f_b) / 2. Of it, `denoised_variance` =
// ((f_a - f_b) / 2)^2 (f's variance, were the halves' errors independent)
// and `denoised_bias2` the rest. Noisy itself: over few blocks (16 px on a
// small image) it may read below zero, and is then 0.
struct ScaleError {
  int scale = 1;
  double raw_mse = 0.0, denoised_mse = 0.0;
  double denoised_variance = 0.0, denoised_bias2 = 0.0;
  double mean = 0.0;  // the raw image's mean value (for relative figures)
  bool denoised_better() const { return denoised_mse < raw_mse; }
};
// Throws DenoiseError when `result` is not of `in` (sizes) or scale < 1.
ScaleError estimate_error(const DenoiseInput& in, const DenoiseResult& result, int scale);

}  // namespace whisker
