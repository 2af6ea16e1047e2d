// The denoiser (render/denoise.h) on closed-form images: noise-free and
// constant images are left as they are, albedo and normal step edges stay
// sharp, the coarse band is the raw image's, the error estimate (bias
// included) is near the true error on images of known noise and bias, the
// result is the same on any number of threads, images smaller than the
// taps are filtered, and bad input is refused with a message.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "render/denoise.h"

using namespace whisker;

namespace {

using Rgb = std::array<float, 3>;

// Owned buffers of a DenoiseInput, features the same in both halves.
struct Halves {
  int w = 0, h = 0;
  std::vector<float> a, b, albedo, normal, depth;

  Halves(int width, int height)
      : w(width), h(height), a(std::size_t(width) * height * 3), b(a.size()),
        albedo(a.size(), 1.0f), normal(a.size(), 0.0f), depth(std::size_t(width) * height, 50.0f) {
    for (std::size_t p = 0; p < depth.size(); ++p) normal[3 * p + 2] = 1.0f;
  }
  DenoiseInput input() const {
    return DenoiseInput{w, h, a, b, albedo, albedo, normal, normal, depth, depth};
  }
  std::size_t at(int x, int y, int c) const { return (std::size_t(y) * w + x) * 3 + c; }
  // The raw image: the mean of the two halves.
  std::vector<float> raw() const {
    std::vector<float> m(a.size());
    for (std::size_t k = 0; k < m.size(); ++k) m[k] = 0.5f * (a[k] + b[k]);
    return m;
  }
};

constexpr DenoiseFilter kFilters[] = {DenoiseFilter::Fast, DenoiseFilter::Quality};
const char* name(DenoiseFilter f) { return f == DenoiseFilter::Fast ? "fast" : "quality"; }

// Each half: truth + Gaussian noise of standard deviation sigma x truth.
void add_noise(Halves& img, const std::vector<float>& truth, float sigma, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> g(0.0f, 1.0f);
  for (std::size_t k = 0; k < truth.size(); ++k) {
    img.a[k] = truth[k] * (1.0f + sigma * g(rng));
    img.b[k] = truth[k] * (1.0f + sigma * g(rng));
  }
}

// The mean squared error of `x` against `truth` after box-filtering by k.
double mse_at(const std::vector<float>& x, const std::vector<float>& truth, int w, int h, int k) {
  double se = 0.0;
  int n = 0;
  for (int by = 0; by < h / k; ++by)
    for (int bx = 0; bx < w / k; ++bx)
      for (int c = 0; c < 3; ++c) {
        double d = 0.0;
        for (int y = by * k; y < (by + 1) * k; ++y)
          for (int xx = bx * k; xx < (bx + 1) * k; ++xx) {
            const std::size_t i = (std::size_t(y) * w + xx) * 3 + c;
            d += double(x[i]) - double(truth[i]);
          }
        d /= double(k) * k;
        se += d * d;
        ++n;
      }
  return se / n;
}

}  // namespace

// Both halves equal (a noise-free image of unrelated values and features):
// the raw image is exact, and whatever a filter changes (each half's
// variance comes from that half alone, so such an image reads as noisy) is
// reported as the denoised image's error, exactly, and as worse than raw.
TEST(Denoise, NoiseFreeImageChangesAreReportedAsTheirError) {
  Halves img(40, 24);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (std::size_t k = 0; k < img.a.size(); ++k) {
    img.a[k] = img.b[k] = 1e4f * u(rng);  // radiance of the report's scale
    img.albedo[k] = u(rng);
  }
  for (std::size_t p = 0; p < img.depth.size(); ++p) img.depth[p] = 10.0f + 50.0f * u(rng);
  for (DenoiseFilter f : kFilters) {
    const DenoiseResult r = denoise(img.input(), {f, 2});
    ASSERT_EQ(r.rgb.size(), img.a.size());
    for (int k : {1, 4}) {
      const ScaleError e = estimate_error(img.input(), r, k);
      EXPECT_EQ(e.raw_mse, 0.0);
      const double truth = mse_at(r.rgb, img.a, img.w, img.h, k);
      EXPECT_NEAR(e.denoised_mse, truth, 1e-4 * truth + 1e-9) << name(f) << " at " << k << " px";
      EXPECT_EQ(e.denoised_better(), false);
    }
  }
}

TEST(Denoise, ConstantImageIsUnchanged) {
  Halves img(33, 17);
  for (std::size_t k = 0; k < img.a.size(); ++k) img.a[k] = img.b[k] = 0.25f;
  for (int x = 0; x < img.w; ++x)  // features that vary do not matter
    for (int y = 0; y < img.h; ++y) img.depth[std::size_t(y) * img.w + x] = 20.0f + float(x);
  for (DenoiseFilter f : kFilters) {
    const DenoiseResult r = denoise(img.input(), {f, 1});
    for (float v : r.rgb) ASSERT_NEAR(v, 0.25f, 0.25e-6f) << name(f);
  }
}

namespace {

// Left of column w/2 the colour `left`, right of it `right` (exact), noise
// of 20 % per half; `feature(img, x, y)` sets the features that explain the
// step. After denoising, the columns on each side of the step keep their
// own side's colour to within a tenth of the step, in each channel.
void expect_step_stays_sharp(Rgb left, Rgb right,
                             const std::function<void(Halves&, int, int)>& feature) {
  Halves img(64, 48);
  std::vector<float> truth(img.a.size());
  for (int y = 0; y < img.h; ++y)
    for (int x = 0; x < img.w; ++x) {
      feature(img, x, y);
      for (int c = 0; c < 3; ++c) truth[img.at(x, y, c)] = x < img.w / 2 ? left[c] : right[c];
    }
  add_noise(img, truth, 0.2f, 11);
  for (DenoiseFilter f : kFilters) {
    const DenoiseResult r = denoise(img.input(), {f, 2});
    for (int side = 0; side < 2; ++side) {
      const int x = img.w / 2 - 1 + side;
      for (int c = 0; c < 3; ++c) {
        const float want = side ? right[c] : left[c], step = std::fabs(right[c] - left[c]);
        double mean = 0.0;
        for (int y = 0; y < img.h; ++y) mean += r.rgb[img.at(x, y, c)];
        mean /= img.h;
        EXPECT_NEAR(mean, want, 0.1 * step) << name(f) << " column " << x << " channel " << c;
      }
    }
    // And it is denoised: the pixel error is well below the raw one.
    EXPECT_LT(mse_at(r.rgb, truth, img.w, img.h, 1), 0.3 * mse_at(img.a, truth, img.w, img.h, 1) / 2)
        << name(f);
  }
}

}  // namespace

TEST(Denoise, AlbedoStepEdgeStaysSharp) {
  const Rgb left{0.8f, 0.2f, 0.3f}, right{0.1f, 0.6f, 0.9f};
  expect_step_stays_sharp(left, right, [&](Halves& img, int x, int y) {
    for (int c = 0; c < 3; ++c) img.albedo[img.at(x, y, c)] = x < img.w / 2 ? left[c] : right[c];
  });
}

TEST(Denoise, NormalStepEdgeStaysSharp) {
  // A white crease: the left face towards the light (cos 1), the right one
  // turned 60 degrees from it (cos 0.5).
  const Rgb left{0.6f, 0.6f, 0.6f}, right{0.3f, 0.3f, 0.3f};
  expect_step_stays_sharp(left, right, [&](Halves& img, int x, int y) {
    const std::size_t i = img.at(x, y, 0);
    img.normal[i] = x < img.w / 2 ? 0.0f : std::sqrt(0.75f);
    img.normal[i + 2] = x < img.w / 2 ? 1.0f : 0.5f;
  });
}

namespace {

// A smooth image (a gradient) with a shadow's edge that no feature shows,
// at 128 x 128: what a filter blurs there is its bias.
std::vector<float> shadowed_gradient(const Halves& img) {
  std::vector<float> truth(img.a.size());
  for (int y = 0; y < img.h; ++y)
    for (int x = 0; x < img.w; ++x) {
      const float lit = (x - 40) * (x - 40) + (y - 60) * (y - 60) < 900 ? 0.3f : 1.0f;
      for (int c = 0; c < 3; ++c)
        truth[img.at(x, y, c)] = lit * (0.5f + 0.004f * float(x + c * y));
    }
  return truth;
}

void expect_within(double estimate, double truth, double factor, const std::string& what) {
  EXPECT_GT(estimate, truth / factor) << what << ": estimated " << estimate << ", true " << truth;
  EXPECT_LT(estimate, truth * factor) << what << ": estimated " << estimate << ", true " << truth;
}

}  // namespace

// The estimate of a made-up filter whose output is each half blurred over
// 3 x 3 plus a known bias of 4 % on the left half of the image: at every
// scale within 30 % of the true error, and its variance and bias parts
// within 30 % of theirs where each is the larger part.
TEST(Denoise, ErrorEstimateOfAKnownBiasIsNearTheTrueError) {
  Halves img(128, 128);
  const std::vector<float> truth = shadowed_gradient(img);
  add_noise(img, truth, 0.2f, 3);
  DenoiseResult r;
  r.width = img.w;
  r.height = img.h;
  r.rgb_a = r.rgb_b = r.rgb = img.a;
  for (int y = 0; y < img.h; ++y)
    for (int x = 0; x < img.w; ++x)
      for (int c = 0; c < 3; ++c) {
        double sa = 0.0, sb = 0.0;
        int n = 0;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int qx = std::clamp(x + dx, 0, img.w - 1), qy = std::clamp(y + dy, 0, img.h - 1);
            sa += img.a[img.at(qx, qy, c)];
            sb += img.b[img.at(qx, qy, c)];
            ++n;
          }
        const std::size_t i = img.at(x, y, c);
        const float bias = x < img.w / 2 ? 0.04f * truth[i] : 0.0f;
        r.rgb_a[i] = float(sa / n) + bias;
        r.rgb_b[i] = float(sb / n) + bias;
        r.rgb[i] = 0.5f * (r.rgb_a[i] + r.rgb_b[i]);
      }
  const std::vector<float> raw = img.raw();
  for (int k : {1, 2, 4, 8, 16}) {
    const ScaleError e = estimate_error(img.input(), r, k);
    const std::string at = std::to_string(k) + " px";
    expect_within(e.denoised_mse, mse_at(r.rgb, truth, img.w, img.h, k), 1.3, "denoised at " + at);
    expect_within(e.raw_mse, mse_at(raw, truth, img.w, img.h, k), 1.3, "raw at " + at);
  }
  // At pixel scale the variance is most of the error, at 16 px the bias.
  const ScaleError fine = estimate_error(img.input(), r, 1), coarse = estimate_error(img.input(), r, 16);
  EXPECT_GT(fine.denoised_variance, fine.denoised_bias2);
  EXPECT_GT(coarse.denoised_bias2, 3.0 * coarse.denoised_variance);
  // The bias alone: 4 % of the left half's values, squared, over the image.
  double bias2 = 0.0;
  for (int y = 0; y < img.h; ++y)
    for (int x = 0; x < img.w / 2; ++x)
      for (int c = 0; c < 3; ++c) bias2 += std::pow(0.04 * truth[img.at(x, y, c)], 2.0);
  expect_within(coarse.denoised_bias2, bias2 / double(img.a.size()), 1.3, "bias at 16 px");
}

// The filters' own estimate on the shadowed gradient: within a factor of
// 2 of the true error at every scale, and each filter better than the raw
// image at pixel scale and no worse than 1.2x it at 16 px.
TEST(Denoise, FiltersErrorEstimateIsWithinAFactorOfTheTrueError) {
  Halves img(256, 256);
  const std::vector<float> truth = shadowed_gradient(img);
  add_noise(img, truth, 0.1f, 8);
  const std::vector<float> raw = img.raw();
  for (DenoiseFilter f : kFilters) {
    const DenoiseResult r = denoise(img.input(), {f, 2});
    for (int k : {1, 2, 4, 8, 16}) {
      const ScaleError e = estimate_error(img.input(), r, k);
      const double true_mse = mse_at(r.rgb, truth, img.w, img.h, k);
      expect_within(e.denoised_mse, true_mse, 2.0, std::string(name(f)) + " at " + std::to_string(k) + " px");
      if (k == 1) {
        EXPECT_LT(true_mse, 0.25 * mse_at(raw, truth, img.w, img.h, 1)) << name(f);
      }
      if (k == 16) {
        EXPECT_LT(true_mse, 1.2 * mse_at(raw, truth, img.w, img.h, 16)) << name(f);
      }
    }
  }
}

namespace {

// The k x k block means of channel-interleaved `x` (blocks past the edge
// dropped).
std::vector<double> blocks(const std::vector<float>& x, int w, int h, int k) {
  std::vector<double> out(std::size_t(w / k) * (h / k) * 3, 0.0);
  for (int y = 0; y < h / k * k; ++y)
    for (int xx = 0; xx < w / k * k; ++xx)
      for (int c = 0; c < 3; ++c)
        out[(std::size_t(y / k) * (w / k) + xx / k) * 3 + c] += x[(std::size_t(y) * w + xx) * 3 + c] / (double(k) * k);
  return out;
}

double mean_square_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) s += (a[i] - b[i]) * (a[i] - b[i]);
  return s / double(a.size());
}

}  // namespace

// The shadowed gradient with little noise: a filter blurs the shadow's edge
// (no feature shows it), and past its own blur that bias is all its error.
// The output's coarse band is the raw image's: its 16 and 32 px block means
// are within 5 % of the raw image's error of the raw image's own (without
// the raw coarse band the fast filter's were 81 % at 16 px, and its error
// there 1.4 times the raw one), so at those scales it is no worse than the
// raw image, and at pixel scale still well below it.
TEST(Denoise, CoarseBandIsTheRawImages) {
  Halves img(256, 256);
  const std::vector<float> truth = shadowed_gradient(img);
  add_noise(img, truth, 0.02f, 21);
  const std::vector<float> raw = img.raw();
  for (DenoiseFilter f : kFilters) {
    const DenoiseResult r = denoise(img.input(), {f, 2});
    for (int k : {16, 32}) {
      const std::vector<double> out = blocks(r.rgb, img.w, img.h, k), in = blocks(raw, img.w, img.h, k),
                                t = blocks(truth, img.w, img.h, k);
      const double raw_err = mean_square_difference(in, t), out_err = mean_square_difference(out, t);
      const double apart = mean_square_difference(out, in);
      EXPECT_LT(apart, 0.05 * raw_err) << name(f) << " at " << k << " px";
      EXPECT_LT(out_err, 1.1 * raw_err) << name(f) << " at " << k << " px";
    }
    EXPECT_LT(mse_at(r.rgb, truth, img.w, img.h, 1), 0.5 * mse_at(raw, truth, img.w, img.h, 1)) << name(f);
  }
}

// The two halves are filtered side by side, each on its share of the
// threads and its rows in bands: the result is the same, value for value,
// on any number of threads.
TEST(Denoise, ResultDoesNotDependOnTheThreadCount) {
  Halves img(45, 37);
  add_noise(img, shadowed_gradient(img), 0.2f, 31);
  for (DenoiseFilter f : kFilters) {
    const DenoiseResult one = denoise(img.input(), {f, 1});
    for (int threads : {2, 3, 5}) {
      const DenoiseResult r = denoise(img.input(), {f, threads});
      EXPECT_EQ(r.rgb, one.rgb) << name(f) << " on " << threads << " threads";
      EXPECT_EQ(r.mse, one.mse) << name(f) << " on " << threads << " threads";
    }
  }
}

// Images smaller than the filters' reach, one pixel wide or tall among
// them (the taps past the edge weigh nothing): a constant image stays
// constant, a noisy one comes out finite.
TEST(Denoise, ImagesSmallerThanTheTapsAreFiltered) {
  for (const auto& [w, h] : {std::pair{1, 1}, std::pair{1, 6}, std::pair{7, 1}, std::pair{9, 3}}) {
    Halves img(w, h);
    const std::vector<float> flat(img.a.size(), 0.5f);
    img.a = img.b = flat;
    for (DenoiseFilter f : kFilters)
      for (float v : denoise(img.input(), {f, 2}).rgb) ASSERT_NEAR(v, 0.5f, 0.5e-6f) << name(f) << " " << w << " x " << h;
    add_noise(img, flat, 0.2f, 3);
    for (DenoiseFilter f : kFilters)
      for (float v : denoise(img.input(), {f, 2}).rgb) ASSERT_TRUE(std::isfinite(v)) << name(f) << " " << w << " x " << h;
  }
}

TEST(Denoise, BadInputIsRefusedWithAMessage) {
  auto message = [](const DenoiseInput& in) -> std::string {
    try {
      denoise(in);
    } catch (const DenoiseError& e) {
      return e.what();
    }
    return "accepted";
  };
  Halves img(3, 2);
  DenoiseInput in = img.input();
  in.colour_b = in.colour_b.first(12);
  EXPECT_EQ(message(in), "denoise: colour_b has 12 values, expected 18 (3 x 2 x 3)");
  in = img.input();
  in.depth_a = in.depth_a.first(5);
  EXPECT_EQ(message(in), "denoise: depth_a has 5 values, expected 6 (3 x 2 x 1)");
  img.normal[4] = NAN;  // pixel 1 of row 0
  EXPECT_EQ(message(img.input()), "denoise: normal_a is not finite at pixel (1, 0) (column, row)");
  img.normal[4] = 0.0f;
  img.b[3 * 5 + 2] = INFINITY;  // pixel 2 of row 1
  EXPECT_EQ(message(img.input()), "denoise: colour_b is not finite at pixel (2, 1) (column, row)");
  img.b[3 * 5 + 2] = 0.0f;
  in = img.input();
  in.width = 0;
  EXPECT_EQ(message(in), "denoise: image size 0 x 2 is empty");
  const DenoiseResult r = denoise(img.input());
  EXPECT_THROW(estimate_error(img.input(), r, 0), DenoiseError);
  EXPECT_THROW(estimate_error(img.input(), r, 3), DenoiseError);
  Halves other(2, 3);
  try {
    estimate_error(other.input(), r, 1);
    ADD_FAILURE() << "a result of another image was accepted";
  } catch (const DenoiseError& e) {
    EXPECT_STREQ(e.what(), "denoise: the result is of a 3 x 2 image, the input 2 x 3");
  }
}
