// The progressive renderer: determinism across thread counts and pass
// sizes, generations that never mix, snapshots that stay consistent.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "render/progressive.h"
#include "scene/scene_io.h"
#include "render_util.h"

using namespace whisker;

namespace {

// The three balls with everything random switched on, small enough to be quick.
Scene small_scene(int spp_per_pass, int target) {
  Scene s = load_scene(resolve_scene("three-balls"));
  s.camera.width = 48;
  s.camera.height = 40;
  s.settings.indirect = s.settings.fresnel = s.settings.aa = true;
  s.settings.spp = spp_per_pass;
  s.settings.target_spp = target;
  s.settings.seed = 42;
  return s;
}

}  // namespace

TEST(Progressive, SameImageForAnyThreadCountAndPassSize) {
  const Snapshot one = render(small_scene(2, 8), 1);
  const Snapshot two = render(small_scene(2, 8), 2);
  const Snapshot five = render(small_scene(8, 8), 5);  // one pass of 8 on 5 threads
  ASSERT_EQ(one.spp, 8u);
  ASSERT_EQ(two.spp, 8u);
  ASSERT_EQ(five.spp, 8u);
  EXPECT_EQ(one.sum, two.sum);  // bit-identical
  EXPECT_EQ(one.sum_sq, two.sum_sq);
  // Pass size changes only the order of double additions of float samples.
  for (std::size_t k = 0; k < one.sum.size(); ++k) ASSERT_NEAR(one.sum[k], five.sum[k], 1e-5f * std::abs(one.sum[k]) + 1e-9f);
  EXPECT_EQ(one.passes, 4u);
  EXPECT_EQ(five.passes, 1u);
  EXPECT_GT(one.rays, std::uint64_t(48 * 40 * 8));
}

TEST(Progressive, DifferentSeedsGiveDifferentNoise) {
  Scene a = small_scene(4, 4), b = small_scene(4, 4);
  b.settings.seed = 43;
  EXPECT_NE(render(a, 2).sum, render(b, 2).sum);
}

// An edit mid-render (here a light move after some passes) ends with exactly
// the image a fresh render of the new scene gives: no sample of the old
// generation leaks in.
TEST(Progressive, RestartDiscardsOldSamples) {
  Scene before = small_scene(1, 0);  // no target: keeps rendering
  Scene after = small_scene(1, 6);
  after.light.position = vec3(15.0f, 10.0f, 30.0f);

  ProgressiveRenderer r(2);
  const auto g1 = r.set_scene(before);
  r.start();
  ASSERT_TRUE(r.wait_for(g1, 3));
  const auto g2 = r.set_scene(after);
  EXPECT_GT(g2, g1);
  ASSERT_TRUE(r.wait_for(g2, 6));
  Snapshot s;
  r.snapshot(s);
  r.stop();
  EXPECT_EQ(s.generation, g2);
  EXPECT_EQ(s.spp, 6u);
  EXPECT_TRUE(s.done);

  const Snapshot fresh = render(after, 1);
  EXPECT_EQ(s.sum, fresh.sum);
}

TEST(Progressive, PauseStopsAccumulationAndSnapshotsStayConsistent) {
  ProgressiveRenderer r(2);
  const auto gen = r.set_scene(small_scene(1, 0));
  r.start();
  ASSERT_TRUE(r.wait_for(gen, 2));
  r.set_paused(true);
  // Wait for the running pass to end: the renderer reports no pass in
  // flight once it has published that pass and waits in the pause (a fixed
  // sleep was too short for a sanitizer build on a loaded machine).
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (r.pass_progress().rendering && std::chrono::steady_clock::now() < give_up)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  ASSERT_FALSE(r.pass_progress().rendering) << "the pass in flight did not end within 30 s";
  Snapshot a;
  r.snapshot(a);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  Snapshot b = a;
  EXPECT_FALSE(r.snapshot(b)) << "no new pass while paused";
  r.set_paused(false);
  ASSERT_TRUE(r.wait_for(gen, a.spp + 2));
  Snapshot c;
  r.snapshot(c);
  r.stop();
  EXPECT_GT(c.spp, a.spp);
  // Sums and count travel together: the mean of an all-positive-light
  // image stays bounded while samples are added (a torn copy would show a
  // sum of n+1 samples over n).
  EXPECT_EQ(c.sum.size(), std::size_t(48 * 40 * 3));
  EXPECT_EQ(c.generation, gen);
}

TEST(Progressive, ReachingTheTargetStops) {
  ProgressiveRenderer r(2);
  Scene s = small_scene(3, 7);
  const auto gen = r.set_scene(s);
  r.start();
  ASSERT_TRUE(r.wait_for(gen, 7));
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  Snapshot snap;
  r.snapshot(snap);
  r.stop();
  EXPECT_EQ(snap.spp, 7u);  // 3 + 3 + 1: the last pass is trimmed to the target
  EXPECT_EQ(snap.passes, 3u);
  EXPECT_TRUE(snap.done);
}

// With previews on, a new generation first shows a coarse image (one sample
// per 4x4 block, flagged) ...
TEST(Progressive, CoarsePreviewComesFirst) {
  // Full size on one worker: the first real pass takes far longer than the
  // preview (1/16 of its samples), so polling sees the preview.
  Scene scene = load_scene(resolve_scene("indirect"));
  scene.settings.target_spp = 1;
  ProgressiveRenderer r(1);
  r.set_preview(true);
  const auto gen = r.set_scene(scene);
  r.start();
  Snapshot first;
  while (!r.snapshot(first)) std::this_thread::yield();
  EXPECT_TRUE(first.preview);
  EXPECT_EQ(first.generation, gen);
  EXPECT_EQ(first.spp, 1u);
  for (int y = 0; y < 4; ++y)  // blocks of 4x4 share one value
    for (int x = 0; x < 4; ++x) EXPECT_EQ(first.mean(x + 200, y + 300, 2), first.mean(200, 300, 2));
  ASSERT_TRUE(r.wait_for(gen, 1));  // previews never satisfy a wait
  Snapshot done;
  r.snapshot(done);
  r.stop();
  EXPECT_FALSE(done.preview);
  EXPECT_EQ(done.spp, 1u);
  EXPECT_EQ(done.passes, 1u);
}

// ... and the accumulation that follows is exactly the one without
// previews: the preview never mixes in, also across an edit.
TEST(Progressive, CoarsePreviewIsNeverAccumulated) {
  const Scene before = small_scene(1, 0);
  Scene after = small_scene(2, 4);
  after.light.position = vec3(5.0f, 20.0f, 30.0f);
  ProgressiveRenderer r(2);
  r.set_preview(true);
  const auto g1 = r.set_scene(before);
  r.start();
  ASSERT_TRUE(r.wait_for(g1, 2));
  const auto g2 = r.set_scene(after);
  ASSERT_TRUE(r.wait_for(g2, 4));
  Snapshot s;
  r.snapshot(s);
  r.stop();
  EXPECT_FALSE(s.preview);
  EXPECT_EQ(s.sum, render(after, 1).sum);
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
  film.reset(2, 1, false);
  film.add(1, p);
  Snapshot s;
  film.publish(s, false);
  s.spp = 2;
  const Image img = mean_image(s);
  EXPECT_EQ(img.width, 2);
  EXPECT_EQ(img.rgb, std::vector<float>({0, 0, 0, 1, 1, 2}));
}
