// The 8-wide BVH's traversal without AVX2 (bvh_wide.cpp has the AVX2 one,
// used wherever the compiler targets it): the same traversal one child and
// one triangle at a time.
#include "geometry/bvh_wide.h"

#include <algorithm>
#include <cmath>

#if !(defined(__AVX2__) && defined(__FMA__))

#include "geometry/bvh_wide_parts.h"

namespace whisker {

using namespace wide_parts;

namespace {

struct RayScalar {
  WatertightRay w;
  vec3 o, inv;
  explicit RayScalar(const Ray& r)
      : w(r), o(r.o), inv(safe_inv(r.d.x), safe_inv(r.d.y), safe_inv(r.d.z)) {}
};

inline bool child_test(const RayScalar& r, const WideNode& n, int i, float tmin, float tmax,
                       float& tnear) {
  float tn = tmin, tf = kInf;
  for (int a = 0; a < 3; ++a) {
    const float lo = n.lo[a][i], hi = n.hi[a][i];
    const float near = r.inv[a] >= 0.0f ? lo : hi, far = r.inv[a] >= 0.0f ? hi : lo;
    tn = std::max(tn, (near - r.o[a]) * r.inv[a]);
    tf = std::min(tf, (far - r.o[a]) * r.inv[a]);
  }
  tnear = tn;
  return tn <= std::min(tf * kFarScale, tmax);
}

inline Triangle packet_tri(const TriPacket& p, int i) {
  return Triangle{vec3(p.v[0][0][i], p.v[0][1][i], p.v[0][2][i]),
                  vec3(p.v[1][0][i], p.v[1][1][i], p.v[1][2][i]),
                  vec3(p.v[2][0][i], p.v[2][1][i], p.v[2][2][i])};
}

}  // namespace

bool WideBvh::intersect(const Ray& ray, Hit& hit) const {
  if (packets.empty() || !traceable(ray)) return false;
  const RayScalar r(ray);
  float best = std::min(ray.tmax, hit.t);
  bool found = false;
  StackEntry stack[kStackSize];
  int sp = 0;
  // Brute force (no nodes): one leaf of every packet.
  stack[sp++] = {nodes.empty() ? kLeafBit : 0u, ray.tmin};
  while (sp > 0) {
    const StackEntry e = stack[--sp];
    if (e.t > best) continue;
    if (!is_leaf(e.ref)) {
      const WideNode& n = nodes[e.ref];
      StackEntry s[kWidth];
      int k = 0;
      for (int i = 0; i < kWidth; ++i) {
        float tn;
        if (n.child[i] != kEmptyRef && child_test(r, n, i, ray.tmin, best, tn)) {
          int j = k++;
          while (j > 0 && s[j - 1].t < tn) {
            s[j] = s[j - 1];
            --j;
          }
          s[j] = {n.child[i], tn};
        }
      }
      for (int j = 0; j < k; ++j) stack[sp++] = s[j];
    } else {
      const std::size_t first = leaf_first(e.ref);
      const std::size_t count = nodes.empty() ? packets.size() : leaf_packets(e.ref);
      for (std::size_t p = first; p < first + count; ++p)
        for (int i = 0; i < kWidth; ++i) {
          float t, u, v;
          if (intersect_triangle(r.w, packet_tri(packets[p], i), ray.tmin, best, t, u, v)) {
            best = t;
            hit.t = t;
            hit.kind = PrimKind::Triangle;
            hit.prim = packets[p].prim[i];
            hit.u = u;
            hit.v = v;
            found = true;
          }
        }
    }
  }
  return found;
}

bool WideBvh::occluded(const Ray& ray) const {
  Hit h;
  h.t = ray.tmax;
  return intersect(ray, h);
}

bool occluded_by_packets(const Ray& ray, const TriPacket* packets, std::size_t count) {
  const RayScalar r(ray);
  float t, u, v;
  for (std::size_t p = 0; traceable(ray) && p < count; ++p)
    for (int i = 0; i < kWidth; ++i)
      if (intersect_triangle(r.w, packet_tri(packets[p], i), ray.tmin, ray.tmax, t, u, v)) return true;
  return false;
}

}  // namespace whisker

#endif
