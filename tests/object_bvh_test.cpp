// The object-level BVH (spheres and the mesh in one structure) against a
// plain loop over every object.
#include <gtest/gtest.h>

#include <random>

#include <glm/geometric.hpp>

#include "geometry/object_bvh.h"
#include "geometry/offset.h"
#include "scene/world.h"
#include "scene/scene_io.h"
#include "directions.h"
#include "sanitized.h"

using namespace whisker;

TEST(ObjectBvh, ThousandsOfSpheresMatchALinearLoop) {
  std::mt19937 g(21);
  std::uniform_real_distribution<float> pos(-50.0f, 50.0f), rad(0.2f, 3.0f);
  std::vector<Sphere> spheres;
  for (int k = 0; k < 3000; ++k) spheres.push_back({vec3(pos(g), pos(g), pos(g)), rad(g)});
  // and the report's six walls around them
  for (const auto& s : load_scene(resolve_scene("diffuse-ball")).spheres)
    if (s.radius > 100.0f) spheres.push_back({s.center, s.radius});
  const ObjectBvh bvh(spheres, Box3{});
  EXPECT_GE(bvh.leaf_count(), spheres.size() / 16);  // a real tree, not one list

  // Float screening tests (scalar here, 8-wide with FMA in the BVH) differ
  // by up to 4e-4 relative plus ~1e-3 absolute for origins near the huge
  // walls (eps |f|^2 / |q| with |f| ~ 1000); two spheres whose hits are that
  // close are a tie either may win.
  auto tol = [](float t) { return 4e-4f * t + 2e-3f; };
  int hits = 0, ties = 0;
  const int rays = release_or_sanitized(100000, 25000);
  for (int k = 0; k < rays; ++k) {
    const Ray r{vec3(pos(g), pos(g), pos(g)), random_direction(g)};
    float best = kInf;
    std::uint32_t best_i = 0;
    for (std::uint32_t i = 0; i < spheres.size(); ++i) {
      // The float test, then the root in double (the BVH solves origins
      // near a sphere in double).
      float t = intersect_sphere(spheres[i], r);
      if (t < kInf) t = float(solve_sphere_t(spheres[i], r, t));
      if (t < best) { best = t; best_i = i; }
    }
    Hit h;
    h.t = r.tmax;
    const bool found = bvh.intersect(r, h, nullptr);
    ASSERT_EQ(found, best < kInf) << k;
    if (!found) continue;
    ++hits;
    EXPECT_NEAR(h.t, best, tol(best)) << k;
    if (h.prim != best_i) ++ties;
    // Any-hit agrees on both sides of the closest hit.
    EXPECT_TRUE(bvh.occluded(Ray{r.o, r.d, 0.0f, best + tol(best)}, nullptr)) << k;
    if (best > tol(best)) {
      EXPECT_FALSE(bvh.occluded(Ray{r.o, r.d, 0.0f, best - tol(best)}, nullptr)) << k;
    }
  }
  EXPECT_GT(hits, rays * 9 / 10);
  EXPECT_LT(ties, hits / 1000);
}

TEST(ObjectBvh, SpheresAndTheCatInOneStructure) {
  // The cat scene plus the three balls: World's one structure returns the
  // same closest hits as testing every sphere and the cat's BVH in turn.
  Scene scene = load_scene(resolve_scene("cat"));
  for (const auto& s : load_scene(resolve_scene("three-balls")).spheres)
    if (s.radius < 100.0f) scene.spheres.push_back(s);
  scene.camera.position = vec3(0.0f);  // render space is then world space
  const World world(scene);
  std::vector<Sphere> spheres;
  for (const auto& s : scene.spheres) {
    spheres.push_back({s.center, s.radius, false});
    if (s.material.kind == MaterialKind::HollowGlass) spheres.push_back({s.center, s.inner_radius, true});
  }
  ASSERT_EQ(world.sphere_count(), spheres.size());
  std::mt19937 g(5);
  std::uniform_real_distribution<float> u(-40.0f, 40.0f);
  int cat_hits = 0;
  for (int k = 0; k < 100000; ++k) {
    const Ray r{vec3(u(g), 0.3f * u(g), u(g)), random_direction(g)};
    Hit ref;
    ref.t = kInf;
    for (std::uint32_t i = 0; i < spheres.size(); ++i) {
      const float t = intersect_sphere(spheres[i], r);
      if (t < ref.t) { ref.t = t; ref.kind = PrimKind::Sphere; ref.prim = i; }
    }
    world.bvh()->intersect(r, ref);
    SurfaceHit h;
    const bool found = world.intersect(r, h);
    ASSERT_EQ(found, ref.valid());
    if (!found) continue;
    // World refines a sphere's t in double; so does the reference.
    float t = ref.t;
    if (ref.kind == PrimKind::Sphere) t = float(refine_sphere_t(spheres[ref.prim], r, ref.t));
    else ++cat_hits;
    EXPECT_NEAR(h.t, t, 1e-5f * t + 1e-6f) << k;
  }
  EXPECT_GT(cat_hits, 1000);
}
