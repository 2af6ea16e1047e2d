// Ray/sphere intersection and ray spawning: exact cases, the huge wall
// spheres against a long-double reference, and re-intersection.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <utility>

#include <glm/geometric.hpp>

#include "geometry/offset.h"
#include "geometry/sphere.h"
#include "geometry/sphere_set.h"
#include "geometry/surface_point.h"
#include "scene/scene_io.h"

using namespace whisker;

namespace {

// Closest positive root in long double, from the textbook quadratic: the
// reference the float code is measured against.
long double reference_t(const Sphere& s, const Ray& r) {
  using L = long double;
  const L fx = L(r.o.x) - s.center.x, fy = L(r.o.y) - s.center.y, fz = L(r.o.z) - s.center.z;
  const L dx = r.d.x, dy = r.d.y, dz = r.d.z;
  const L a = dx * dx + dy * dy + dz * dz;
  const L b = 2 * (fx * dx + fy * dy + fz * dz);
  const L c = fx * fx + fy * fy + fz * fz - L(s.radius) * L(s.radius);
  const L disc = b * b - 4 * a * c;
  if (disc < 0) return -1;
  const L sq = std::sqrt(disc);
  const L t0 = (-b - sq) / (2 * a), t1 = (-b + sq) / (2 * a);
  if (t0 > 0) return t0;
  if (t1 > 0) return t1;
  return -1;
}

vec3 uniform_direction(std::mt19937& g) {
  std::normal_distribution<float> n;
  for (;;) {
    const vec3 v(n(g), n(g), n(g));
    const float l = glm::length(v);
    if (l > 1e-3f) return v / l;
  }
}

std::vector<Sphere> report_spheres() {
  // The six walls and the three balls' shells (hollow = two shells).
  const Scene scene = load_scene(resolve_scene("three-balls"));
  std::vector<Sphere> out;
  for (const auto& s : scene.spheres) {
    out.push_back({s.center, s.radius, false});
    if (s.material.kind == MaterialKind::HollowGlass) out.push_back({s.center, s.inner_radius, true});
  }
  return out;
}

}  // namespace

TEST(Sphere, HitMissTangentInside) {
  const Sphere s{vec3(0, 0, 0), 2.0f};
  // Head on: enters at 8.
  EXPECT_FLOAT_EQ(intersect_sphere(s, Ray{vec3(0, 0, 10), vec3(0, 0, -1)}), 8.0f);
  // Pointing away: no hit.
  EXPECT_EQ(intersect_sphere(s, Ray{vec3(0, 0, 10), vec3(0, 0, 1)}), kInf);
  // Passing beside it.
  EXPECT_EQ(intersect_sphere(s, Ray{vec3(0, 2.001f, 10), vec3(0, 0, -1)}), kInf);
  // Tangent: touches at t = 10 (x = 2 exactly on the silhouette).
  EXPECT_NEAR(intersect_sphere(s, Ray{vec3(2, 0, 10), vec3(0, 0, -1)}), 10.0f, 1e-3f);
  // From the centre: leaves at r.
  EXPECT_FLOAT_EQ(intersect_sphere(s, Ray{vec3(0, 0, 0), vec3(0, 1, 0)}), 2.0f);
  // From inside off-centre: the far root.
  EXPECT_FLOAT_EQ(intersect_sphere(s, Ray{vec3(1, 0, 0), vec3(-1, 0, 0)}), 3.0f);
  // tmax cuts the hit off.
  EXPECT_EQ(intersect_sphere(s, Ray{vec3(0, 0, 10), vec3(0, 0, -1), 0.0f, 7.9f}), kInf);
}

// Hits on the walls (radius 940-990, centres 1000 away) from points in the
// room, against the long-double reference. Stated bounds: the float test
// (which only picks the closest sphere) within 2e-4 relative even at the
// grazing angles along the floor, where the float discriminant's absolute
// error ~ eps |f|^2 dominates; the double refinement used for shading within
// 1e-6 (a float ULP of t plus the rounding of the float ray it was given).
TEST(Sphere, WallHitsMatchLongDouble) {
  std::mt19937 g(1);
  std::uniform_real_distribution<float> u(-50.0f, 50.0f);
  double worst_float = 0.0, worst_refined = 0.0;
  int hits = 0;
  for (const Sphere& s : report_spheres()) {
    if (s.radius < 100.0f) continue;
    for (int k = 0; k < 20000; ++k) {
      const Ray r{vec3(u(g), u(g) * 0.15f, u(g)), uniform_direction(g)};
      const float t = intersect_sphere(s, r);
      const long double ref = reference_t(s, r);
      if (ref < 0) {
        EXPECT_EQ(t, kInf);
        continue;
      }
      // Grazing rays within float rounding of the silhouette may go either way.
      if (t == kInf) continue;
      ++hits;
      worst_float = std::max(worst_float, double(std::fabs((long double)t - ref) / ref));
      const double tr = refine_sphere_t(s, r, t);
      worst_refined = std::max(worst_refined, double(std::fabs((long double)tr - ref) / ref));
    }
  }
  EXPECT_GT(hits, 10000);
  EXPECT_LT(worst_float, 2e-4) << "float screening test";
  EXPECT_LT(worst_refined, 1e-6) << "double refinement";
}

// Rays spawned from hit points on every sphere, in all directions, never hit
// their own surface again near the origin; shadow rays towards the light are
// never blocked by their own surface. The spawn rule (geometry/offset.h)
// leaves from the point itself and excludes the sphere left: outwards never
// again, inwards only the far side, a chord of 2 r |cos| away.
TEST(Sphere, SpawnedRaysNeverReHitTheirSurface) {
  std::mt19937 g(7);
  const vec3 light(-10.0f, 20.0f, 40.0f);
  for (const Sphere& s : report_spheres()) {
    const SphereSet set({s});
    int self_hits = 0, blocked = 0, tested = 0;
    while (tested < 100000) {
      // A ray from a random point in the room (outside the balls) towards the sphere.
      const vec3 target = s.center + s.radius * uniform_direction(g);
      vec3 from(std::uniform_real_distribution<float>(-55, 55)(g),
                std::uniform_real_distribution<float>(-9, 50)(g),
                std::uniform_real_distribution<float>(-55, 55)(g));
      if (s.radius < 100.0f && s.inverted) from = s.center;  // the bubble is seen from inside glass
      const Ray primary{from, glm::normalize(target - from)};
      const float t = intersect_sphere(s, primary);
      if (t == kInf) continue;
      ++tested;
      const double td = refine_sphere_t(s, primary, t);
      const glm::dvec3 pd = glm::dvec3(primary.o) + td * glm::dvec3(primary.d);
      const vec3 p(pd), lo(pd - glm::dvec3(p));
      const vec3 outward(glm::normalize(pd - glm::dvec3(s.center)));
      const vec3 ng = s.inverted ? -outward : outward;
      const vec3 d = uniform_direction(g);
      const Ray spawned = spawn_from(p, ng, lo, 0, outward, d);
      float t2 = kInf;
      std::uint32_t id = 0;
      set.intersect(spawned, kInf, t2, id);
      const float cos_out = glm::dot(outward, d);
      if (cos_out > 0.0f) {
        if (t2 != kInf) ++self_hits;
      } else {
        const float chord = -2.0f * s.radius * cos_out;
        if (t2 < 0.5f * chord && chord > 1e-2f * s.radius) ++self_hits;
      }
      // Shadow ray to the light from the lit side.
      if (glm::dot(outward, light - p) > 0.0f) {
        if (set.occluded(spawn_shadow_from(p, ng, lo, 0, outward, light))) ++blocked;
      }
    }
    EXPECT_EQ(self_hits, 0) << "sphere at (" << s.center.x << "," << s.center.y << ","
                            << s.center.z << ") r " << s.radius;
    EXPECT_EQ(blocked, 0) << "sphere r " << s.radius;
  }
}

TEST(Sphere, HitPointIsOnTheSurface) {
  // The double-precision projection leaves the point within a few float ULPs
  // of the wall's surface, which the ray offset's margin relies on.
  const Sphere wall{vec3(0, -1000, 0), 990.0f};
  std::mt19937 g(3);
  for (int k = 0; k < 10000; ++k) {
    const Ray r{vec3(0, 0, 55), glm::normalize(vec3(std::uniform_real_distribution<float>(-1, 1)(g), -0.5f,
                                                    std::uniform_real_distribution<float>(-1, 1)(g)))};
    const float t = intersect_sphere(wall, r);
    ASSERT_NE(t, kInf);
    const SurfacePoint h = sphere_surface_point(wall, 0, r, t);
    const vec3 p = h.p;
    const long double dx = p.x, dy = (long double)p.y + 1000.0L, dz = p.z;
    const long double dist = std::sqrt(dx * dx + dy * dy + dz * dz) - 990.0L;
    EXPECT_LT(std::fabs(dist), 8 * 6.2e-5L);  // 8 ULPs of 990
    // The normal is (p - c)/r, unit to float precision without normalising.
    EXPECT_NEAR(glm::length(h.ng), 1.0f, 1e-6f);
  }
}

// Forward error bound of the float root: the computed t is the exact root of
// g(t) = |f + t d|^2 - r^2 perturbed by |dg| <= gamma_n ((|f| + t)^2 + r^2)
// (each term of g rounded at most n times: f = o - c, a three-term dot
// product, the subtraction, the square root, the Vieta sum and division;
// n = 8), so t moves by |dg| / |g'(t)| with g'(t) = 2 (f + t d).d, the
// root's condition (Higham, Accuracy and Stability of Numerical
// Algorithms, 2nd ed., sec. 3.1 for gamma_n; first-order perturbation of a
// simple root). It holds for any evaluation order, with or without FMA, so
// it does not depend on the compiler or the build type.
long double float_root_bound(const Sphere& s, const Ray& r, long double t) {
  using L = long double;
  const L u = std::numeric_limits<float>::epsilon() / 2;
  const L n = 8;
  const L gamma = n * u / (1 - n * u);
  const L fx = L(r.o.x) - s.center.x, fy = L(r.o.y) - s.center.y, fz = L(r.o.z) - s.center.z;
  const L px = fx + t * r.d.x, py = fy + t * r.d.y, pz = fz + t * r.d.z;
  const L gp = 2 * std::fabs(px * r.d.x + py * r.d.y + pz * r.d.z);
  const L flen = std::sqrt(fx * fx + fy * fy + fz * fz);
  const L scale = (flen + t) * (flen + t) + L(s.radius) * L(s.radius);
  return gamma * scale / gp;
}

TEST(Sphere, EightWideSetAgreesWithTheScalarTest) {
  // SphereSet evaluates the same formula in AVX lanes (with FMA): the same
  // sphere wins, and both its t and the scalar test's lie within the float
  // root's error bound of the long-double root (the double refinement that
  // follows makes the shading t exact either way).
  const std::vector<Sphere> spheres = report_spheres();
  const SphereSet set(spheres);
  std::mt19937 g(11);
  std::uniform_real_distribution<float> u(-50.0f, 50.0f);
  int agree = 0;
  long double worst = 0;  // largest error as a fraction of its bound
  for (int k = 0; k < 100000; ++k) {
    const Ray r{vec3(u(g), u(g) * 0.15f, u(g)), uniform_direction(g)};
    float best = kInf;
    std::uint32_t best_i = 0;
    for (std::uint32_t i = 0; i < spheres.size(); ++i) {
      const float t = intersect_sphere(spheres[i], r);
      if (t < best) { best = t; best_i = i; }
    }
    float t = 0;
    std::uint32_t idx = 0;
    const bool hit = set.intersect(r, kInf, t, idx);
    if (best == kInf) continue;  // inside a ball or leaving through a seam
    ASSERT_TRUE(hit);
    if (idx == best_i) ++agree;
    const long double ref = reference_t(spheres[idx], r);
    ASSERT_GT(ref, 0);
    const long double bound = float_root_bound(spheres[idx], r, ref);
    worst = std::max(worst, std::fabs(t - ref) / bound);
    EXPECT_LE(std::fabs(t - ref), bound) << "eight-wide t " << t << " vs " << double(ref);
    if (idx == best_i) {
      worst = std::max(worst, std::fabs(best - ref) / bound);
      EXPECT_LE(std::fabs(best - ref), bound) << "scalar t " << best << " vs " << double(ref);
    }
    // Shadow rays: a hit just beyond the bound counts, one just short does not.
    const float margin = float(2 * bound) + 1e-3f * best;
    EXPECT_TRUE(set.occluded(Ray{r.o, r.d, 0.0f, best + margin}));
    if (best - margin > 0.0f) {
      EXPECT_FALSE(set.occluded(Ray{r.o, r.d, 0.0f, best - margin}));
    }
  }
  EXPECT_GT(agree, 99000);  // ties only where two walls meet
  std::printf("worst error / bound: %.3Lg\n", worst);
}

TEST(Sphere, BatchOfEightRaysAgreesWithOneAtATime) {
  // intersect_batch() puts rays in the lanes instead of spheres: each lane
  // must give intersect()'s answer bit for bit (the renderer's images do
  // not change with it). Sets of at most eight spheres: the six walls with
  // the hollow ball's two shells (1e-6 thick here: ties in double), and the
  // walls alone. Rays from the room, and rays spawned on a sphere (skip,
  // far_only, origins a float ULP off the surface: the near test).
  std::vector<Sphere> walls_and_shell;
  for (const Sphere& s : report_spheres())
    if (s.radius > 100.0f) walls_and_shell.push_back(s);
  ASSERT_EQ(walls_and_shell.size(), 6u);
  const std::vector<Sphere> walls = walls_and_shell;
  walls_and_shell.push_back({vec3(20.0f, 0.0f, 0.0f), 10.0f, false});
  walls_and_shell.push_back({vec3(20.0f, 0.0f, 0.0f), 10.0f - 1e-6f, true});
  std::mt19937 g(23);
  std::uniform_real_distribution<float> u(-55.0f, 55.0f), unit(0.0f, 1.0f);
  for (const std::vector<Sphere>* spheres : {&std::as_const(walls_and_shell), &walls}) {
    const SphereSet set(*spheres);
    ASSERT_TRUE(set.batchable());
    int hits = 0, spawned_rays = 0;
    for (int batch = 0; batch < 20000; ++batch) {
      Ray rays[8];
      const Ray* ptr[8];
      for (int l = 0; l < 8; ++l) {
        if (unit(g) < 0.5f) {
          rays[l] = Ray{vec3(u(g), u(g) * 0.5f + 20.0f, u(g)), uniform_direction(g)};
        } else {  // leaving a point on one of the spheres
          const std::uint32_t k = std::uint32_t(g() % spheres->size());
          const Sphere& s = (*spheres)[k];
          const vec3 outward = uniform_direction(g);
          const glm::dvec3 pd = glm::dvec3(s.center) + double(s.radius) * glm::dvec3(outward);
          const vec3 p(pd), lo(pd - glm::dvec3(p));
          const vec3 ng = s.inverted ? -outward : outward;
          // Half of them with the sphere to skip, half as a bare origin on it.
          rays[l] = spawn_from(p, ng, lo, unit(g) < 0.5f ? k : kNoSkip, outward, uniform_direction(g));
          ++spawned_rays;
        }
        rays[l].tmax = unit(g) < 0.25f ? 100.0f * unit(g) : kInf;
        ptr[l] = &rays[l];
      }
      const unsigned lanes = unsigned(g() & 0xffu);
      float t[8];
      std::uint32_t index[8];
      const unsigned found = set.intersect_batch(ptr, lanes, t, index);
      ASSERT_EQ(found & ~lanes, 0u);
      for (int l = 0; l < 8; ++l) {
        if (!(lanes >> l & 1u)) continue;
        float t1 = kInf;
        std::uint32_t i1 = 0;
        const bool hit = set.intersect(rays[l], rays[l].tmax, t1, i1);
        ASSERT_EQ(hit, bool(found >> l & 1u)) << "batch " << batch << " lane " << l;
        if (!hit) continue;
        ++hits;
        ASSERT_EQ(t[l], t1) << "batch " << batch << " lane " << l;
        ASSERT_EQ(index[l], i1) << "batch " << batch << " lane " << l;
      }
    }
    EXPECT_GT(hits, 50000);
    EXPECT_GT(spawned_rays, 50000);
  }
  // Nine spheres are not a batch.
  std::vector<Sphere> nine = walls_and_shell;
  nine.push_back({vec3(-20.0f, 0.0f, 0.0f), 10.0f, false});
  EXPECT_FALSE(SphereSet(nine).batchable());
}
