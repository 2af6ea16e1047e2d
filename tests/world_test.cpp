// The World (scene/world.h): closest hits at exact distances with their
// records and materials, in render space, and its shadow queries.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>

#include <glm/geometric.hpp>

#include "geometry/mesh.h"
#include "scene/scene_io.h"
#include "scene/world.h"
#include "directions.h"

using namespace whisker;

namespace {

// A diffuse ball (radius 2 at the origin), a hollow glass ball (radius 3,
// bubble 2, at x = 10) and one triangle in the plane z = -10 with corner
// normals, seen from a camera at z = 20: render space is world space moved
// by (0, 0, -20).
Scene small_scene() {
  Scene s;
  s.camera.position = dvec3(0.0, 0.0, 20.0);
  SphereObject ball;
  ball.radius = 2.0f;
  ball.material.albedo = vec3(0.5f, 0.25f, 0.125f);
  s.spheres.push_back(ball);
  SphereObject hollow;
  hollow.center = dvec3(10.0, 0.0, 0.0);
  hollow.radius = 3.0f;
  hollow.inner_radius = 2.0f;
  hollow.material.kind = MaterialKind::HollowGlass;
  hollow.material.ior = 1.25f;
  s.spheres.push_back(hollow);
  auto mesh = std::make_shared<TriangleMesh>();
  mesh->positions = {vec3(-5, -5, -10), vec3(5, -5, -10), vec3(0, 5, -10)};
  mesh->triangles = {glm::uvec3(0, 1, 2)};
  mesh->normals = {vec3(0, 0, 1), vec3(1, 0, 0), vec3(0, 1, 0)};
  mesh->normal_idx = {glm::uvec3(0, 1, 2)};
  MeshObject m;
  m.mesh = mesh;
  m.vertex_normals = true;
  m.material.albedo = vec3(0.75f);
  s.meshes.push_back(m);
  return s;
}

}  // namespace

TEST(World, ClosestHitsAtExactDistancesWithTheirMaterials) {
  const Scene scene = small_scene();
  const World world(scene);
  ASSERT_EQ(world.sphere_count(), 3u);  // the hollow ball is two shells
  ASSERT_EQ(world.triangle_count(), 1u);
  SurfaceHit h;
  // From the camera straight at the ball: its pole at z = 2, 18 away.
  ASSERT_TRUE(world.intersect(world.to_render(dvec3(0, 0, 20), vec3(0, 0, -1)), h));
  EXPECT_EQ(h.t, 18.0f);
  EXPECT_EQ(h.p, world.to_render(vec3(0, 0, 2)));
  EXPECT_EQ(h.ng, vec3(0, 0, 1));
  EXPECT_EQ(h.sphere, 0u);
  ASSERT_NE(h.material, nullptr);
  EXPECT_EQ(h.material->albedo, vec3(0.5f, 0.25f, 0.125f));
  // Below the ball (y = -3 > its radius) to the triangle at z = -10, 30 away.
  ASSERT_TRUE(world.intersect(world.to_render(dvec3(0, -3, 20), vec3(0, 0, -1)), h));
  EXPECT_EQ(h.t, 30.0f);
  // The point from the weights 0.4, 0.4, 0.2 (not exact in float): within
  // its error bound.
  const vec3 exact = world.to_render(vec3(0, -3, -10));
  for (int k = 0; k < 3; ++k) EXPECT_LE(std::fabs(h.p[k] - exact[k]), h.err[k]) << k;
  EXPECT_GT(h.err.z, 0.0f);
  EXPECT_EQ(h.sphere, kNoSkip);
  EXPECT_EQ(h.material->albedo, vec3(0.75f));
  // (0, -3) has the weights 0.4, 0.4, 0.2 of the corners: the shading
  // normal (0.4, 0.2, 0.4) / 0.6 = (2, 1, 2) / 3; the geometric one is +z.
  EXPECT_NEAR(h.ns.x, 2.0f / 3.0f, 1e-6f);
  EXPECT_NEAR(h.ns.y, 1.0f / 3.0f, 1e-6f);
  EXPECT_NEAR(h.ns.z, 2.0f / 3.0f, 1e-6f);
  EXPECT_NEAR(h.ng.z, 1.0f, 1e-7f);
  // Nothing above; nothing before tmax.
  EXPECT_FALSE(world.intersect(world.to_render(dvec3(0, 0, 20), vec3(0, 1, 0)), h));
  Ray shortened = world.to_render(dvec3(0, 0, 20), vec3(0, 0, -1));
  shortened.tmax = 17.5f;
  EXPECT_FALSE(world.intersect(shortened, h));
}

TEST(World, HollowGlassIsTwoShellsTheInnerOneInverted) {
  const World world(small_scene());
  SurfaceHit h;
  // Down the hollow ball's axis from z = 10: the outer shell at z = 3.
  ASSERT_TRUE(world.intersect(world.to_render(dvec3(10, 0, 10), vec3(0, 0, -1)), h));
  EXPECT_EQ(h.t, 7.0f);
  EXPECT_EQ(h.ng, vec3(0, 0, 1));
  EXPECT_EQ(h.material->kind, MaterialKind::Glass);
  EXPECT_EQ(h.material->ior, 1.25f);
  const std::uint32_t outer = h.sphere;
  // From between the shells (z = 2.5): the bubble at z = 2, its normal
  // pointing into it (inverted) and its outward normal out of the sphere.
  ASSERT_TRUE(world.intersect(world.to_render(dvec3(10, 0, 2.5), vec3(0, 0, -1)), h));
  EXPECT_EQ(h.t, 0.5f);
  EXPECT_EQ(h.ng, vec3(0, 0, -1));
  EXPECT_EQ(h.outward, vec3(0, 0, 1));
  EXPECT_NE(h.sphere, outer);
  EXPECT_EQ(h.material->kind, MaterialKind::Glass);
}

TEST(World, OccludedOnlyBeforeTheHit) {
  const World world(small_scene());
  Ray r = world.to_render(dvec3(0, 0, 20), vec3(0, 0, -1));
  r.tmax = 17.9f;
  EXPECT_FALSE(world.occluded(r));
  r.tmax = 18.1f;
  EXPECT_TRUE(world.occluded(r));
  Ray below = world.to_render(dvec3(0, -3, 20), vec3(0, 0, -1));
  below.tmax = 29.9f;
  EXPECT_FALSE(world.occluded(below));
  below.tmax = 30.1f;
  EXPECT_TRUE(world.occluded(below));
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
    ASSERT_EQ(world.occluded_to_light(shadow, d2, -to), full) << k;
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
  EXPECT_TRUE(world.occluded_to_light(shadow, d2, p - light));
  // The glass ball's nearest point is |L - c| - r = 45.8 - 10 from the light.
  EXPECT_LT(world.light_clearance2(), 36.0f * 36.0f);
}
