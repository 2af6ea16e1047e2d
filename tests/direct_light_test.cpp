// The direct-light term (render/direct_light.h): on its own, the formula at
// a lit point, points facing away, occluders, and overflow-prone lights;
// through the renderer, the diffuse ball's pixels against the closed form
// and vertex normals that shade but never leak past the terminator.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/geometric.hpp>

#include "geometry/mesh.h"
#include "render/direct_light.h"
#include "scene/scene_io.h"
#include "scene/world.h"
#include "render_util.h"

using namespace whisker;

namespace {

constexpr double kPi = 3.14159265358979323846;

// The hit record of the point p (world space) of the unit ball, sphere 0 of
// the World (render space, relative to the scene's camera).
SurfaceHit on_ball(const World& world, const vec3& p) {
  SurfaceHit h;
  h.p = world.to_render(p);
  h.err = vec3(glm::dvec3(p) - world.origin() - glm::dvec3(h.p));
  h.ng = h.ns = h.outward = p;
  h.sphere = 0;
  return h;
}

}  // namespace

// The direct-light module on its own: the point light the World owns, the
// formula at a lit point, nothing (and no shadow ray) for a point facing
// away, and nothing behind an occluder (whose shadow ray is counted).
TEST(DirectLight, ThePointLightOfTheWorldAndItsShadow) {
  Scene s;
  s.spheres.push_back({"ball", vec3(0.0f), 1.0f, 0.0f, {MaterialKind::Diffuse, vec3(0.5f)}});
  s.light = {vec3(0.0f, 10.0f, 0.0f), 1000.0f};
  const World world(s);
  const double I = 1000.0;
  for (double deg : {0.0, 30.0, 60.0}) {
    const double a = deg * kPi / 180.0;
    const glm::dvec3 p(std::sin(a), std::cos(a), 0.0), to = glm::dvec3(0, 10, 0) - p;
    const double d2 = glm::dot(to, to), cos_s = glm::dot(p, to) / std::sqrt(d2);
    std::uint64_t rays = 0;
    const LightArrival arrival = direct_light(world, on_ball(world, vec3(p)), {vec3(p), vec3(p)}, rays);
    ASSERT_TRUE(arrival.lit) << deg;
    const float weight = arrival.weight;
    EXPECT_EQ(rays, 1u);
    // I/(4 pi d^2) * <N, w_i> / pi: the albedo is the caller's.
    const double expect = I * cos_s / (4.0 * kPi * kPi * d2);
    EXPECT_NEAR(weight, expect, 1e-5 * expect) << deg;
  }
  std::uint64_t rays = 0;
  const vec3 down(0.0f, -1.0f, 0.0f);
  EXPECT_FALSE(direct_light(world, on_ball(world, down), {down, down}, rays).lit);  // facing away
  EXPECT_EQ(rays, 0u);

  s.spheres.push_back({"blocker", vec3(0.0f, 5.0f, 0.0f), 1.0f, 0.0f, {}});
  const World blocked(s);
  const vec3 up(0.0f, 1.0f, 0.0f);
  EXPECT_FALSE(direct_light(blocked, on_ball(blocked, up), {up, up}, rays).lit);
  EXPECT_EQ(rays, 1u);
}

// I cos / d^2 leaves float's range before the 1/(4 pi^2) brings the term
// back into it (here 1e29 / 1e-10 = 1e39): the term is finite and right, not
// an infinity whose product with a zero channel was a NaN, a dropped sample.
TEST(DirectLight, ABrightLightCloseAboveTheSurfaceIsFiniteAndMatchesTheFormula) {
  Scene s;
  s.spheres.push_back({"ball", vec3(0.0f), 1.0f, 0.0f, {MaterialKind::Diffuse, vec3(0.5f)}});
  s.light = {vec3(0.0f, 1.00001f, 0.0f), 1e29f};
  const World world(s);
  const vec3 up(0.0f, 1.0f, 0.0f);
  const SurfaceHit h = on_ball(world, up);
  // The formula in double, from the render-space floats the term is made of.
  const glm::dvec3 to = glm::dvec3(world.light().position) - glm::dvec3(h.p);
  const double d2 = glm::dot(to, to), cos_s = to.y / std::sqrt(d2);
  const double expect = 1e29 * cos_s / (4.0 * kPi * kPi * d2);
  ASSERT_LT(expect, 3e38);
  ASSERT_GT(1e29 * cos_s / d2, 3.5e38);  // the case: the partial product overflows float
  std::uint64_t rays = 0;
  const LightArrival a = direct_light(world, h, {up, up}, rays);
  ASSERT_TRUE(a.lit);
  EXPECT_NEAR(a.weight, expect, 1e-5 * expect);
}

// Fig 1: the white ball lit directly. Every pixel whose camera and shadow
// rays are not on a silhouette equals I/(4 pi d^2) rho/pi cos, computed here
// in double with an independent intersection.
TEST(DirectLight, DiffuseBallPixelsEqualTheClosedForm) {
  Scene scene = load_scene(resolve_scene("diffuse-ball"));
  const Snapshot snap = render(scene);
  ASSERT_EQ(snap.spp, 1u);

  struct S { glm::dvec3 c; double r; glm::dvec3 albedo; };
  std::vector<S> spheres;
  for (const auto& s : scene.spheres) spheres.push_back({glm::dvec3(s.center), double(s.radius), glm::dvec3(s.material.albedo)});
  // Closest hit in double; `margin` is how far the ray passes from any silhouette.
  auto trace = [&](glm::dvec3 o, glm::dvec3 d, double tmax, int& idx, double& margin) {
    double best = tmax;
    idx = -1;
    margin = 1e300;
    for (int k = 0; k < int(spheres.size()); ++k) {
      const glm::dvec3 f = o - spheres[k].c;
      const double b = glm::dot(f, d);
      const glm::dvec3 perp = f - b * d;
      const double dist = std::sqrt(glm::dot(perp, perp));
      margin = std::min(margin, std::fabs(dist - spheres[k].r));
      const double disc = spheres[k].r * spheres[k].r - glm::dot(perp, perp);
      if (disc < 0) continue;
      const double sq = std::sqrt(disc);
      for (double t : {-b - sq, -b + sq})
        if (t > 1e-6 && t < best) { best = t; idx = k; break; }
    }
    return best;
  };
  const glm::dvec3 light(scene.light.position);
  const double I = scene.light.intensity;
  const double W = scene.camera.width, H = scene.camera.height;
  const double focal = W / (2 * std::tan(kPi / 6));
  int checked = 0;
  for (int i = 3; i < 512; i += 8) {
    for (int j = 5; j < 512; j += 8) {
      const glm::dvec3 o(0, 0, 55);
      const glm::dvec3 d = glm::normalize(glm::dvec3(j - W / 2 + 0.5, H / 2 - i - 0.5, -focal));
      int idx;
      double margin;
      const double t = trace(o, d, 1e30, idx, margin);
      if (idx < 0 || margin < 1e-2) continue;
      const glm::dvec3 p = o + t * d;
      glm::dvec3 n = glm::normalize(p - spheres[idx].c);
      if (glm::dot(n, d) > 0) n = -n;
      const glm::dvec3 to = light - p;
      const double dist = glm::length(to);
      const glm::dvec3 wi = to / dist;
      double expect[3] = {0, 0, 0};
      const double cos = glm::dot(n, wi);
      int blocker;
      double smargin;
      trace(p + 1e-6 * n, wi, dist, blocker, smargin);
      if (smargin < 1e-2) continue;  // shadow boundary: float may go either way
      if (cos > 1e-4 && blocker < 0)
        for (int c = 0; c < 3; ++c) expect[c] = I / (4 * kPi * dist * dist) * spheres[idx].albedo[c] / kPi * cos;
      for (int c = 0; c < 3; ++c) {
        const double got = snap.mean(j, i, c);
        EXPECT_NEAR(got, expect[c], 2e-5 * expect[c] + 1e-3) << "pixel row " << i << " col " << j << " c " << c;
      }
      ++checked;
    }
  }
  EXPECT_GT(checked, 3500);
}

namespace {

// One triangle in the plane z = 0 facing +z, seen straight down from
// (0, 0, 10) by a one-pixel camera, every corner's normal `n`.
Scene tilted_normal_triangle(vec3 n, vec3 light, bool vertex_normals) {
  auto mesh = std::make_shared<TriangleMesh>();
  mesh->positions = {vec3(-5, -5, 0), vec3(5, -5, 0), vec3(0, 5, 0)};
  mesh->triangles = {glm::uvec3(0, 1, 2)};
  mesh->normals = {glm::normalize(n)};
  mesh->normal_idx = {glm::uvec3(0, 0, 0)};
  Scene s;
  MeshObject m;
  m.vertex_normals = vertex_normals;
  m.mesh = mesh;
  s.meshes.push_back(m);
  s.light = {light, 1000.0f};
  s.camera.position = vec3(0, 0, 10);
  s.camera.look_at = vec3(0, 0, 0);
  s.camera.width = s.camera.height = 1;
  s.settings.spp = s.settings.target_spp = 1;
  return s;
}

}  // namespace

// The file's vertex normals shade (cos from the interpolated normal), and
// never light a point whose geometric side faces away from the light.
TEST(DirectLight, VertexNormalsShadeButNeverLeakThroughTheTerminator) {
  const double I = 1000.0;
  // Light above at (3, 0, 4), distance 5 from the hit point (0, 0, 0).
  const vec3 n(1, 0, 1);
  const double cos_smooth = (0.6 + 0.8) / std::sqrt(2.0), cos_flat = 0.8;
  const Snapshot flat = render(tilted_normal_triangle(n, vec3(3, 0, 4), false));
  const Snapshot smooth = render(tilted_normal_triangle(n, vec3(3, 0, 4), true));
  EXPECT_NEAR(flat.mean(0, 0, 0), I * cos_flat / (4 * kPi * kPi * 25), 1e-5);
  EXPECT_NEAR(smooth.mean(0, 0, 0), I * cos_smooth / (4 * kPi * kPi * 25), 1e-5);
  // Light just below the plane: the tilted shading normal (1, 0, 0.1) still
  // faces it (cos 0.94), the geometry does not: no light at all.
  const Snapshot leak = render(tilted_normal_triangle(vec3(1, 0, 0.1f), vec3(4, 0, -1), true));
  EXPECT_EQ(leak.mean(0, 0, 0), 0.0f);
}
