// The light cache (render/light_cache.h): its entries are the first hits of
// light paths in stratified directions, with the light's weight and the
// light paths' density there; a vertex picks among the entries that share
// one of its colour channels, weighed by M / M_c; a sample's cache depends
// on the seed and the sample number only. (That connections through it keep
// every pixel's expectation: light_connect_test.cpp.)
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>

#include <glm/geometric.hpp>

#include "render/light_cache.h"
#include "scene/world.h"
#include "closed_sphere.h"
#include "render_util.h"

using namespace whisker;

namespace {

// Sample `sample`'s cache of a scene's world.
LightCache built(const World& world, const Scene& scene, std::uint64_t sample) {
  LightCache cache;
  std::uint64_t rays = 0;
  cache.build(world, scene.settings, sample, rays);
  return cache;
}

}  // namespace

// Inside a closed grey sphere every light path meets the shell, lit: all M
// entries are kept (factor 1), each on the sphere, with the light's weight
// I cos/(4 pi^2 d^2) (report section 2) and B = cos_l/(4 d^2), checked in
// double from the point; the directions are stratified, so exactly half of
// the entries lie above the light (z = 1 - 2 u2, rows of equal area).
TEST(LightCache, EntriesAreTheLightPathsFirstHits) {
  const glm::dvec3 c(3.0, -2.0, 1.0);
  const double I = 1000.0, R = 10.0;
  const Scene scene = closed_sphere(0.5f, vec3(c), 2, 1, 4);
  const World world(scene);
  LightCache cache;
  std::uint64_t rays = 0;
  cache.build(world, scene.settings, 7, rays);
  EXPECT_EQ(rays, std::uint64_t(LightCache::kPaths));
  EXPECT_EQ(cache.density_scale(7u), 1.0f);
  int above = 0, seen = 0;
  const int M = LightCache::kPaths;
  std::set<const CachedLightVertex*> distinct;
  for (int k = 0; k < M; ++k) {
    const CachedLightVertex* e = cache.pick(1u, (float(k) + 0.5f) / float(M));
    ASSERT_NE(e, nullptr);
    distinct.insert(e);
    const glm::dvec3 p(e->p);
    // Render space is the scene's space moved by the camera position.
    const glm::dvec3 world_p = p + glm::dvec3(scene.camera.position);
    EXPECT_NEAR(glm::length(world_p), R, 1e-4) << k;
    const glm::dvec3 to_light = c - world_p;
    const double d2 = glm::dot(to_light, to_light);
    const double cos_l = glm::dot(glm::dvec3(e->ng), to_light) / std::sqrt(d2);
    EXPECT_NEAR(glm::dot(glm::dvec3(e->ng), -world_p / R), 1.0, 1e-6);  // the inside faces the light
    EXPECT_NEAR(e->B, cos_l / (4.0 * d2), 1e-5 * cos_l / (4.0 * d2));
    EXPECT_NEAR(e->weight, I * cos_l / (4.0 * kPi * kPi * d2), 1e-5 * I * cos_l / (4.0 * kPi * kPi * d2));
    EXPECT_EQ(e->albedo, vec3(0.5f));
    above += to_light.z < 0.0 ? 1 : 0;
    ++seen;
  }
  EXPECT_EQ(int(distinct.size()), M);  // each entry picked once by M even steps
  EXPECT_EQ(above, M / 2);
  EXPECT_EQ(seen, M);
}

// In the cat's room (walls of pure primaries and their pairs, a white cat)
// a vertex carrying red picks only entries with red in them, each equally
// often, and M / M_c is what makes them stand for all M light paths; a
// vertex whose colour nothing in a room has picks nothing (factor 0: its
// bounces take the whole weight).
TEST(LightCache, PicksOnlyEntriesThatShareAChannel) {
  const Scene scene = sized("cat", 8, 8, 1, 1);
  const World world(scene);
  LightCache cache = built(world, scene, 3);
  for (unsigned channels = 1; channels < 8; ++channels) {
    const float scale = cache.density_scale(channels);
    // Some light paths meet walls of other colours; every wall has one.
    if (channels == 7u) ASSERT_GE(scale, 1.0f); else ASSERT_GT(scale, 1.0f) << channels;
    const int matching = int(std::lround(float(LightCache::kPaths) / scale));
    std::set<const CachedLightVertex*> distinct;
    for (int k = 0; k < matching; ++k) {
      const CachedLightVertex* e = cache.pick(channels, (float(k) + 0.5f) / float(matching));
      ASSERT_NE(e, nullptr);
      EXPECT_NE(channel_bits(e->albedo) & channels, 0u) << channels;
      distinct.insert(e);
    }
    EXPECT_EQ(int(distinct.size()), matching) << channels;
  }
  // The entries with red or green: more than those with red, at most those
  // with red plus those with green (the yellow wall and the cat have both),
  // fewer than all (the floor is blue only).
  const auto count = [&](unsigned ch) { return std::lround(float(LightCache::kPaths) / cache.density_scale(ch)); };
  EXPECT_LT(count(1u), count(3u));
  EXPECT_LT(count(3u), count(1u) + count(2u));
  EXPECT_LT(count(3u), count(7u));

  const Scene red = closed_sphere(vec3(1.0f, 0.0f, 0.0f), vec3(1.0f, 2.0f, 0.0f), 2, 1, 4);
  const World red_world(red);
  cache = built(red_world, red, 3);
  EXPECT_EQ(cache.density_scale(1u), 1.0f);
  EXPECT_EQ(cache.density_scale(2u), 0.0f);
  EXPECT_EQ(cache.pick(2u, 0.5f), nullptr);
  EXPECT_EQ(cache.pick(6u, 0.0f), nullptr);
}

// A vertex on a wall of the cat's room, reached from the room, leaves out
// the entries on that wall (none can be connected to it): with them left
// out, M_c' even steps pick every other entry of its channels once and none
// on the wall, and M / M_c' is the factor. The floor, lit from above, holds
// some of the blue entries, so a floor vertex's factor is larger than its
// channels' alone.
TEST(LightCache, LeavesOutTheSphereOfTheVertex) {
  const Scene scene = sized("cat", 8, 8, 1, 1);
  const World world(scene);
  LightCache cache = built(world, scene, 3);
  int walls_with_entries = 0;
  for (unsigned channels = 1; channels < 8; ++channels) {
    const int all = int(std::lround(float(LightCache::kPaths) / cache.density_scale(channels)));
    for (std::uint32_t wall = 0; wall < 6; ++wall) {
      const float scale = cache.density_scale(channels, wall);
      ASSERT_GE(scale, cache.density_scale(channels)) << channels << " " << wall;
      const int left = int(std::lround(float(LightCache::kPaths) / scale));
      std::set<const CachedLightVertex*> distinct;
      for (int k = 0; k < left; ++k) {
        const CachedLightVertex* e = cache.pick(channels, (float(k) + 0.5f) / float(left), wall);
        ASSERT_NE(e, nullptr);
        EXPECT_NE(e->sphere, wall) << channels;
        EXPECT_NE(channel_bits(e->albedo) & channels, 0u) << channels;
        distinct.insert(e);
      }
      EXPECT_EQ(int(distinct.size()), left) << channels << " " << wall;
      // What was left out is exactly the wall's entries: picked without
      // leaving anything out, `all` even steps meet all - left of them.
      int on_wall = 0;
      for (int k = 0; k < all; ++k)
        on_wall += cache.pick(channels, (float(k) + 0.5f) / float(all))->sphere == wall ? 1 : 0;
      EXPECT_EQ(on_wall, all - left) << channels << " " << wall;
      walls_with_entries += on_wall > 0 ? 1 : 0;
    }
  }
  EXPECT_GT(walls_with_entries, 6);
  const std::uint32_t floor = 1;  // assets/scenes/cat.json: ceiling, floor, front, ...
  ASSERT_EQ(world.material(Hit{.kind = PrimKind::Sphere, .prim = floor}).albedo, vec3(0.0f, 0.0f, 1.0f));
  EXPECT_GT(cache.density_scale(4u, floor), cache.density_scale(4u) * 1.1f);
  EXPECT_EQ(cache.density_scale(4u, kNoSkip), cache.density_scale(4u));
  EXPECT_EQ(cache.density_scale(4u, 1000u), cache.density_scale(4u));  // no such sphere
}

// A scene of many spheres costs at most kRunSpheres runs a list: inside a
// closed grey shell (sphere 0), 299 small grey balls (spheres 1-299) spread
// over a sphere around the light. A vertex on a ball numbered below the bound leaves
// its ball's entries out; past the bound it leaves none out (its picks may
// land on its own ball, which then brings nothing: unbiased, as before the
// rule), and every entry is still picked.
TEST(LightCache, LeavesOutOnlySpheresBelowTheBound) {
  Scene scene = closed_sphere(0.5f, vec3(0.0f), 2, 1, 4);
  for (int k = 0; k < 299; ++k) {  // a Fibonacci sphere of radius 5, balls 0.6 wide about 1 apart
    const double z = 1.0 - 2.0 * (k + 0.5) / 299.0, r = std::sqrt(1.0 - z * z);
    const double a = k * kPi * (3.0 - std::sqrt(5.0));
    scene.spheres.push_back({"ball", 5.0 * dvec3(r * std::cos(a), r * std::sin(a), z), 0.3f, 0.0f,
                             {MaterialKind::Diffuse, vec3(0.5f)}});
  }
  const World world(scene);
  LightCache cache = built(world, scene, 3);
  const int all = int(std::lround(float(LightCache::kPaths) / cache.density_scale(1u)));
  ASSERT_EQ(all, LightCache::kPaths);  // every light path meets the shell or a ball
  std::map<std::uint32_t, int> on;  // entries per sphere
  for (int k = 0; k < all; ++k) ++on[cache.pick(1u, (float(k) + 0.5f) / float(all))->sphere];
  ASSERT_GT(on.size(), 280u);  // the shell and nearly every ball hold entries (about 4 a ball)
  ASSERT_GT(on.rbegin()->first, LightCache::kRunSpheres);
  for (const auto& [sphere, count] : on) {
    const float expected = sphere < LightCache::kRunSpheres ? float(LightCache::kPaths) / float(all - count)
                                                             : cache.density_scale(1u);
    EXPECT_FLOAT_EQ(cache.density_scale(1u, sphere), expected) << sphere;
  }
  // Past the bound, a pick at the same u is the pick without leaving out.
  for (int k = 0; k < 64; ++k) {
    const float u = (float(k) + 0.5f) / 64.0f;
    EXPECT_EQ(cache.pick(1u, u, on.rbegin()->first), cache.pick(1u, u)) << k;
  }
}

// A sample's cache is a function of the seed and the sample number: built
// twice it is the same, and the next sample's differs.
TEST(LightCache, DependsOnTheSeedAndSampleOnly) {
  const Scene scene = sized("cat", 8, 8, 1, 1);
  const World world(scene);
  LightCache a, b, c;
  std::uint64_t rays = 0;
  a.build(world, scene.settings, 5, rays);
  b.build(world, scene.settings, 5, rays);
  c.build(world, scene.settings, 6, rays);
  int same = 0, differ = 0;
  for (int k = 0; k < 64; ++k) {
    const float u = (float(k) + 0.5f) / 64.0f;
    const CachedLightVertex *ea = a.pick(7u, u), *eb = b.pick(7u, u), *ec = c.pick(7u, u);
    same += ea->p == eb->p && ea->weight == eb->weight ? 1 : 0;
    differ += ea->p != ec->p ? 1 : 0;
  }
  EXPECT_EQ(same, 64);
  EXPECT_GT(differ, 60);
}
