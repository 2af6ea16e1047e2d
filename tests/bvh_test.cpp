// The BVH: watertight on a closed mesh (also far from the origin), the same
// closest hit as brute force on the cat, hard triangles, any-hit; the SAH
// tree's runs of triangles and the optimal collapse to 8-wide.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <utility>

#include "geometry/bvh.h"
#include "geometry/bvh_build.h"
#include "scene/mesh_io.h"
#include "sanitized.h"

namespace whisker {
namespace {

constexpr BvhMethod kAll[] = {BvhMethod::Brute, BvhMethod::BBox, BvhMethod::Midpoint,
                              BvhMethod::Sah};
// For failure messages.
const char* name(BvhMethod m) {
  constexpr const char* kNames[] = {"brute", "bbox", "midpoint", "sah"};
  return kNames[int(m)];
}

// Closed sphere: an icosahedron subdivided `levels` times, vertices pushed to
// radius r around c. Shared vertices are stored once, as a real mesh is.
struct IndexedMesh {
  std::vector<vec3> p;
  std::vector<std::array<int, 3>> f;
  std::vector<Triangle> triangles() const {
    std::vector<Triangle> t;
    for (const auto& x : f) t.push_back({p[x[0]], p[x[1]], p[x[2]]});
    return t;
  }
};

IndexedMesh icosphere(int levels, vec3 c, float r) {
  const float g = 1.6180340f;
  std::vector<glm::dvec3> p = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0},
                               {0, -1, g}, {0, 1, g}, {0, -1, -g}, {0, 1, -g},
                               {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
  std::vector<std::array<int, 3>> f = {
      {0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
      {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
      {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      p.push_back(0.5 * (p[a] + p[b]));
      return mid[key] = static_cast<int>(p.size() - 1);
    };
    std::vector<std::array<int, 3>> g2;
    for (const auto& t : f) {
      const int a = midpoint(t[0], t[1]), b = midpoint(t[1], t[2]), cc = midpoint(t[2], t[0]);
      g2.push_back({t[0], a, cc});
      g2.push_back({t[1], b, a});
      g2.push_back({t[2], cc, b});
      g2.push_back({a, b, cc});
    }
    f = std::move(g2);
  }
  IndexedMesh m;
  for (const auto& q : p) m.p.push_back(c + r * vec3(glm::normalize(q)));
  m.f = f;
  return m;
}

// Rays from inside: through every vertex, every edge midpoint (both exactly on
// shared edges or vertices as far as float allows) and random directions;
// every one must hit.
void expect_watertight(const IndexedMesh& m, vec3 inside, int random_rays) {
  const std::vector<Triangle> tris = m.triangles();
  std::vector<vec3> targets = m.p;
  for (const auto& f : m.f)
    for (int k = 0; k < 3; ++k) targets.push_back(0.5f * (m.p[f[k]] + m.p[f[(k + 1) % 3]]));
  for (BvhMethod kind : kAll) {
    const Bvh bvh = Bvh::build(tris, kind);
    const bool brute = kind == BvhMethod::Brute || kind == BvhMethod::BBox;
    std::size_t escapes = 0;
    for (const vec3& t : targets) {
      const Ray r{inside, glm::normalize(t - inside)};
      Hit h;
      escapes += !bvh.intersect(r, h);
      escapes += !bvh.occluded(r);
    }
    EXPECT_EQ(escapes, 0u) << name(kind) << " vertex/edge rays";
    if (brute) continue;  // slow for a million rays; same triangle test
    std::mt19937 rng(5);
    std::normal_distribution<float> N;
    escapes = 0;
    for (int i = 0; i < random_rays; ++i) {
      const Ray r{inside, glm::normalize(vec3(N(rng), N(rng), N(rng)))};
      Hit h;
      escapes += !bvh.intersect(r, h);
    }
    EXPECT_EQ(escapes, 0u) << name(kind) << " random rays";
  }
}

TEST(Bvh, WatertightSphereAtOrigin) {
  const IndexedMesh m = icosphere(3, vec3(0.0f), 1.0f);  // 1280 triangles
  expect_watertight(m, vec3(0.0f), 1000000);
  expect_watertight(m, vec3(0.3f, -0.2f, 0.1f), 100000);
}

TEST(Bvh, WatertightSphereFarFromOrigin) {
  const vec3 c(1.0e4f, -1.2e4f, 0.9e4f);
  const IndexedMesh m = icosphere(3, c, 1.0f);
  expect_watertight(m, c, 1000000);
  expect_watertight(m, c + vec3(0.25f, 0.5f, -0.125f), 100000);
}

// Random rays at the cat: from a sphere around it towards points in its box,
// and from inside its box in any direction.
std::vector<Ray> cat_rays(const std::vector<Triangle>& tris, int n) {
  Box3 box;
  for (const Triangle& t : tris) box.grow(bounds_of(t));
  const vec3 c = 0.5f * (box.lo + box.hi), e = box.hi - box.lo;
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> U(0.0f, 1.0f);
  std::normal_distribution<float> N;
  std::vector<Ray> rays;
  for (int i = 0; i < n; ++i) {
    const vec3 in = box.lo + vec3(U(rng), U(rng), U(rng)) * e;
    Ray r;
    if (i % 2 == 0) {
      r.o = c + 60.0f * glm::normalize(vec3(N(rng), N(rng), N(rng)));
      r.d = glm::normalize(in - r.o);
    } else {
      r.o = in;
      r.d = glm::normalize(vec3(N(rng), N(rng), N(rng)));
    }
    rays.push_back(r);
  }
  return rays;
}

std::vector<Triangle> load_cat() {
  const TriangleMesh m =
      load_obj(WHISKER_ASSETS_DIR "/cat.obj", 0.6f, vec3(0.0f, -10.0f, 0.0f));
  std::vector<Triangle> tris;
  for (const auto& t : m.triangles)
    tris.push_back({m.positions[t.x], m.positions[t.y], m.positions[t.z]});
  return tris;
}

TEST(Bvh, SahMidpointAndBruteAgreeOnTheCat) {
  const std::vector<Triangle> tris = load_cat();
  ASSERT_EQ(tris.size(), 3954u);
  const std::vector<Ray> rays = cat_rays(tris, release_or_sanitized(100000, 25000));
  const Bvh brute = Bvh::build(tris, BvhMethod::Brute);
  const Bvh bbox = Bvh::build(tris, BvhMethod::BBox);
  const Bvh mid = Bvh::build(tris, BvhMethod::Midpoint);
  const Bvh sah = Bvh::build(tris, BvhMethod::Sah);
  EXPECT_GT(sah.node_count(), 1u);
  EXPECT_GT(mid.node_count(), 1u);
  std::size_t hits = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    Hit hb, hx, hm, hs;
    const bool b = brute.intersect(rays[i], hb);
    ASSERT_EQ(bbox.intersect(rays[i], hx), b) << i;
    // The scalar test of triangle.h over every triangle, on a twentieth.
    if (i % 20 == 0) {
      const WatertightRay w(rays[i]);
      Hit hr;
      for (std::size_t k = 0; k < tris.size(); ++k) {
        float t, u, v;
        if (intersect_triangle(w, tris[k], rays[i].tmin, hr.t, t, u, v))
          hr = Hit{t, PrimKind::Triangle, static_cast<std::uint32_t>(k), u, v};
      }
      ASSERT_EQ(hr.valid(), b) << i;
      if (b) {
        // The 8-wide test repeats the scalar one operation for operation.
        ASSERT_EQ(hr.prim, hb.prim) << i;
        ASSERT_EQ(hr.t, hb.t) << i;
        ASSERT_EQ(hr.u, hb.u) << i;
        ASSERT_EQ(hr.v, hb.v) << i;
      }
    }
    ASSERT_EQ(mid.intersect(rays[i], hm), b) << i;
    ASSERT_EQ(sah.intersect(rays[i], hs), b) << i;
    ASSERT_EQ(sah.occluded(rays[i]), b) << i;
    ASSERT_EQ(mid.occluded(rays[i]), b) << i;
    if (!b) continue;
    ++hits;
    ASSERT_EQ(hb.kind, PrimKind::Triangle);
    for (const Hit* h : {&hx, &hm, &hs}) {
      ASSERT_EQ(h->prim, hb.prim) << i;
      ASSERT_EQ(h->t, hb.t) << i;
      ASSERT_EQ(h->u, hb.u) << i;
      ASSERT_EQ(h->v, hb.v) << i;
      ASSERT_EQ(h->kind, PrimKind::Triangle);
    }
    // A shadow ray stopping just short of the hit is not occluded by it...
    Ray s = rays[i];
    s.tmax = std::nextafter(hb.t, 0.0f);
    ASSERT_FALSE(sah.occluded(s)) << i;
    // ...and only closer hits than hit.t are reported.
    Hit closer;
    closer.t = hb.t;
    ASSERT_FALSE(sah.intersect(rays[i], closer)) << i;
  }
  EXPECT_GT(hits, rays.size() / 4);  // the case was exercised
  EXPECT_LT(hits, rays.size());
}

// Long thin triangles along about the same diagonal: all their object splits
// overlap badly, the hard case for a tree of whole triangles.
std::vector<Triangle> slivers(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> U(-1.0f, 1.0f);
  std::vector<Triangle> tris;
  for (int i = 0; i < n; ++i) {
    const vec3 p = 2.0f * vec3(U(rng), U(rng), U(rng));
    const vec3 u = glm::normalize(vec3(1.0f) + 0.2f * vec3(U(rng), U(rng), U(rng)));
    const vec3 w = glm::normalize(glm::cross(u, vec3(U(rng), U(rng), U(rng)) + vec3(2e-3f)));
    tris.push_back({p - 4.0f * u, p + 4.0f * u, p + 0.05f * w});
  }
  return tris;
}

// The collapse into the 8-wide tree takes a subtree's triangles as one run
// of prims: every triangle once, each subtree's run starting at its first.
TEST(Bvh, SahTreeHoldsEveryTriangleOnceInOneRunPerSubtree) {
  const std::vector<Triangle> tris = slivers(800, 3);
  const BinaryBvh bin = build_binary_sah(tris, kWidth);
  EXPECT_EQ(bin.prims.size(), tris.size());
  std::vector<int> seen(tris.size(), 0);
  // References under node i, checking boxes and that each subtree's
  // references are one run of prims from its first.
  std::function<std::uint32_t(std::uint32_t)> walk = [&](std::uint32_t i) -> std::uint32_t {
    const BinaryNode& n = bin.nodes[i];
    if (n.leaf()) {
      EXPECT_LE(n.count, std::uint32_t(kWidth));
      std::set<std::uint32_t> in_leaf;
      for (std::uint32_t k = n.first; k < n.first + n.count; ++k) {
        const std::uint32_t prim = bin.prims[k];
        EXPECT_TRUE(in_leaf.insert(prim).second) << "twice in one leaf: " << prim;
        ++seen[prim];
        const Box3 b = bounds_of(tris[prim]);  // the leaf's box holds it
        for (int a = 0; a < 3; ++a) EXPECT_TRUE(n.box.lo[a] <= b.lo[a] && b.hi[a] <= n.box.hi[a]);
      }
      return n.count;
    }
    const BinaryNode &l = bin.nodes[n.left], &r = bin.nodes[n.right];
    for (int a = 0; a < 3; ++a)
      EXPECT_TRUE(n.box.lo[a] <= std::min(l.box.lo[a], r.box.lo[a]) &&
                  n.box.hi[a] >= std::max(l.box.hi[a], r.box.hi[a]));
    EXPECT_EQ(l.first, n.first);
    const std::uint32_t left = walk(n.left);
    EXPECT_EQ(r.first, n.first + left);
    return left + walk(n.right);
  };
  EXPECT_EQ(walk(0), bin.prims.size());
  for (std::size_t i = 0; i < seen.size(); ++i) EXPECT_EQ(seen[i], 1) << i;
}

TEST(Bvh, SliversFindTheClosestHitsOfBruteForce) {
  const std::vector<Triangle> tris = slivers(800, 4);
  const Bvh brute = Bvh::build(tris, BvhMethod::Brute);
  const Bvh sah = Bvh::build(tris, BvhMethod::Sah);
  std::mt19937 rng(8);
  std::uniform_real_distribution<float> U(-1.0f, 1.0f);
  std::uniform_int_distribution<std::size_t> pick(0, tris.size() - 1);
  std::size_t hits = 0;
  for (int i = 0; i < 40000; ++i) {
    // Half aimed at a point of a triangle, so there are hits to compare.
    const Triangle& t = tris[pick(rng)];
    const float a = 0.5f * (U(rng) + 1.0f), b = 0.5f * (1.0f - a) * (U(rng) + 1.0f);
    const vec3 target = i % 2 ? t.v0 + a * (t.v1 - t.v0) + b * (t.v2 - t.v0)
                              : 6.0f * vec3(U(rng), U(rng), U(rng));
    const vec3 o = 10.0f * vec3(U(rng), U(rng), U(rng));
    const Ray r{o, glm::normalize(target - o)};
    Hit hb, hs;
    const bool hit = brute.intersect(r, hb);
    ASSERT_EQ(sah.intersect(r, hs), hit) << i;
    ASSERT_EQ(sah.occluded(r), hit) << i;
    if (!hit) continue;
    ++hits;
    ASSERT_TRUE(hs.prim == hb.prim && hs.t == hb.t && hs.u == hb.u && hs.v == hb.v) << i;
    const Ray s{r.o, r.d, 0.0f, std::nextafter(hb.t, 0.0f)};  // stops just short
    ASSERT_EQ(sah.occluded(s), brute.occluded(s)) << i;
  }
  EXPECT_GT(hits, 10000u);
}

TEST(Bvh, OptimalCollapseHoldsEveryTriangleOnceInFewerNodes) {
  const std::vector<Triangle> tris = load_cat();
  const BinaryBvh bin = build_binary_sah(tris, kWidth);
  const WideBvh greedy = collapse_to_wide(bin, tris);
  const WideBvh best = collapse_to_wide_sah(bin, tris);
  EXPECT_LT(best.nodes.size(), greedy.nodes.size());
  std::vector<int> seen(tris.size(), 0);
  for (const WideNode& n : best.nodes)
    for (std::uint32_t ref : n.child) {
      if (ref == kEmptyRef || !(ref & kLeafBit)) continue;
      const std::uint32_t first = ref & 0xffffffu, count = ((ref >> 24) & 0x7fu) + 1;
      for (const TriPacket* pk = &best.packets[first]; pk < &best.packets[first] + count; ++pk)
        for (int i = 0; i < kWidth; ++i)  // an unused lane is all zeros
          seen[pk->prim[i]] += pk->v[0][0][i] != 0 || pk->v[1][1][i] != 0 || pk->v[2][2][i] != 0;
    }
  for (std::size_t i = 0; i < seen.size(); ++i) ASSERT_EQ(seen[i], 1) << i;
  const Bvh brute = Bvh::build(tris, BvhMethod::Brute);
  for (const Ray& r : cat_rays(tris, 20000)) {
    Hit hb, hw;
    const bool hit = brute.intersect(r, hb);
    ASSERT_EQ(best.intersect(r, hw), hit);
    ASSERT_EQ(best.occluded(r), hit);
    ASSERT_TRUE(!hit || (hw.prim == hb.prim && hw.t == hb.t));
  }
}

TEST(Bvh, BarycentricsReconstructTheHitPoint) {
  const std::vector<Triangle> tris = load_cat();
  const Bvh sah = Bvh::build(tris, BvhMethod::Sah);
  for (const Ray& r : cat_rays(tris, 2000)) {
    Hit h;
    if (!sah.intersect(r, h)) continue;
    const Triangle& t = tris[h.prim];
    const glm::dvec3 p = glm::dvec3(t.v0) * double(1 - h.u - h.v) + glm::dvec3(t.v1) * double(h.u) +
                         glm::dvec3(t.v2) * double(h.v);
    const glm::dvec3 q = glm::dvec3(r.o) + glm::dvec3(r.d) * double(h.t);
    ASSERT_LT(glm::length(p - q), 1e-4 * (1.0 + glm::length(q)));
  }
}

TEST(Bvh, DegenerateSliverAndHugeTriangles) {
  std::vector<Triangle> tris = {
      {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}},              // 0 collinear
      {{0, 0, -1}, {0, 0, -1}, {1, 0, -1}},           // 1 repeated vertex
      {{-1, -1, -5}, {1, -1, -5}, {0, 1e-6f, -5}},    // 2 sliver-ish, far
      {{-1e6f, -1e6f, -100}, {1e6f, -1e6f, -100}, {0, 1e6f, -100}},  // 3 huge
      {{0, 0, -2}, {1, 0, -2}, {0, 1e-7f, -2}},       // 4 sliver, near
  };
  for (int i = 0; i < 50; ++i) tris.push_back(tris[1]);  // many degenerates
  for (BvhMethod kind : kAll) {
    const Bvh bvh = Bvh::build(tris, kind);
    ASSERT_EQ(bvh.triangle_count(), tris.size());
    Hit h;
    // Straight down the collinear triangle and through the repeated vertex.
    ASSERT_TRUE(bvh.intersect(Ray{{1, 1, 1}, {0, 0, -1}}, h)) << name(kind);
    EXPECT_EQ(h.prim, 3u);
    EXPECT_EQ(h.t, 101.0f);
    // Inside the near sliver (its width at x = 0.5 is 5e-8).
    h = Hit{};
    ASSERT_TRUE(bvh.intersect(Ray{{0.5f, 2e-8f, 0}, {0, 0, -1}}, h)) << name(kind);
    EXPECT_EQ(h.prim, 4u);
    EXPECT_EQ(h.t, 2.0f);
    // Parallel to all of them: nothing.
    h = Hit{};
    EXPECT_FALSE(bvh.intersect(Ray{{-5, 0, -2}, {1, 0, 0}}, h)) << name(kind);
    EXPECT_FALSE(bvh.intersect(Ray{{-5e6f, 0, -100}, {1, 0, 0}}, h)) << name(kind);
    EXPECT_FALSE(bvh.occluded(Ray{{-5, 0, -2}, {1, 0, 0}})) << name(kind);
    // tmin past the near hits.
    h = Hit{};
    ASSERT_TRUE(bvh.intersect(Ray{{0, -0.5f, 0}, {0, 0, -1}, 5.0f, kInf}, h));
    EXPECT_EQ(h.prim, 3u);
    EXPECT_EQ(h.t, 100.0f);
  }
}

TEST(Bvh, CollinearTrianglesAreNeverHit) {
  const std::vector<Triangle> tris = {{{0, 0, 0}, {1, 1, 1}, {2, 2, 2}},
                                      {{0.1f, 0.0f, 3.0f}, {0.3f, 0.0f, 3.0f}, {0.7f, 0.0f, 3.0f}},
                                      {{-1, 2, 0.5f}, {-1, 2, 0.5f}, {-1, 3, 0.5f}}};
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> U(-1.0f, 1.0f);
  for (BvhMethod kind : kAll) {
    const Bvh bvh = Bvh::build(tris, kind);
    for (int i = 0; i < 30000; ++i) {
      const Triangle& t = tris[i % 3];
      const vec3 target = t.v0 + 0.5f * (U(rng) + 1.0f) * (t.v2 - t.v0);  // on the segment
      const vec3 o(U(rng) * 5, U(rng) * 5, U(rng) * 5);
      const Ray r{o, glm::normalize(target - o)};
      Hit h;
      ASSERT_FALSE(bvh.intersect(r, h)) << name(kind) << " " << i;
      ASSERT_FALSE(bvh.occluded(r)) << name(kind) << " " << i;
    }
  }
}

TEST(Bvh, EmptyAndSingle) {
  for (BvhMethod kind : kAll) {
    const Bvh empty = Bvh::build({}, kind);
    Hit h;
    EXPECT_FALSE(empty.intersect(Ray{}, h));
    EXPECT_FALSE(empty.occluded(Ray{}));
    const Bvh one = Bvh::build({{{-1, -1, -3}, {1, -1, -3}, {0, 1, -3}}}, kind);
    ASSERT_TRUE(one.intersect(Ray{}, h));
    EXPECT_EQ(h.t, 3.0f);
    EXPECT_EQ(h.prim, 0u);
    EXPECT_TRUE(one.occluded(Ray{}));
    EXPECT_FALSE(one.occluded(Ray{{0, 0, 0}, {0, 0, -1}, 0.0f, 3.0f}));
  }
}

TEST(Bvh, NonFiniteRaysHitNothingAndStayInTheTree) {
  // A ray with a NaN in its direction or origin (a degenerate shading normal
  // upstream) must miss, not enter every box: an unused child slot's box is
  // inverted, and a slab test that lets NaN through descends into it, a read
  // far outside the tree (a crash on a two-triangle mesh).
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<Triangle> two = {{{-1, -1, -3}, {1, -1, -3}, {0, 1, -3}},
                                     {{-1, -1, -4}, {1, -1, -4}, {0, 1, -4}}};
  const IndexedMesh ball = icosphere(3, vec3(0.0f), 1.0f);
  for (const auto& tris : {two, ball.triangles()}) {
    for (BvhMethod kind : kAll) {
      const Bvh bvh = Bvh::build(tris, kind);
      for (const Ray& r : {Ray{{0, 0, 0}, {nan, nan, nan}}, Ray{{0, 0, 0}, {0, nan, -1}},
                           Ray{{nan, 0, 0}, {0, 0, -1}}, Ray{{0, 0, 0}, {0, 0, -1}, 0.0f, nan}}) {
        Hit h;
        EXPECT_FALSE(bvh.intersect(r, h)) << name(kind);
        EXPECT_FALSE(bvh.occluded(r)) << name(kind);
      }
    }
  }
}

}  // namespace
}  // namespace whisker
