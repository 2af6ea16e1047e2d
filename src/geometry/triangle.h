// A triangle as three vertices: the unit the BVH stores and intersects, and
// the watertight ray/triangle test of Woop, Benthin and Wald, "Watertight
// Ray/Triangle Intersection", JCGT 2(1), 2013 (below: "the paper").
#pragma once

#include <cmath>

#include "geometry/ray.h"

namespace whisker {

struct Triangle {
  vec3 v0, v1, v2;
};

// The per-ray part of the paper's test (section 3): the dominant axis kz of
// the direction becomes z, kx/ky the other two (swapped when d[kz] < 0 so the
// winding, hence the sign of the edge functions, is preserved), and the shear
// constants that map the ray onto the +z axis through the origin.
struct WatertightRay {
  vec3 o;
  int kx = 0, ky = 1, kz = 2;
  float sx = 0.0f, sy = 0.0f, sz = 1.0f;

  WatertightRay() = default;
  explicit WatertightRay(const Ray& r) : o(r.o) {
    const float ax = std::fabs(r.d.x), ay = std::fabs(r.d.y), az = std::fabs(r.d.z);
    kz = (ax > ay) ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2);
    kx = (kz + 1) % 3;
    ky = (kx + 1) % 3;
    if (r.d[kz] < 0.0f) {
      const int t = kx;
      kx = ky;
      ky = t;
    }
    // One division: any shear constants keep the test watertight so long
    // as every triangle sees the same ones.
    sz = 1.0f / r.d[kz];
    sx = r.d[kx] * sz;
    sy = r.d[ky] * sz;
  }
};

// a*b - c*d with an exactly right sign: Kahan's difference of products with
// a fused multiply-add, accurate to 2 ulps (Jeannerod, Louvet, Muller, "Further
// analysis of Kahan's algorithm for the accurate computation of 2x2
// determinants", Math. Comp. 2013), so it is zero only when the exact value is.
// The paper gets the same guarantee by redoing the edge functions in double
// when one is zero (its section 3.3); a compiler that fuses a*b - c*d into one
// FMA breaks that plain-float antisymmetry, this cannot be broken.
inline float diff_of_products(float a, float b, float c, float d) {
  const float cd = c * d;
  const float err = std::fma(-c, d, cd);  // cd - c*d exactly
  const float dop = std::fma(a, b, -cd);
  return dop + err;
}

// The per-triangle part of the paper's test (section 3): translate to the ray
// origin, shear so the ray is the +z axis, then the signs of the three 2D edge
// functions decide the hit. Vertex terms are computed the same way for every
// triangle sharing a vertex, and the edge functions have exact signs, so the
// edge shared by two triangles gives opposite signs in both: no gaps.
// Intersects both sides. On a hit with tmin < t < tmax returns true with t and
// the barycentric weights u (of v1) and v (of v2); a degenerate triangle
// (zero determinant) is never hit.
inline bool intersect_triangle(const WatertightRay& r, const Triangle& tri,
                               float tmin, float tmax, float& t, float& u,
                               float& v) {
  // Plain arrays: indexing a glm vector by a run-time axis compiles to a switch.
  const float a[3] = {tri.v0.x - r.o.x, tri.v0.y - r.o.y, tri.v0.z - r.o.z};
  const float b[3] = {tri.v1.x - r.o.x, tri.v1.y - r.o.y, tri.v1.z - r.o.z};
  const float c[3] = {tri.v2.x - r.o.x, tri.v2.y - r.o.y, tri.v2.z - r.o.z};
  const float ax = std::fma(-r.sx, a[r.kz], a[r.kx]), ay = std::fma(-r.sy, a[r.kz], a[r.ky]);
  const float bx = std::fma(-r.sx, b[r.kz], b[r.kx]), by = std::fma(-r.sy, b[r.kz], b[r.ky]);
  const float cx = std::fma(-r.sx, c[r.kz], c[r.kx]), cy = std::fma(-r.sy, c[r.kz], c[r.ky]);
  // Weights of v0, v1, v2 times the determinant.
  const float e0 = diff_of_products(cx, by, cy, bx);
  const float e1 = diff_of_products(ax, cy, ay, cx);
  const float e2 = diff_of_products(bx, ay, by, ax);
  if ((e0 < 0.0f || e1 < 0.0f || e2 < 0.0f) && (e0 > 0.0f || e1 > 0.0f || e2 > 0.0f))
    return false;
  const float det = e0 + e1 + e2;
  if (det == 0.0f) return false;
  const float az = r.sz * a[r.kz], bz = r.sz * b[r.kz], cz = r.sz * c[r.kz];
  const float tt = std::fma(e2, cz, std::fma(e1, bz, e0 * az));
  const float inv = 1.0f / det;
  const float th = tt * inv;
  if (!(th > tmin && th < tmax)) return false;
  t = th;
  u = e1 * inv;
  v = e2 * inv;
  return true;
}

inline bool intersect_triangle(const Ray& ray, const Triangle& tri, float& t,
                               float& u, float& v) {
  return intersect_triangle(WatertightRay(ray), tri, ray.tmin, ray.tmax, t, u, v);
}

}  // namespace whisker
