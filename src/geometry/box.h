// Axis-aligned boxes (the binary BVH builders' bounds) and the conservative
// scalar ray-box slab test (the one-box BBox method, the object-level BVH).
#pragma once

#include <algorithm>
#include <cmath>

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

}  // namespace whisker
