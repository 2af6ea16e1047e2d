// The watertight ray/triangle test (geometry/triangle.h) on small exact
// cases, and against a long double reference on random rays.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <random>

#include "geometry/triangle.h"

namespace whisker {
namespace {

Ray ray(vec3 o, vec3 d, float tmin = 0.0f, float tmax = kInf) {
  return Ray{o, d, tmin, tmax};
}

TEST(Triangle, HitsInteriorWithExactDistanceAndBarycentrics) {
  const Triangle tri{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  float t, u, v;
  ASSERT_TRUE(intersect_triangle(ray({0.25f, 0.5f, 2}, {0, 0, -1}), tri, t, u, v));
  EXPECT_EQ(t, 2.0f);
  EXPECT_EQ(u, 0.25f);  // weight of v1 = x
  EXPECT_EQ(v, 0.5f);   // weight of v2 = y
  // From below: both sides are hit, same point.
  ASSERT_TRUE(intersect_triangle(ray({0.25f, 0.5f, -3}, {0, 0, 1}), tri, t, u, v));
  EXPECT_EQ(t, 3.0f);
  EXPECT_EQ(u, 0.25f);
  EXPECT_EQ(v, 0.5f);
}

TEST(Triangle, RespectsTheOpenInterval) {
  const Triangle tri{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  float t, u, v;
  EXPECT_FALSE(intersect_triangle(ray({0.2f, 0.2f, 1}, {0, 0, 1}), tri, t, u, v));  // behind
  EXPECT_FALSE(intersect_triangle(ray({0.2f, 0.2f, 1}, {0, 0, -1}, 0.0f, 1.0f), tri, t, u, v));
  EXPECT_FALSE(intersect_triangle(ray({0.2f, 0.2f, 1}, {0, 0, -1}, 1.0f, 5.0f), tri, t, u, v));
  EXPECT_TRUE(intersect_triangle(ray({0.2f, 0.2f, 1}, {0, 0, -1}, 0.0f, 1.0001f), tri, t, u, v));
  EXPECT_FALSE(intersect_triangle(ray({0.6f, 0.6f, 1}, {0, 0, -1}), tri, t, u, v));  // outside
}

// Distinct collinear vertices are not covered here: the shear may round them
// off their line; Bvh::build turns those into points (bvh_test.cpp).
TEST(Triangle, DegenerateTrianglesAreNeverHit) {
  const Triangle deg[] = {
      {{0, 0, 0}, {0, 0, 0}, {1, 0, 0}},  // repeated vertex
      {{0.1f, 0.2f, 0.3f}, {1.7f, -0.3f, 2.9f}, {1.7f, -0.3f, 2.9f}},  // repeated vertex
      {{1, 2, 3}, {1, 2, 3}, {1, 2, 3}},  // a point
  };
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> U(-1.0f, 1.0f);
  for (const Triangle& tri : deg) {
    for (int i = 0; i < 20000; ++i) {
      // Aim through a point of the degenerate triangle itself.
      const float a = 0.5f * (U(rng) + 1.0f);
      const vec3 target = tri.v0 + a * (tri.v2 - tri.v0);
      const vec3 o(U(rng) * 5, U(rng) * 5, U(rng) * 5);
      const vec3 d = glm::normalize(target - o);
      float t, u, v;
      ASSERT_FALSE(intersect_triangle(ray(o, d), tri, t, u, v)) << i;
    }
    // Along the line of the segment itself.
    float t, u, v;
    EXPECT_FALSE(intersect_triangle(ray(tri.v0 - vec3(1), glm::normalize(vec3(1))), tri, t, u, v));
  }
}

TEST(Triangle, RaysParallelToThePlaneMiss) {
  const Triangle tri{{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}};
  float t, u, v;
  for (float z : {0.0f, 1e-3f, -1e-3f, 1e-30f})
    for (float y : {-1.0f, -0.5f, 0.0f, 0.5f, 1.0f}) {
      EXPECT_FALSE(intersect_triangle(ray({-5, y, z}, {1, 0, 0}), tri, t, u, v)) << y << " " << z;
      EXPECT_FALSE(intersect_triangle(ray({0, -5, z}, glm::normalize(vec3(0.1f, 1, 0))), tri, t, u, v));
    }
}

TEST(Triangle, SliverIsHitInsideAndMissedOutside) {
  // 1 unit long, 1e-6 wide at its base.
  const Triangle tri{{0, 0, 0}, {1, 0, 0}, {0, 1e-6f, 0}};
  float t, u, v;
  ASSERT_TRUE(intersect_triangle(ray({0.5f, 2e-7f, 1}, {0, 0, -1}), tri, t, u, v));
  EXPECT_EQ(t, 1.0f);
  EXPECT_NEAR(u, 0.5f, 1e-6f);
  EXPECT_NEAR(v, 0.2f, 1e-5f);
  EXPECT_FALSE(intersect_triangle(ray({0.5f, 6e-7f, 1}, {0, 0, -1}), tri, t, u, v));
  EXPECT_FALSE(intersect_triangle(ray({0.5f, -1e-9f, 1}, {0, 0, -1}), tri, t, u, v));
}

TEST(Triangle, HugeTriangleGivesAccurateDistance) {
  const Triangle tri{{-1e7f, -1e7f, -40}, {1e7f, -1e7f, -40}, {0, 1e7f, -40}};
  float t, u, v;
  const Ray r = ray({3, 4, 10}, glm::normalize(vec3(0.1f, 0.2f, -1)));
  ASSERT_TRUE(intersect_triangle(r, tri, t, u, v));
  const long double exact = 50.0L / -static_cast<long double>(r.d.z);  // plane z = -40
  EXPECT_NEAR(t, exact, 1e-6L * exact);
}

TEST(Triangle, SharedEdgeAndVertexAreNeverSlippedThrough) {
  // A fan of 6 triangles around the origin in the z = 0 plane; rays aimed
  // exactly at the shared edges (points on the spokes) and the centre.
  const vec3 c(0, 0, 0);
  vec3 rim[6];
  for (int i = 0; i < 6; ++i)
    rim[i] = vec3(std::cos(i * 1.0471975f), std::sin(i * 1.0471975f), 0.0f);
  std::vector<Triangle> fan;
  for (int i = 0; i < 6; ++i) fan.push_back({c, rim[i], rim[(i + 1) % 6]});
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> U(-1.0f, 1.0f);
  for (int k = 0; k < 20000; ++k) {
    const float s = 0.5f * (U(rng) + 1.0f);
    const vec3 target = (k % 7 == 0) ? c : rim[k % 6] * s;  // on a spoke
    const vec3 o(U(rng) * 3, U(rng) * 3, 0.5f + 2.0f * (U(rng) + 1.0f));
    const Ray r = ray(o, glm::normalize(target - o));
    int hits = 0;
    for (const Triangle& tri : fan) {
      float t, u, v;
      hits += intersect_triangle(r, tri, t, u, v);
    }
    ASSERT_GE(hits, 1) << k;
  }
}

// Long double reference (Moller-Trumbore); returns false when the ray passes
// within `margin` (in barycentric terms) of an edge, where float may differ.
bool reference(const Ray& r, const Triangle& tri, long double& t, long double margin) {
  using L = long double;
  const L o[3] = {r.o.x, r.o.y, r.o.z}, d[3] = {r.d.x, r.d.y, r.d.z};
  const L a[3] = {tri.v0.x, tri.v0.y, tri.v0.z};
  const L e1[3] = {tri.v1.x - a[0], L(tri.v1.y) - a[1], L(tri.v1.z) - a[2]};
  const L e2[3] = {tri.v2.x - a[0], L(tri.v2.y) - a[1], L(tri.v2.z) - a[2]};
  auto cross = [](const L* x, const L* y, L* z) {
    z[0] = x[1] * y[2] - x[2] * y[1];
    z[1] = x[2] * y[0] - x[0] * y[2];
    z[2] = x[0] * y[1] - x[1] * y[0];
  };
  auto dot = [](const L* x, const L* y) { return x[0] * y[0] + x[1] * y[1] + x[2] * y[2]; };
  L p[3], q[3];
  cross(d, e2, p);
  const L det = dot(e1, p);
  const L s[3] = {o[0] - a[0], o[1] - a[1], o[2] - a[2]};
  cross(s, e1, q);
  const L u = dot(s, p) / det, v = dot(d, q) / det;
  t = dot(e2, q) / det;
  return u > margin && v > margin && u + v < 1 - margin && t > 0;
}

TEST(Triangle, AgreesWithLongDoubleReferenceOnRandomRays) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> U(-1.0f, 1.0f);
  int hits = 0;
  for (int i = 0; i < 200000; ++i) {
    const Triangle tri{{U(rng), U(rng), U(rng)}, {U(rng), U(rng), U(rng)}, {U(rng), U(rng), U(rng)}};
    const vec3 o(U(rng) * 4, U(rng) * 4, U(rng) * 4);
    const vec3 target(U(rng) * 0.5f, U(rng) * 0.5f, U(rng) * 0.5f);
    const Ray r = ray(o, glm::normalize(target - o));
    long double tr;
    const bool inside = reference(r, tri, tr, 1e-4L);
    const bool outside = !reference(r, tri, tr, -1e-4L);
    float t, u, v;
    const bool h = intersect_triangle(r, tri, t, u, v);
    if (inside) {
      ASSERT_TRUE(h) << i;
      EXPECT_NEAR(t, tr, 1e-5L * tr) << i;
      ++hits;
    }
    if (outside) {
      ASSERT_FALSE(h) << i;
    }
  }
  EXPECT_GT(hits, 10000);  // the case was exercised
}

}  // namespace
}  // namespace whisker
