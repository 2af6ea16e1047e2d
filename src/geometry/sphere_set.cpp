#include "geometry/sphere_set.h"

#include <immintrin.h>

#include <limits>

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
  for (std::size_t k = 0; k < count_; ++k) {
    cx_[k] = spheres[k].center.x;
    cy_[k] = spheres[k].center.y;
    cz_[k] = spheres[k].center.z;
    r2_[k] = spheres[k].radius * spheres[k].radius;
  }
}

namespace {

// Eight lanes of intersect_sphere(): the RTG ch. 7 discriminant and Vieta root.
inline __m256 hit_t(const float* cx, const float* cy, const float* cz, const float* r2,
                    __m256 ox, __m256 oy, __m256 oz, __m256 dx, __m256 dy, __m256 dz,
                    __m256 tmin, __m256 tmax) {
  const __m256 fx = _mm256_sub_ps(ox, _mm256_loadu_ps(cx));
  const __m256 fy = _mm256_sub_ps(oy, _mm256_loadu_ps(cy));
  const __m256 fz = _mm256_sub_ps(oz, _mm256_loadu_ps(cz));
  const __m256 rr = _mm256_loadu_ps(r2);
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
  const __m256 t0 = _mm256_min_ps(t0r, q), t1 = _mm256_max_ps(t0r, q);
  const __m256 inf = _mm256_set1_ps(kInf);
  const __m256 ok0 = _mm256_and_ps(_mm256_cmp_ps(t0, tmin, _CMP_GT_OQ), _mm256_cmp_ps(t0, tmax, _CMP_LT_OQ));
  const __m256 ok1 = _mm256_and_ps(_mm256_cmp_ps(t1, tmin, _CMP_GT_OQ), _mm256_cmp_ps(t1, tmax, _CMP_LT_OQ));
  __m256 t = _mm256_blendv_ps(_mm256_blendv_ps(inf, t1, ok1), t0, ok0);
  const __m256 hit = _mm256_cmp_ps(disc, _mm256_setzero_ps(), _CMP_GE_OQ);
  return _mm256_blendv_ps(inf, t, hit);
}

}  // namespace

bool SphereSet::intersect(const Ray& r, float tmax, float& t_out, std::uint32_t& index) const {
  const __m256 ox = _mm256_set1_ps(r.o.x), oy = _mm256_set1_ps(r.o.y), oz = _mm256_set1_ps(r.o.z);
  const __m256 dx = _mm256_set1_ps(r.d.x), dy = _mm256_set1_ps(r.d.y), dz = _mm256_set1_ps(r.d.z);
  const __m256 tmin = _mm256_set1_ps(r.tmin);
  float best = tmax;
  bool found = false;
  for (std::size_t k = 0; k < cx_.size(); k += 8) {
    const __m256 t = hit_t(&cx_[k], &cy_[k], &cz_[k], &r2_[k], ox, oy, oz, dx, dy, dz, tmin,
                           _mm256_set1_ps(best));
    // Horizontal minimum without branches (hits are t < best; misses are
    // +inf), then the first lane that holds it.
    __m256 m = _mm256_min_ps(t, _mm256_permute2f128_ps(t, t, 1));
    m = _mm256_min_ps(m, _mm256_shuffle_ps(m, m, _MM_SHUFFLE(1, 0, 3, 2)));
    m = _mm256_min_ps(m, _mm256_shuffle_ps(m, m, _MM_SHUFFLE(2, 3, 0, 1)));
    const float t_min = _mm256_cvtss_f32(m);
    if (!(t_min < best)) continue;
    const int lane = __builtin_ctz(unsigned(_mm256_movemask_ps(_mm256_cmp_ps(t, m, _CMP_EQ_OQ))));
    best = t_min;
    index = id_[k + lane];
    found = true;
  }
  if (found) t_out = best;
  return found;
}

bool SphereSet::occluded(const Ray& r) const {
  const __m256 ox = _mm256_set1_ps(r.o.x), oy = _mm256_set1_ps(r.o.y), oz = _mm256_set1_ps(r.o.z);
  const __m256 dx = _mm256_set1_ps(r.d.x), dy = _mm256_set1_ps(r.d.y), dz = _mm256_set1_ps(r.d.z);
  const __m256 tmin = _mm256_set1_ps(r.tmin), tmax = _mm256_set1_ps(r.tmax);
  for (std::size_t k = 0; k < cx_.size(); k += 8) {
    const __m256 t = hit_t(&cx_[k], &cy_[k], &cz_[k], &r2_[k], ox, oy, oz, dx, dy, dz, tmin, tmax);
    if (_mm256_movemask_ps(_mm256_cmp_ps(t, tmax, _CMP_LT_OQ))) return true;
  }
  return false;
}

}  // namespace whisker
