// The accumulated image (render/accumulation.h) through a whole render:
// double sums that keep their digits over millions of samples, and
// non-finite samples dropped and counted.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "closed_sphere.h"
#include "render_util.h"

using namespace whisker;

// Sums over millions of samples keep their digits: 2^21 samples of one pixel
// whose every path has the same value still give that value to 1e-6.
TEST(Accumulation, MillionsOfSamplesKeepPrecision) {
  Scene scene = closed_sphere(0.6f, vec3(0.0f), 2, 1 << 17, 1);
  scene.settings.target_spp = 1 << 21;
  const Snapshot s = render(scene);
  ASSERT_EQ(s.spp, std::uint64_t(1) << 21);
  const double rho = 0.6, expect = rho * 1000.0 / (kPi * 100.0) * (1 - rho * rho * rho) / (1 - rho) / (4 * kPi);
  // A float running sum would be off by ~1e-3 here; the buffer is double.
  EXPECT_NEAR(double(s.sum[0]) / double(s.spp), expect, 1e-6 * expect);
}

TEST(Accumulation, InfiniteSamplesAreDroppedAndCounted) {
  // A light a hundred-thousandth above the ball's surface (a few float ULPs
  // at the 45 units from the camera that render space measures), at huge
  // intensity: the direct term overflows float to +inf on the pixel that
  // looks straight at it.
  Scene scene;
  scene.spheres.push_back({"ball", vec3(0.0f), 10.0f, 0.0f, {MaterialKind::Diffuse, vec3(1.0f)}});
  scene.light = {vec3(0.0f, 0.0f, 10.00001f), 1e36f};
  scene.camera.width = scene.camera.height = 1;
  scene.settings.spp = scene.settings.target_spp = 4;
  const Snapshot s = render(scene);
  EXPECT_EQ(s.nan_count, 4u);
  EXPECT_EQ(s.sum[0], 0.0f);
  EXPECT_TRUE(std::isfinite(s.sum[0]));
}
