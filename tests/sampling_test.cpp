// The estimator's sampling helpers (render/sampling.h): sin/cos of a turn,
// the orthonormal frame, and cosine-weighted directions against their
// formula, moments and distribution.
#include <algorithm>

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <random>

#include <glm/geometric.hpp>

#include "render/sampling.h"

using namespace whisker;

namespace {

constexpr double kPi = 3.14159265358979323846;

}  // namespace

TEST(Sampling, SinCosOfATurnMatchesDoublePrecision) {
  double worst = 0.0;
  for (int k = 0; k <= 1 << 20; ++k) {
    const float u = float(k) / float(1 << 20);
    float s, c;
    sincos_turn(u, s, c);
    const double a = 2.0 * kPi * double(u);
    worst = std::max({worst, std::fabs(s - std::sin(a)), std::fabs(c - std::cos(a))});
  }
  EXPECT_LT(worst, 1e-7);
}

// log_positive() (the AA jitter's Box-Muller radius) against double
// precision: at every uniform the camera can draw (1 - k 2^-24, the
// sampler's 24-bit numbers) and across every binade of positive normal
// floats, within 2e-7 of the logarithm, relative.
TEST(Sampling, LogarithmMatchesDoublePrecision) {
  double worst = 0.0;
  for (std::uint32_t k = 0; k < (1u << 24); ++k) {
    const float u = 1.0f - float(k) * 0x1p-24f;
    const double truth = std::log(double(u));
    const double err = std::fabs(double(log_positive(u)) - truth);
    worst = std::max(worst, truth == 0.0 ? err : err / std::fabs(truth));
  }
  EXPECT_LT(worst, 2e-7);
  worst = 0.0;
  for (std::uint32_t b = 0x00800000u; b < 0x7f800000u; b += 4099u) {
    const float u = std::bit_cast<float>(b);
    const double truth = std::log(double(u));
    const double err = std::fabs(double(log_positive(u)) - truth);
    worst = std::max(worst, truth == 0.0 ? err : err / std::fabs(truth));
  }
  EXPECT_LT(worst, 2e-7);
  EXPECT_EQ(log_positive(1.0f), 0.0f);
}

// The same formulas on eight lanes (__m256, the camera's rays side by
// side) give each lane what one float gives, to a rounding.
TEST(Sampling, EightLanesComputeWhatOneFloatComputes) {
  std::mt19937 g(11);
  std::uniform_real_distribution<float> uni(0.0f, 1.0f);
  for (int round = 0; round < 20000; ++round) {
    alignas(32) float u[8];
    for (float& x : u) x = round == 0 ? 1.0f : uni(g);
    const __m256 v = _mm256_load_ps(u);
    const __m256 lg = log_positive(v);
    __m256 s8, c8;
    sincos_turn(v, s8, c8);
    for (int l = 0; l < 8; ++l) {
      float s, c;
      sincos_turn(u[l], s, c);
      ASSERT_NEAR(s8[l], s, 1e-7f) << u[l];
      ASSERT_NEAR(c8[l], c, 1e-7f) << u[l];
      ASSERT_NEAR(lg[l], log_positive(u[l]), 2e-7f * std::fabs(log_positive(u[l])) + 1e-30f) << u[l];
    }
  }
}

TEST(Sampling, CosineSamplingHasTheRightMoments) {
  // For p(w) = cos/pi: E[cos] = 2/3, E[cos^2] = 1/2, and the tangential
  // components average to zero.
  std::mt19937 g(5);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const vec3 n = glm::normalize(vec3(0.3f, -0.5f, 0.8f));
  double c1 = 0, c2 = 0;
  vec3 mean(0.0f);
  const int N = 400000;
  for (int k = 0; k < N; ++k) {
    const vec3 w = cosine_direction(n, u(g), u(g));
    const double c = glm::dot(w, n);
    ASSERT_GE(c, 0.0);
    c1 += c;
    c2 += c * c;
    mean += w - float(c) * n;
  }
  EXPECT_NEAR(c1 / N, 2.0 / 3.0, 5 * std::sqrt(1.0 / 18.0 / N));  // var(cos) = 1/2 - 4/9
  EXPECT_NEAR(c2 / N, 0.5, 5 * std::sqrt(1.0 / 12.0 / N));
  EXPECT_LT(glm::length(mean) / N, 3e-3);
}

// The direction is built from an orthonormal basis without a final
// normalisation: it must be unit to a few ULP for every normal, including
// the basis' special case n.z = -1 and its neighbourhood.
TEST(Sampling, CosineDirectionsAreUnitWithoutNormalising) {
  std::mt19937 g(6);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  double worst = 0.0;
  for (const vec3 n : {glm::normalize(vec3(0.3f, -0.5f, 0.8f)), vec3(0.0f, 0.0f, -1.0f),
                       glm::normalize(vec3(1e-4f, -2e-4f, -1.0f)), vec3(1.0f, 0.0f, 0.0f),
                       glm::normalize(vec3(-0.6f, 0.7f, -0.2f))}) {
    for (int k = 0; k < 100000; ++k) {
      const glm::dvec3 w(cosine_direction(n, u(g), u(g)));
      worst = std::max(worst, std::fabs(glm::length(w) - 1.0));
    }
  }
  EXPECT_LT(worst, 1e-6) << worst;
}

// The frame around n is orthonormal and right-handed, including n.z = -1.
TEST(Sampling, FrameIsOrthonormalAroundAnyNormal) {
  for (const vec3 n : {vec3(0, 0, 1), vec3(0, 0, -1), glm::normalize(vec3(0.3f, -0.5f, 0.8f)),
                       glm::normalize(vec3(1e-4f, 2e-4f, -1.0f)), vec3(1, 0, 0)}) {
    const Frame f(n);
    EXPECT_NEAR(glm::length(f.b1), 1.0f, 1e-6f);
    EXPECT_NEAR(glm::length(f.b2), 1.0f, 1e-6f);
    EXPECT_NEAR(glm::dot(f.b1, f.b2), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::dot(f.b1, n), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::dot(f.b2, n), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::length(glm::cross(f.b1, f.b2) - n), 0.0f, 1e-6f);
  }
}

// The direction is the formula the code cites: cos(theta) = sqrt(u2), the
// azimuth 2 pi u1 from b1 towards b2.
TEST(Sampling, CosineDirectionFollowsItsFormula) {
  const Frame f(glm::normalize(vec3(-0.6f, 0.7f, -0.2f)));
  for (const float u1 : {0.0f, 0.1f, 0.25f, 0.6f, 0.95f}) {
    for (const float u2 : {0.0f, 0.2f, 0.5f, 0.99f}) {
      const vec3 w = cosine_direction(f, u1, u2);
      const double r = std::sqrt(1.0 - u2), a = 2.0 * kPi * u1;
      EXPECT_NEAR(glm::dot(w, f.n), std::sqrt(double(u2)), 1e-6);
      EXPECT_NEAR(glm::dot(w, f.b1), r * std::cos(a), 1e-6);
      EXPECT_NEAR(glm::dot(w, f.b2), r * std::sin(a), 1e-6);
    }
  }
}

// The pdf cos/pi: the mean direction is 2/3 n, and cos(theta) has the
// distribution P(cos <= c) = c^2 (chi-square over 20 equal-probability
// bins, 19 degrees of freedom: P(chi2 > 50) < 1e-4).
TEST(Sampling, CosineSamplingHasTheRightMeanAndDistribution) {
  std::mt19937 g(9);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const vec3 n = glm::normalize(vec3(0.2f, 0.9f, -0.4f));
  const int N = 200000, bins = 20;
  std::vector<int> count(bins, 0);
  glm::dvec3 mean(0.0);
  for (int k = 0; k < N; ++k) {
    const vec3 w = cosine_direction(n, u(g), u(g));
    mean += glm::dvec3(w);
    const double c = std::clamp(double(glm::dot(w, n)), 0.0, 1.0);
    ++count[std::min(bins - 1, int(c * c * bins))];  // c^2 is uniform
  }
  mean /= double(N);
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(mean[a], 2.0 / 3.0 * n[a], 4e-3) << a;
  double chi2 = 0.0;
  const double expect = double(N) / bins;
  for (const int c : count) chi2 += (c - expect) * (c - expect) / expect;
  EXPECT_LT(chi2, 50.0);
}
