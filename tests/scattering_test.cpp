// The materials' scattering (render/scattering.h): the laws of reflection
// and refraction, Schlick's Fresnel term against its formula and the exact
// Fresnel equations, and the glass, mirror and facing-normal rules.
#include <gtest/gtest.h>

#include <cmath>
#include <utility>

#include <glm/geometric.hpp>

#include "render/sampler.h"
#include "render/scattering.h"

using namespace whisker;

namespace {

constexpr double kPi = 3.14159265358979323846;

// The exact unpolarised Fresnel reflectance (Rs + Rp) / 2 from n1 into n2
// at the incidence cosine cos_i, 1 on total internal reflection.
double fresnel_exact(double cos_i, double n1, double n2) {
  const double sin_t = n1 / n2 * std::sqrt(1.0 - cos_i * cos_i);
  if (sin_t >= 1.0) return 1.0;
  const double cos_t = std::sqrt(1.0 - sin_t * sin_t);
  const double rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
  const double rp = (n1 * cos_t - n2 * cos_i) / (n1 * cos_t + n2 * cos_i);
  return 0.5 * (rs * rs + rp * rp);
}

// A glass hit at the origin of the plane z = 0, geometric normal ng: left
// from p moved off the plane (no sphere), so only the direction matters here.
SurfaceHit glass_hit(const vec3& ng) {
  SurfaceHit h;
  h.ng = h.ns = h.outward = ng;
  return h;
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

// Schlick's R0 + (1 - R0)(1 - |cos|)^5, the formula the code cites, in
// double; and within 0.036 of the exact Fresnel equations from air into
// glass of index 1.5 (its worst error there, near grazing incidence).
TEST(Optics, SchlickFollowsItsFormulaAndStaysNearTheExactFresnel) {
  const double r0 = (0.5 / 2.5) * (0.5 / 2.5);
  for (const double c : {0.05, 0.1, 0.3, 0.5, 0.7, 0.9, 1.0}) {
    const double formula = r0 + (1.0 - r0) * std::pow(1.0 - c, 5);
    EXPECT_NEAR(schlick(float(c), 1.0f, 1.5f), formula, 1e-6) << c;
    EXPECT_NEAR(schlick(float(-c), 1.0f, 1.5f), formula, 1e-6) << c;  // either side
    EXPECT_NEAR(schlick(float(c), 1.5f, 1.0f), formula, 1e-6) << c;   // symmetric in n1, n2
    EXPECT_NEAR(schlick(float(c), 1.0f, 1.5f), fresnel_exact(c, 1.0, 1.5), 0.036) << c;
  }
  EXPECT_NEAR(fresnel_exact(1.0, 1.0, 1.5), 0.04, 1e-12);  // the check's own endpoint
}

// Snell's law in 3D about a tilted normal: n1 sin(i) = n2 sin(t), the
// refracted ray unit, in the plane of d and n, on the far side.
TEST(Optics, RefractionAboutATiltedNormalObeysSnell) {
  const vec3 n = glm::normalize(vec3(0.3f, 0.8f, -0.2f));
  for (const vec3 raw : {vec3(0.5f, -1.0f, 0.3f), vec3(-0.2f, -1.0f, -0.6f), vec3(0.9f, -0.4f, 0.1f)}) {
    const vec3 d = glm::normalize(raw);
    ASSERT_LT(glm::dot(d, n), 0.0f);
    for (const float eta : {1.0f / 1.5f, 1.0f / 1.33f}) {
      vec3 t;
      ASSERT_TRUE(refract(d, n, eta, t));
      const double sin_i = glm::length(glm::cross(glm::dvec3(d), glm::dvec3(n)));
      const double sin_t = glm::length(glm::cross(glm::dvec3(t), glm::dvec3(n)));
      EXPECT_NEAR(sin_t, eta * sin_i, 2e-6);
      EXPECT_NEAR(glm::length(t), 1.0f, 1e-6f);
      EXPECT_NEAR(glm::dot(glm::cross(d, n), t), 0.0f, 1e-6f);  // coplanar
      EXPECT_LT(glm::dot(t, n), 0.0f);
    }
  }
}

// Without Fresnel, glass refracts: entering from air by Snell with 1/ior,
// and leaving (the ray along the normal's side, the indices swapped) with
// ior; past the critical angle on the way out it reflects.
TEST(Optics, GlassRefractsEnteringAndLeavingAndReflectsPastTheCriticalAngle) {
  const vec3 ng(0, 0, 1);
  const SurfaceHit h = glass_hit(ng);
  Sampler unused;
  const double i = 40.0 * kPi / 180.0;  // below asin(1/1.5) = 41.8 deg
  const vec3 in(float(std::sin(i)), 0.0f, float(-std::cos(i)));
  const Ray entering = sample_glass(Ray{vec3(0, 0, 1), in}, h, 1.5f, false, unused);
  EXPECT_NEAR(entering.d.x, std::sin(i) / 1.5, 1e-6);
  EXPECT_LT(entering.d.z, 0.0f);
  const vec3 out(in.x, 0.0f, -in.z);  // from inside, at 40 deg
  const Ray leaving = sample_glass(Ray{vec3(0, 0, -1), out}, h, 1.5f, false, unused);
  ASSERT_LT(std::sin(i) * 1.5, 1.0);
  EXPECT_NEAR(leaving.d.x, std::sin(i) * 1.5, 1e-6);
  EXPECT_GT(leaving.d.z, 0.0f);
  const double j = 45.0 * kPi / 180.0;  // past it
  const vec3 steep(float(std::sin(j)), 0.0f, float(std::cos(j)));
  const Ray tir = sample_glass(Ray{vec3(0, 0, -1), steep}, h, 1.5f, false, unused);
  EXPECT_NEAR(tir.d.x, steep.x, 1e-6f);
  EXPECT_NEAR(tir.d.z, -steep.z, 1e-6f);  // mirrored back inside
  // An inverted shell (normal into the bubble) read from the bubble's air:
  // the ray meets it against its normal, so it enters glass (1 -> 1.5).
  const SurfaceHit shell = glass_hit(-ng);
  const vec3 up(in.x, 0.0f, -in.z);
  const Ray into_glass = sample_glass(Ray{vec3(0, 0, -1), up}, shell, 1.5f, false, unused);
  EXPECT_NEAR(into_glass.d.x, std::sin(i) / 1.5, 1e-6);
}

// With Fresnel, glass reflects with Schlick's probability: the fraction of
// reflected rays over many samples matches it within 5 standard errors.
TEST(Optics, GlassReflectsWithSchlicksProbability) {
  const SurfaceHit h = glass_hit(vec3(0, 0, 1));
  for (const double c : {0.9, 0.3, 0.1}) {
    const vec3 d(float(std::sqrt(1.0 - c * c)), 0.0f, float(-c));
    const int n = 40000;
    int reflected = 0;
    for (int k = 0; k < n; ++k) {
      Sampler s(SamplerKind::Independent, 7, std::uint64_t(k), 11);
      reflected += sample_glass(Ray{vec3(0, 0, 1), d}, h, 1.5f, true, s).d.z > 0.0f;
    }
    const double p = schlick(float(-c), 1.0f, 1.5f);
    EXPECT_NEAR(double(reflected) / n, p, 5.0 * std::sqrt(p * (1.0 - p) / n)) << c;
  }
}

// The mirror reflects about the shading normal; a diffuse hit's normals
// are turned to the side the ray came from, the shading one to the
// geometric one's side.
TEST(Optics, MirrorAndFacingNormals) {
  SurfaceHit h = glass_hit(vec3(0, 0, 1));
  h.ns = glm::normalize(vec3(0.1f, 0.0f, 1.0f));
  const vec3 d = glm::normalize(vec3(1.0f, 0.0f, -1.0f));
  const Ray r = sample_mirror(Ray{vec3(0, 0, 1), d}, h);
  const vec3 expect = d - 2.0f * glm::dot(d, h.ns) * h.ns;
  EXPECT_NEAR(glm::length(r.d - expect), 0.0f, 1e-6f);
  const FacingNormals above(h, d);
  EXPECT_EQ(above.ng, h.ng);
  EXPECT_EQ(above.ns, h.ns);
  const FacingNormals below(h, -d);  // from under the surface: both flipped
  EXPECT_EQ(below.ng, -h.ng);
  EXPECT_EQ(below.ns, -h.ns);
  h.ns = glm::normalize(vec3(1.0f, 0.0f, -0.1f));  // a shading normal past the terminator
  const FacingNormals turned(h, d);
  EXPECT_EQ(turned.ns, -h.ns);
}
