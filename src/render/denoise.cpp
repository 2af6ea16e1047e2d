#include "render/denoise.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <string>
#include <thread>

#include "render/denoise_planes.h"

namespace whisker {

namespace {

using denoising::Planes;

// ---- input checks ---------------------------------------------------------

void check_buffer(std::span<const float> v, const char* name, const DenoiseInput& in, int per_pixel) {
  const std::size_t pixels = std::size_t(in.width) * std::size_t(in.height);
  const std::size_t want = pixels * std::size_t(per_pixel);
  if (v.size() != want)
    throw DenoiseError("denoise: " + std::string(name) + " has " + std::to_string(v.size()) +
                       " values, expected " + std::to_string(want) + " (" + std::to_string(in.width) +
                       " x " + std::to_string(in.height) + " x " + std::to_string(per_pixel) + ")");
  // A value is not finite when its exponent bits are all set: OR of those
  // tests over the buffer (a loop the compiler vectorises), then the search
  // for the pixel only when one is.
  constexpr std::uint32_t kExponent = 0x7f800000u;
  std::uint32_t bad = 0;
  for (const float x : v) bad |= std::uint32_t((std::bit_cast<std::uint32_t>(x) & kExponent) == kExponent);
  if (!bad) return;
  for (std::size_t k = 0; k < v.size(); ++k)
    if (!std::isfinite(v[k])) {
      const std::size_t p = k / std::size_t(per_pixel);
      throw DenoiseError("denoise: " + std::string(name) + " is not finite at pixel (" +
                         std::to_string(p % std::size_t(in.width)) + ", " +
                         std::to_string(p / std::size_t(in.width)) + ") (column, row)");
    }
}

// ---- the error estimate's terms -----------------------------------------

// The three terms of the MSE estimate (denoise.h, ScaleError) of one value:
// (f - r)^2, (f_a - f_b)(a - b) / 2 and (a - b)^2 / 4.
// Each half filtered alone (f_a from a, f_b from b) is compared with the
// other, independent half: E (f_a - b)^2 = MSE(f_a) + var(b), and
// E (a - b)^2 / 2 = var(b) for halves of equal variance, so
// (f_a - b)^2 - (a - b)^2 / 2 is an unbiased estimate of MSE(f_a), bias
// included (the other-half reference of NFOR, Bitterli et al. 2016,
// section 5). The denoised image f = (f_a + f_b) / 2 has at most the mean of
// the two halves' errors less a quarter of their squared difference
// (((x + y) / 2)^2 = (x^2 + y^2) / 2 - (x - y)^2 / 4, with x, y the halves'
// errors). The raw image (a + b) / 2: (a - b)^2 / 4.
struct ErrorTerms {
  double halves = 0.0, raw = 0.0, spread = 0.0;  // spread: ((f_a - f_b) / 2)^2
  void add(double a, double b, double fa, double fb) {
    const double d2 = (a - b) * (a - b);
    halves += 0.5 * ((fa - b) * (fa - b) + (fb - a) * (fb - a)) - 0.5 * d2;
    raw += 0.25 * d2;
    spread += 0.25 * (fa - fb) * (fa - fb);
  }
  double denoised() const { return halves - spread; }
};

// Per pixel, the estimated MSE of the denoised and the raw image, each the
// mean over channels of its terms summed over the 7 x 7 pixels around
// (the image's edge: the pixels inside).
void error_maps(const DenoiseInput& in, DenoiseResult& out) {
  const int w = in.width, h = in.height;
  const std::size_t pixels = std::size_t(w) * std::size_t(h);
  std::vector<float> den(pixels), raw(pixels);
  for (std::size_t p = 0; p < pixels; ++p) {
    ErrorTerms t;
    for (std::size_t c = 0; c < 3; ++c)
      t.add(in.colour_a[3 * p + c], in.colour_b[3 * p + c], out.rgb_a[3 * p + c], out.rgb_b[3 * p + c]);
    den[p] = float(t.denoised() / 3.0);
    raw[p] = float(t.raw / 3.0);
  }
  constexpr int kRadius = 3;
  out.mse = denoising::box_mean(den, w, h, kRadius);
  out.raw_mse = denoising::box_mean(raw, w, h, kRadius);
  for (float& m : out.mse) m = std::max(m, 0.0f);
}

// ---- the raw image's coarse band ------------------------------------------

// A normalised Gaussian of standard deviation `sigma` px over one plane of
// a w x h image (separable, cut at 3 sigma, each tap set divided by its
// weight inside the image, so a constant stays constant).
void gaussian(std::vector<float>& v, int w, int h, float sigma) {
  const int r = int(std::ceil(3.0f * sigma));
  std::vector<float> taps(std::size_t(2 * r + 1));
  for (int i = -r; i <= r; ++i) taps[std::size_t(i + r)] = std::exp(-0.5f * float(i * i) / (sigma * sigma));
  // The taps' weight inside the image at each of n positions.
  auto inside = [&](int n) {
    std::vector<float> ws(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
      float s = 0.0f;
      for (int j = std::max(0, i - r); j <= std::min(n - 1, i + r); ++j) s += taps[std::size_t(j - i + r)];
      ws[std::size_t(i)] = s;
    }
    return ws;
  };
  const std::vector<float> wx = inside(w), wy = inside(h);
  // Each pass a sum of shifted lines, tap by tap (loops over whole lines,
  // which the compiler vectorises), then divided by the weight inside.
  std::vector<float> tmp(v.size(), 0.0f);
  for (int y = 0; y < h; ++y) {
    const float* src = &v[std::size_t(y) * std::size_t(w)];
    float* dst = &tmp[std::size_t(y) * std::size_t(w)];
    for (int j = -r; j <= r; ++j) {
      const float t = taps[std::size_t(j + r)];
      for (int x = std::max(0, -j); x < std::min(w, w - j); ++x) dst[x] += t * src[x + j];
    }
    for (int x = 0; x < w; ++x) dst[x] /= wx[std::size_t(x)];
  }
  for (int y = 0; y < h; ++y) {
    float* dst = &v[std::size_t(y) * std::size_t(w)];
    std::fill(dst, dst + w, 0.0f);
    for (int j = std::max(-r, -y); j <= std::min(r, h - 1 - y); ++j) {
      const float t = taps[std::size_t(j + r)];
      const float* src = &tmp[std::size_t(y + j) * std::size_t(w)];
      for (int x = 0; x < w; ++x) dst[x] += t * src[x];
    }
    const float inv = wy[std::size_t(y)];
    for (int x = 0; x < w; ++x) dst[x] /= inv;
  }
}

// The filtered half f's coarse band replaced by the raw half's:
// f + G(raw - f) = G(raw) + (f - G(f)), G a Gaussian of `sigma` px: the two
// bands of a Laplacian pyramid (Burt and Adelson, "The Laplacian Pyramid as
// a Compact Image Code", IEEE Trans. Commun. 1983), the coarse one from the
// unbiased raw half (E[G(raw)] = G(truth)), the fine one from the filter.
// A filter's error at scales wider than its own blur is mostly its bias
// (the blur of what the features do not explain: a shadow's edge, light
// across a silhouette), which no filtering lowers; the output's bias is
// (I - G) of the filter's, whose block means at scales past G's width
// are near zero. G's noise is 1 / (4 pi sigma^2) of a pixel's variance.
//
// G's width, 1 px, is chosen by bench/denoise_error.sh (docs/PERFORMANCE.md,
// "The denoised copy"): a wider G leaves the filter's bias between G's width
// and the filter's.
constexpr float kCoarseSigma = 1.0f;

void restore_coarse_band(std::span<const float> raw, std::vector<float>& f, int w, int h, float sigma) {
  const std::size_t pixels = std::size_t(w) * std::size_t(h);
  std::vector<float> d(pixels);
  for (std::size_t c = 0; c < 3; ++c) {
    for (std::size_t p = 0; p < pixels; ++p) d[p] = raw[3 * p + c] - f[3 * p + c];
    gaussian(d, w, h, sigma);
    for (std::size_t p = 0; p < pixels; ++p) f[3 * p + c] += d[p];
  }
}

}  // namespace

void validate(const DenoiseInput& in) {
  if (in.width <= 0 || in.height <= 0)
    throw DenoiseError("denoise: image size " + std::to_string(in.width) + " x " +
                       std::to_string(in.height) + " is empty");
  check_buffer(in.colour_a, "colour_a", in, 3);
  check_buffer(in.colour_b, "colour_b", in, 3);
  check_buffer(in.albedo_a, "albedo_a", in, 3);
  check_buffer(in.albedo_b, "albedo_b", in, 3);
  check_buffer(in.normal_a, "normal_a", in, 3);
  check_buffer(in.normal_b, "normal_b", in, 3);
  check_buffer(in.depth_a, "depth_a", in, 1);
  check_buffer(in.depth_b, "depth_b", in, 1);
}

DenoiseResult denoise(const DenoiseInput& in, const DenoiseOptions& options) {
  validate(in);
  const int threads = options.threads > 0 ? options.threads
                                          : int(std::max(1u, std::thread::hardware_concurrency()));
  DenoiseResult out;
  out.width = in.width;
  out.height = in.height;
  // Each half alone, its colour and its own features given as both halves:
  // then nothing of the other half (not even its features, whose edges move
  // with its colour's) reaches it, and estimate_error may compare the two.
  // With two threads or more, the halves side by side, each on half of them.
  auto filter_half = [&](int half, int half_threads) {
    DenoiseInput one = in;
    if (half == 0) {
      one.colour_b = in.colour_a, one.albedo_b = in.albedo_a, one.normal_b = in.normal_a, one.depth_b = in.depth_a;
    } else {
      one.colour_a = in.colour_b, one.albedo_a = in.albedo_b, one.normal_a = in.normal_b, one.depth_a = in.depth_b;
    }
    std::vector<float>& filtered = half == 0 ? out.rgb_a : out.rgb_b;
    std::vector<float> unused;
    if (options.filter == DenoiseFilter::Quality)
      denoising::regression_filter(one, half_threads, filtered, unused);
    else
      denoising::atrous_filter(one, half_threads, filtered, unused);
    // From this half alone, so the estimate may still compare the halves.
    restore_coarse_band(one.colour_a, filtered, in.width, in.height, kCoarseSigma);
  };
  if (threads >= 2) {
    std::exception_ptr failed;
    std::thread other([&] {
      try {
        filter_half(1, threads - threads / 2);
      } catch (...) {
        failed = std::current_exception();
      }
    });
    try {
      filter_half(0, threads / 2);
    } catch (...) {
      other.join();
      throw;
    }
    other.join();
    if (failed) std::rethrow_exception(failed);
  } else {
    filter_half(0, 1);
    filter_half(1, 1);
  }
  out.rgb.resize(out.rgb_a.size());
  for (std::size_t k = 0; k < out.rgb.size(); ++k) out.rgb[k] = 0.5f * (out.rgb_a[k] + out.rgb_b[k]);
  error_maps(in, out);
  return out;
}

ScaleError estimate_error(const DenoiseInput& in, const DenoiseResult& result, int scale) {
  validate(in);
  const std::size_t values = std::size_t(in.width) * std::size_t(in.height) * 3;
  if (result.width != in.width || result.height != in.height || result.rgb_a.size() != values ||
      result.rgb_b.size() != values)
    throw DenoiseError("denoise: the result is of a " + std::to_string(result.width) + " x " +
                       std::to_string(result.height) + " image, the input " +
                       std::to_string(in.width) + " x " + std::to_string(in.height));
  if (scale < 1 || scale > std::min(in.width, in.height))
    throw DenoiseError("denoise: error scale " + std::to_string(scale) + " is not within 1 to " +
                       std::to_string(std::min(in.width, in.height)));
  const int bw = in.width / scale, bh = in.height / scale;
  ErrorTerms total;
  double sum = 0.0;
  const double inv = 1.0 / (double(scale) * scale);
  for (int by = 0; by < bh; ++by)
    for (int bx = 0; bx < bw; ++bx)
      for (int c = 0; c < 3; ++c) {
        double m[4] = {0.0, 0.0, 0.0, 0.0};  // block means of a, b, f_a, f_b
        for (int y = by * scale; y < (by + 1) * scale; ++y)
          for (int x = bx * scale; x < (bx + 1) * scale; ++x) {
            const std::size_t i = (std::size_t(y) * std::size_t(in.width) + std::size_t(x)) * 3 + std::size_t(c);
            m[0] += in.colour_a[i];
            m[1] += in.colour_b[i];
            m[2] += result.rgb_a[i];
            m[3] += result.rgb_b[i];
          }
        total.add(m[0] * inv, m[1] * inv, m[2] * inv, m[3] * inv);
        sum += 0.5 * (m[0] + m[1]) * inv;
      }
  const double n = double(bw) * double(bh) * 3.0;
  ScaleError e;
  e.scale = scale;
  e.raw_mse = total.raw / n;
  e.denoised_mse = std::max(0.0, total.denoised() / n);
  e.denoised_variance = total.spread / n;
  e.denoised_bias2 = e.denoised_mse - e.denoised_variance;
  e.mean = sum / n;
  return e;
}

}  // namespace whisker
