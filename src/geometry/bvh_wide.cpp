// The 8-wide BVH: single-ray traversal in AVX2. The collapse that builds it
// is in bvh_collapse.cpp.
#include "geometry/bvh_wide.h"

// Whisker targets AVX2 and FMA (x86-64-v3; CMakeLists.txt): the spheres'
// batches and the camera's lanes use them too.
#if !(defined(__AVX2__) && defined(__FMA__))
#error "Whisker needs AVX2 and FMA: build with -march=native or -march=x86-64-v3"
#endif

#include <immintrin.h>

#include <cmath>
#include <cstring>

#include "geometry/bvh_wide_parts.h"

namespace whisker {

using namespace wide_parts;

namespace {

struct RayAvx {
  __m256 ix, iy, iz;                 // 1 / d
  __m256 onx, ony, onz, ofx, ofy, ofz;  // o / d, nudged (see below)
  int near_x, near_y, near_z;  // offsets (in floats) of the near-plane rows
  int far_x, far_y, far_z;
  // Watertight test, in the permuted axes of WatertightRay.
  int kx, ky, kz;
  __m256 okx, oky, okz, sx, sy, sz;
  bool tmin_nonneg;  // then a hit needs t > 0

  explicit RayAvx(const Ray& r) {
    const float inv[3] = {safe_inv(r.d.x), safe_inv(r.d.y), safe_inv(r.d.z)};
    ix = _mm256_set1_ps(inv[0]);
    iy = _mm256_set1_ps(inv[1]);
    iz = _mm256_set1_ps(inv[2]);
    // A slab distance as one FMA, b * (1/d) - o * (1/d), errs by up to an
    // ulp of o/d besides the ulps of t that kFarScale covers. Moving o/d by
    // 4 of its ulps (up for near planes, down for far ones) keeps the test
    // conservative: near never later, far never earlier than exact.
    __m256* on[3] = {&onx, &ony, &onz};
    __m256* of[3] = {&ofx, &ofy, &ofz};
    for (int a = 0; a < 3; ++a) {
      const float oi = r.o[a] * inv[a];
      const float slack = std::fabs(oi) * (4.0f * 0x1p-24f) + 1e-37f;
      *on[a] = _mm256_set1_ps(oi + slack);
      *of[a] = _mm256_set1_ps(oi - slack);
    }
    // lo[a] starts at float offset a*8, hi[a] at 24 + a*8.
    near_x = inv[0] >= 0.0f ? 0 : 24;
    near_y = inv[1] >= 0.0f ? 8 : 32;
    near_z = inv[2] >= 0.0f ? 16 : 40;
    far_x = near_x < 24 ? near_x + 24 : near_x - 24;
    far_y = near_y < 24 ? near_y + 24 : near_y - 24;
    far_z = near_z < 24 ? near_z + 24 : near_z - 24;
    inv4 = _mm_setr_ps(inv[0], inv[1], inv[2], 0.0f);
    tmin_nonneg = r.tmin >= 0.0f;
  }

  // The triangle test's part, made once the root's box test passes: most
  // rays in the report's room never come near the mesh. The same axes and
  // shear as WatertightRay (triangle.h), but picked by a table and permutes
  // rather than branches, which an incoherent ray would mispredict. 1/d[kz]
  // is its division too: |d[kz]| >= |d| / sqrt(3) is never nudged.
  __m128 inv4;  // 1 / d
  void prepare_triangles(const Ray& r) {
    const __m128 d4 = _mm_setr_ps(r.d.x, r.d.y, r.d.z, 0.0f);
    const __m128 o4 = _mm_setr_ps(r.o.x, r.o.y, r.o.z, 0.0f);
    const __m128 i4 = inv4;
    const float ax = std::fabs(r.d.x), ay = std::fabs(r.d.y), az = std::fabs(r.d.z);
    // kz = ax > ay ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2); kx, ky follow
    // it cyclically, swapped when d[kz] < 0.
    static constexpr std::int8_t kZ[8] = {2, 2, 2, 0, 1, 2, 1, 0};
    kz = kZ[(ax > ay) | (ax > az) << 1 | (ay > az) << 2];
    const int flip = (_mm_movemask_ps(_mm_cmplt_ps(d4, _mm_setzero_ps())) >> kz) & 1;
    static constexpr std::int8_t kXY[3][2][2] = {
        {{1, 2}, {2, 1}}, {{2, 0}, {0, 2}}, {{0, 1}, {1, 0}}};
    kx = kXY[kz][flip][0];
    ky = kXY[kz][flip][1];
    const __m128i bx = _mm_set1_epi32(kx), by = _mm_set1_epi32(ky), bz = _mm_set1_epi32(kz);
    const __m128 z = _mm_permutevar_ps(i4, bz);
    const __m128 sd = _mm_mul_ps(d4, z);
    auto wide = [](__m128 v) { return _mm256_set_m128(v, v); };
    okx = wide(_mm_permutevar_ps(o4, bx));
    oky = wide(_mm_permutevar_ps(o4, by));
    okz = wide(_mm_permutevar_ps(o4, bz));
    sx = wide(_mm_permutevar_ps(sd, bx));
    sy = wide(_mm_permutevar_ps(sd, by));
    sz = wide(z);
  }
};

// Slab test of the 8 children: bit i of the result set when child i is
// entered within [tmin, tmax]; tnear receives the entry distances.
inline unsigned box_test(const RayAvx& r, const WideNode& n, __m256 tmin, __m256 tmax,
                         __m256& tnear) {
  const float* base = &n.lo[0][0];
  const __m256 nx = _mm256_fmsub_ps(_mm256_load_ps(base + r.near_x), r.ix, r.onx);
  const __m256 ny = _mm256_fmsub_ps(_mm256_load_ps(base + r.near_y), r.iy, r.ony);
  const __m256 nz = _mm256_fmsub_ps(_mm256_load_ps(base + r.near_z), r.iz, r.onz);
  const __m256 fx = _mm256_fmsub_ps(_mm256_load_ps(base + r.far_x), r.ix, r.ofx);
  const __m256 fy = _mm256_fmsub_ps(_mm256_load_ps(base + r.far_y), r.iy, r.ofy);
  const __m256 fz = _mm256_fmsub_ps(_mm256_load_ps(base + r.far_z), r.iz, r.ofz);
  tnear = _mm256_max_ps(_mm256_max_ps(nx, ny), _mm256_max_ps(nz, tmin));
  const __m256 tfar = _mm256_min_ps(
      _mm256_mul_ps(_mm256_min_ps(_mm256_min_ps(fx, fy), fz), _mm256_set1_ps(kFarScale)), tmax);
  return static_cast<unsigned>(_mm256_movemask_ps(_mm256_cmp_ps(tnear, tfar, _CMP_LE_OQ)));
}

// The watertight test of triangle.h on 8 triangles, operation for operation
// (same fused multiply-adds), so it returns the same t, u, v bit for bit.
// Returns the lanes hit within (tmin, tmax). One exit, after all three edges
// and the sign of t: an early exit on its own branch mispredicted on the
// incoherent rays more than it saved.
inline unsigned tri_test(const RayAvx& r, const TriPacket& p, __m256 tmin, __m256 tmax,
                         __m256& t, __m256& e1, __m256& e2, __m256& inv) {
  __m256 X[3], Y[3], Z[3];
  for (int j = 0; j < 3; ++j) {
    const __m256 px = _mm256_sub_ps(_mm256_load_ps(p.v[j][r.kx]), r.okx);
    const __m256 py = _mm256_sub_ps(_mm256_load_ps(p.v[j][r.ky]), r.oky);
    const __m256 pz = _mm256_sub_ps(_mm256_load_ps(p.v[j][r.kz]), r.okz);
    X[j] = _mm256_fnmadd_ps(r.sx, pz, px);
    Y[j] = _mm256_fnmadd_ps(r.sy, pz, py);
    Z[j] = _mm256_mul_ps(r.sz, pz);
  }
  // diff_of_products(a, b, c, d) = a*b - c*d with an exact sign.
  auto dop = [](__m256 a, __m256 b, __m256 c, __m256 d) {
    const __m256 cd = _mm256_mul_ps(c, d);
    const __m256 err = _mm256_fnmadd_ps(c, d, cd);
    return _mm256_add_ps(_mm256_fmsub_ps(a, b, cd), err);
  };
  const __m256 zero = _mm256_setzero_ps();
  const __m256 e0 = dop(X[2], Y[1], Y[2], X[1]);
  e1 = dop(X[0], Y[2], Y[0], X[2]);
  __m256 neg = _mm256_or_ps(_mm256_cmp_ps(e0, zero, _CMP_LT_OQ), _mm256_cmp_ps(e1, zero, _CMP_LT_OQ));
  __m256 pos = _mm256_or_ps(_mm256_cmp_ps(e0, zero, _CMP_GT_OQ), _mm256_cmp_ps(e1, zero, _CMP_GT_OQ));
  e2 = dop(X[1], Y[0], Y[1], X[0]);
  neg = _mm256_or_ps(neg, _mm256_cmp_ps(e2, zero, _CMP_LT_OQ));
  pos = _mm256_or_ps(pos, _mm256_cmp_ps(e2, zero, _CMP_GT_OQ));
  const unsigned mixed = static_cast<unsigned>(_mm256_movemask_ps(_mm256_and_ps(neg, pos)));
  if (!r.tmin_nonneg && mixed == 0xffu) return 0;
  const __m256 det = _mm256_add_ps(_mm256_add_ps(e0, e1), e2);
  const __m256 tt = _mm256_fmadd_ps(e2, Z[2], _mm256_fmadd_ps(e1, Z[1], _mm256_mul_ps(e0, Z[0])));
  // t = tt / det > tmin >= 0 needs tt and det of one sign. A ray leaving a
  // surface passes its own triangle's edges with t < 0: no division then.
  const unsigned ahead = ~static_cast<unsigned>(_mm256_movemask_ps(_mm256_xor_ps(tt, det)));
  if (r.tmin_nonneg && (ahead & ~mixed & 0xffu) == 0) return 0;
  inv = _mm256_div_ps(_mm256_set1_ps(1.0f), det);
  t = _mm256_mul_ps(tt, inv);
  const __m256 ok = _mm256_and_ps(
      _mm256_and_ps(_mm256_cmp_ps(det, zero, _CMP_NEQ_OQ), _mm256_cmp_ps(t, tmin, _CMP_GT_OQ)),
      _mm256_cmp_ps(t, tmax, _CMP_LT_OQ));
  return static_cast<unsigned>(_mm256_movemask_ps(ok)) & ~mixed;
}

// Whether any triangle of `count` packets is hit within (tmin, tmax).
inline bool any_hit(const RayAvx& r, const TriPacket* p, std::size_t count, __m256 tmin,
                    __m256 tmax) {
  __m256 t, e1, e2, inv;
  for (std::size_t k = 0; k < count; ++k)
    if (tri_test(r, p[k], tmin, tmax, t, e1, e2, inv)) return true;
  return false;
}

inline float lane(__m256 v, unsigned i) {
  alignas(32) float a[kWidth];
  _mm256_store_ps(a, v);
  return a[i];
}

// The closest hit so far, over packets of triangles.
struct Closest {
  float best;
  __m256 tmax;
  bool found = false;
  std::uint32_t prim = 0;
  float u = 0.0f, v = 0.0f;

  explicit Closest(float tmax_) : best(tmax_), tmax(_mm256_set1_ps(tmax_)) {}

  void packets(const RayAvx& r, const TriPacket* p, std::size_t count, __m256 tmin) {
    for (std::size_t k = 0; k < count; ++k) {
      __m256 t, e1, e2, inv;
      unsigned mask = tri_test(r, p[k], tmin, tmax, t, e1, e2, inv);
      if (mask == 0) continue;
      alignas(32) float ts[kWidth];
      _mm256_store_ps(ts, t);
      unsigned bi = static_cast<unsigned>(__builtin_ctz(mask));
      for (mask &= mask - 1; mask; mask &= mask - 1) {
        const unsigned i = static_cast<unsigned>(__builtin_ctz(mask));
        if (ts[i] < ts[bi]) bi = i;
      }
      best = ts[bi];
      tmax = _mm256_set1_ps(best);
      const float iv = lane(inv, bi);
      u = lane(e1, bi) * iv;
      v = lane(e2, bi) * iv;
      prim = p[k].prim[bi];
      found = true;
    }
  }

  bool store(Hit& hit) const {
    if (!found) return false;
    hit.t = best;
    hit.kind = PrimKind::Triangle;
    hit.prim = prim;
    hit.u = u;
    hit.v = v;
    return true;
  }
};

// The children of n in mask (entry distances tnear), front to back: the
// nearest becomes ref, the others go on the stack far to near, so the
// nearest of them pops next.
inline void descend(const WideNode& n, unsigned mask, __m256 tnear, StackEntry* stack, int& sp,
                    std::uint32_t& ref) {
  const unsigned first = static_cast<unsigned>(__builtin_ctz(mask));
  mask &= mask - 1;
  if (mask == 0) {
    ref = n.child[first];
    return;
  }
  alignas(32) float dist[kWidth];
  _mm256_store_ps(dist, tnear);
  const unsigned second = static_cast<unsigned>(__builtin_ctz(mask));
  mask &= mask - 1;
  // Two, the common case: ordered by selects rather than a branch.
  const StackEntry a{n.child[first], dist[first]}, b{n.child[second], dist[second]};
  const bool b_first = b.t < a.t;
  const StackEntry near = b_first ? b : a, far = b_first ? a : b;
  StackEntry* top = stack + sp;
  top[0] = far;
  if (mask == 0) {
    ++sp;
    ref = near.ref;
    return;
  }
  // More: insertion sort on top of the stack, descending by distance.
  top[1] = near;
  int k = 2;
  while (mask) {
    const unsigned i = static_cast<unsigned>(__builtin_ctz(mask));
    mask &= mask - 1;
    const StackEntry x{n.child[i], dist[i]};
    int j = k++;
    while (j > 0 && top[j - 1].t < x.t) {
      top[j] = top[j - 1];
      --j;
    }
    top[j] = x;
  }
  sp += k - 1;
  ref = top[k - 1].ref;
}

}  // namespace

bool WideBvh::intersect(const Ray& ray, Hit& hit) const {
  if (packets.empty() || !traceable(ray)) return false;
  RayAvx r(ray);
  const __m256 tmin = _mm256_set1_ps(ray.tmin);
  Closest c(std::min(ray.tmax, hit.t));
  if (nodes.empty()) {  // brute force: every packet
    r.prepare_triangles(ray);
    c.packets(r, packets.data(), packets.size(), tmin);
    return c.store(hit);
  }
  __m256 tnear;
  const unsigned root = box_test(r, nodes[0], tmin, c.tmax, tnear);
  if (root == 0) return false;
  r.prepare_triangles(ray);
  StackEntry stack[kStackSize];
  int sp = 0;
  std::uint32_t ref;
  descend(nodes[0], root, tnear, stack, sp, ref);
  for (;;) {
    if (!is_leaf(ref)) {
      const WideNode& n = nodes[ref];
      const unsigned mask = box_test(r, n, tmin, c.tmax, tnear);
      if (mask != 0) {
        descend(n, mask, tnear, stack, sp, ref);
        continue;
      }
    } else {
      c.packets(r, &packets[leaf_first(ref)], leaf_packets(ref), tmin);
    }
    // Pop the next node that may still hold a closer hit.
    for (;;) {
      if (sp == 0) return c.store(hit);
      const StackEntry& e = stack[--sp];
      if (e.t <= c.best) {
        ref = e.ref;
        break;
      }
    }
  }
}

bool WideBvh::occluded(const Ray& ray) const {
  if (packets.empty() || !traceable(ray)) return false;
  RayAvx r(ray);
  const __m256 tmin = _mm256_set1_ps(ray.tmin);
  const __m256 tmax = _mm256_set1_ps(ray.tmax);
  if (nodes.empty()) {  // brute force: every packet
    r.prepare_triangles(ray);
    return any_hit(r, packets.data(), packets.size(), tmin, tmax);
  }
  __m256 tnear;
  const unsigned root = box_test(r, nodes[0], tmin, tmax, tnear);
  if (root == 0) return false;
  r.prepare_triangles(ray);
  std::uint32_t stack[kStackSize];
  int sp = 0;
  for (unsigned mask = root; mask; mask &= mask - 1)
    stack[sp++] = nodes[0].child[__builtin_ctz(mask)];
  while (sp > 0) {
    const std::uint32_t ref = stack[--sp];
    if (!is_leaf(ref)) {
      const WideNode& n = nodes[ref];
      __m256 tnear;
      for (unsigned mask = box_test(r, n, tmin, tmax, tnear); mask; mask &= mask - 1)
        stack[sp++] = n.child[__builtin_ctz(mask)];
    } else {
      if (any_hit(r, &packets[leaf_first(ref)], leaf_packets(ref), tmin, tmax)) return true;
    }
  }
  return false;
}

bool occluded_by_packets(const Ray& ray, const TriPacket* packets, std::size_t count) {
  if (count == 0 || !traceable(ray)) return false;
  RayAvx r(ray);
  r.prepare_triangles(ray);
  return any_hit(r, packets, count, _mm256_set1_ps(ray.tmin), _mm256_set1_ps(ray.tmax));
}

}  // namespace whisker
