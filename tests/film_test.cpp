// The film (render/film.h): its noise figures (the pixel figure from the
// sums of squares, the scale figures from the two half images, and the
// figure the stats and the viewer show, which must not read low when pixels
// share their errors, nor overflow or underflow at extreme intensities),
// and pixel sums that drop non-finite samples.
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include <glm/vec3.hpp>

#include "render/film.h"
#include "same_bits.h"

namespace whisker {
namespace {

using glm::vec3;

constexpr int kSide = 128;

// A grey snapshot of two samples per pixel (indices 0 and 1), the image 1
// plus noise of standard deviation sigma per sample: independent per pixel,
// or one value shared by each block x block square.
Snapshot two_sample_snapshot(double sigma, int block, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  Snapshot s;
  s.width = s.height = kSide;
  s.spp = 2;
  s.first_sample = 0;
  s.sum.assign(std::size_t(kSide) * kSide * 3, 0.0f);
  s.sum_sq.assign(std::size_t(kSide) * kSide, 0.0);
  s.odd_sum.assign(std::size_t(kSide) * kSide, 0.0);
  const int blocks = kSide / block;
  std::vector<double> shared(std::size_t(blocks) * blocks * 2);
  for (double& v : shared) v = noise(rng);
  for (int y = 0; y < kSide; ++y)
    for (int x = 0; x < kSide; ++x) {
      const std::size_t p = std::size_t(y) * kSide + x, b = std::size_t(y / block) * blocks + x / block;
      // Grey: luminance = the channel value (the weights sum to 1).
      const double even = 1.0 + shared[2 * b], odd = 1.0 + shared[2 * b + 1];
      for (int c = 0; c < 3; ++c) s.sum[3 * p + c] = float(even + odd);
      s.sum_sq[p] = even * even + odd * odd;
      s.odd_sum[p] = odd;
    }
  return s;
}

TEST(FilmNoise, IndependentPixelsReadTheSameAtEveryScale) {
  const double sigma = 0.2;
  const Snapshot s = two_sample_snapshot(sigma, 1, 7);
  // The standard error of a 2-sample mean, relative to the mean 1.
  const double expected = sigma / std::sqrt(2.0);
  EXPECT_NEAR(s.pixel_standard_error(), expected, 0.05 * expected);
  for (int k : {2, 4, 8}) EXPECT_NEAR(s.scale_standard_error(k), expected, 0.2 * expected) << k;
}

TEST(FilmNoise, BlocksSharingTheirErrorsReadHigherAtTheirScale) {
  // 4 x 4 blocks share their noise: per pixel the same variance, but a 4 x 4
  // box filter averages nothing away, so the scale figure is 4x the pixel's.
  const double sigma = 0.2;
  const Snapshot s = two_sample_snapshot(sigma, 4, 11);
  const double pixel = s.pixel_standard_error();
  EXPECT_NEAR(pixel, sigma / std::sqrt(2.0), 0.1 * sigma);
  EXPECT_NEAR(s.scale_standard_error(4), 4.0 * pixel, 0.8 * pixel);
  EXPECT_NEAR(s.scale_standard_error(8), 4.0 * pixel, 0.8 * pixel);  // 2x2 independent blocks
  // The figure shown is the worst scale's, never the pixel one.
  EXPECT_GT(s.relative_standard_error(), 3.0 * pixel);
}

TEST(FilmNoise, NoiseFreeImageReadsZero) {
  const Snapshot s = two_sample_snapshot(0.0, 1, 3);
  EXPECT_EQ(s.pixel_standard_error(), 0.0);
  for (int k : kNoiseScales) EXPECT_EQ(s.scale_standard_error(k), 0.0) << k;
  EXPECT_EQ(s.relative_standard_error(), 0.0);
}

TEST(FilmNoise, WithoutHalvesTheScaleFiguresAreUnknownAndThePixelFigureShows) {
  Snapshot s = two_sample_snapshot(0.2, 4, 5);
  s.odd_sum.clear();  // a resumed part: the halves are not known
  for (int k : kNoiseScales) EXPECT_TRUE(std::isnan(s.scale_standard_error(k))) << k;
  EXPECT_EQ(s.relative_standard_error(), s.pixel_standard_error());
}

TEST(FilmNoise, OddSamplesCountFromTheFirstSampleIndex) {
  // Samples 1 and 2: sample 1 is the odd one. With first_sample 1 and the
  // odd sums holding sample 1's values, the same figure as indices 0 and 1
  // with the halves swapped; one sample of either parity gives nothing.
  Snapshot s = two_sample_snapshot(0.2, 1, 9);
  const double base = s.scale_standard_error(2);
  Snapshot shifted = s;
  shifted.first_sample = 1;
  for (std::size_t p = 0; p < s.odd_sum.size(); ++p)
    shifted.odd_sum[p] = double(s.sum[3 * p]) - s.odd_sum[p];
  EXPECT_NEAR(shifted.scale_standard_error(2), base, 1e-6 * base);
  s.spp = 1;
  EXPECT_TRUE(std::isnan(s.scale_standard_error(2)));
}

TEST(FilmNoise, PixelSumsTakeOddIndicesIntoTheOddHalf) {
  PixelSum p;
  p.add(glm::vec3(1.0f), 4);
  p.add(glm::vec3(2.0f), 5);
  p.add(glm::vec3(NAN), 7);  // dropped: no half gets it
  EXPECT_NEAR(p.odd_sum, 2.0, 1e-6);  // its luminance (weights summing to 1 in float)
  EXPECT_DOUBLE_EQ(p.sum.x, 3.0);
  EXPECT_EQ(p.dropped, 1u);
}

TEST(Film, NonFiniteSamplesAreDroppedAndCountedAndLuminanceIsRec709) {
  PixelSum p;
  p.add(vec3(1.0f, 2.0f, 4.0f), 0);
  p.add(vec3(NAN, 0.0f, 0.0f), 1);
  p.add(vec3(0.0f, INFINITY, 0.0f), 2);
  p.add(vec3(1.0f, 0.0f, 0.0f), 3);
  EXPECT_EQ(p.dropped, 2u);
  EXPECT_EQ(p.sum, glm::dvec3(2.0, 2.0, 4.0));
  const double y1 = 0.2126f * 1.0f + 0.7152f * 2.0f + 0.0722f * 4.0f, y2 = 0.2126f;
  EXPECT_EQ(p.sum_sq, y1 * y1 + y2 * y2);

  Film film;
  film.reset(2, 1);
  film.add(1, p);
  Snapshot s;
  film.publish(s);
  s.spp = 2;
  const Image img = mean_image(s);
  EXPECT_EQ(img.width, 2);
  EXPECT_EQ(img.rgb, std::vector<float>({0, 0, 0, 1, 1, 2}));
}


TEST(Film, RelativeStandardErrorIsFiniteAndScaleInvariant) {
  // Two pixels, four samples each, scaled by 1, 1e30 and 1e-30: squares of
  // 1e30 overflow float and squares of 1e-30 underflow it.
  const auto snapshot = [](double k) {
    Snapshot s;
    s.width = 2;
    s.height = 1;
    s.spp = 4;
    const double samples[2][4] = {{1, 2, 3, 4}, {0.5, 0.5, 1.5, 2.5}};
    for (const auto& px : samples) {
      double sum = 0, sq = 0;
      for (double v : px) {
        sum += v * k;
        sq += (v * k) * (v * k);
      }
      for (int c = 0; c < 3; ++c) s.sum.push_back(float(sum));
      s.sum_sq.push_back(sq);
    }
    return s;
  };
  const double e1 = snapshot(1).relative_standard_error();
  // By hand: variances of the mean (5/3)/4 and (11/12)/4, mean of means 1.875.
  EXPECT_NEAR(e1, std::sqrt((20.0 / 48 + 11.0 / 48) / 2) / 1.875, 1e-6);
  for (double k : {1e30, 1e-30}) {
    const double e = snapshot(k).relative_standard_error();
    EXPECT_TRUE(std::isfinite(e)) << k;
    EXPECT_NEAR(e, e1, 1e-5 * e1) << k;
  }
}

// A pass of 3 samples (indices first..first+2) at each of 2 pixels, with
// features varied by pixel and sample.
PixelSum feature_pass(std::uint32_t pixel, std::uint64_t first) {
  PixelSum p;
  for (std::uint64_t i = first; i < first + 3; ++i) {
    const float t = 0.1f * float(i) + 0.37f * float(pixel);
    p.add(vec3(t, 2.0f * t, 0.5f + t), i);
    p.add_features(vec3(0.3f + t, 0.2f, 0.1f * t), vec3(-t, 0.5f, t - 1.0f), 10.0f + t, i);
  }
  return p;
}

// A resumed film: loaded with a part's feature sums, it goes on to the
// feature sums of the film that never stopped, bit for bit; loaded without
// them it publishes none.
TEST(Film, LoadedFeatureSumsGoOnExactly) {
  Film whole, resumed, plain;
  whole.reset(2, 1, true);
  for (std::uint32_t px = 0; px < 2; ++px) whole.add(px, feature_pass(px, 0));
  Snapshot part;
  whole.publish(part);
  ASSERT_EQ(part.features.size(), 2u * kFeatureSums);
  for (std::uint32_t px = 0; px < 2; ++px) whole.add(px, feature_pass(px, 3));
  resumed.reset(2, 1, true);
  resumed.load(part.sum, part.sum_sq, part.odd_rgb, part.features);
  for (std::uint32_t px = 0; px < 2; ++px) resumed.add(px, feature_pass(px, 3));
  Snapshot a, b;
  whole.publish(a);
  resumed.publish(b);
  EXPECT_TRUE(same_bits(a.features, b.features));
  EXPECT_TRUE(same_bits(a.odd_rgb, b.odd_rgb));
  EXPECT_TRUE(same_bits(a.sum, b.sum));
  EXPECT_TRUE(b.odd_sum.empty());  // the luminance halves are not in a part
  plain.reset(2, 1, true);
  plain.load(part.sum, part.sum_sq);
  plain.publish(b);
  EXPECT_TRUE(b.features.empty());
  EXPECT_TRUE(b.odd_rgb.empty());
}

}  // namespace
}  // namespace whisker
