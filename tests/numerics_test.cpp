// The numerics of spawning and render space (docs/NUMERICS.md): shading that
// does not depend on triangle size, the spawn rule's exclusions and bounds,
// and render space's invariance under moving the scene.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include <glm/geometric.hpp>

#include "geometry/mesh.h"
#include "geometry/offset.h"
#include "geometry/sphere.h"
#include "geometry/sphere_set.h"
#include "render/camera.h"
#include "render/integrator.h"
#include "scene/mesh_io.h"
#include "scene/scene_io.h"
#include "scene/world.h"

namespace whisker {
namespace {

// The scene's image, direct light only at pixel centres (no anti-aliasing,
// no bounce: deterministic), straight through sample_pixel.
std::vector<float> direct_image(Scene scene, int size) {
  scene.camera.width = scene.camera.height = size;
  scene.settings.indirect = false;
  scene.settings.aa = false;
  const World world(scene);
  const CameraFrame cam(scene.camera);
  std::vector<float> img;
  PathStats stats;
  const PathContext ctx{world, scene.settings, stats};
  for (int i = 0; i < size; ++i)
    for (int j = 0; j < size; ++j) {
      Sampler sampler(scene.settings.sampler, std::uint32_t(i * size + j), 0, 0);
      const vec3 L = sample_pixel(ctx, cam, Pixel{i, j}, sampler);
      img.insert(img.end(), {L.x, L.y, L.z});
    }
  return img;
}

// Each triangle split into 4 at its edge midpoints (taken in double, so the
// new vertices lie on the old plane but for one rounding).
std::shared_ptr<TriangleMesh> subdivided(const TriangleMesh& m) {
  auto out = std::make_shared<TriangleMesh>();
  out->exact = m.exact;
  for (const auto& t : m.triangles) {
    const unsigned a = t.x, b = t.y, c = t.z;
    const auto mid = [&](unsigned p, unsigned q) {
      out->exact.push_back(0.5 * (m.exact[p] + m.exact[q]));
      return unsigned(out->exact.size() - 1);
    };
    const unsigned ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
    out->triangles.insert(out->triangles.end(),
                          {{a, ab, ca}, {ab, b, bc}, {ca, bc, c}, {ab, bc, ca}});
  }
  for (const auto& p : out->exact) out->positions.push_back(vec3(p));
  return out;
}

TEST(Numerics, CatShadingDoesNotDependOnTriangleSize) {
  // The report's program takes a triangle's normal as cross(e1, e2) without
  // normalising it, so its direct light scales with twice the triangle's
  // area; here a mesh with every triangle split in 4 (a quarter of the area)
  // must render the same image, but for pixels where a silhouette or a
  // shadow edge passes within float rounding of the pixel centre.
  Scene scene = load_scene(resolve_scene("cat"));
  const Scene fine_scene = [&] {
    Scene s = scene;
    s.meshes[0].mesh = subdivided(*scene.meshes[0].mesh);
    return s;
  }();
  ASSERT_EQ(fine_scene.meshes[0].mesh->triangles.size(), 4 * scene.meshes[0].mesh->triangles.size());
  const int size = 96;
  const std::vector<float> a = direct_image(scene, size), b = direct_image(fine_scene, size);
  int differ = 0, cat_pixels = 0;
  double sum_a = 0.0, sum_b = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    sum_a += a[k];
    sum_b += b[k];
    if (!(std::fabs(a[k] - b[k]) <= 1e-4f * std::fabs(a[k]) + 1e-3f)) ++differ;
  }
  // The cat covers a good part of the image: a test of something.
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x)
      cat_pixels += a[(std::size_t(y) * size + x) * 3] == a[(std::size_t(y) * size + x) * 3 + 2];
  EXPECT_GT(cat_pixels, size * size / 20);  // white cat: equal red and blue
  EXPECT_LE(differ, int(a.size()) / 1000) << "of " << a.size() << " channel values";
  EXPECT_NEAR(sum_b / sum_a, 1.0, 1e-4);
}

TEST(Numerics, FloatStepMovesOneUlpAwayFromTheSurface) {
  EXPECT_EQ(float_step(1.0f, 1.0f), std::nextafter(1.0f, 2.0f));
  EXPECT_EQ(float_step(1.0f, -1.0f), std::nextafter(1.0f, 0.0f));
  EXPECT_EQ(float_step(-1.0f, 1.0f), std::nextafter(-1.0f, 0.0f));
  EXPECT_EQ(float_step(-1.0f, -1.0f), std::nextafter(-1.0f, -2.0f));
  EXPECT_GT(float_step(0.0f, 1.0f), 0.0f);
  EXPECT_LT(float_step(0.0f, -1.0f), 0.0f);
  EXPECT_EQ(float_step(3.0f, 0.0f), 3.0f);
}

TEST(Numerics, TriangleOriginsLeaveThePlaneAtEveryScale) {
  // A point on a triangle from its barycentric weights, offset by the error
  // bound: on the side of the direction, strictly, in exact arithmetic (the
  // plane's side decided in double), from 1e-5 to 1e6 in size and offset.
  std::mt19937 g(3);
  std::uniform_real_distribution<float> u(0.0f, 1.0f), s(-1.0f, 1.0f);
  for (double scale : {1e-5, 1e-2, 1.0, 1e3, 1e6}) {
    for (double shift : {0.0, 1e2, 1e5}) {
      int wrong = 0;
      for (int k = 0; k < 20000; ++k) {
        const auto vtx = [&] {
          return vec3(glm::dvec3(s(g), s(g), s(g)) * scale + glm::dvec3(shift));
        };
        const vec3 v0 = vtx(), v1 = vtx(), v2 = vtx();
        const glm::dvec3 e1 = glm::dvec3(v1) - glm::dvec3(v0), e2 = glm::dvec3(v2) - glm::dvec3(v0);
        const glm::dvec3 cr = glm::cross(e1, e2);
        if (cr == glm::dvec3(0.0)) continue;  // collinear in float: never hit
        const glm::dvec3 nd = glm::normalize(cr);
        float b1 = u(g), b2 = u(g);
        if (b1 + b2 > 1.0f) { b1 = 1.0f - b1; b2 = 1.0f - b2; }
        const float b0 = 1.0f - b1 - b2;
        const vec3 a = b0 * v0, b = b1 * v1, c = b2 * v2;
        const vec3 p = a + b + c;
        constexpr float kGamma7x2 = 2.0f * 7.0f * 0x1p-24f / (1.0f - 7.0f * 0x1p-24f);
        const vec3 err = (glm::abs(a) + glm::abs(b) + glm::abs(c)) * kGamma7x2;
        const vec3 d = vec3(s(g), s(g), s(g));
        const vec3 o = offset_ray_origin(p, err, vec3(nd), d);
        const double side = glm::dot(glm::dvec3(o) - glm::dvec3(v0), nd);
        const double want = glm::dot(glm::dvec3(d), nd);
        if (want != 0.0 && !(side * want > 0.0)) ++wrong;
      }
      EXPECT_EQ(wrong, 0) << "scale " << scale << " shift " << shift;
    }
  }
}

TEST(Numerics, ARayLeavingASphereFindsAShellOneUlpAway) {
  // Two concentric spheres one float ULP of the radius apart, far from the
  // origin: a ray leaving the outer one inwards (from its double hit point)
  // meets the inner one next, at about the gap over the cosine; one leaving
  // outwards never meets its own sphere.
  const vec3 c(50.0f, -20.0f, 30.0f);
  const float r = 10.0f, ri = std::nextafter(10.0f, 0.0f);
  const SphereSet set({Sphere{c, r, false}, Sphere{c, ri, true}});
  std::mt19937 g(9);
  std::normal_distribution<float> n;
  int tested = 0, wrong = 0;
  for (int k = 0; k < 20000; ++k) {
    const glm::dvec3 dir = glm::normalize(glm::dvec3(n(g), n(g), n(g)));
    const glm::dvec3 pd = glm::dvec3(c) + double(r) * dir;
    vec3 p, lo;
    split_double(pd, p, lo);
    vec3 d = vec3(n(g), n(g), n(g));
    d = glm::normalize(d);
    const float cos_out = glm::dot(d, vec3(dir));
    if (std::fabs(cos_out) < 0.05f) continue;  // grazing: the gap is a chord, not a crossing
    ++tested;
    const Ray ray = spawn_from(p, vec3(dir), lo, 0, vec3(dir), d);
    float t = kInf;
    std::uint32_t id = 99;
    const bool hit = set.intersect(ray, kInf, t, id);
    if (cos_out > 0.0f) {
      wrong += hit;  // leaving outwards: nothing else out there
    } else {
      const double gap = double(r) - double(ri);
      wrong += !(hit && id == 1 && t < 4.0 * gap / -cos_out);
    }
  }
  EXPECT_GT(tested, 15000);
  EXPECT_EQ(wrong, 0);
}

TEST(Numerics, RenderSpaceMakesAMovedSceneRenderTheSame) {
  // The three balls moved by 1e6 (every position a float exactly): render
  // space subtracts the camera in double, so the images agree to the bit.
  Scene scene = load_scene(resolve_scene("three-balls"));
  Scene moved = scene;
  const vec3 t(1e6f, -1e6f, 1e6f);
  moved.camera.position += t;
  moved.camera.look_at += t;
  moved.light.position += t;
  for (auto& s : moved.spheres) s.center += t;
  EXPECT_EQ(direct_image(scene, 48), direct_image(moved, 48));
}

TEST(Numerics, CameraBasisOfAnyUpLengthAndNearlyVerticalView) {
  // The scene file takes `up` of any length in [1e-30, 1e30]: the image must
  // not depend on it. Squared in float, an up of 1e-23 underflowed (a NaN
  // basis, a black image) and one of 1e20 overflowed (a zero basis).
  Scene scene = load_scene(resolve_scene("three-balls"));
  const std::vector<float> ref = direct_image(scene, 16);
  for (const float k : {1e-23f, 1e-30f, 1e20f, 1e30f}) {
    Scene s = scene;
    s.camera.up *= k;
    EXPECT_EQ(direct_image(s, 16), ref) << "up times " << k;
  }
  // A view straight down with look_at 1e-30 off the vertical: the side
  // vector is 2e-32 long, not zero; the frame must be orthonormal.
  Camera c = scene.camera;
  c.position = {0.0, 55.0, 0.0};
  c.look_at = {1e-30, 0.0, 0.0};
  const CameraFrame cam(c);
  EXPECT_NEAR(glm::length(cam.right), 1.0f, 1e-6f);
  EXPECT_NEAR(glm::length(cam.up), 1.0f, 1e-6f);
  EXPECT_NEAR(glm::dot(cam.right, cam.forward), 0.0f, 1e-6f);
  Scene down = scene;
  down.camera = c;
  for (const float v : direct_image(down, 16)) EXPECT_TRUE(std::isfinite(v));
  const std::vector<float> img = direct_image(down, 16);
  EXPECT_GT(*std::max_element(img.begin(), img.end()), 0.0f);  // the floor is lit
}

}  // namespace
}  // namespace whisker
