// The light buffer (geometry/light_buffer.h): the cells of directions around
// the point light must hold every triangle a shadow ray in them can meet, so
// that its answer is the tree's on every ray.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <glm/geometric.hpp>

#include "geometry/bvh.h"
#include "geometry/light_buffer.h"
#include "geometry/surface_point.h"
#include "scene/mesh_io.h"
#include "sanitized.h"

using namespace whisker;

namespace {

std::vector<Triangle> load_cat() {
  const TriangleMesh m = load_obj(WHISKER_ASSETS_DIR "/cat.obj", 0.6f, vec3(0.0f, -10.0f, 0.0f));
  std::vector<Triangle> tris;
  for (const auto& t : m.triangles)
    tris.push_back({m.positions[t.x], m.positions[t.y], m.positions[t.z]});
  return tris;
}

struct Tally {
  int rays = 0, covered = 0, blocked = 0;
};

// Shadow rays to `light`, spawned as the renderer spawns them
// (spawn_shadow_ray), from points on the triangles (inside, on an edge, at
// a corner) and from points in the room around them; each answered by the
// buffer where it covers the ray, and compared with the tree.
Tally agree_with_tree(const std::vector<Triangle>& tris, const vec3& light, int cells, int rays,
                      unsigned seed) {
  const Bvh tree = Bvh::build(tris, BvhMethod::Sah);
  const LightBuffer buffer(light, tris, 200.0f, cells);
  std::mt19937 g(seed);
  std::uniform_real_distribution<float> uni(0.0f, 1.0f);
  std::uniform_int_distribution<std::size_t> pick(0, tris.size() - 1);
  Tally tally;
  for (int k = 0; k < rays; ++k) {
    SurfacePoint h;
    if (k % 4 == 3) {  // a point in the room, no surface
      h.p = vec3(-60.0f + 120.0f * uni(g), -10.0f + 70.0f * uni(g), -60.0f + 120.0f * uni(g));
      h.ng = h.ns = h.outward = glm::normalize(light - h.p);
      h.err = vec3(0.0f);
      h.sphere = kNoSkip;
    } else {
      const Triangle& t = tris[pick(g)];
      float u = uni(g), v = uni(g);
      if (u + v > 1.0f) u = 1.0f - u, v = 1.0f - v;
      if (k % 4 == 1) v = 0.0f;           // on an edge
      if (k % 8 == 2) u = v = 0.0f;       // at a corner
      const vec3 n = glm::normalize(glm::cross(t.v1 - t.v0, t.v2 - t.v0));
      if (!(glm::length(n) > 0.5f)) continue;  // a degenerate triangle has no side
      h = triangle_surface_point(t, n, 1.0f, u, v);
      if (glm::dot(h.ng, light - h.p) < 0.0f) h.ng = h.ns = h.outward = -n;
    }
    const Ray shadow = spawn_shadow_ray(h, light);
    const bool tree_says = tree.occluded(shadow);
    ++tally.rays;
    tally.blocked += tree_says;
    if (!buffer.covers(shadow)) continue;
    ++tally.covered;
    // The cell along the hit point less the light (the renderer's), and
    // along the ray's own direction, which rounds differently.
    EXPECT_EQ(buffer.occluded(shadow, h.p - light), tree_says)
        << "ray " << k << " from " << h.p.x << ", " << h.p.y << ", " << h.p.z;
    EXPECT_EQ(buffer.occluded(shadow, -shadow.d), tree_says) << "ray " << k;
    if (::testing::Test::HasFailure()) break;
  }
  return tally;
}

}  // namespace

// The cat scene's light, and lights that test the cells' edge cases: in the
// middle of the cat (its triangles all around, crossing the planes through
// the light), a hair off a triangle (tiny distances, large margins) and on
// a corner of one (a triangle through the light: every cell of a face).
TEST(LightBuffer, AnswersAsTheTreeDoesForLightsAroundAndInsideTheCat) {
  const std::vector<Triangle> tris = load_cat();
  ASSERT_EQ(tris.size(), 3954u);
  const int rays = release_or_sanitized(40000, 8000);
  const Triangle& t = tris[1234];
  const vec3 centroid = (t.v0 + t.v1 + t.v2) / 3.0f;
  const vec3 n = glm::normalize(glm::cross(t.v1 - t.v0, t.v2 - t.v0));
  const vec3 lights[] = {vec3(-10.0f, 20.0f, 40.0f), vec3(0.0f, 0.0f, 0.0f),
                         centroid + 1e-3f * n, t.v1};
  int covered = 0;
  for (const vec3& light : lights) {
    for (const int cells : {8, 125}) {
      const Tally tally = agree_with_tree(tris, light, cells, rays, 17);
      covered += tally.covered;
      // The scene's own light: every ray is the buffer's (the room is within
      // its reach, and the cat's lists within its bounds).
      if (light == lights[0]) {
        EXPECT_EQ(tally.covered, tally.rays) << cells;
      }
      // Both answers occur: the comparison is of shadows, not of empty rooms.
      EXPECT_GT(tally.blocked, tally.rays / 20) << light.x << " " << cells;
      EXPECT_LT(tally.blocked, tally.rays - tally.rays / 20) << light.x << " " << cells;
    }
  }
  EXPECT_GT(covered, rays * 4);  // the buffer answered most of them
}

// Cells cover the whole sphere of directions, each once: every direction,
// those on the cube's edges and corners too, finds a cell in range, and
// opposite directions different cells.
TEST(LightBuffer, EveryDirectionHasACell) {
  const std::vector<Triangle> tris = load_cat();
  const LightBuffer buffer(vec3(-10.0f, 20.0f, 40.0f), tris, 200.0f, 16);
  ASSERT_FALSE(buffer.empty());
  const std::uint32_t count = 6u * 16u * 16u;
  std::vector<int> seen(count, 0);
  std::mt19937 g(3);
  std::normal_distribution<float> normal;
  for (int k = 0; k < 200000; ++k) {
    const vec3 u = glm::normalize(vec3(normal(g), normal(g), normal(g)));
    const std::uint32_t c = buffer.cell_of(u);
    ASSERT_LT(c, count);
    ++seen[c];
    ASSERT_NE(buffer.cell_of(-u), c);
  }
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 0), 0);  // no cell is never reached
  const float s = 1.0f / std::sqrt(3.0f);
  for (const vec3& u : {vec3(s, s, s), vec3(-s, s, -s), vec3(1, 0, 0), vec3(0, -1, 0),
                        glm::normalize(vec3(1, 1, 0)), glm::normalize(vec3(0, -1, 1))})
    EXPECT_LT(buffer.cell_of(u), count);
  EXPECT_LT(buffer.cell_of(vec3(std::nanf(""))), count);  // NaN: some cell, no crash
}

// A mesh that surrounds the light closely puts its triangles in every cell
// of several faces; past 16 entries a triangle the buffer keeps nothing and
// covers no ray, so the tree answers alone.
TEST(LightBuffer, GivesUpWhereTheListsWouldOutgrowTheMesh) {
  std::vector<Triangle> tris;
  // A closed octahedron around the origin, 1e-4 across: all of it within
  // the margins of the rays' rounding, at every face.
  const float r = 1e-4f;
  const vec3 p[6] = {{r, 0, 0}, {-r, 0, 0}, {0, r, 0}, {0, -r, 0}, {0, 0, r}, {0, 0, -r}};
  for (int a = 0; a < 2; ++a)
    for (int b = 2; b < 4; ++b)
      for (int c = 4; c < 6; ++c) tris.push_back({p[a], p[b], p[c]});
  const Ray ray{vec3(10.0f, 0.0f, 0.0f), vec3(-1.0f, 0.0f, 0.0f), 0.0f, 9.9f};
  for (const int copies : {1, 20000}) {
    // 20000 copies: 4.9e9 cell entries, counted from the rectangles before
    // any cell is filled (filled, they would take minutes and 20 GB).
    std::vector<Triangle> many;
    for (int k = 0; k < copies; ++k) many.insert(many.end(), tris.begin(), tris.end());
    const LightBuffer buffer(vec3(0.0f), many, 200.0f, 64);
    EXPECT_TRUE(buffer.empty());
    EXPECT_EQ(buffer.packet_count(), 0u);
    EXPECT_FALSE(buffer.covers(ray));
  }
}

// The cells' margins: shadow rays aimed at the light from up to 150 away
// along directions within a few float ULPs of a boundary between cells
// (a = y / x = 1/4 on face +x, between cells 4 and 5 of 8), past a
// triangle whose edge lies on that boundary (y = 2.5 at x = 10). Whether a
// ray meets the triangle, and in which cell its own direction falls, are
// both decided by rounding; some meet it from cell 4, beside the triangle's
// own cells, and the margin puts the triangle there too. (With no margin,
// this fails.)
TEST(LightBuffer, RaysThroughACellBoundaryFindTheirTriangle) {
  const std::vector<Triangle> tris = {
      {vec3(10.0f, 2.5f, -1.0f), vec3(10.0f, 2.5f, 1.0f), vec3(10.0f, 4.5f, 0.0f)}};
  const vec3 light(0.0f);
  const Bvh tree = Bvh::build(tris, BvhMethod::Sah);
  const LightBuffer buffer(light, tris, 200.0f, 8);
  std::mt19937 g(5);
  std::uniform_real_distribution<float> uni(0.0f, 1.0f);
  std::uniform_int_distribution<int> ulps(-4, 4);
  int hits = 0, other_cell = 0;
  for (int k = 0; k < 20000; ++k) {
    const float x = 20.0f + 130.0f * uni(g);
    float y = 0.25f * x;  // exact: on the boundary
    for (int n = ulps(g); n != 0; n += n < 0 ? 1 : -1)
      y = std::nextafter(y, n < 0 ? -kInf : kInf);
    const vec3 o(x, y, x * 0.1f * (uni(g) - 0.5f));
    const vec3 to = light - o;
    const float dist = std::sqrt(glm::dot(to, to));
    const Ray ray{o, to * (1.0f / dist), 0.0f, dist * (1.0f - 1e-5f)};
    ASSERT_TRUE(buffer.covers(ray));
    const bool tree_says = tree.occluded(ray);
    hits += tree_says;
    other_cell += tree_says && buffer.cell_of(-ray.d) / 8 % 8 == 4;  // a < 1/4
    ASSERT_EQ(buffer.occluded(ray, o - light), tree_says) << k;
    ASSERT_EQ(buffer.occluded(ray, -ray.d), tree_says) << k;
  }
  EXPECT_GT(hits, 1000);
  EXPECT_GT(other_cell, 100);  // the case the margin is for occurs
}
