#include "render/film.h"

#include <algorithm>

namespace whisker {

static_assert(float(kLuminanceWeights[0]) == 0.2126f && float(kLuminanceWeights[1]) == 0.7152f &&
              float(kLuminanceWeights[2]) == 0.0722f);

double Snapshot::relative_standard_error() const {
  if (spp < 2 || width <= 0 || height <= 0) return INFINITY;
  const double n = double(spp);
  double var_sum = 0.0, mean_sum = 0.0;
  const std::size_t pixels = std::size_t(width) * height;
  const double* w = kLuminanceWeights;
  for (std::size_t p = 0; p < pixels; ++p) {
    const double m = (w[0] * sum[3 * p] + w[1] * sum[3 * p + 1] + w[2] * sum[3 * p + 2]) / n;
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

Image mean_image(const Snapshot& s) {
  Image img;
  img.width = s.width;
  img.height = s.height;
  img.rgb.resize(s.sum.size());
  const float inv = s.spp ? 1.0f / float(s.spp) : 0.0f;
  for (std::size_t k = 0; k < s.sum.size(); ++k) img.rgb[k] = s.sum[k] * inv;
  return img;
}

void Film::reset(int width, int height, bool preview) {
  width_ = width;
  height_ = height;
  const std::size_t pixels = std::size_t(width) * height;
  acc_.assign(pixels * 3, 0.0);
  acc_sq_.assign(pixels, 0.0);
  if (preview) preview_.assign(pixels * 3, 0.0f);
}

void Film::fill_preview(int x0, int y0, int x1, int y1, glm::vec3 c) {
  if (!finite_sample(c)) c = glm::vec3(0.0f);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x)
      for (int ch = 0; ch < 3; ++ch) preview_[(std::size_t(y) * width_ + x) * 3 + ch] = c[ch];
}

void Film::publish(Snapshot& s, bool preview) const {
  s.width = width_;
  s.height = height_;
  if (preview) {
    s.sum = preview_;
    s.sum_sq.assign(acc_sq_.size(), 0.0);
  } else {
    s.sum.resize(acc_.size());
    for (std::size_t k = 0; k < acc_.size(); ++k) s.sum[k] = float(acc_[k]);
    s.sum_sq = acc_sq_;
  }
}

void Film::publish_exact(Snapshot& s) const {
  s.exact_sum = acc_;
  s.exact_sum_sq = acc_sq_;
}

void Film::load(const std::vector<double>& sum, const std::vector<double>& sum_sq) {
  if (sum.size() == acc_.size()) acc_ = sum;
  if (sum_sq.size() == acc_sq_.size()) acc_sq_ = sum_sq;
}

}  // namespace whisker
