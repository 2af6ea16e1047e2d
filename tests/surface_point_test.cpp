// Hit records (geometry/surface_point.h), the code the World runs on every
// hit: a sphere's point and normal against the formula, at grazing angles
// and from inside; a triangle's point, error bound and interpolated normal
// against hand-computed values.
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include <glm/geometric.hpp>

#include "geometry/surface_point.h"

namespace whisker {
namespace {

using L = long double;

// The exact hit of r on s in long double (the textbook quadratic on the
// float inputs): the near root if in front of the origin, else the far one.
struct ExactHit {
  L t, p[3], n[3];
};

ExactHit exact_hit(const Sphere& s, const Ray& r) {
  const L o[3] = {r.o.x, r.o.y, r.o.z}, d[3] = {r.d.x, r.d.y, r.d.z};
  const L c[3] = {s.center.x, s.center.y, s.center.z};
  L a = 0, b = 0, cc = -L(s.radius) * L(s.radius);
  for (int k = 0; k < 3; ++k) {
    a += d[k] * d[k];
    b += 2 * (o[k] - c[k]) * d[k];
    cc += (o[k] - c[k]) * (o[k] - c[k]);
  }
  const L sq = std::sqrt(std::max(L(0), b * b - 4 * a * cc));
  const L t0 = (-b - sq) / (2 * a), t1 = (-b + sq) / (2 * a);
  ExactHit h{t0 > 0 ? t0 : t1, {}, {}};
  for (int k = 0; k < 3; ++k) {
    h.p[k] = o[k] + h.t * d[k];
    h.n[k] = (h.p[k] - c[k]) / s.radius;
  }
  return h;
}

// The record of r's hit on s (sphere number 5), through the float test the
// World runs first.
SurfacePoint record(const Sphere& s, const Ray& r) {
  const float t = intersect_sphere(s, r);
  EXPECT_NE(t, kInf);
  return sphere_surface_point(s, 5, r, t);
}

// p + err (the double hit split in two floats) is the exact point to far
// below a float ULP; p itself to half a ULP; the normal to float precision.
void expect_matches(const SurfacePoint& h, const ExactHit& e) {
  EXPECT_NEAR(h.t, double(e.t), 1e-6 * double(e.t));
  for (int k = 0; k < 3; ++k) {
    const L scale = std::max(L(1), std::fabs(e.p[k]));
    EXPECT_LE(std::fabs(L(h.p[k]) + L(h.err[k]) - e.p[k]), 1e-12L * scale) << k;
    EXPECT_LE(std::fabs(L(h.p[k]) - e.p[k]), 0x1p-24L * scale) << k;
    EXPECT_NEAR(h.outward[k], double(e.n[k]), 2e-7) << k;
  }
}

TEST(SurfacePoint, SphereHeadOnIsExact) {
  const Sphere s{vec3(1, 2, 3), 2.0f};
  const SurfacePoint h = record(s, Ray{vec3(1, 2, 13), vec3(0, 0, -1)});
  EXPECT_EQ(h.t, 8.0f);
  EXPECT_EQ(h.p, vec3(1, 2, 5));
  EXPECT_EQ(h.err, vec3(0.0f));
  EXPECT_EQ(h.ng, vec3(0, 0, 1));
  EXPECT_EQ(h.ns, h.ng);
  EXPECT_EQ(h.outward, vec3(0, 0, 1));
  EXPECT_EQ(h.sphere, 5u);  // the ray leaving it skips this sphere
}

TEST(SurfacePoint, SphereOffAxisMatchesTheFormula) {
  const Sphere s{vec3(0.5f, -1.25f, 2.0f), 3.0f};
  const Ray r{vec3(-4, 3, 9), glm::normalize(vec3(0.45f, -0.4f, -0.8f))};
  const SurfacePoint h = record(s, r);
  expect_matches(h, exact_hit(s, r));
  EXPECT_NEAR(glm::length(h.ng), 1.0f, 1e-7f);
}

// A ray passing 1e-4 of the radius inside the silhouette: the float root
// is poor there (the derivative of |f + t d|^2 - r^2 nearly vanishes), the
// record's double refinement is not.
TEST(SurfacePoint, SphereGrazingHitMatchesTheFormula) {
  const Sphere s{vec3(0.0f), 1.0f};
  const Ray r{vec3(-10, 1.0f - 1e-4f, 0), vec3(1, 0, 0)};
  const SurfacePoint h = record(s, r);
  const ExactHit e = exact_hit(s, r);
  expect_matches(h, e);
  // The point is x = -sqrt(1 - y^2), y the ray's height, to float precision.
  const L y = L(1.0f - 1e-4f);
  EXPECT_NEAR(h.p.x, double(-std::sqrt(1 - y * y)), 1e-7);
  EXPECT_EQ(h.p.y, 1.0f - 1e-4f);
}

// From the centre the hit is the far root, at the radius; the normal still
// points out of the sphere (scattering turns it to face the ray), and into
// it for an inverted shell, whose `outward` stays the sphere's.
TEST(SurfacePoint, SphereFromInsideAndInvertedShell) {
  Sphere s{vec3(3, -2, 1), 5.0f};
  const Ray r{vec3(3, -2, 1), vec3(0, 1, 0)};
  SurfacePoint h = record(s, r);
  EXPECT_EQ(h.t, 5.0f);
  EXPECT_EQ(h.p, vec3(3, 3, 1));
  EXPECT_EQ(h.ng, vec3(0, 1, 0));
  s.inverted = true;
  h = record(s, r);
  EXPECT_EQ(h.ng, vec3(0, -1, 0));
  EXPECT_EQ(h.ns, h.ng);
  EXPECT_EQ(h.outward, vec3(0, 1, 0));
  // Off-centre inside: the far root against the formula.
  const Ray off{vec3(4, -1, 0), glm::normalize(vec3(-0.3f, 0.5f, 0.7f))};
  expect_matches(record(s, off), exact_hit(s, off));
}

// The triangle (0,0,0), (4,0,0), (0,2,0) hit at (1, 0.5): weights u = x/4 =
// 0.25 of v1, v = y/2 = 0.25 of v2, b0 = 0.5; every product is exact.
TEST(SurfacePoint, TrianglePointAndErrorBoundFromTheWeights) {
  const Triangle tri{{0, 0, 0}, {4, 0, 0}, {0, 2, 0}};
  float t, u, v;
  ASSERT_TRUE(intersect_triangle(Ray{vec3(1, 0.5f, 5), vec3(0, 0, -1)}, tri, t, u, v));
  EXPECT_EQ(u, 0.25f);
  EXPECT_EQ(v, 0.25f);
  const SurfacePoint h = triangle_surface_point(tri, vec3(0, 0, 1), t, u, v);
  EXPECT_EQ(h.t, 5.0f);
  EXPECT_EQ(h.p, vec3(1, 0.5f, 0));
  // err = gamma(7) doubled times sum |b_i v_i| = (0 + 1 + 0, 0 + 0 + 0.5, 0).
  const float g = 2.0f * 7.0f * 0x1p-24f / (1.0f - 7.0f * 0x1p-24f);
  EXPECT_FLOAT_EQ(h.err.x, g);
  EXPECT_FLOAT_EQ(h.err.y, 0.5f * g);
  EXPECT_EQ(h.err.z, 0.0f);
  EXPECT_EQ(h.ng, vec3(0, 0, 1));
  EXPECT_EQ(h.ns, h.ng);
  EXPECT_EQ(h.outward, h.ng);
  EXPECT_EQ(h.sphere, kNoSkip);  // a triangle's hit is left by an offset
}

// A tilted triangle: the point from the weights lies on the plane to within
// the error bound, wherever the ray comes from.
TEST(SurfacePoint, TrianglePointLiesOnThePlaneWithinItsBound) {
  const Triangle tri{{10.1f, -3.3f, 7.7f}, {12.9f, 1.7f, 5.2f}, {8.4f, 0.6f, 11.9f}};
  const glm::dvec3 n = glm::normalize(glm::cross(glm::dvec3(tri.v1 - tri.v0),
                                                  glm::dvec3(tri.v2 - tri.v0)));
  float t, u, v;
  const vec3 target = 0.2f * tri.v0 + 0.3f * tri.v1 + 0.5f * tri.v2;
  const vec3 o(-5, 20, 40);
  ASSERT_TRUE(intersect_triangle(Ray{o, glm::normalize(target - o)}, tri, t, u, v));
  EXPECT_NEAR(u, 0.3f, 1e-5f);
  EXPECT_NEAR(v, 0.5f, 1e-5f);
  const SurfacePoint h = triangle_surface_point(tri, vec3(n), t, u, v);
  const double off_plane = glm::dot(glm::dvec3(h.p) - glm::dvec3(tri.v0), n);
  EXPECT_LE(std::fabs(off_plane), glm::dot(glm::abs(glm::dvec3(n)), glm::dvec3(h.err)));
  EXPECT_LT(glm::length(h.p - target), 1e-4f);
}

// Corner normals (0,0,1), (1,0,0), (0,1,0) at u = v = 0.25: the weights
// 0.5, 0.25, 0.25 give (0.25, 0.25, 0.5), over its length sqrt(0.375).
TEST(SurfacePoint, InterpolatedNormalAgainstHandComputedValues) {
  const std::array<vec3, 3> corner{vec3(0, 0, 1), vec3(1, 0, 0), vec3(0, 1, 0)};
  const vec3 ng(0, 0, 1);
  const vec3 n = interpolated_normal(corner, 0.25f, 0.25f, ng);
  const float inv = 1.0f / std::sqrt(0.375f);
  EXPECT_NEAR(n.x, 0.25f * inv, 1e-6f);  // 0.408248
  EXPECT_NEAR(n.y, 0.25f * inv, 1e-6f);
  EXPECT_NEAR(n.z, 0.5f * inv, 1e-6f);   // 0.816497
  // At a corner, that corner's normal.
  EXPECT_EQ(interpolated_normal(corner, 1.0f, 0.0f, ng), vec3(1, 0, 0));
  EXPECT_EQ(interpolated_normal(corner, 0.0f, 0.0f, ng), vec3(0, 0, 1));
}

TEST(SurfacePoint, CancellingCornerNormalsFallBackToTheGeometricNormal) {
  const vec3 ng(0, 1, 0);
  const std::array<vec3, 3> opposed{vec3(0, 0, 1), vec3(0, 0, -1), vec3(0, 0, 1)};
  EXPECT_EQ(interpolated_normal(opposed, 0.5f, 0.0f, ng), ng);  // 0.5 n0 + 0.5 n1 = 0
  const std::array<vec3, 3> zero{vec3(0.0f), vec3(0.0f), vec3(0.0f)};
  EXPECT_EQ(interpolated_normal(zero, 0.2f, 0.3f, ng), ng);
}

}  // namespace
}  // namespace whisker
