// The estimator against closed forms: reflection and refraction laws,
// Schlick, the diffuse ball's direct light, and interreflection inside a
// closed diffuse sphere.
#include <algorithm>

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <glm/geometric.hpp>

#include "geometry/mesh.h"
#include "render/direct_light.h"
#include "render/integrator.h"
#include "render/progressive.h"
#include "render/sampling.h"
#include "render/scattering.h"
#include "render/splitting.h"
#include "scene/scene_io.h"
#include "render_util.h"

using namespace whisker;

namespace {

constexpr double kPi = 3.14159265358979323846;

// A closed diffuse sphere of radius R and grey albedo rho, the camera inside
// looking at the far wall.
Scene closed_sphere(vec3 rho, vec3 light, int depth, int spp, int size) {
  Scene s;
  s.name = "closed-sphere";
  s.spheres.push_back({"shell", vec3(0.0f), 10.0f, 0.0f, {MaterialKind::Diffuse, rho}});
  s.light = {light, 1000.0f};
  s.camera.position = vec3(0.0f, 0.0f, 5.0f);
  s.camera.look_at = vec3(0.0f, 0.0f, -10.0f);
  s.camera.width = s.camera.height = size;
  s.camera.fov_deg = 90.0f;
  s.settings.indirect = true;
  s.settings.max_depth = depth;
  s.settings.spp = spp;
  s.settings.target_spp = spp;
  return s;
}
Scene closed_sphere(float rho, vec3 light, int depth, int spp, int size) {
  return closed_sphere(vec3(rho), light, depth, spp, size);
}

}  // namespace

TEST(Optics, ReflectionMirrorsTheNormalComponent) {
  const vec3 d = glm::normalize(vec3(1, -2, 0.5f));
  const vec3 n(0, 1, 0);
  const vec3 r = reflect(d, n);
  EXPECT_FLOAT_EQ(r.x, d.x);
  EXPECT_FLOAT_EQ(r.y, -d.y);
  EXPECT_FLOAT_EQ(r.z, d.z);
}

TEST(Optics, SnellAtManyAngles) {
  // n1 sin(i) = n2 sin(t), with the refracted ray in the plane of d and n.
  const vec3 n(0, 0, 1);
  for (const auto& [n1, n2] : {std::pair{1.0f, 1.5f}, {1.5f, 1.0f}, {1.0f, 2.4f}}) {
    for (int k = 0; k < 90; ++k) {
      const double i = k * kPi / 180.0;
      const vec3 d(float(std::sin(i)), 0.0f, float(-std::cos(i)));
      vec3 t;
      const double sin_t = n1 / n2 * std::sin(i);
      if (sin_t >= 1.0) {
        EXPECT_FALSE(refract(d, n, n1 / n2, t)) << "TIR expected at " << k << " deg";
        continue;
      }
      if (sin_t > 0.9999) continue;  // grazing: the boundary itself
      ASSERT_TRUE(refract(d, n, n1 / n2, t)) << k;
      EXPECT_NEAR(glm::length(t), 1.0f, 1e-6f);
      EXPECT_NEAR(t.x, sin_t, 2e-6) << k;
      EXPECT_NEAR(t.y, 0.0f, 1e-7f);
      EXPECT_LT(t.z, 0.0f);
    }
  }
}

TEST(Optics, TotalInternalReflectionPastTheCriticalAngle) {
  // From glass (1.5) to air the critical angle is asin(1/1.5) = 41.81 deg.
  const double crit = std::asin(1.0 / 1.5);
  const vec3 n(0, 0, 1);
  vec3 t;
  for (const double i : {crit + 1e-3, crit + 0.1, 1.2, 1.5}) {
    const vec3 d(float(std::sin(i)), 0.0f, float(-std::cos(i)));
    EXPECT_FALSE(refract(d, n, 1.5f, t)) << i;
  }
  const vec3 d(float(std::sin(crit - 1e-3)), 0.0f, float(-std::cos(crit - 1e-3)));
  EXPECT_TRUE(refract(d, n, 1.5f, t));
}

TEST(Optics, SchlickMatchesItsEndpoints) {
  EXPECT_NEAR(schlick(1.0f, 1.0f, 1.5f), 0.04f, 1e-7f);  // ((1.5-1)/(1.5+1))^2
  EXPECT_NEAR(schlick(-1.0f, 1.5f, 1.0f), 0.04f, 1e-7f);
  EXPECT_NEAR(schlick(0.0f, 1.0f, 1.5f), 1.0f, 1e-7f);   // grazing
  // Halfway: R0 + (1 - R0) 0.5^5.
  EXPECT_NEAR(schlick(0.5f, 1.0f, 1.5f), 0.04f + 0.96f / 32.0f, 1e-6f);
}

TEST(Optics, SinCosOfATurnMatchesDoublePrecision) {
  double worst = 0.0;
  for (int k = 0; k <= 1 << 20; ++k) {
    const float u = float(k) / float(1 << 20);
    float s, c;
    sincos_turn(u, s, c);
    const double a = 2.0 * kPi * double(u);
    worst = std::max({worst, std::fabs(s - std::sin(a)), std::fabs(c - std::cos(a))});
  }
  EXPECT_LT(worst, 1e-7);
}

TEST(Optics, CosineSamplingHasTheRightMoments) {
  // For p(w) = cos/pi: E[cos] = 2/3, E[cos^2] = 1/2, and the tangential
  // components average to zero.
  std::mt19937 g(5);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const vec3 n = glm::normalize(vec3(0.3f, -0.5f, 0.8f));
  double c1 = 0, c2 = 0;
  vec3 mean(0.0f);
  const int N = 400000;
  for (int k = 0; k < N; ++k) {
    const vec3 w = cosine_direction(n, u(g), u(g));
    const double c = glm::dot(w, n);
    ASSERT_GE(c, 0.0);
    c1 += c;
    c2 += c * c;
    mean += w - float(c) * n;
  }
  EXPECT_NEAR(c1 / N, 2.0 / 3.0, 5 * std::sqrt(1.0 / 18.0 / N));  // var(cos) = 1/2 - 4/9
  EXPECT_NEAR(c2 / N, 0.5, 5 * std::sqrt(1.0 / 12.0 / N));
  EXPECT_LT(glm::length(mean) / N, 3e-3);
}

// The direction is built from an orthonormal basis without a final
// normalisation: it must be unit to a few ULP for every normal, including
// the basis' special case n.z = -1 and its neighbourhood.
TEST(Optics, CosineDirectionsAreUnitWithoutNormalising) {
  std::mt19937 g(6);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  double worst = 0.0;
  for (const vec3 n : {glm::normalize(vec3(0.3f, -0.5f, 0.8f)), vec3(0.0f, 0.0f, -1.0f),
                       glm::normalize(vec3(1e-4f, -2e-4f, -1.0f)), vec3(1.0f, 0.0f, 0.0f),
                       glm::normalize(vec3(-0.6f, 0.7f, -0.2f))}) {
    for (int k = 0; k < 100000; ++k) {
      const glm::dvec3 w(cosine_direction(n, u(g), u(g)));
      worst = std::max(worst, std::fabs(glm::length(w) - 1.0));
    }
  }
  EXPECT_LT(worst, 1e-6) << worst;
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
  int reuse = 1;  // path reuse's block side (render/path_reuse.h)
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
                                           OffCentreCase{{4, 4}, SamplerKind::Sobol, vec3(0.5f)},
                                           OffCentreCase{{4, 4}, SamplerKind::Sobol, vec3(1.0f), 2},
                                           OffCentreCase{{2, 2}, SamplerKind::Independent, vec3(1.0f), 4},
                                           OffCentreCase{{1}, SamplerKind::Sobol, vec3(1.0f), 3}),
                         [](const auto& info) {
                           std::string name = to_string(info.param.sampler);
                           for (int k : info.param.split) name += "Split" + std::to_string(k);
                           if (info.param.split_weights != vec3(1.0f)) name += "Weighted";
                           if (info.param.reuse > 1) name += "Reuse" + std::to_string(info.param.reuse);
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
    scene.settings.reuse = GetParam().reuse;
    const Snapshot s = render(scene);
    const int B = depth + 1;
    const CameraFrame cam(scene.camera);
    double chi2 = 0.0;
    for (int i = 0; i < size; ++i) {
      for (int j = 0; j < size; ++j) {
        const Ray r = cam.ray(i, j, 0.0f, 0.0f);
        const glm::dvec3 o(r.o), d(r.d);
        const double b = glm::dot(o, d);
        const double t = -b + std::sqrt(b * b - (glm::dot(o, o) - R * R));
        const glm::dvec3 y = o + t * d;
        const glm::dvec3 n = -y / R;  // inward
        const glm::dvec3 to = c - y;
        const double d2 = glm::dot(to, to);
        const double cos = glm::dot(n, to) / std::sqrt(d2);
        const double expect = rho / kPi * (I * cos / d2 + I / (R * R) * rho * (1 - std::pow(rho, B - 1)) / (1 - rho)) / (4 * kPi);
        const std::size_t p = std::size_t(i) * size + j;
        const double mean = s.sum[3 * p] / double(spp);
        const double var = (s.sum_sq[p] / double(spp) - mean * mean) * spp / (spp - 1.0);
        const double se = std::sqrt(var / spp);
        EXPECT_NEAR(mean, expect, 5 * se + 1e-9) << "depth " << depth << " pixel " << i << "," << j;
        chi2 += (mean - expect) * (mean - expect) / (se * se);
      }
    }
    // 36 pixels: the sum of squared z-scores is chi-square with 36 dof;
    // P(chi2 > 80) < 1e-4.
    EXPECT_LT(chi2, 80.0) << "depth " << depth;
  }
}

// Sums over millions of samples keep their digits: 2^21 samples of one pixel
// whose every path has the same value still give that value to 1e-6.
TEST(Accumulation, MillionsOfSamplesKeepPrecision) {
  Scene scene = closed_sphere(0.6f, vec3(0.0f), 2, 1 << 17, 1);
  scene.settings.target_spp = 1 << 21;
  const Snapshot s = render(scene);
  ASSERT_EQ(s.spp, std::uint64_t(1) << 21);
  const double rho = 0.6, expect = rho * 1000.0 / (kPi * 100.0) * (1 - rho * rho * rho) / (1 - rho) / (4 * kPi);
  // A float running sum would be off by ~1e-3 here; the buffer is double.
  EXPECT_NEAR(double(s.sum[0]) / double(s.spp), expect, 1e-6 * expect);
}

TEST(Accumulation, InfiniteSamplesAreDroppedAndCounted) {
  // A light a hundred-thousandth above the ball's surface (a few float ULPs
  // at the 45 units from the camera that render space measures), at huge
  // intensity: the direct term overflows float to +inf on the pixel that
  // looks straight at it.
  Scene scene;
  scene.spheres.push_back({"ball", vec3(0.0f), 10.0f, 0.0f, {MaterialKind::Diffuse, vec3(1.0f)}});
  scene.light = {vec3(0.0f, 0.0f, 10.00001f), 1e36f};
  scene.camera.width = scene.camera.height = 1;
  scene.settings.spp = scene.settings.target_spp = 4;
  const Snapshot s = render(scene);
  EXPECT_EQ(s.counters.nan_count, 4u);
  EXPECT_EQ(s.sum[0], 0.0f);
  EXPECT_TRUE(std::isfinite(s.sum[0]));
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
