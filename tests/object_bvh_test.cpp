// The object-level BVH (spheres and the mesh in one structure) against a
// plain loop over every object.
#include <gtest/gtest.h>

#include <random>

#include <glm/geometric.hpp>

#include "geometry/object_bvh.h"
#include "geometry/offset.h"
#include "scene/world.h"
#include "scene/scene_io.h"

using namespace whisker;

namespace {

vec3 random_direction(std::mt19937& g) {
  std::normal_distribution<float> n;
  const vec3 v(n(g), n(g), n(g));
  return glm::normalize(v);
}

}  // namespace

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
  for (int k = 0; k < 100000; ++k) {
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
  EXPECT_GT(hits, 90000);
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

TEST(World, ShadowRaysToTheLightGiveTheSameAnswerWithoutTheWalls) {
  // occluded_to_light() skips the spheres when no sphere can stand between
  // the light and a point that near it; it must agree with occluded() at
  // every surface point a path can reach.
  Scene scene = load_scene(resolve_scene("cat"));
  scene.camera.position = vec3(0.0f);  // render space is then world space
  const World world(scene);
  const vec3 light = scene.light.position;
  // The room's walls: the light's power against each is at least
  // (960.26^2 - 940^2) ~ 196^2, farther than any corner of the room.
  EXPECT_GT(world.light_clearance2(), 190.0f * 190.0f);
  std::mt19937 g(8);
  std::uniform_real_distribution<float> u(-40.0f, 40.0f);
  int blocked = 0, tested = 0;
  for (int k = 0; k < 50000; ++k) {
    const Ray r{vec3(u(g), 0.3f * u(g) + 10.0f, u(g)), random_direction(g)};
    SurfaceHit h;
    if (!world.intersect(r, h)) continue;
    const vec3 ng = glm::dot(h.ng, r.d) < 0.0f ? h.ng : -h.ng;
    const vec3 to = world.light().position - h.p;
    if (glm::dot(ng, to) <= 0.0f) continue;
    const Ray shadow = spawn_shadow_ray(h, world.light().position);
    const float d2 = glm::dot(to, to);
    ASSERT_LT(d2, world.light_clearance2()) << k;  // the fast path is the one taken
    const bool full = world.occluded(shadow);
    ASSERT_EQ(world.occluded_to_light(shadow, d2), full) << k;
    blocked += full;
    ++tested;
  }
  EXPECT_GT(tested, 20000);
  EXPECT_GT(blocked, 1000);  // the cat's shadow is in the sample
  // The World owns the scene's light; a World rebuilt for a moved light
  // (the viewer's edits) takes the new one and its own clearance.
  EXPECT_EQ(world.light().position, world.to_render(light));
  EXPECT_EQ(world.light().intensity, scene.light.intensity);
  Scene moved = scene;
  moved.light.position = vec3(0.0f, 100.0f, 0.0f);  // outside the room
  const World rebuilt(moved, &world);
  EXPECT_EQ(rebuilt.light().position, rebuilt.to_render(moved.light.position));
  EXPECT_EQ(rebuilt.light_clearance2(), 0.0f);  // inside a wall sphere: no shortcut
}

TEST(World, ShadowRaysFromInsideAGlassBallStillSeeTheGlass) {
  // A diffuse ball inside the glass ball of the three-ball scene: its points
  // lie inside a sphere, where only the nearest-distance bound holds.
  Scene scene = load_scene(resolve_scene("three-balls"));
  SphereObject inner;
  inner.center = vec3(0.0f);
  inner.radius = 3.0f;
  scene.spheres.push_back(inner);
  const World world(scene);
  const vec3 light = world.light().position;  // render space
  const vec3 p = world.to_render(vec3(0.0f, 3.0f, 0.0f)), n(0.0f, 1.0f, 0.0f);
  SurfaceHit h;
  h.p = p;
  h.ng = h.ns = h.outward = n;
  h.sphere = std::uint32_t(world.sphere_count() - 1);  // the diffuse ball, added last
  const Ray shadow = spawn_shadow_ray(h, light);
  const float d2 = glm::dot(light - p, light - p);
  ASSERT_TRUE(world.occluded(shadow));  // the glass shell is in the way
  EXPECT_TRUE(world.occluded_to_light(shadow, d2));
  // The glass ball's nearest point is |L - c| - r = 45.8 - 10 from the light.
  EXPECT_LT(world.light_clearance2(), 36.0f * 36.0f);
}
