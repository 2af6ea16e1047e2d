#include "geometry/sphere_set.h"

#include <immintrin.h>

#include <algorithm>
#include <cassert>
#include <cstddef>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

namespace whisker {

SphereSet::SphereSet(const std::vector<Sphere>& spheres, std::vector<std::uint32_t> ids)
    : count_(spheres.size()), id_(std::move(ids)) {
  if (id_.empty())
    for (std::size_t k = 0; k < count_; ++k) id_.push_back(std::uint32_t(k));
  const std::size_t padded = (count_ + 7) / 8 * 8;
  // Padding lanes: radius^2 = -1 makes the discriminant negative for any ray.
  cx_.assign(padded, 0.0f);
  cy_.assign(padded, 0.0f);
  cz_.assign(padded, 0.0f);
  r2_.assign(padded, -1.0f);
  idf_.assign(padded, -1.0f);
  near2_.assign(padded, -1.0f);
  spheres_ = spheres;
  for (std::size_t k = 0; k < count_; ++k) {
    idf_[k] = float(id_[k]);
    cx_[k] = spheres[k].center.x;
    cy_[k] = spheres[k].center.y;
    cz_[k] = spheres[k].center.z;
    r2_[k] = spheres[k].radius * spheres[k].radius;
    near2_[k] = r2_[k] * 0x1p-10f;
  }
}

namespace {

// Eight lanes of intersect_sphere(): the RTG ch. 7 discriminant and Vieta root.
// Lanes of `skip` (the sphere the ray leaves, see Ray::skip) keep only their
// far root (far_only) or none. `near` receives the lanes whose origin lies so
// close to the sphere (|c| < 2^-10 r^2, within about r/2000 of it) that
// float may get the sign of the near root wrong: the caller solves those
// again in double.
// The sphere data come as vectors: eight spheres (one ray broadcast), or
// one sphere broadcast (eight rays, SphereSet::intersect_batch).
inline __m256 hit_t(__m256 cx, __m256 cy, __m256 cz, __m256 rr, __m256 near2, __m256 idf,
                    __m256 ox, __m256 oy, __m256 oz, __m256 dx, __m256 dy, __m256 dz, __m256 tmin,
                    __m256 tmax, __m256 skip, __m256 far_only, unsigned& near) {
  const __m256 fx = _mm256_sub_ps(ox, cx);
  const __m256 fy = _mm256_sub_ps(oy, cy);
  const __m256 fz = _mm256_sub_ps(oz, cz);
  const __m256 fd = _mm256_fmadd_ps(fx, dx, _mm256_fmadd_ps(fy, dy, _mm256_mul_ps(fz, dz)));
  const __m256 b = _mm256_sub_ps(_mm256_setzero_ps(), fd);
  const __m256 px = _mm256_fmadd_ps(b, dx, fx);
  const __m256 py = _mm256_fmadd_ps(b, dy, fy);
  const __m256 pz = _mm256_fmadd_ps(b, dz, fz);
  const __m256 pp = _mm256_fmadd_ps(px, px, _mm256_fmadd_ps(py, py, _mm256_mul_ps(pz, pz)));
  const __m256 disc = _mm256_sub_ps(rr, pp);
  const __m256 ff = _mm256_fmadd_ps(fx, fx, _mm256_fmadd_ps(fy, fy, _mm256_mul_ps(fz, fz)));
  const __m256 c = _mm256_sub_ps(ff, rr);
  const __m256 sign = _mm256_set1_ps(-0.0f);
  const __m256 sq = _mm256_sqrt_ps(_mm256_max_ps(disc, _mm256_setzero_ps()));
  const __m256 q = _mm256_add_ps(b, _mm256_or_ps(sq, _mm256_and_ps(b, sign)));  // copysign
  const __m256 qnz = _mm256_cmp_ps(q, _mm256_setzero_ps(), _CMP_NEQ_OQ);
  const __m256 t0r = _mm256_and_ps(_mm256_div_ps(c, q), qnz);
  const __m256 inf = _mm256_set1_ps(kInf);
  const __m256 self = _mm256_cmp_ps(idf, skip, _CMP_EQ_OQ);
  // On the skipped sphere the near root is dropped, and the far one too
  // unless far_only: OR with the all-ones mask makes a NaN, which fails the
  // interval tests below.
  const __m256 t0 = _mm256_or_ps(_mm256_min_ps(t0r, q), self);
  const __m256 t1 = _mm256_or_ps(_mm256_max_ps(t0r, q), _mm256_andnot_ps(far_only, self));
  const __m256 absc = _mm256_andnot_ps(sign, c);
  near = unsigned(_mm256_movemask_ps(
      _mm256_andnot_ps(self, _mm256_cmp_ps(absc, near2, _CMP_LT_OQ))));
  const __m256 ok0 = _mm256_and_ps(_mm256_cmp_ps(t0, tmin, _CMP_GT_OQ), _mm256_cmp_ps(t0, tmax, _CMP_LT_OQ));
  const __m256 ok1 = _mm256_and_ps(_mm256_cmp_ps(t1, tmin, _CMP_GT_OQ), _mm256_cmp_ps(t1, tmax, _CMP_LT_OQ));
  __m256 t = _mm256_blendv_ps(_mm256_blendv_ps(inf, t1, ok1), t0, ok0);
  const __m256 hit = _mm256_cmp_ps(disc, _mm256_setzero_ps(), _CMP_GE_OQ);
  return _mm256_blendv_ps(inf, t, hit);
}

// Both roots of |o + t d - c| = r in double (the stable form of
// intersect_sphere()): f = o - c and |f|^2 - r^2 are exact to double rounding
// from the float inputs and the origin's residual (Ray::o_lo), so the sign of the near root is right even for an
// origin a float ULP off the sphere (a 1e-6 shell, a seam between walls).
// Returns the smallest root in (tmin, tmax), or kInf.
float solve_double(const Sphere& s, const Ray& r, float tmin, float tmax) {
  const glm::dvec3 f = exact_origin(r) - glm::dvec3(s.center);
  const glm::dvec3 d(r.d);
  const double inv_len2 = 1.0 / glm::dot(d, d);
  const double b = -glm::dot(f, d) * inv_len2;
  const glm::dvec3 perp = f + b * d;
  const double r2 = double(s.radius) * double(s.radius);
  const double disc = (r2 - glm::dot(perp, perp)) * inv_len2;
  if (disc < 0.0) return kInf;
  const double c = (glm::dot(f, f) - r2) * inv_len2;
  const double q = b + std::copysign(std::sqrt(disc), b);
  const double a0 = q != 0.0 ? c / q : 0.0;
  const float t0 = float(std::min(a0, q)), t1 = float(std::max(a0, q));
  if (t0 > tmin && t0 < tmax) return t0;
  if (t1 > tmin && t1 < tmax) return t1;
  return kInf;
}

}  // namespace

// The lanes of block k flagged `near` by hit_t(), solved again in double,
// merged into t (8 floats).
void SphereSet::redo_near(std::size_t k, unsigned near, const Ray& r, float tmax,
                          float* t) const {
  for (; near; near &= near - 1) {
    const unsigned lane = unsigned(__builtin_ctz(near));
    if (k + lane < count_) t[lane] = solve_double(spheres_[k + lane], r, r.tmin, tmax);
  }
}

// Of the lanes in `tie`, the one whose root (the one float found, solved in
// double from the exact origin) is nearest; on an exact tie (a ray through a
// seam of two walls, by symmetry) the sphere listed first in the scene.
int SphereSet::closest_of(std::size_t k, unsigned tie, const Ray& r, __m256 t) const {
  alignas(32) float ts[8];
  _mm256_store_ps(ts, t);
  int lane = -1;
  double nearest = kInf;
  for (; tie; tie &= tie - 1) {
    const int l = __builtin_ctz(tie);
    const double td = solve_sphere_t(spheres_[k + std::size_t(l)], r, ts[l]);
    if (lane < 0 || td < nearest || (td == nearest && id_[k + std::size_t(l)] < id_[k + std::size_t(lane)])) {
      nearest = td;
      lane = l;
    }
  }
  return lane;
}

// The loops below run in two passes. The first (kExact false) handles the
// common case, no lane near its sphere and no tie, with no call in the loop:
// every ymm register is caller-saved, so a call the loop might make (the
// double-precision re-tests) would have the broadcast ray spilled to the
// stack on every ray. Meeting either case, it gives up (kRetry) and the
// second pass, out of line, runs the whole loop again with the re-tests:
// the same arithmetic lane by lane, so the same answer as a single pass.
namespace {
enum : int { kMiss = 0, kFound = 1, kRetry = 2 };
}  // namespace

template <bool kExact>
int SphereSet::intersect_pass(const Ray& r, float tmax, float& t_out, std::uint32_t& index) const {
  const __m256 ox = _mm256_set1_ps(r.o.x), oy = _mm256_set1_ps(r.o.y), oz = _mm256_set1_ps(r.o.z);
  const __m256 dx = _mm256_set1_ps(r.d.x), dy = _mm256_set1_ps(r.d.y), dz = _mm256_set1_ps(r.d.z);
  const __m256 tmin = _mm256_set1_ps(r.tmin);
  const __m256 skip = _mm256_set1_ps(r.skip == kNoSkip ? -2.0f : float(r.skip));
  const __m256 far_only = _mm256_castsi256_ps(_mm256_set1_epi32(r.far_only ? -1 : 0));
  float best = tmax;
  std::uint32_t found_index = 0;
  bool found = false;
  for (std::size_t k = 0; k < cx_.size(); k += 8) {
    unsigned near = 0;
    __m256 t = hit_t(_mm256_loadu_ps(&cx_[k]), _mm256_loadu_ps(&cy_[k]), _mm256_loadu_ps(&cz_[k]),
                     _mm256_loadu_ps(&r2_[k]), _mm256_loadu_ps(&near2_[k]), _mm256_loadu_ps(&idf_[k]),
                     ox, oy, oz, dx, dy, dz, tmin,
                     _mm256_set1_ps(best), skip, far_only, near);
    if (near) {
      if constexpr (!kExact) return kRetry;
      alignas(32) float ts[8];
      _mm256_store_ps(ts, t);
      redo_near(k, near, r, best, ts);
      t = _mm256_load_ps(ts);
    }
    // Horizontal minimum without branches (hits are t < best; misses are
    // +inf), then the first lane that holds it.
    __m256 m = _mm256_min_ps(t, _mm256_permute2f128_ps(t, t, 1));
    m = _mm256_min_ps(m, _mm256_shuffle_ps(m, m, _MM_SHUFFLE(1, 0, 3, 2)));
    m = _mm256_min_ps(m, _mm256_shuffle_ps(m, m, _MM_SHUFFLE(2, 3, 0, 1)));
    const float t_min = _mm256_cvtss_f32(m);
    if (!(t_min < best)) continue;
    int lane = __builtin_ctz(unsigned(_mm256_movemask_ps(_mm256_cmp_ps(t, m, _CMP_EQ_OQ))));
    // Spheres met within a few float ULPs of t of each other (a hollow
    // shell 1e-6 thick, crossed): their order is decided in double.
    const unsigned tie = unsigned(_mm256_movemask_ps(
        _mm256_cmp_ps(t, _mm256_set1_ps(t_min * (1.0f + 0x1p-19f)), _CMP_LE_OQ)));
    if (tie & (tie - 1)) {
      if constexpr (!kExact) return kRetry;
      lane = closest_of(k, tie, r, t);
    }
    best = t_min;
    found_index = id_[k + std::size_t(lane)];
    found = true;
  }
  if (!found) return kMiss;
  t_out = best;
  index = found_index;
  return kFound;
}

[[gnu::noinline]] bool SphereSet::intersect_exact(const Ray& r, float tmax, float& t_out,
                                                  std::uint32_t& index) const {
  return intersect_pass<true>(r, tmax, t_out, index) == kFound;
}

bool SphereSet::intersect(const Ray& r, float tmax, float& t_out, std::uint32_t& index) const {
  const int res = intersect_pass<false>(r, tmax, t_out, index);
  if (res == kRetry) return intersect_exact(r, tmax, t_out, index);
  return res == kFound;
}

template <bool kExact>
int SphereSet::occluded_pass(const Ray& r, float end) const {
  const __m256 ox = _mm256_set1_ps(r.o.x), oy = _mm256_set1_ps(r.o.y), oz = _mm256_set1_ps(r.o.z);
  const __m256 dx = _mm256_set1_ps(r.d.x), dy = _mm256_set1_ps(r.d.y), dz = _mm256_set1_ps(r.d.z);
  const __m256 tmin = _mm256_set1_ps(r.tmin), tmax = _mm256_set1_ps(r.tmax);
  const __m256 skip = _mm256_set1_ps(r.skip == kNoSkip ? -2.0f : float(r.skip));
  const __m256 far_only = _mm256_castsi256_ps(_mm256_set1_epi32(r.far_only ? -1 : 0));
  const __m256 end_id = _mm256_set1_ps(end);
  for (std::size_t k = 0; k < cx_.size(); k += 8) {
    unsigned near = 0;
    __m256 t = hit_t(_mm256_loadu_ps(&cx_[k]), _mm256_loadu_ps(&cy_[k]), _mm256_loadu_ps(&cz_[k]),
                     _mm256_loadu_ps(&r2_[k]), _mm256_loadu_ps(&near2_[k]), _mm256_loadu_ps(&idf_[k]),
                     ox, oy, oz, dx, dy, dz, tmin,
                     tmax, skip, far_only, near);
    // The sphere the segment ends on is not an occluder (see occluded()).
    const __m256 at_end = _mm256_cmp_ps(_mm256_loadu_ps(&idf_[k]), end_id, _CMP_EQ_OQ);
    t = _mm256_blendv_ps(t, _mm256_set1_ps(kInf), at_end);
    near &= ~unsigned(_mm256_movemask_ps(at_end));
    if (near) {
      if constexpr (!kExact) return kRetry;
      alignas(32) float ts[8];
      _mm256_store_ps(ts, t);
      redo_near(k, near, r, r.tmax, ts);
      t = _mm256_load_ps(ts);
    }
    if (_mm256_movemask_ps(_mm256_cmp_ps(t, tmax, _CMP_LT_OQ))) return kFound;
  }
  return kMiss;
}

[[gnu::noinline]] bool SphereSet::occluded_exact(const Ray& r, float end) const {
  return occluded_pass<true>(r, end) == kFound;
}

bool SphereSet::occluded(const Ray& r, std::uint32_t end_sphere) const {
  // An id as a float (exact below 2^24, see idf_); -2 matches no lane.
  const float end = end_sphere == kNoSkip ? -2.0f : float(end_sphere);
  const int res = occluded_pass<false>(r, end);
  if (res == kRetry) return occluded_exact(r, end);
  return res == kFound;
}

namespace {

// The lanes' rays as vectors, read from the rays themselves: the first 32
// bytes of each (o, d, tmin, tmax) transposed, and skip and far_only from
// the next 8. Lanes gathered by scalar stores into arrays and read back as
// vectors waited on those stores (a store-to-load forward fails across
// several stores). Lanes not in `lanes` repeat a lane that is.
struct RayLanes {
  __m256 ox, oy, oz, dx, dy, dz, tmin, tmax, skip, far_only;
};

static_assert(offsetof(Ray, o) == 0 && offsetof(Ray, d) == 12 && offsetof(Ray, tmin) == 24 &&
              offsetof(Ray, tmax) == 28 && offsetof(Ray, skip) == 32 &&
              offsetof(Ray, far_only) == 36, "RayLanes reads a Ray's fields by offset");

RayLanes load_lanes(const Ray* const* rays, unsigned lanes) {
  const Ray* r[8];
  const Ray* live = rays[__builtin_ctz(lanes)];
  for (int l = 0; l < 8; ++l) r[l] = lanes >> l & 1u ? rays[l] : live;
  __m256 row[8];
  for (int l = 0; l < 8; ++l) row[l] = _mm256_loadu_ps(&r[l]->o.x);
  // 8 x 8 transpose: pairs of rows interleaved, then quads, then halves.
  __m256 q[8];
  for (int k = 0; k < 8; k += 4) {
    const __m256 a = _mm256_unpacklo_ps(row[k], row[k + 1]);
    const __m256 b = _mm256_unpackhi_ps(row[k], row[k + 1]);
    const __m256 c = _mm256_unpacklo_ps(row[k + 2], row[k + 3]);
    const __m256 d = _mm256_unpackhi_ps(row[k + 2], row[k + 3]);
    q[k] = _mm256_shuffle_ps(a, c, _MM_SHUFFLE(1, 0, 1, 0));
    q[k + 1] = _mm256_shuffle_ps(a, c, _MM_SHUFFLE(3, 2, 3, 2));
    q[k + 2] = _mm256_shuffle_ps(b, d, _MM_SHUFFLE(1, 0, 1, 0));
    q[k + 3] = _mm256_shuffle_ps(b, d, _MM_SHUFFLE(3, 2, 3, 2));
  }
  RayLanes v;
  v.ox = _mm256_permute2f128_ps(q[0], q[4], 0x20);
  v.oy = _mm256_permute2f128_ps(q[1], q[5], 0x20);
  v.oz = _mm256_permute2f128_ps(q[2], q[6], 0x20);
  v.dx = _mm256_permute2f128_ps(q[3], q[7], 0x20);
  v.dy = _mm256_permute2f128_ps(q[0], q[4], 0x31);
  v.dz = _mm256_permute2f128_ps(q[1], q[5], 0x31);
  v.tmin = _mm256_permute2f128_ps(q[2], q[6], 0x31);
  v.tmax = _mm256_permute2f128_ps(q[3], q[7], 0x31);
  // skip and the word holding far_only (its other bytes are padding).
  __m128i half[2][2];
  for (int h = 0; h < 2; ++h) {
    __m128i p[4];
    for (int k = 0; k < 4; ++k)
      p[k] = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(&r[4 * h + k]->skip));
    const __m128i a = _mm_unpacklo_epi32(p[0], p[1]), b = _mm_unpacklo_epi32(p[2], p[3]);
    half[h][0] = _mm_unpacklo_epi64(a, b);
    half[h][1] = _mm_unpackhi_epi64(a, b);
  }
  const __m256i skip = _mm256_set_m128i(half[1][0], half[0][0]);
  const __m256i word = _mm256_set_m128i(half[1][1], half[0][1]);
  // No sphere to skip: -2, which matches no sphere's index (padding is -1).
  v.skip = _mm256_blendv_ps(_mm256_cvtepi32_ps(skip), _mm256_set1_ps(-2.0f),
                            _mm256_castsi256_ps(_mm256_cmpeq_epi32(skip, _mm256_set1_epi32(-1))));
  const __m256i flag = _mm256_and_si256(word, _mm256_set1_epi32(0xff));
  v.far_only = _mm256_castsi256_ps(
      _mm256_xor_si256(_mm256_cmpeq_epi32(flag, _mm256_setzero_si256()), _mm256_set1_epi32(-1)));
  return v;
}

}  // namespace

// Eight rays at once, one per lane, against each sphere in turn: for the
// report's scenes (six walls, up to four balls) one ray against the spheres'
// lanes is a chain of dependent steps (sqrt, then a division, then a
// horizontal minimum) with a third of the lanes idle, where eight rays side
// by side are eight independent chains. Each lane does hit_t()'s arithmetic
// on the same numbers as intersect_pass(), so it finds the same roots; a ray
// that would take intersect_pass()'s second pass (near a sphere, or a tie)
// is solved by intersect() itself.
unsigned SphereSet::intersect_batch(const Ray* const* rays, unsigned lanes, float* t_out,
                                    std::uint32_t* index) const {
  assert(batchable());
  if (!lanes) return 0;
  const RayLanes v = load_lanes(rays, lanes);
  const __m256 vox = v.ox, voy = v.oy, voz = v.oz, vdx = v.dx, vdy = v.dy, vdz = v.dz;
  const __m256 vtmin = v.tmin, vtmax = v.tmax, vskip = v.skip, vfar = v.far_only;
  __m256 ts[8];
  unsigned retry = 0;
  __m256 m = _mm256_set1_ps(kInf);
  for (std::size_t k = 0; k < count_; ++k) {
    unsigned near = 0;
    ts[k] = hit_t(_mm256_set1_ps(cx_[k]), _mm256_set1_ps(cy_[k]), _mm256_set1_ps(cz_[k]),
                  _mm256_set1_ps(r2_[k]), _mm256_set1_ps(near2_[k]), _mm256_set1_ps(idf_[k]), vox, voy,
                  voz, vdx, vdy, vdz, vtmin, vtmax, vskip, vfar, near);
    retry |= near;
    m = _mm256_min_ps(m, ts[k]);
  }
  // Per lane: the first sphere at the minimum, and how many lie within the
  // tie bound of intersect_pass() (two or more: decided there, in double).
  const __m256 bound = _mm256_mul_ps(m, _mm256_set1_ps(1.0f + 0x1p-19f));
  __m256 first = _mm256_setzero_ps();
  __m256 ties = _mm256_setzero_ps();
  for (std::size_t k = count_; k-- > 0;) {
    first = _mm256_blendv_ps(first, _mm256_set1_ps(float(k)), _mm256_cmp_ps(ts[k], m, _CMP_EQ_OQ));
    ties = _mm256_add_ps(ties, _mm256_and_ps(_mm256_cmp_ps(ts[k], bound, _CMP_LE_OQ), _mm256_set1_ps(1.0f)));
  }
  const unsigned hit = unsigned(_mm256_movemask_ps(_mm256_cmp_ps(m, vtmax, _CMP_LT_OQ))) & lanes;
  retry |= hit & unsigned(_mm256_movemask_ps(_mm256_cmp_ps(ties, _mm256_set1_ps(1.5f), _CMP_GT_OQ)));
  retry &= lanes;
  alignas(32) float tm[8], kf[8];
  _mm256_store_ps(tm, m);
  _mm256_store_ps(kf, first);
  unsigned found = 0;
  for (unsigned a = lanes; a; a &= a - 1) {
    const int l = __builtin_ctz(a);
    if (retry >> l & 1u) {
      if (intersect(*rays[l], rays[l]->tmax, t_out[l], index[l])) found |= 1u << l;
    } else if (hit >> l & 1u) {
      t_out[l] = tm[l];
      index[l] = id_[std::size_t(kf[l])];
      found |= 1u << l;
    }
  }
  return found;
}

}  // namespace whisker
