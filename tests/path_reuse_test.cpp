// Path reuse (render/path_reuse.h): pixels of a block share their indirect
// paths. Each pixel must keep the expectation of its own estimator: the
// reused image against the per-pixel one, pixel by pixel within their
// standard errors, in the cat's room and in the room with glass and a mirror;
// a block of one pixel is the plain estimator; the image is the same for any
// thread count; and the closed forms hold (integrator_test.cpp, OffCentre).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>

#include "geometry/sphere_set.h"
#include "render/integrator.h"
#include "render/path_reuse.h"
#include "render/progressive.h"
#include "scene/scene_io.h"
#include "scene/world.h"
#include "render_util.h"

using namespace whisker;

namespace {

Scene small(const char* name, int width, int height, int spp, int reuse, std::uint64_t seed) {
  Scene s = load_scene(resolve_scene(name));
  s.camera.width = width;
  s.camera.height = height;
  s.settings.spp = spp;
  s.settings.target_spp = spp;
  s.settings.reuse = reuse;
  s.settings.seed = seed;
  return s;
}

// Two independent renders of one scene, with and without reuse, have the
// same expectation in every pixel (render_util.h).
// With `zoom`, the view narrows so that a pixel covers what one of the
// 512 x 512 image does (the centre 1/zoom of the field).
void expect_reuse_keeps_expectation(const char* name, int width, int height, int spp, float zoom = 1.0f) {
  Scene a = small(name, width, height, spp, 1, 11), b = small(name, width, height, spp, 4, 22);
  a.camera.fov_deg = b.camera.fov_deg =
      float(2.0 * std::atan(std::tan(a.camera.fov_deg * 3.14159265358979 / 360.0) / zoom) * 360.0 / 3.14159265358979);
  // It does what it is for: less noise in a typical pixel, where
  // neighbouring pixels see nearby points (not in a 22-pixel view of the whole
  // room). The median: pixels on an edge keep the noise of anti-aliasing,
  // which the first hit holds and reuse cannot share.
  const double ratio = expect_same_expectation(render(a), render(b), name);
  if (zoom > 1.0f) {
    EXPECT_LT(ratio, 0.35) << name;
  }
}

}  // namespace

// The cat's room: every surface diffuse, the cat a mesh, anti-aliasing on.
// 22 x 18 leaves partial blocks at the right and bottom edges.
TEST(PathReuse, CatRoomKeepsEachPixelsExpectation) {
  expect_reuse_keeps_expectation("cat", 22, 18, 96);
}

// The same at the 512 x 512 image's pixel size, the middle of the cat: the
// variance per pixel at least halves.
TEST(PathReuse, CatAtFullResolutionPixelsHasLessNoise) {
  expect_reuse_keeps_expectation("cat", 22, 18, 64, 512.0f / 22.0f);
}

// Glass and a mirror: pixels whose first hit is glass, and bounces that meet
// glass or the mirror, keep to their own pixel.
TEST(PathReuse, GlassAndMirrorRoomKeepsEachPixelsExpectation) {
  expect_reuse_keeps_expectation("indirect", 22, 18, 96);
}

// A block of one pixel is the plain estimator: the same numbers drawn, the
// same paths, the same value to float rounding (the weights g / (n g)).
TEST(PathReuse, BlockOfOnePixelIsThePlainEstimator) {
  Scene scene = small("cat", 32, 32, 1, 4, 7);
  scene.settings.connect = false;  // reuse makes no connection at the first vertex
  const World world(scene);
  const CameraFrame cam(scene.camera);
  int compared = 0;
  for (int i = 0; i < 32; i += 3) {
    for (int j = 0; j < 32; j += 3) {
      for (std::uint64_t k = 0; k < 4; ++k) {
        const std::uint32_t pixel = std::uint32_t(i * 32 + j);
        Sampler sampler(scene.settings.sampler, pixel, k, scene.settings.seed);
        PathStats stats;
        const PathContext ctx{world, scene.settings, stats};
        const vec3 plain = sample_pixel(ctx, cam, Pixel{i, j}, sampler);
        vec3 block;
        sample_block(ctx, cam, PixelBlock{i, i + 1, j, j + 1}, k, &block);
        for (int c = 0; c < 3; ++c)
          ASSERT_NEAR(block[c], plain[c], 2e-5f * std::max(plain[c], 1.0f)) << i << "," << j;
        ++compared;
      }
    }
  }
  EXPECT_EQ(compared, 11 * 11 * 4);
}

// Tiles never split a block, so the image is the same bit for bit whatever
// the thread count (and so are parts merged into one render).
TEST(PathReuse, SameImageForAnyThreadCount) {
  const Scene scene = small("cat", 70, 45, 2, 4, 3);  // 70 x 45: partial tiles and blocks
  const Snapshot one = render(scene, 1);
  const Snapshot three = render(scene, 3);
  EXPECT_EQ(one.sum, three.sum);
  EXPECT_EQ(one.sum_sq, three.sum_sq);
}

// The visibility test between a first hit and a bounce's point y names y's
// sphere: the segment seen from outside that sphere cannot be blocked by it
// (near y float cannot tell the surface from a root a little before it),
// while any other sphere in the way still blocks.
TEST(PathReuse, SegmentEndingOnASphereIsNotBlockedByIt) {
  const Sphere wall{vec3(0.0f, 0.0f, -1000.0f), 940.0f};
  const Sphere ball{vec3(0.0f, 0.0f, -30.0f), 5.0f};
  const SphereSet set({wall, ball});
  int grazing = 0;
  for (int k = 1; k <= 200; ++k) {
    // Points y on the wall seen at ever more grazing angles from x.
    const float a = 0.02f + 0.3f * float(k) / 200.0f;
    const vec3 y = wall.center + wall.radius * glm::normalize(vec3(std::sin(a), 0.0f, std::cos(a)));
    const vec3 x(-55.0f, 0.0f, -55.0f);
    const vec3 d = glm::normalize(y - x);
    const vec3 n = glm::normalize(y - wall.center);
    if (!(glm::dot(n, x - y) > 0.0f)) continue;  // x must see the outer side
    Ray r{x, d, 0.0f, glm::length(y - x) * (1.0f - 1e-5f)};
    EXPECT_FALSE(set.occluded(r, 0)) << "angle " << a;
    if (glm::dot(n, -d) < 0.05f) ++grazing;
  }
  EXPECT_GT(grazing, 0);
  // The ball between x and a point on the wall blocks, named end or not.
  const vec3 y = wall.center + wall.radius * vec3(0.0f, 0.0f, 1.0f);
  const vec3 x(0.0f, 0.0f, 0.0f);
  Ray r{x, glm::normalize(y - x), 0.0f, glm::length(y - x) * (1.0f - 1e-5f)};
  EXPECT_TRUE(set.occluded(r, 0));
  EXPECT_TRUE(set.occluded(r));
}
