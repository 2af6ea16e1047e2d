#include "render/film.h"

#include <algorithm>

namespace whisker {

static_assert(float(kLuminanceWeights[0]) == 0.2126f && float(kLuminanceWeights[1]) == 0.7152f &&
              float(kLuminanceWeights[2]) == 0.0722f);

namespace {

// Pixel p's luminance sum from its RGB sums rounded to float: the noise
// figures are of the image as it is shown and written, and their rounding
// thresholds below are set for float sums.
double luminance_sum(const Snapshot& s, std::size_t p) {
  const double* w = kLuminanceWeights;
  return w[0] * float(s.sum[3 * p]) + w[1] * float(s.sum[3 * p + 1]) + w[2] * float(s.sum[3 * p + 2]);
}

}  // namespace

double Snapshot::pixel_standard_error() const {
  if (spp < 2 || width <= 0 || height <= 0) return INFINITY;
  const double n = double(spp);
  double var_sum = 0.0, mean_sum = 0.0;
  const std::size_t pixels = std::size_t(width) * height;
  for (std::size_t p = 0; p < pixels; ++p) {
    const double m = luminance_sum(*this, p) / n;
    // m comes from float sums of float samples, sum_sq from float
    // luminances: each is known to about 2^-23 of m^2, so a smaller
    // difference is their rounding, not variance (a noise-free image).
    const double raw = sum_sq[p] / n - m * m;
    const double var = raw > 0x1p-20 * m * m ? raw * n / (n - 1.0) : 0.0;  // sample variance
    var_sum += var / n;                                                     // of the mean
    mean_sum += m;
  }
  return mean_sum > 0.0 ? std::sqrt(var_sum / double(pixels)) / (mean_sum / double(pixels))
                        : INFINITY;
}

double Snapshot::scale_standard_error(int k) const {
  const std::size_t pixels = std::size_t(width) * height;
  if (k < 1 || width < k || height < k || odd_sum.size() != pixels || 3 * pixels != sum.size())
    return NAN;
  // Odd sample indices in [first_sample, first_sample + spp).
  const std::uint64_t n = spp, n_odd = (first_sample + spp) / 2 - first_sample / 2;
  const std::uint64_t n_even = n - n_odd;
  if (n_odd == 0 || n_even == 0) return NAN;
  const int bw = width / k, bh = height / k;
  double var_sum = 0.0, mean_sum = 0.0;
  for (int by = 0; by < bh; ++by)
    for (int bx = 0; bx < bw; ++bx) {
      double odd = 0.0, all = 0.0;
      for (int y = by * k; y < (by + 1) * k; ++y)
        for (int x = bx * k; x < (bx + 1) * k; ++x) {
          const std::size_t p = std::size_t(y) * width + x;
          odd += odd_sum[p];
          all += luminance_sum(*this, p);
        }
      // The block's two half means a and b are independent estimates of its
      // mean m = (n_odd a + n_even b) / n, so E(a - b)^2 = var(a) + var(b),
      // and var(m) = (a - b)^2 n_odd n_even / n^2 in expectation.
      const double a = odd / double(n_odd), b = (all - odd) / double(n_even), m = all / double(n);
      // As for the pixel figure: a difference within the float sums'
      // rounding is no variance (a noise-free image).
      if ((a - b) * (a - b) > 0x1p-40 * m * m)
        var_sum += (a - b) * (a - b) * double(n_odd) * double(n_even) / (double(n) * double(n));
      mean_sum += m;
    }
  // Per block of k^2 pixels: the relative error of the block mean, times k
  // (what it would be for k^2 independent pixels of the pixel figure).
  const double blocks = double(bw) * bh;
  return mean_sum > 0.0 ? double(k) * std::sqrt(var_sum / blocks) / (mean_sum / blocks) : NAN;
}

double Snapshot::relative_standard_error() const {
  double e = pixel_standard_error();
  for (int k : kNoiseScales) {
    const double ek = scale_standard_error(k);
    if (ek > e) e = ek;  // NaN (unknown) never wins
  }
  return e;
}

Image mean_image(const Snapshot& s) {
  Image img;
  img.width = s.width;
  img.height = s.height;
  img.rgb.resize(s.sum.size());
  const float inv = s.spp ? 1.0f / float(s.spp) : 0.0f;
  for (std::size_t k = 0; k < s.sum.size(); ++k) img.rgb[k] = float(s.sum[k]) * inv;
  return img;
}

void Film::reset(int width, int height, bool features) {
  width_ = width;
  height_ = height;
  const std::size_t pixels = std::size_t(width) * height;
  acc_.assign(pixels * 3, 0.0);
  acc_sq_.assign(pixels, 0.0);
  acc_odd_.assign(pixels, 0.0);
  halves_known_ = true;
  features_ = features;
  features_known_ = true;
  odd_rgb_.assign(features ? pixels * 3 : 0, 0.0);
  features_sum_.assign(features ? pixels * kFeatureSums : 0, 0.0);
}

void Film::publish(Snapshot& s) const {
  s.width = width_;
  s.height = height_;
  s.sum = acc_;
  s.sum_sq = acc_sq_;
  if (halves_known_)
    s.odd_sum = acc_odd_;
  else
    s.odd_sum.clear();
  s.odd_rgb = features_known_ ? odd_rgb_ : std::vector<double>();
  s.features = features_known_ ? features_sum_ : std::vector<double>();
}

void Film::load(const std::vector<double>& sum, const std::vector<double>& sum_sq) {
  if (sum.size() == acc_.size()) acc_ = sum;
  if (sum_sq.size() == acc_sq_.size()) acc_sq_ = sum_sq;
  halves_known_ = false;
  features_known_ = false;
}

void Film::load(const std::vector<double>& sum, const std::vector<double>& sum_sq,
                const std::vector<double>& odd_rgb, const std::vector<double>& features) {
  load(sum, sum_sq);
  if (!features_ || odd_rgb.size() != odd_rgb_.size() || features.size() != features_sum_.size()) return;
  odd_rgb_ = odd_rgb;
  features_sum_ = features;
  features_known_ = true;
}

}  // namespace whisker
