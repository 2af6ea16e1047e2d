// Test helper: render a scene to its target samples per pixel and return the
// final snapshot, through the same ProgressiveRenderer the app uses.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "render/progressive.h"
#include "scene/scene_io.h"

namespace whisker {

// A bundled scene at a small size, with its samples per pass and target.
inline Scene sized(const char* name, int width, int height, int spp_per_pass, int target) {
  Scene s = load_scene(resolve_scene(name));
  s.camera.width = width;
  s.camera.height = height;
  s.settings.spp = spp_per_pass;
  s.settings.target_spp = target;
  return s;
}

inline Snapshot render(const Scene& scene, int threads = 0) {
  ProgressiveRenderer r(threads);
  const auto gen = r.set_scene(scene);
  r.start();
  EXPECT_TRUE(r.wait_for(gen, std::uint64_t(scene.settings.target_spp)));
  Snapshot s;
  r.snapshot(s);
  r.stop();
  return s;
}

// A pixel's luminance mean and its squared standard error, from a
// snapshot's per-sample sums.
struct PixelStat {
  double mean, se2;
};
inline PixelStat pixel_stat(const Snapshot& s, std::size_t p) {
  const double n = double(s.spp);
  const double mean = (kLuminanceWeights[0] * s.sum[3 * p] + kLuminanceWeights[1] * s.sum[3 * p + 1] +
                       kLuminanceWeights[2] * s.sum[3 * p + 2]) / n;
  const double var = std::max(0.0, (s.sum_sq[p] / n - mean * mean) * n / (n - 1.0));
  return {mean, var / n};
}

// Two independent renders a and b of estimators with the same expectation:
// every pixel's difference over its standard error is a z-score; their
// squares sum to about the pixel count (chi-square; its standard deviation
// is sqrt(2 x count)), and no single one is far out. Returns the median
// ratio of the pixels' variances, b's over a's.
inline double expect_same_expectation(const Snapshot& a, const Snapshot& b, const char* what) {
  EXPECT_EQ(a.counters.nan_count, 0u) << what;
  EXPECT_EQ(b.counters.nan_count, 0u) << what;
  double chi2 = 0.0;
  int counted = 0;
  std::vector<double> ratios;
  const std::size_t pixels = std::size_t(a.width) * std::size_t(a.height);
  for (std::size_t p = 0; p < pixels; ++p) {
    const PixelStat pa = pixel_stat(a, p), pb = pixel_stat(b, p);
    if (pa.se2 > 0.0) ratios.push_back(pb.se2 / pa.se2);
    const double se2 = pa.se2 + pb.se2;
    if (se2 <= 1e-12 * pa.mean * pa.mean) {  // noise-free (direct light only)
      EXPECT_NEAR(pb.mean, pa.mean, 1e-4 * pa.mean + 1e-9) << what << " pixel " << p;
      continue;
    }
    const double z = (pb.mean - pa.mean) / std::sqrt(se2);
    EXPECT_LT(std::abs(z), 5.5) << what << " pixel " << p;
    chi2 += z * z;
    ++counted;
  }
  EXPECT_GT(counted, int(pixels / 2)) << what;
  EXPECT_LT(chi2, counted + 6.0 * std::sqrt(2.0 * counted)) << what;
  if (ratios.empty()) return 1.0;
  std::nth_element(ratios.begin(), ratios.begin() + ratios.size() / 2, ratios.end());
  return ratios[ratios.size() / 2];
}

}  // namespace whisker
