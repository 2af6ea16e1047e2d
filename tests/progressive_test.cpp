// The progressive renderer: determinism across thread counts and pass
// sizes, generations that never mix, snapshots that stay consistent, a
// raised target that continues the accumulation, and pass progress.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>
#include <vector>

#include "render/integrator.h"
#include "render/light_cache.h"
#include "render/progressive.h"
#include "render/quick_passes.h"
#include "scene/scene_io.h"
#include "scene/world.h"
#include "render_util.h"

using namespace whisker;

namespace {

// The three balls with everything random switched on, small enough to be quick.
Scene small_scene(int spp_per_pass, int target) {
  Scene s = sized("three-balls", 48, 40, spp_per_pass, target);
  s.settings.indirect = s.settings.fresnel = s.settings.aa = true;
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
  EXPECT_EQ(one.counters.passes, 4u);
  EXPECT_EQ(five.counters.passes, 1u);
  EXPECT_GT(one.counters.rays, std::uint64_t(48 * 40 * 8));
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
  EXPECT_EQ(snap.counters.passes, 3u);
  EXPECT_TRUE(snap.done);
}

// The viewer's growing passes: at 16 samples per pass the first image of a
// generation is one sample, and the passes double (1, 1, 2, 4, 8, 16, 16)
// up to the pass size: 48 spp in 7 passes instead of 3, the same samples.
TEST(Progressive, GrowingPassesStartAtOneSample) {
  Snapshot last;
  for (const bool growing : {false, true}) {
    ProgressiveRenderer r(2);
    r.set_growing_passes(growing);
    std::vector<std::uint64_t> published;  // each pass's spp, seen by the publishing worker
    r.set_on_publish([&] {
      Snapshot s;
      r.snapshot(s);
      published.push_back(s.spp);
    });
    const auto gen = r.set_scene(small_scene(16, 48));
    r.start();
    ASSERT_TRUE(r.wait_for(gen, 48));
    r.stop();
    r.take_snapshot(last);
    EXPECT_EQ(last.spp, 48u);
    const std::vector<std::uint64_t> expected =
        growing ? std::vector<std::uint64_t>{1, 2, 4, 8, 16, 32, 48} : std::vector<std::uint64_t>{16, 32, 48};
    EXPECT_EQ(published, expected) << (growing ? "growing" : "fixed") << " passes";
    EXPECT_EQ(last.counters.passes, expected.size());
  }
  // The same samples as 16-sample passes, summed in another order.
  const Snapshot fixed = render(small_scene(16, 48), 2);
  ASSERT_EQ(fixed.sum.size(), last.sum.size());
  for (std::size_t k = 0; k < fixed.sum.size(); ++k)
    ASSERT_NEAR(fixed.sum[k], last.sum[k], 1e-5 * std::abs(fixed.sum[k]) + 1e-9);
}

TEST(Progressive, QuickPassesComeFirstAtFullResolution) {
  // The viewer's quick passes (set_quick_passes): an edit's first images are
  // whole passes of one path per sample, published apart from the
  // generation's own, pixel for pixel what a render with the quick settings
  // gives.
  Scene scene = sized("indirect", 96, 80, 1, 2);
  scene.settings.split = {4, 4};
  ASSERT_TRUE(quick_differs(scene.settings));
  ProgressiveRenderer r(1);
  r.set_quick_passes(true);
  const auto gen = r.set_scene(scene);
  r.start();
  Snapshot quick;
  while (!r.quick_snapshot(quick)) std::this_thread::yield();
  EXPECT_EQ(quick.generation, gen);
  // The latest quick pass: usually the first, but another may have landed
  // before this thread looked (one pass of this size takes milliseconds).
  ASSERT_GE(quick.spp, 1u);
  EXPECT_EQ(quick.stride, 1);
  ASSERT_TRUE(r.wait_for(gen, 2));
  Snapshot own;
  r.snapshot(own);
  r.stop();
  Scene cheap = scene;
  cheap.settings = quick_settings(scene.settings);
  cheap.settings.target_spp = int(quick.spp);
  EXPECT_EQ(quick.sum, render(cheap, 1).sum);
  // No 4x4 blocks: most horizontal neighbours differ (each pixel its own path).
  int differ = 0, pairs = 0;
  for (int y = 0; y < quick.height; ++y)
    for (int x = 0; x + 1 < quick.width; ++x, ++pairs)
      differ += quick.mean(x, y, 0) + quick.mean(x, y, 1) + quick.mean(x, y, 2) !=
                quick.mean(x + 1, y, 0) + quick.mean(x + 1, y, 1) + quick.mean(x + 1, y, 2);
  EXPECT_GT(differ, pairs / 2);
  EXPECT_FALSE(own.quick);
  EXPECT_EQ(own.spp, 2u);
  EXPECT_EQ(own.counters.passes, 2u);
  EXPECT_EQ(own.sum, render(scene, 1).sum);  // the quick passes never mix in
}

// While the mouse drags (set_dragging), a quick pass renders one path per
// 2 x 2 pixels on the same image plane: pixel for pixel a render of the
// quick settings at half the size, flagged with its stride. An edit made
// after the drag gets full-size quick passes again.
TEST(Progressive, QuickPassesWhileDraggingAreCoarseThenFullSize) {
  Scene scene = sized("indirect", 96, 80, 1, 2);
  scene.settings.split = {4, 4};
  ProgressiveRenderer r(1);
  r.set_quick_passes(true);
  r.set_dragging(true);  // before the first pass: no full-size pass timed yet
  const auto gen = r.set_scene(scene);
  r.start();
  Snapshot quick;
  while (!r.quick_snapshot(quick)) std::this_thread::yield();
  ASSERT_EQ(quick.generation, gen);
  EXPECT_EQ(quick.stride, 2);
  EXPECT_EQ(quick.width, 48);
  EXPECT_EQ(quick.height, 40);
  ASSERT_GE(quick.spp, 1u);
  Scene coarse = scene;
  coarse.settings = quick_settings(scene.settings);
  coarse.settings.target_spp = int(quick.spp);
  coarse.camera.width = 48;
  coarse.camera.height = 40;
  EXPECT_EQ(quick.sum, render(coarse, 1).sum);

  r.set_dragging(false);
  scene.light.position.x += 1.0f;
  const auto after = r.set_scene(scene);
  while (!r.quick_snapshot(quick) || quick.generation != after) std::this_thread::yield();
  EXPECT_EQ(quick.stride, 1);
  EXPECT_EQ(quick.width, 96);
  ASSERT_TRUE(r.wait_for(after, 2));
  Snapshot own;
  r.snapshot(own);
  r.stop();
  EXPECT_EQ(own.stride, 1);
  EXPECT_EQ(own.sum, render(scene, 1).sum);  // the quick passes never mix in
}

// A deterministic estimate (no indirect light, no jitter, no Fresnel choice)
// is done after one pass when asked, whatever the target; Fresnel on a scene
// with glass is not deterministic.
TEST(Progressive, ADeterministicEstimateStopsAfterOnePass) {
  Scene scene = small_scene(1, 64);
  scene.settings.indirect = scene.settings.aa = scene.settings.fresnel = false;
  ASSERT_TRUE(deterministic_estimate(scene));
  Scene fresnel = scene;
  fresnel.settings.fresnel = true;
  EXPECT_FALSE(deterministic_estimate(fresnel));  // three-balls has glass
  ProgressiveRenderer r(2);
  r.set_stop_when_exact(true);
  const auto gen = r.set_scene(scene);
  r.start();
  ASSERT_TRUE(r.wait_for(gen, 64));  // returns on `done`
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  Snapshot s;
  r.snapshot(s);
  r.stop();
  EXPECT_TRUE(s.done);
  EXPECT_EQ(s.counters.passes, 1u);
  EXPECT_EQ(s.spp, 1u);
}

// ... and the accumulation that follows is exactly the one without quick
// passes: they never mix in, also across an edit.
TEST(Progressive, QuickPassesAreNeverAccumulated) {
  const Scene before = small_scene(1, 0);
  Scene after = small_scene(2, 4);
  after.light.position = vec3(5.0f, 20.0f, 30.0f);
  ProgressiveRenderer r(2);
  r.set_quick_passes(true);
  const auto g1 = r.set_scene(before);
  r.start();
  ASSERT_TRUE(r.wait_for(g1, 2));
  const auto g2 = r.set_scene(after);
  ASSERT_TRUE(r.wait_for(g2, 4));
  Snapshot s;
  r.snapshot(s);
  r.stop();
  EXPECT_FALSE(s.quick);
  EXPECT_EQ(s.sum, render(after, 1).sum);
}

// Raising the target after it was reached renders more passes in the same
// generation, and the result is the same image as a render to the higher
// target from the start (samples are indexed, so nothing repeats).
TEST(TargetSpp, RaisingTheTargetContinuesTheAccumulation) {
  Scene s = sized("three-balls", 40, 32, 2, 4);
  s.settings.indirect = s.settings.aa = true;

  ProgressiveRenderer r(2);
  const std::uint64_t gen = r.set_scene(s);
  r.start();
  ASSERT_TRUE(r.wait_for(gen, 4));
  Snapshot first;
  r.snapshot(first);
  EXPECT_TRUE(first.done);
  r.set_target_spp(10);
  ASSERT_TRUE(r.wait_for(gen, 10));
  Snapshot more;
  r.snapshot(more);
  r.stop();
  EXPECT_EQ(more.generation, gen);
  EXPECT_EQ(more.spp, 10u);
  EXPECT_EQ(more.counters.passes, 5u);  // 2 + 2 + 2 + 2 + 2: the first two were kept
  EXPECT_TRUE(more.done);

  s.settings.target_spp = 10;
  const Snapshot ref = render(s, 2);  // the same target from the start
  EXPECT_EQ(more.sum, ref.sum);
  EXPECT_EQ(more.sum_sq, ref.sum_sq);
}

// A pass reports its tiles as they finish; between passes nothing runs.
TEST(TargetSpp, PassProgressCountsTiles) {
  Scene s = sized("three-balls", 70, 40, 1, 2);  // 3 x 2 tiles of 32
  ProgressiveRenderer r(1);
  const std::uint64_t gen = r.set_scene(s);
  r.start();
  ASSERT_TRUE(r.wait_for(gen, 2));
  // Done: the workers wait, so the progress is "not rendering".
  for (int k = 0; k < 100 && r.pass_progress().rendering; ++k)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  const auto p = r.pass_progress();
  r.stop();
  EXPECT_FALSE(p.rendering);
  EXPECT_EQ(p.generation, gen);
  EXPECT_EQ(p.tiles_total, 6);
  EXPECT_EQ(p.tiles_done, 6);
}

// During a long pass the tiles done climb before the pass publishes.
TEST(TargetSpp, PassProgressClimbsDuringALongPass) {
  Scene s = sized("three-balls", 64, 64, 300, 300);  // 2 x 2 tiles
  ProgressiveRenderer r(1);
  const std::uint64_t gen = r.set_scene(s);
  r.start();
  bool seen_midway = false;
  for (int k = 0; k < 2000 && !seen_midway; ++k) {
    const auto p = r.pass_progress();
    Snapshot snap;
    const bool published = r.snapshot(snap) && snap.spp > 0;
    seen_midway = p.rendering && p.generation == gen && p.pass_spp == 300 &&
                  p.tiles_done > 0 && p.tiles_done < p.tiles_total && !published;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  r.stop();
  EXPECT_TRUE(seen_midway);
}

// Light connections: a pass of 40 samples runs in chunks of 16, 16 and 8,
// each with its samples' light caches, built by all the threads (at most
// 16 caches at a time, whatever --spp), the pixels' sums carried from chunk
// to chunk. The film gets the sums of the 40 samples as one piece, in order
// from zero, bit for bit (so parts of a render still merge exactly,
// docs/SHARDS.md), whatever the thread count.
TEST(Progressive, LightConnectionsPassInChunksAddsTheSumsOfOnePiece) {
  Scene scene = sized("cat", 24, 20, 40, 40);
  scene.settings.connect = true;
  const Snapshot one = render(scene, 1);
  const Snapshot two = render(scene, 2);
  ASSERT_EQ(one.spp, 40u);
  EXPECT_EQ(one.counters.passes, 1u);
  EXPECT_EQ(one.sum, two.sum);  // bit-identical
  EXPECT_EQ(one.sum_sq, two.sum_sq);
  // The pass in one piece: the 40 caches at once, one tile of the image.
  const World world(scene);
  const CameraFrame cam(scene.camera);
  std::vector<LightCache> caches(40);
  std::uint64_t rays = 0;
  for (std::size_t k = 0; k < caches.size(); ++k) caches[k].build(world, scene.settings, k, rays);
  Film film;
  film.reset(24, 20);
  PathStats stats;
  const PathContext ctx{world, scene.settings, stats};
  const TileWork work{{0, 20, 0, 24}, 0, 40, nullptr, caches.data(), {}};
  render_tile(ctx, cam, work, film);
  Snapshot whole;
  film.publish(whole);
  EXPECT_EQ(one.sum, whole.sum);
  EXPECT_EQ(one.sum_sq, whole.sum_sq);
}
