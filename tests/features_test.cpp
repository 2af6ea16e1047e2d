// The denoiser's features (render/features.h) against closed forms on tiny
// scenes: a diffuse ball's albedo, normal and hit distance; a mirror ball and
// a glass ball in front of diffuse walls (the wall's albedo, the chain's
// length); a miss; a chain that never ends on a diffuse surface; the Fresnel
// choice; and a pixel's mean over its jittered camera rays.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>

#include <glm/geometric.hpp>

#include "render/features.h"
#include "render/integrator.h"
#include "scene/world.h"

using namespace whisker;

namespace {

SphereObject ball(dvec3 c, float r, MaterialKind kind, vec3 albedo = vec3(1.0f)) {
  SphereObject s;
  s.name = "s";
  s.center = c;
  s.radius = r;
  s.material.kind = kind;
  s.material.albedo = albedo;
  return s;
}

Scene tiny(std::vector<SphereObject> spheres) {
  Scene s;
  s.name = "tiny";
  s.spheres = std::move(spheres);
  s.camera.width = s.camera.height = 16;
  s.settings.max_depth = 5;
  return s;
}

// The first root t > eps of |o + t d - c| = r, in double.
std::optional<double> hit(glm::dvec3 o, glm::dvec3 d, glm::dvec3 c, double r) {
  const glm::dvec3 f = o - c;
  const double b = glm::dot(f, d), disc = b * b - (glm::dot(f, f) - r * r);
  if (disc < 0) return std::nullopt;
  const double sq = std::sqrt(disc);
  for (double t : {-b - sq, -b + sq})
    if (t > 1e-6) return t;
  return std::nullopt;
}

const glm::dvec3 kCam(0.0, 0.0, 55.0);

}  // namespace

TEST(Features, DiffuseBallAlbedoNormalAndDepthAreExact) {
  const vec3 colour(0.2f, 0.5f, 0.8f);
  const glm::dvec3 c(1.0, -2.0, 0.0);
  const Scene scene = tiny({ball(c, 10.0f, MaterialKind::Diffuse, colour)});
  const World world(scene);
  const glm::dvec3 d = glm::normalize(glm::dvec3(0.07, 0.05, -1.0));
  const Features f = ray_features(world, scene.settings, world.to_render(kCam, vec3(d)));
  const double t = *hit(kCam, d, c, 10.0);
  const glm::dvec3 n = (kCam + t * d - c) / 10.0;
  EXPECT_EQ(f.albedo, colour);
  EXPECT_NEAR(f.normal.x, n.x, 1e-5);
  EXPECT_NEAR(f.normal.y, n.y, 1e-5);
  EXPECT_NEAR(f.normal.z, n.z, 1e-5);
  EXPECT_NEAR(f.depth, t, 1e-5 * t);
}

// A mirror ball in front of the camera, a diffuse wall behind it (a huge
// sphere, as the report's walls): the feature is the wall's, at the end of
// the reflected ray, and the depth the length of both segments.
TEST(Features, MirrorShowsTheWallsAlbedoAtTheReflectedHit) {
  const vec3 wall(0.3f, 0.6f, 0.9f);
  const glm::dvec3 wc(0.0, 0.0, 1000.0);
  const Scene scene = tiny({ball(dvec3(0.0), 10.0f, MaterialKind::Mirror),
                            ball(wc, 940.0f, MaterialKind::Diffuse, wall)});
  const World world(scene);
  const glm::dvec3 d = glm::normalize(glm::dvec3(0.05, -0.03, -1.0));
  const Features f = ray_features(world, scene.settings, world.to_render(kCam, vec3(d)));
  const double t1 = *hit(kCam, d, glm::dvec3(0.0), 10.0);
  const glm::dvec3 p1 = kCam + t1 * d, n1 = p1 / 10.0;
  const glm::dvec3 r = d - 2.0 * glm::dot(d, n1) * n1;
  const double t2 = *hit(p1, r, wc, 940.0);
  const glm::dvec3 n2 = (p1 + t2 * r - wc) / 940.0;
  EXPECT_EQ(f.albedo, wall);
  EXPECT_NEAR(f.depth, t1 + t2, 1e-5 * (t1 + t2));
  // The wall is seen from inside its sphere, on its near side: the outward
  // normal n2 there already faces the reflected ray.
  ASSERT_LT(glm::dot(n2, r), 0.0);
  EXPECT_NEAR(f.normal.x, n2.x, 1e-5);
  EXPECT_NEAR(f.normal.y, n2.y, 1e-5);
  EXPECT_NEAR(f.normal.z, n2.z, 1e-5);
}

// Glass is followed along the transmitted ray: through the ball's centre
// the ray goes straight on, to the wall in front (45 + 20 + 50 = 115 away).
TEST(Features, GlassIsFollowedAlongTheTransmittedRay) {
  const vec3 front(0.1f, 0.9f, 0.2f), behind(0.7f, 0.1f, 0.4f);
  Scene scene = tiny({ball(dvec3(0.0), 10.0f, MaterialKind::Glass),
                      ball(dvec3(0.0, 0.0, -1000.0), 940.0f, MaterialKind::Diffuse, front),
                      ball(dvec3(0.0, 0.0, 1000.0), 940.0f, MaterialKind::Diffuse, behind)});
  const World world(scene);
  const Ray ray = world.to_render(kCam, vec3(0.0f, 0.0f, -1.0f));
  const Features f = ray_features(world, scene.settings, ray);
  EXPECT_EQ(f.albedo, front);
  EXPECT_NEAR(f.depth, 115.0, 1e-4);
  EXPECT_NEAR(f.normal.z, 1.0, 1e-6);

  // With Fresnel on, a given sampler makes the path's own choice: about
  // Schlick's R0 = 0.04 of the samples reflect at normal incidence on the
  // way in (and again on the way out), and see the wall behind; without a
  // sampler the chain always transmits.
  scene.settings.fresnel = true;
  int reflected = 0, transmitted = 0;
  for (std::uint64_t s = 0; s < 2000; ++s) {
    Sampler sampler(SamplerKind::Independent, 7, s, 3);
    const Features g = ray_features(world, scene.settings, ray, &sampler);
    reflected += g.albedo == behind;
    transmitted += g.albedo == front;
    EXPECT_EQ(ray_features(world, scene.settings, ray).albedo, front);
  }
  EXPECT_EQ(reflected + transmitted, 2000);
  // Reflected on entering (R0 = 0.04), or transmitted, reflected on leaving
  // and transmitted back out towards the camera (0.96 x 0.04 x 0.96), and
  // so on: p = 0.077, 154 of 2000 (standard deviation 12).
  EXPECT_GT(reflected, 110);
  EXPECT_LT(reflected, 200);
}

TEST(Features, MissHasZeroAlbedoAndNormalAndTheMissDepth) {
  const Scene scene = tiny({ball(dvec3(0.0), 10.0f, MaterialKind::Diffuse)});
  const World world(scene);
  const Features f = ray_features(world, scene.settings, world.to_render(kCam, vec3(0.0f, 1.0f, 0.0f)));
  EXPECT_EQ(f.albedo, vec3(0.0f));
  EXPECT_EQ(f.normal, vec3(0.0f));
  EXPECT_EQ(f.depth, kMissDepth);
}

// Inside a mirror ball no chain ever ends on a diffuse surface: after the
// path's max_depth + 1 hits the albedo is zero (the path's light is), the
// normal the last mirror's, the depth the chords' sum.
TEST(Features, EndlessMirrorChainStopsAtThePathsDepthWithZeroAlbedo) {
  Scene scene = tiny({ball(dvec3(0.0, 0.0, 55.0), 100.0f, MaterialKind::Mirror)});
  scene.settings.max_depth = 3;
  const World world(scene);
  // Along a diameter: 100 to the wall, then 200 per chord.
  const Features f = ray_features(world, scene.settings, world.to_render(kCam, vec3(0.0f, 0.0f, -1.0f)));
  EXPECT_EQ(f.albedo, vec3(0.0f));
  EXPECT_NEAR(std::fabs(f.normal.z), 1.0, 1e-6);
  EXPECT_NEAR(f.depth, 100.0 + 3 * 200.0, 1e-3);
}

// A pixel's features are the mean over its samples' camera rays, jittered
// as the render jitters them: inside the ball the albedo is the ball's; on
// its silhouette, between the ball's and none.
TEST(Features, PixelMeanFollowsTheSamplesJitteredRays) {
  const vec3 colour(0.4f, 0.4f, 0.4f);
  Scene scene = tiny({ball(dvec3(0.0), 10.0f, MaterialKind::Diffuse, colour)});
  scene.camera.width = scene.camera.height = 64;
  scene.settings.aa = true;
  const World world(scene);
  const CameraFrame cam(scene.camera);
  PathStats stats;
  const PathContext ctx{world, scene.settings, stats};
  const Features inside = pixel_features(ctx, cam, Pixel{32, 32}, 0, 64).mean();
  EXPECT_EQ(inside.albedo, colour);
  // The pixel's centre is half a pixel off the ball's: its normals tilt by
  // about 0.05 rad (0.009 rad of view times 55 / 10).
  EXPECT_NEAR(inside.normal.z, 1.0, 1e-2);
  // The ball's silhouette on row 32: radius 10 at distance 55 is about
  // 64 / (2 tan 30 deg) x 10 / sqrt(55^2 - 10^2) = 10.3 px from the centre.
  double lo = 1.0, hi = 0.0;
  int edges = 0;
  for (int j = 38; j <= 46; ++j) {
    const FeatureSum s = pixel_features(ctx, cam, Pixel{32, j}, 0, 64);
    EXPECT_EQ(s.count, 64u);
    lo = std::min(lo, double(s.mean().albedo.x));
    hi = std::max(hi, double(s.mean().albedo.x));
    const bool edge = s.mean().albedo.x > 0.01f && s.mean().albedo.x < 0.39f;
    if (edge) {
      EXPECT_GT(s.mean().depth, 50.0f);  // part ball, part miss
    }
    edges += edge;
  }
  EXPECT_GE(edges, 1);
  EXPECT_FLOAT_EQ(float(hi), 0.4f);
  EXPECT_FLOAT_EQ(float(lo), 0.0f);
  // Without AA the mean is the centre ray's features, exactly.
  scene.settings.aa = false;
  const PathContext plain{world, scene.settings, stats};
  const Features one = pixel_features(plain, cam, Pixel{30, 35}, 0, 4).mean();
  const Features centre = ray_features(world, scene.settings,
                                       world.to_render(cam.origin, cam.centre_direction(30, 35)));
  EXPECT_EQ(one.albedo, centre.albedo);
  EXPECT_EQ(one.normal, centre.normal);
  EXPECT_EQ(one.depth, centre.depth);
}

// The render takes its features from the path itself (PathState::features):
// through mirrors, glass with Fresnel choices, misses and chains cut at the
// depth limit they are those ray_features() finds for the same camera ray
// and numbers, bit for bit, and the path's light is the same with and
// without them.
TEST(Features, ThePathRecordsWhatTheRayFindsAlongIt) {
  Scene scene = tiny({ball(dvec3(-12.0, 0.0, 0.0), 9.0f, MaterialKind::Mirror),
                      ball(dvec3(12.0, 0.0, 0.0), 9.0f, MaterialKind::Glass),
                      ball(dvec3(0.0, 0.0, -60.0), 40.0f, MaterialKind::Diffuse, vec3(0.3f, 0.6f, 0.9f)),
                      ball(dvec3(0.0, 0.0, 0.0), 200.0f, MaterialKind::Diffuse, vec3(0.5f))});
  scene.camera.width = scene.camera.height = 24;
  scene.settings.fresnel = scene.settings.aa = scene.settings.indirect = true;
  for (int depth : {0, 1, 5}) {
    scene.settings.max_depth = depth;
    const World world(scene);
    const CameraFrame cam(scene.camera);
    PathStats stats;
    const PathContext ctx{world, scene.settings, stats};
    int specular_first = 0;
    for (int i = 0; i < 24; ++i)
      for (int j = 0; j < 24; ++j)
        for (std::uint64_t sample = 0; sample < 3; ++sample) {
          const Pixel px{i, j};
          Sampler with = pixel_sampler(scene.settings, cam, px, sample);
          Sampler without = with;
          PathState a{camera_ray(ctx, cam, px, with)};
          PathState b{camera_ray(ctx, cam, px, without)};
          Sampler choices = with;
          const Features expected = ray_features(world, scene.settings, a.ray, &choices);
          Features got;
          a.features = &got;
          trace_paths(ctx, &a, &with, 1);
          trace_paths(ctx, &b, &without, 1);
          EXPECT_EQ(got.albedo, expected.albedo) << i << "," << j << " depth " << depth;
          EXPECT_EQ(got.normal, expected.normal) << i << "," << j << " depth " << depth;
          EXPECT_EQ(got.depth, expected.depth) << i << "," << j << " depth " << depth;
          EXPECT_EQ(a.L, b.L);
          specular_first += expected.depth > 0.0f && expected.albedo != vec3(0.3f, 0.6f, 0.9f) &&
                            expected.albedo != vec3(0.5f);
        }
    // Below full depth some chains of mirrors and glass are cut short.
    if (depth < 5) EXPECT_GT(specular_first, 0) << "no chain was cut at depth " << depth;
  }
}
