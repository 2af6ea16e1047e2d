// Accumulations (src/render/accumulation.h): through a whole render, double
// sums that keep their digits over millions of samples and non-finite
// samples dropped and counted; the counters a render carries beside its
// sums, and how parts and snapshots hand both on.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "closed_sphere.h"
#include "render/accumulation.h"
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
  EXPECT_EQ(s.counters.nan_count, 4u);
  EXPECT_EQ(s.sum[0], 0.0f);
  EXPECT_TRUE(std::isfinite(s.sum[0]));
}

namespace whisker {
namespace {

Accumulation part(SampleRange range, RenderCounters counters) {
  Accumulation a;
  a.width = 2;
  a.height = 1;
  a.sum = {1, 2, 3, 4, 5, 6};
  a.sum_sq = {1, 2};
  a.ranges = {range};
  a.counters = counters;
  a.id = {"room", "0123456789abcdef", R"({"seed":1})", estimator_identity()};
  return a;
}

TEST(RenderCounters, MergingAddsEveryField) {
  RenderCounters a{.passes = 2, .nan_count = 3, .rays = 1ull << 40, .seconds = 1.5};
  a += {.passes = 5, .nan_count = 0, .rays = 7, .seconds = 0.25};
  EXPECT_EQ(a.passes, 7u);
  EXPECT_EQ(a.nan_count, 3u);
  EXPECT_EQ(a.rays, (1ull << 40) + 7);
  EXPECT_EQ(a.seconds, 1.75);
  // Adding nothing changes nothing.
  const RenderCounters before = a;
  a += RenderCounters{};
  EXPECT_EQ(a, before);
}

TEST(RenderCounters, AMergeSumsThePartsCounters) {
  // Given out of sample order: the counters are the sums all the same.
  std::vector<NamedAccumulation> parts = {
      {"b.exr", part({4, 8}, {.passes = 1, .nan_count = 2, .rays = 100, .seconds = 0.5})},
      {"a.exr", part({0, 4}, {.passes = 3, .nan_count = 0, .rays = 50, .seconds = 2.0})},
  };
  const Accumulation merged = merge_accumulations(parts);
  EXPECT_EQ(merged.counters, (RenderCounters{.passes = 4, .nan_count = 2, .rays = 150, .seconds = 2.5}));
  EXPECT_EQ(merged.ranges, (std::vector<SampleRange>{{0, 8}}));
}

TEST(RenderCounters, SnapshotsAndAccumulationsHandThemOnWhole) {
  const RenderCounters c{.passes = 3, .nan_count = 5, .rays = 1ull << 40, .seconds = 12.25};
  const Accumulation a = part({16, 20}, c);
  const Snapshot s = snapshot_of(a);
  EXPECT_EQ(s.counters, c);
  const Accumulation back = accumulation_of(s, 16, a.id);
  EXPECT_EQ(back.counters, c);
  EXPECT_EQ(back.ranges, a.ranges);
  // The sums go through the snapshot exactly, so a checkpoint of a resumed
  // render writes what it read.
  EXPECT_EQ(back.sum, a.sum);
  EXPECT_EQ(back.sum_sq, a.sum_sq);
}

}  // namespace
}  // namespace whisker
