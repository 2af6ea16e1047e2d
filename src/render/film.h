// The film: where samples land. A double-precision accumulation of RGB sums
// and luminance sums of squares per pixel, the policy for samples that are
// not finite, and the snapshots readers take of it (with the noise estimate).
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "render/image.h"

namespace whisker {

// Rec. 709 luminance weights: the noise estimate, the viewer's noise view.
inline constexpr double kLuminanceWeights[3] = {0.2126, 0.7152, 0.0722};

inline float luminance(const glm::vec3& c) {
  return float(kLuminanceWeights[0]) * c.x + float(kLuminanceWeights[1]) * c.y +
         float(kLuminanceWeights[2]) * c.z;
}

// The NaN policy: a sample with a non-finite channel is never accumulated;
// it is dropped and counted (RenderCounters::nan_count).
inline bool finite_sample(const glm::vec3& c) {
  return std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z);
}

// What rendering took and met, beside the samples: one set per generation,
// per accumulation file, per merge. Parts of one render add up (a merge, a
// resumed render's earlier passes), so the merged counters are the sums.
struct RenderCounters {
  std::uint64_t passes = 0;
  std::uint64_t nan_count = 0;  // NaN/Inf samples dropped
  std::uint64_t rays = 0;       // rays traced
  double seconds = 0.0;         // render time

  RenderCounters& operator+=(const RenderCounters& o) {
    passes += o.passes;
    nan_count += o.nan_count;
    rays += o.rays;
    seconds += o.seconds;
    return *this;
  }
  bool operator==(const RenderCounters&) const = default;
};

// A consistent copy of the accumulation: sums and count always belong together.
struct Snapshot {
  int width = 0, height = 0;
  // RGB radiance sums, width*height*3, row 0 = top: the film's double sums
  // as they are, which accumulation files merge and resume from exactly.
  // What is shown or written rounds them to float first (mean_image, mean,
  // the viewer's texture): the images are float, so a sum past float's
  // range shows as infinite there (docs/NUMERICS.md).
  std::vector<double> sum;
  // Per-pixel sum of squared luminance (noise estimate); double, since a
  // square doubles the exponent: float overflows for radiance near 1e19
  // and underflows below 1e-19 (light intensities of 1e30 and 1e-30).
  std::vector<double> sum_sq;
  // Per-pixel luminance sum of the samples with an odd index: with `sum`,
  // two independent half images, whose difference measures the noise at any
  // scale, correlated pixels included (empty when not known: a resumed part).
  std::vector<double> odd_sum;
  // With feature buffers (ProgressiveRenderer::set_features; empty without):
  // the RGB sums of the odd-indexed samples (3 a pixel), and the sums of the
  // denoiser's features of every sample and of the odd ones (kFeatureSums a
  // pixel: albedo, normal, depth, then the same of the odd samples).
  std::vector<double> odd_rgb;
  std::vector<double> features;
  std::uint64_t first_sample = 0;  // index of the first sample in `sum`
  std::uint64_t spp = 0;      // samples per pixel in `sum`
  std::uint64_t generation = 0;
  std::uint64_t version = 0;  // bumps with every published pass
  RenderCounters counters;    // this generation's
  bool done = false;            // reached the target samples per pixel
  // A quick pass's image (ProgressiveRenderer::set_quick_passes: one path per
  // sample, shown in the first moments after an edit), never a render's.
  bool quick = false;
  // A quick pass rendered while dragging (ProgressiveRenderer::set_dragging):
  // each of its pixels covers stride x stride pixels of the image.
  int stride = 1;
  std::size_t triangles = 0;  // the scene's geometry, for display
  std::size_t bvh_nodes = 0;

  // Mean radiance of pixel (x, y), channel c.
  float mean(int x, int y, int c) const {
    return spp ? float(sum[(std::size_t(y) * width + x) * 3 + c]) / float(spp) : 0.0f;
  }
  // Relative standard error of the image mean: sqrt(sum_px var_px/n) over
  // sum_px mean_px, from the luminance sums of squares; per-pixel variances,
  // so it reads low when pixels share their errors (path reuse's blocks).
  double pixel_standard_error() const;
  // The same figure after box-filtering by k (k x k blocks), from the two
  // half images (Snapshot::odd_sum), times k: for independent pixels it
  // equals the pixel figure at every k; larger where errors are correlated
  // across pixels, smaller for blue noise. NaN when unknown (no halves, or
  // fewer than 2 samples).
  double scale_standard_error(int k) const;
  // The noise figure the stats and the viewer show: the largest of the
  // pixel figure and the scale figures at 2, 4, 8 and 16 px, so it never
  // reads low for correlated pixels (issue 27; Celarek et al., "Quantifying
  // the Error of Light Transport Algorithms", EGSR 2019, on error at
  // several scales).
  double relative_standard_error() const;
};

// The scales the noise figure looks at (box filter sides, pixels).
inline constexpr int kNoiseScales[] = {2, 4, 8, 16};

// The mean radiance image of a snapshot.
Image mean_image(const Snapshot& s);

// Feature sums a pixel: albedo (3), normal (3), depth (1) of every sample,
// then of the odd-indexed ones.
inline constexpr int kFeatureSums = 14;

// One pixel's samples of a pass, in arrival order; double, since a pass may
// hold many thousands of samples per pixel.
struct PixelSum {
  glm::dvec3 sum{0.0};
  double sum_sq = 0.0;
  double odd_sum = 0.0;       // luminance of the odd-indexed samples
  std::uint64_t dropped = 0;  // non-finite samples
  glm::dvec3 odd_rgb{0.0};    // RGB of the odd-indexed samples (with features)
  double features[kFeatureSums] = {};

  void add(const glm::vec3& c, std::uint64_t sample) {
    if (!finite_sample(c)) {
      ++dropped;  // dropped and counted, never accumulated
      return;
    }
    sum += glm::dvec3(c);
    const double y = luminance(c);
    sum_sq += y * y;
    if (sample & 1) {
      odd_sum += y;
      odd_rgb += glm::dvec3(c);
    }
  }
  // A sample's features (render/features.h), always finite.
  void add_features(const glm::vec3& albedo, const glm::vec3& normal, float depth,
                    std::uint64_t sample) {
    for (int half = 0; half < ((sample & 1) ? 2 : 1); ++half) {
      double* f = features + 7 * half;
      for (int c = 0; c < 3; ++c) {
        f[c] += albedo[c];
        f[3 + c] += normal[c];
      }
      f[6] += depth;
    }
  }
};

// The accumulation of one generation; pixels are written by one thread each.
class Film {
 public:
  // Clears to black at the given size; with `features`, the film also keeps
  // the odd samples' RGB and the feature sums (Snapshot::odd_rgb, features).
  void reset(int width, int height, bool features = false);
  bool has_features() const { return features_; }
  int width() const { return width_; }
  int height() const { return height_; }

  void add(std::uint32_t pixel, const PixelSum& p) {
    double* a = &acc_[std::size_t(pixel) * 3];
    a[0] += p.sum.x;
    a[1] += p.sum.y;
    a[2] += p.sum.z;
    acc_sq_[pixel] += p.sum_sq;
    acc_odd_[pixel] += p.odd_sum;
    if (features_) {
      double* o = &odd_rgb_[std::size_t(pixel) * 3];
      o[0] += p.odd_rgb.x;
      o[1] += p.odd_rgb.y;
      o[2] += p.odd_rgb.z;
      double* f = &features_sum_[std::size_t(pixel) * kFeatureSums];
      for (int k = 0; k < kFeatureSums; ++k) f[k] += p.features[k];
    }
  }

  // Copies the sums into `s`.
  void publish(Snapshot& s) const;
  // Starts from these sums (a resumed render); sizes must match the film's.
  // The half images are then unknown: the scale figures say so.
  void load(const std::vector<double>& sum, const std::vector<double>& sum_sq);
  // The same, and a part's feature sums (Accumulation::odd_rgb, features):
  // a film reset with features goes on keeping them, exactly as the render
  // never stopped would (the luminance halves stay unknown). Without
  // features, or sums not of the film's size, as the load above.
  void load(const std::vector<double>& sum, const std::vector<double>& sum_sq,
            const std::vector<double>& odd_rgb, const std::vector<double>& features);

 private:
  int width_ = 0, height_ = 0;
  std::vector<double> acc_;     // RGB sums, double so millions of samples keep their digits
  std::vector<double> acc_sq_;  // luminance sums of squares
  std::vector<double> acc_odd_; // luminance sums of the odd-indexed samples
  bool halves_known_ = true;    // false once loaded from a part
  bool features_ = false;
  bool features_known_ = true;  // false once loaded from a part without its feature sums
  std::vector<double> odd_rgb_, features_sum_;  // with features_
};

}  // namespace whisker
