// The paths (render/integrator.h) against closed forms: interreflection
// inside a closed diffuse sphere; paths and camera rays side by side the
// same as one at a time; the split factors.
#include <algorithm>

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <glm/geometric.hpp>

#include "geometry/mesh.h"
#include "render/integrator.h"
#include "render/progressive.h"
#include "scene/scene_io.h"
#include "closed_sphere.h"
#include "render_util.h"

using namespace whisker;

// A point light at the centre of a closed diffuse sphere: every path sees the
// same values, so with B = depth + 1 diffuse hits
//   L = rho I / (pi R^2) (1 - rho^B) / (1 - rho) * 1/(4 pi)   (report normalisation)
// holds for every sample, to float precision; also when each camera sample
// splits into several indirect paths.
TEST(IndirectLight, CentredLightInClosedSphereAtEveryDepth) {
  const double rho = 0.6, I = 1000.0, R = 10.0;
  for (const std::vector<int>& split : {std::vector<int>{1}, std::vector<int>{3, 2}}) {
    for (int depth = 0; depth <= 5; ++depth) {
      Scene scene = closed_sphere(float(rho), vec3(0.0f), depth, 64, 8);
      scene.settings.split = split;
      const Snapshot s = render(scene);
      const int B = depth + 1;
      const double expect = rho * I / (kPi * R * R) * (1 - std::pow(rho, B)) / (1 - rho) / (4 * kPi);
      for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x)
          for (int c = 0; c < 3; ++c)
            ASSERT_NEAR(s.mean(x, y, c), expect, 2e-5 * expect) << depth << " split " << split_to_string(split);
    }
  }
}

// The same with a coloured shell and channel weights that halve the split
// (split_weights): paths carrying red and green split round(3 * 0.5) = 2,
// then round(2 * 0.5) = 1 ways; every channel keeps its closed form, and
// blue (albedo 0) stays exactly 0.
TEST(IndirectLight, WeightedSplitKeepsEveryChannelsClosedForm) {
  const glm::dvec3 rho(0.6, 0.3, 0.0);
  const double I = 1000.0, R = 10.0;
  for (int depth = 0; depth <= 4; ++depth) {
    Scene scene = closed_sphere(vec3(rho), vec3(0.0f), depth, 16, 4);
    scene.settings.split = {3, 2};
    scene.settings.split_weights = vec3(0.5f, 0.25f, 1.0f);
    ASSERT_EQ(weighted_split(3, vec3(rho), scene.settings.split_weights), 2);
    const Snapshot s = render(scene);
    const int B = depth + 1;
    for (int c = 0; c < 3; ++c) {
      const double expect =
          rho[c] * I / (kPi * R * R) * (1 - std::pow(rho[c], B)) / (1 - rho[c]) / (4 * kPi);
      for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x)
          ASSERT_NEAR(s.mean(x, y, c), expect, 2e-5 * expect) << depth << " channel " << c;
    }
  }
}

// Off-centre light c: at the first hit y,
//   L(y) = rho/pi [I cos/|c-y|^2 + (I/R^2) rho (1 - rho^(B-1))/(1 - rho)] * 1/(4 pi)
// (a cosine-sampled direction inside a sphere lands uniformly on its area).
// Each pixel mean must sit within a few standard errors of it, with one
// path per sample and with samples split 4 then 4 ways (Sobol) or 3 then 2
// ways (independent), whose standard error comes from the same per-sample sums.
struct OffCentreCase {
  std::vector<int> split;
  SamplerKind sampler;
  vec3 split_weights{1.0f};
  int paths() const {
    int n = 1;
    for (int k : split) n *= k;
    return n;
  }
};
class OffCentre : public ::testing::TestWithParam<OffCentreCase> {};

INSTANTIATE_TEST_SUITE_P(Splits, OffCentre,
                         ::testing::Values(OffCentreCase{{1}, SamplerKind::Sobol},
                                           OffCentreCase{{4, 4}, SamplerKind::Sobol},
                                           OffCentreCase{{3, 2}, SamplerKind::Independent},
                                           OffCentreCase{{4, 4}, SamplerKind::Sobol, vec3(0.5f)}),
                         [](const auto& info) {
                           std::string name = to_string(info.param.sampler);
                           for (int k : info.param.split) name += "Split" + std::to_string(k);
                           if (info.param.split_weights != vec3(1.0f)) name += "Weighted";
                           return name;
                         });

TEST_P(OffCentre, LightInClosedSphere) {
  const double rho = 0.5, I = 1000.0, R = 10.0;
  const glm::dvec3 c(3.0, -2.0, 1.0);
  for (int depth : {1, 3, 5}) {
    const int size = 6, spp = 4096 / GetParam().paths();
    Scene scene = closed_sphere(float(rho), vec3(c), depth, spp, size);
    scene.settings.split = GetParam().split;
    scene.settings.sampler = GetParam().sampler;
    scene.settings.split_weights = GetParam().split_weights;
    expect_closed_form(render(scene), scene, ClosedSphereLight{rho, I, R, c},
                       "depth " + std::to_string(depth));
  }
}

// trace_paths() (paths side by side, render_tile's lanes for one path per
// sample) against trace_path(), the group of one, path by path: the same
// light bit for bit and the same ray count, so no path of a group sees
// another's hit, numbers or state; for groups of 3 and 8 paths of different
// pixels and samples, through glass, mirrors and the hollow ball (Fresnel
// choices draw numbers), the cat's mesh, splitting inside a path and depths
// 0 to 5. (That the loop itself is the report's estimator, the closed forms
// above check, at every depth.)
TEST(TracePaths, SideBySideEqualsOneAtATime) {
  struct Case {
    const char* scene;
    std::vector<int> split;
    int depth;
  };
  const Case cases[] = {{"three-balls-fresnel", {1}, 5}, {"indirect", {1}, 5}, {"indirect", {1}, 0},
                        {"cat", {1}, 5},                 {"cat", {1}, 1},      {"cat", {3, 2}, 3}};
  for (const Case& c : cases) {
    Scene scene = load_scene(resolve_scene(c.scene));
    scene.settings.indirect = true;
    scene.settings.aa = true;
    scene.settings.connect = false;
    scene.settings.split = c.split;
    scene.settings.max_depth = c.depth;
    const World world(scene);
    const CameraFrame cam(scene.camera);
    std::mt19937 rng(7);
    std::uniform_int_distribution<int> coord(0, 511);
    std::uint64_t rays_one = 0, rays_lanes = 0, lit = 0;
    for (const int group : {3, kLanes}) {
      for (int round = 0; round < 40; ++round) {
        PathState one[kLanes], lanes[kLanes];
        Sampler s_one[kLanes], s_lanes[kLanes];
        for (int l = 0; l < group; ++l) {
          const Pixel px{coord(rng), coord(rng)};
          const std::uint64_t sample = std::uint64_t(round * kLanes + l);
          s_one[l] = s_lanes[l] = pixel_sampler(scene.settings, cam, px, sample);
          PathStats unused;
          const PathContext ctx{world, scene.settings, unused};
          one[l] = PathState{camera_ray(ctx, cam, px, s_one[l])};
          lanes[l] = PathState{camera_ray(ctx, cam, px, s_lanes[l])};
        }
        PathStats stats_one, stats_lanes;
        const PathContext ctx_one{world, scene.settings, stats_one};
        const PathContext ctx_lanes{world, scene.settings, stats_lanes};
        for (int l = 0; l < group; ++l) trace_path(ctx_one, one[l], s_one[l]);
        trace_paths(ctx_lanes, lanes, s_lanes, group);
        for (int l = 0; l < group; ++l) {
          for (int k = 0; k < 3; ++k)
            ASSERT_EQ(lanes[l].L[k], one[l].L[k]) << c.scene << " group " << group << " path " << l;
          lit += one[l].L != vec3(0.0f);
        }
        rays_one += stats_one.rays;
        rays_lanes += stats_lanes.rays;
      }
    }
    EXPECT_EQ(rays_lanes, rays_one) << c.scene;
    EXPECT_GT(lit, 200u) << c.scene;  // the comparisons are of light, not of zeros
  }
}

// Camera rays are made eight at a time (camera_paths(), SIMD lanes):
// each lane's ray and sampler are bit for bit those of camera_ray() for
// that sample alone, and the jitter read back from the direction (its
// pixel position on the image plane, less the pixel centre) is the
// report's Gaussian, N(0, 0.5^2) per axis and uncorrelated (section 3);
// none without AA.
TEST(CameraRays, EightSideBySideAreOneAtATimeAndTheJitterIsGaussian) {
  for (const SamplerKind kind : {SamplerKind::Independent, SamplerKind::Sobol}) {
    for (const bool aa : {true, false}) {
      Scene scene = load_scene(resolve_scene("cat"));
      scene.settings.aa = aa;
      scene.settings.sampler = kind;
      const World world(scene);
      const CameraFrame cam(scene.camera);
      PathStats stats;
      const PathContext ctx{world, scene.settings, stats};
      std::mt19937 rng(3);
      std::uniform_int_distribution<int> coord(0, 511);
      double sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0, worst = 0;
      int within = 0, count = 0;
      for (int round = 0; round < 4000; ++round) {
        const int n = 1 + round % 8;
        Pixel px[8];
        Sampler lanes[8], alone[8];
        for (int l = 0; l < n; ++l) {
          px[l] = Pixel{coord(rng), coord(rng)};
          lanes[l] = alone[l] = pixel_sampler(scene.settings, cam, px[l], std::uint64_t(round));
        }
        PathState paths[8];
        camera_paths(ctx, cam, {px, std::size_t(n)}, lanes, paths);
        for (int l = 0; l < n; ++l) {
          const Ray one = camera_ray(ctx, cam, px[l], alone[l]);
          for (int k = 0; k < 3; ++k) {
            ASSERT_EQ(paths[l].ray.d[k], one.d[k]);
            ASSERT_EQ(paths[l].ray.o[k], one.o[k]);
            ASSERT_EQ(paths[l].ray.o_lo[k], one.o_lo[k]);
          }
          ASSERT_EQ(lanes[l].get1d(), alone[l].get1d());  // the same numbers drawn
          const glm::dvec3 d(paths[l].ray.d);
          const double z = glm::dot(d, glm::dvec3(cam.forward));
          const double dx = glm::dot(d, glm::dvec3(cam.right)) / z * cam.focal -
                            (px[l].j - cam.half_w + 0.5);
          const double dy = (cam.half_h - px[l].i - 0.5) -
                            glm::dot(d, glm::dvec3(cam.up)) / z * cam.focal;
          sx += dx, sy += dy, sxx += dx * dx, syy += dy * dy, sxy += dx * dy;
          within += std::fabs(dx) < 0.5;
          worst = std::max({worst, std::fabs(dx), std::fabs(dy)});
          ++count;
        }
      }
      if (!aa) {
        EXPECT_LT(worst, 1e-3);  // the pixel centre, to float rounding
        continue;
      }
      const double N = count;
      // Moments of N(0, 1/4): mean 0 (sd 0.5/sqrt N), variance 1/4 (sd of
      // the estimate sqrt(2/N)/4), covariance 0 (sd 1/(4 sqrt N)),
      // P(|x| < 1 sd) = 0.6827 (sd sqrt(p(1-p)/N)); 5 sd each.
      EXPECT_NEAR(sx / N, 0.0, 5 * 0.5 / std::sqrt(N));
      EXPECT_NEAR(sy / N, 0.0, 5 * 0.5 / std::sqrt(N));
      EXPECT_NEAR(sxx / N, 0.25, 5 * std::sqrt(2.0 / N) / 4);
      EXPECT_NEAR(syy / N, 0.25, 5 * std::sqrt(2.0 / N) / 4);
      EXPECT_NEAR(sxy / N, 0.0, 5 / (4 * std::sqrt(N)));
      EXPECT_NEAR(within / N, 0.682689, 5 * std::sqrt(0.6827 * 0.3173 / N));
    }
  }
}

// render_tile() traces kLanes (pixel, sample) pairs at a time, a group
// straddling pixels when the tile's samples are not a multiple of kLanes: the
// film still gets each pixel's samples added one at a time in order, as
// sample_pixel() gives them, bit for bit, and nothing outside the tile; with
// one path per sample and with split samples alike.
TEST(TracePaths, TileInLanesAddsEachPixelsSamplesInOrder) {
  for (const std::vector<int>& split : {std::vector<int>{1}, std::vector<int>{4, 2}}) {
  Scene scene = sized("cat", 21, 13, 1, 1);
  scene.settings.indirect = scene.settings.aa = true;
  scene.settings.connect = false;
  scene.settings.split = split;
  const World world(scene);
  const CameraFrame cam(scene.camera);
  const PixelBlock block{2, 11, 3, 19};
  for (const int spp : {1, 3, kLanes, 11}) {
    Film lanes, one;
    lanes.reset(21, 13);
    one.reset(21, 13);
    PathStats stats;
    const PathContext ctx{world, scene.settings, stats};
    TileWork tile;
    tile.pixels = block;
    tile.first_sample = 5;
    tile.spp = spp;
    const TileResult r = render_tile(ctx, cam, tile, lanes);
    EXPECT_FALSE(r.abandoned);
    for (int i = block.i0; i < block.i1; ++i)
      for (int j = block.j0; j < block.j1; ++j) {
        PixelSum s;
        for (int k = 0; k < spp; ++k) {
          const std::uint64_t sample = tile.first_sample + std::uint64_t(k);
          Sampler sampler = pixel_sampler(scene.settings, cam, Pixel{i, j}, sample);
          s.add(sample_pixel(ctx, cam, Pixel{i, j}, sampler), sample);
        }
        one.add(std::uint32_t(i * 21 + j), s);
      }
    Snapshot a, b;
    lanes.publish(a);
    one.publish(b);
    EXPECT_EQ(a.sum, b.sum) << spp;
    EXPECT_EQ(a.sum_sq, b.sum_sq) << spp;
    EXPECT_EQ(a.odd_sum, b.odd_sum) << spp;
    EXPECT_GT(*std::max_element(a.sum.begin(), a.sum.end()), 0.0) << spp;
  }
  }
}

// Split factors per diffuse hit: the listed ones, then 1 past the end.
TEST(Splitting, FactorsPerDiffuseHitEndInOnes) {
  RenderSettings settings;
  settings.split = {4, 2};
  const vec3 white(1.0f);
  EXPECT_EQ(split_factor(settings, 0, white), 4);
  EXPECT_EQ(split_factor(settings, 1, white), 2);
  EXPECT_EQ(split_factor(settings, 2, white), 1);
  settings.split_weights = vec3(1.0f, 1.0f, 0.25f);
  EXPECT_EQ(split_factor(settings, 0, vec3(0.0f, 0.0f, 0.7f)), 1);  // blue only: 4 * 0.25
}

TEST(Split, WeightsScaleByTheMostWeightedCarriedChannel) {
  const vec3 w(1.0f, 0.5f, 0.25f);
  EXPECT_EQ(weighted_split(4, vec3(1, 1, 1), w), 4);        // white: the largest weight
  EXPECT_EQ(weighted_split(4, vec3(0, 1, 0), w), 2);        // green only
  EXPECT_EQ(weighted_split(4, vec3(0, 0, 1), w), 1);        // blue only: 4 * 0.25
  EXPECT_EQ(weighted_split(4, vec3(0, 0.3f, 0.7f), w), 2);  // cyan: green's 0.5 wins
  EXPECT_EQ(weighted_split(2, vec3(0, 0, 1), w), 1);        // 0.5 rounds up to 1
  EXPECT_EQ(weighted_split(3, vec3(0, 0, 1), vec3(0.01f)), 1);  // never below 1
  EXPECT_EQ(weighted_split(6, vec3(0, 1, 0), w), 3);
  EXPECT_EQ(weighted_split(4, vec3(1, 0, 0), vec3(1.0f)), 4);   // all 1: the plain factor
  // The cat scene's file: paths that carry green but neither red nor blue split half.
  const Scene cat = load_scene(resolve_scene("cat"));
  EXPECT_EQ(cat.settings.split_weights, vec3(1.0f, 0.5f, 1.0f));
}
