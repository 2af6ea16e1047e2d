// The traversed structure: an 8-wide BVH with boxes and triangles laid out for
// AVX2 (one node tests 8 boxes at once, one packet tests 8 triangles at once).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/common.hpp>

#include "geometry/ray.h"
#include "geometry/triangle.h"

namespace whisker {

struct Box3 {
  vec3 lo{kInf}, hi{-kInf};
  void grow(const vec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  void grow(const Box3& b) {
    lo = glm::min(lo, b.lo);
    hi = glm::max(hi, b.hi);
  }
  bool empty() const { return !(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z); }
  float half_area() const {
    if (empty()) return 0.0f;
    const vec3 e = hi - lo;
    return e.x * e.y + e.y * e.z + e.z * e.x;
  }
};

// 1/d per axis, with zero components nudged to +-1e-30 so that no slab
// distance becomes 0 * inf = NaN.
inline vec3 safe_inverse(const vec3& d) {
  vec3 inv;
  for (int a = 0; a < 3; ++a)
    inv[a] = 1.0f / (std::fabs(d[a]) < 1e-30f ? std::copysign(1e-30f, d[a]) : d[a]);
  return inv;
}

// Where the ray enters box b within (ray.tmin, tmax), or kInf on a miss
// (Kay-Kajiya slabs). The exit is widened by 1 + 2 gamma(3), rounded up, so
// rounding never culls a box the ray grazes (Ize, "Robust BVH Ray
// Traversal", JCGT 2013). inv = safe_inverse(ray.d).
inline float box_entry(const Box3& b, const Ray& ray, const vec3& inv, float tmax) {
  float tn = ray.tmin, tf = kInf;
  for (int a = 0; a < 3; ++a) {
    const float t0 = (b.lo[a] - ray.o[a]) * inv[a], t1 = (b.hi[a] - ray.o[a]) * inv[a];
    tn = std::max(tn, std::min(t0, t1));
    tf = std::min(tf, std::max(t0, t1));
  }
  return tn <= std::min(tf * (1.0f + 4e-7f), tmax) ? tn : kInf;
}

inline Box3 bounds_of(const Triangle& t) {
  Box3 b;
  b.grow(t.v0);
  b.grow(t.v1);
  b.grow(t.v2);
  return b;
}

constexpr int kWidth = 8;  // children per node, triangles per packet

// 224 bytes of data in 256: boxes as [axis][child] so one load gets one slab
// of all 8 children. An unused slot has an inverted box (lo = +inf, hi =
// -inf), which the sign-selected slab test below never enters.
struct alignas(64) WideNode {
  float lo[3][kWidth];
  float hi[3][kWidth];
  // Child reference: an inner node index, or kLeafBit | (packets - 1) << 24 |
  // first packet.
  std::uint32_t child[kWidth];
};

constexpr std::uint32_t kLeafBit = 0x80000000u;
constexpr std::uint32_t kEmptyRef = 0xffffffffu;
constexpr std::uint32_t kMaxLeafPackets = 128;

// 8 triangles as vertex coordinates [vertex][axis][lane]; an unused lane is
// all zeros, a degenerate triangle the watertight test never hits.
struct alignas(32) TriPacket {
  float v[3][3][kWidth];
  std::uint32_t prim[kWidth];
};

struct WideBvh {
  std::vector<WideNode> nodes;  // nodes[0] is the root; none: brute force
  std::vector<TriPacket> packets;

  bool empty() const { return nodes.empty(); }
  // See Bvh::intersect and Bvh::occluded.
  bool intersect(const Ray& ray, Hit& hit) const;
  bool occluded(const Ray& ray) const;
};

struct BinaryBvh;
// Collapses a binary tree into the 8-wide one: each wide node takes its
// binary node's children and keeps opening the largest-area inner one until
// it has 8 (Wald, Benthin, Boulos, "Getting rid of packets", RT 2008).
WideBvh collapse_to_wide(const BinaryBvh& bin, const std::vector<Triangle>& tris);
// No tree: every triangle in packets, in their order (brute force).
WideBvh packets_only(const std::vector<Triangle>& tris);

}  // namespace whisker
