// The denoiser's shared preparation (the colour divided by the albedo, the
// variance, the feature planes) and its fast filter, edge-avoiding a-trous
// wavelets (render/denoise.h).
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <new>
#include <stdexcept>
#include <thread>

#include <sys/mman.h>

#include "render/denoise_planes.h"

namespace whisker::denoising {

void parallel_rows(int rows, int threads, const std::function<void(int, int)>& fn) {
  const int n = std::clamp(threads, 1, std::max(1, rows));
  if (n == 1) {
    fn(0, rows);
    return;
  }
  std::vector<std::thread> pool;
  pool.reserve(std::size_t(n - 1));
  for (int t = 1; t < n; ++t) pool.emplace_back(fn, rows * t / n, rows * (t + 1) / n);
  fn(0, rows / n);
  for (std::thread& t : pool) t.join();
}

void* allocate_planes(std::size_t bytes) {
  constexpr std::size_t kHuge = std::size_t(2) << 20;
  if (bytes < 2 * kHuge) {
    void* p = std::malloc(bytes);
    if (!p) throw std::bad_alloc();
    return p;
  }
  void* p = std::aligned_alloc(kHuge, (bytes + kHuge - 1) / kHuge * kHuge);
  if (!p) throw std::bad_alloc();
  madvise(p, bytes, MADV_HUGEPAGE);  // advice: without it, small pages
  return p;
}

void free_planes(void* p) noexcept { std::free(p); }

std::vector<float> box_mean(const std::vector<float>& v, int w, int h, int radius) {
  // Separable: columns, then rows, each dividing by the count inside; each
  // pass sums whole lines (loops the compiler vectorises). At most
  // (2 radius + 1) terms a pass: float sums are within a few ulp.
  std::vector<float> tmp(v.size()), out(v.size(), 0.0f);
  const std::size_t sw = std::size_t(w);
  for (int y = 0; y < h; ++y) {
    const int y0 = std::max(0, y - radius), y1 = std::min(h - 1, y + radius);
    float* t = &tmp[std::size_t(y) * sw];
    std::copy_n(&v[std::size_t(y0) * sw], sw, t);
    for (int i = y0 + 1; i <= y1; ++i) {
      const float* src = &v[std::size_t(i) * sw];
      for (int x = 0; x < w; ++x) t[x] += src[x];
    }
    const float n = float(y1 - y0 + 1);
    for (int x = 0; x < w; ++x) t[x] /= n;
  }
  std::vector<float> count(sw);
  for (int x = 0; x < w; ++x) count[std::size_t(x)] = float(std::min(w - 1, x + radius) - std::max(0, x - radius) + 1);
  for (int y = 0; y < h; ++y) {
    const float* t = &tmp[std::size_t(y) * sw];
    float* o = &out[std::size_t(y) * sw];
    for (int j = -radius; j <= radius; ++j)
      for (int x = std::max(0, -j); x < std::min(w, w - j); ++x) o[x] += t[x + j];
    for (int x = 0; x < w; ++x) o[x] /= count[std::size_t(x)];
  }
  return out;
}

namespace {

// The albedo below which a channel is not divided by it: a channel of
// albedo 0 has no colour (the path's throughput is zero there), and one
// that is nearly so would be amplified past its use.
constexpr float kAlbedoFloor = 0.01f;

// The smaller of the depth's differences to the two neighbours along a
// line (n values `step` apart, from z): one across an edge is large; the
// other then says the slope. At the line's ends, the one neighbour's.
void depth_slopes(const float* z, std::size_t step, int n, float* out) {
  if (n == 1) {
    out[0] = 0.0f;
    return;
  }
  out[0] = std::fabs(z[step] - z[0]);
  for (int i = 1; i + 1 < n; ++i) {
    const float c = z[std::size_t(i) * step];
    out[i] = std::min(std::fabs(z[std::size_t(i - 1) * step] - c), std::fabs(z[std::size_t(i + 1) * step] - c));
  }
  out[n - 1] = std::fabs(z[std::size_t(n - 2) * step] - z[std::size_t(n - 1) * step]);
}

void prepare_features(const DenoiseInput& in, Prepared& p) {
  const int w = in.width, h = in.height;
  const std::size_t sw = std::size_t(w);
  std::vector<float> z(sw * static_cast<std::size_t>(h)), slope(static_cast<std::size_t>(h));
  for (std::size_t i = 0; i < z.size(); ++i) z[i] = 0.5f * (in.depth_a[i] + in.depth_b[i]);
  for (int y = 0; y < h; ++y) {
    const std::size_t row = std::size_t(y) * sw;
    for (int c = 0; c < 3; ++c) {
      float* n = p.features.at(kNx + c, y, 0);
      float* a = p.features.at(kAr + c, y, 0);
      for (int x = 0; x < w; ++x) {
        const std::size_t k = 3 * (row + std::size_t(x)) + std::size_t(c);
        n[x] = 0.5f * (in.normal_a[k] + in.normal_b[k]);
        a[x] = 0.5f * (in.albedo_a[k] + in.albedo_b[k]);
      }
    }
    std::copy_n(&z[row], w, p.features.at(kDepth, y, 0));
    depth_slopes(&z[row], 1, w, p.features.at(kGradX, y, 0));
    std::fill_n(p.features.at(kInside, y, 0), w, 1.0f);
  }
  for (int x = 0; x < w; ++x) {
    depth_slopes(&z[std::size_t(x)], sw, h, slope.data());
    for (int y = 0; y < h; ++y) *p.features.at(kGradY, y, x) = slope[std::size_t(y)];
  }
}

}  // namespace

Prepared prepare(const DenoiseInput& in, int threads) {
  (void)threads;
  const int w = in.width, h = in.height;
  const std::size_t values = std::size_t(w) * std::size_t(h) * 3;
  // Every pixel of every plane is written below.
  Prepared p{Planes::margins_zeroed(w, h, kFeaturePlanes), Planes::margins_zeroed(w, h, kStreamPlanes),
             std::vector<float>(values)};
  prepare_features(in, p);
  // The image's scale: its mean value, so that the filters' constants are
  // the same for any light intensity.
  // Eight float sums side by side over runs of 4096 values (a loop the
  // compiler vectorises), the runs summed in double.
  double sum = 0.0;
  for (std::size_t start = 0; start < values; start += 4096) {
    const std::size_t end = std::min(values, start + 4096);
    float part[8] = {0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f};
    std::size_t k = start;
    for (; k + 8 <= end; k += 8)
      for (int l = 0; l < 8; ++l) part[l] += in.colour_a[k + std::size_t(l)] + in.colour_b[k + std::size_t(l)];
    for (; k < end; ++k) part[0] += in.colour_a[k] + in.colour_b[k];
    for (const float v : part) sum += 0.5 * double(v);
  }
  const double mean = sum / double(values);
  const float scale = mean > 0.0 && std::isfinite(mean) ? float(mean) : 1.0f;
  const bool same = same_halves(in);
  std::vector<float> channel[2][3];
  for (int half = 0; half < (same ? 1 : 2); ++half)
    for (auto& c : channel[half]) c.resize(std::size_t(w) * std::size_t(h));
  for (int y = 0; y < h; ++y)
    for (int c = 0; c < 3; ++c) {
      const float* albedo = p.features.at(kAr + c, y, 0);
      float* xa = p.streams.at(kXa + c, y, 0);
      float* xb = p.streams.at(kXb + c, y, 0);
      const std::size_t row = std::size_t(y) * std::size_t(w);
      float* ca = &channel[0][c][row];
      for (int x = 0; x < w; ++x) {
        const std::size_t k = 3 * (row + std::size_t(x)) + std::size_t(c);
        const float m = (albedo[x] > kAlbedoFloor ? albedo[x] : 1.0f) * scale;
        p.modulation[k] = m;
        xa[x] = ca[x] = in.colour_a[k] / m;
      }
      if (same) {
        std::copy_n(xa, w, xb);
        continue;
      }
      float* cb = &channel[1][c][row];
      for (int x = 0; x < w; ++x) {
        const std::size_t k = 3 * (row + std::size_t(x)) + std::size_t(c);
        xb[x] = cb[x] = in.colour_b[k] / p.modulation[k];
      }
    }
  // Each half's variance (summed over channels) from that half alone, as
  // SVGF estimates it where it has no history (Schied et al. 2017, section
  // 4.2: spatially): the squared residual from the 3 x 3 mean (times 9/8,
  // the residual's share of a pixel's variance), averaged over 7 x 7. From
  // the half alone, so that neither filtered half depends on the other.
  // Both halves one image (denoise() filters each alone): computed once.
  for (int half = 0; half < 2; ++half) {
    if (half == 1 && same) {
      for (int y = 0; y < h; ++y) std::copy_n(p.streams.at(kVa, y, 0), w, p.streams.at(kVb, y, 0));
      break;
    }
    std::vector<float> residual(std::size_t(w) * std::size_t(h), 0.0f);
    for (int c = 0; c < 3; ++c) {
      const std::vector<float> local = box_mean(channel[half][c], w, h, 1);
      for (std::size_t i = 0; i < residual.size(); ++i) {
        const float d = channel[half][c][i] - local[i];
        residual[i] += 9.0f / 8.0f * d * d;
      }
    }
    const std::vector<float> v = box_mean(residual, w, h, 3);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        *p.streams.at(half ? kVb : kVa, y, x) = v[std::size_t(y) * std::size_t(w) + std::size_t(x)];
  }
  return p;
}

void modulate(const Prepared& p, const Planes& streams, std::vector<float>& a, std::vector<float>& b) {
  const int w = streams.w, h = streams.h;
  a.assign(std::size_t(w) * std::size_t(h) * 3, 0.0f);
  b.assign(a.size(), 0.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) {
        const std::size_t k = (std::size_t(y) * std::size_t(w) + std::size_t(x)) * 3 + std::size_t(c);
        a[k] = *streams.at(kXa + c, y, x) * p.modulation[k];
        b[k] = *streams.at(kXb + c, y, x) * p.modulation[k];
      }
}

namespace {

// The B3-spline's taps (Dammertz et al. 2010): h = (1, 4, 6, 4, 1) / 16.
constexpr int kRadius = 2;
constexpr float kB3[5] = {1.0f / 16.0f, 1.0f / 4.0f, 3.0f / 8.0f, 1.0f / 4.0f, 1.0f / 16.0f};

// The features as the weights compare them: the normal and the albedo
// scaled by the square roots of their constants, as one 6-vector g with
// |g|^2 beside it (so |g_p - g_q|^2 = |g_p|^2 + |g_q|^2 - 2 g_p . g_q, the
// two feature terms of Dammertz et al.'s weight), and the depth, which past
// the image is kFar, so that a tap there weighs nothing (e^-87 at most,
// against the centre's tap weight).
enum GuidePlane { kGn, kGa = 3, kGsq = 6, kGz, kGuidePlanes };
constexpr float kFar = 1e30f;

Planes guide_planes(const Planes& f, const AtrousParams& k) {
  const int w = f.w, h = f.h;
  Planes g = Planes::margins_zeroed(w, h, kGuidePlanes);
  std::fill_n(g.at(kGz, -kMargin, -kMargin), g.rows * g.stride, kFar);
  const float sn = std::sqrt(k.normal), sa = std::sqrt(k.albedo);
  for (int y = 0; y < h; ++y) {
    for (int c = 0; c < 3; ++c)
      for (int x = 0; x < w; ++x) {
        *g.at(kGn + c, y, x) = sn * *f.at(kNx + c, y, x);
        *g.at(kGa + c, y, x) = sa * *f.at(kAr + c, y, x);
      }
    for (int x = 0; x < w; ++x) {
      float sq = 0.0f;
      for (int c = 0; c < 6; ++c) sq += *g.at(kGn + c, y, x) * *g.at(kGn + c, y, x);
      *g.at(kGsq, y, x) = sq;
    }
    std::copy_n(f.at(kDepth, y, 0), w, g.at(kGz, y, 0));
  }
  return g;
}

struct Level {
  const Planes& f;  // the features (the centre's depth slopes)
  const Planes& g;  // guide_planes()
  const Planes& in;
  Planes& out;
  const AtrousParams& params;
};

inline __m256 abs8(__m256 v) { return _mm256_andnot_ps(_mm256_set1_ps(-0.0f), v); }

// e^x for x <= 0 (below -87: e^-87) to about 5e-5 relative, for the
// weights: x = n ln 2 + r with |r| <= ln 2 / 2, e^r by its Taylor series
// to r^4, times 2^n from the exponent bits.
inline __m256 exp_weight(__m256 x) {
  x = _mm256_max_ps(x, _mm256_set1_ps(-87.0f));
  const __m256 n = _mm256_round_ps(x * 1.44269504f, _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC);
  const __m256 r = _mm256_fnmadd_ps(n, _mm256_set1_ps(0.693147182f), x);
  __m256 p = _mm256_set1_ps(1.0f / 24.0f);
  p = p * r + 1.0f / 6.0f;
  p = p * r + 0.5f;
  p = p * r + 1.0f;
  p = p * r + 1.0f;
  const __m256i e = _mm256_slli_epi32(_mm256_cvtps_epi32(n + 127.0f), 23);
  return p * _mm256_castsi256_ps(e);
}

// One level at 8 pixels of row y from column x: each half's colour and
// variance filtered with weights from its own colour (and both
// halves' features); with kBoth false half a alone (half b the same).
// The taps kStep apart, kRadius each side.
template <bool kBoth, int kStep>
void atrous_pixels(const Level& L, int y, int x) {
  const AtrousParams& k = L.params;
  // The planes of one pixel lie a plane apart, rows a stride apart.
  const std::ptrdiff_t gp = L.g.at(1, 0, 0) - L.g.at(0, 0, 0), sp = L.in.at(1, 0, 0) - L.in.at(0, 0, 0);
  const std::ptrdiff_t gs = L.g.at(0, 1, 0) - L.g.at(0, 0, 0), ss = L.in.at(0, 1, 0) - L.in.at(0, 0, 0);
  const float* g = L.g.at(0, y, x);
  const float* s = L.in.at(0, y, x);
  __m256 pn[3], pa[3], pxa[3], pxb[3];
  for (int c = 0; c < 3; ++c) {
    pn[c] = load8(g + (kGn + c) * gp);
    pa[c] = load8(g + (kGa + c) * gp);
    pxa[c] = load8(s + (kXa + c) * sp);
    if constexpr (kBoth) pxb[c] = load8(s + (kXb + c) * sp);
  }
  const __m256 pz = load8(g + kGz * gp);
  // The depth's tolerance (Dammertz et al.'s depth term, over the depth's
  // slope times the distance) depends on the tap only through |kx| and
  // |ky|: its reciprocal for each, here once.
  const __m256 base = 1e-3f * pz + 1e-6f;
  const __m256 tx = (k.depth * float(kStep)) * load8(L.f.at(kGradX, y, x));
  const __m256 ty = (k.depth * float(kStep)) * load8(L.f.at(kGradY, y, x));
  __m256 rtol[kRadius + 1][kRadius + 1];
  for (int ay = 0; ay <= kRadius; ++ay)
    for (int ax = 0; ax <= kRadius; ++ax) rtol[ay][ax] = 1.0f / (tx * float(ax) + ty * float(ay) + base);
  const float c2 = k.colour * k.colour;
  constexpr float kEps = 1e-14f;  // a noise-free image (variance 0) is left as it is
  const __m256 c2va = c2 * load8(s + kVa * sp) + kEps;
  __m256 c2vb = c2va;
  if constexpr (kBoth) c2vb = c2 * load8(s + kVb * sp) + kEps;
  const __m256 psq = load8(g + kGsq * gp);
  // In two passes over the taps, each of short chains of operations that
  // do not depend on the other taps': the exponents, then their
  // exponentials and the sums. The centre's weight is its tap weight alone.
  constexpr int kSide = 2 * kRadius + 1, kTaps = kSide * kSide, kCentre = kTaps / 2;
  __m256 ea[kTaps], eb[kTaps];
#pragma GCC unroll 25
  for (int t = 0; t < kTaps; ++t) {
    if (t == kCentre) continue;
    const int ky = t / kSide - kRadius, kx = t % kSide - kRadius;
    const float* gq = g + ky * kStep * gs + kx * kStep;
    const float* sq = s + ky * kStep * ss + kx * kStep;
    __m256 dot = pn[0] * load8(gq + kGn * gp), dca = _mm256_setzero_ps(), dcb = dca;
    for (int c = 1; c < 3; ++c) dot += pn[c] * load8(gq + (kGn + c) * gp);
    for (int c = 0; c < 3; ++c) dot += pa[c] * load8(gq + (kGa + c) * gp);
    for (int c = 0; c < 3; ++c) {
      const __m256 da = pxa[c] - load8(sq + (kXa + c) * sp);
      dca += da * da;
      if constexpr (kBoth) {
        const __m256 db = pxb[c] - load8(sq + (kXb + c) * sp);
        dcb += db * db;
      }
    }
    const __m256 d2 = (psq + load8(gq + kGsq * gp)) - 2.0f * dot;
    const __m256 dz = abs8(pz - load8(gq + kGz * gp));
    // The tap's weight h as log h in the exponent: h e^-x = e^(log h - x).
    const float log_h = std::log(kB3[ky + kRadius] * kB3[kx + kRadius]);
    const __m256 feature = (log_h - d2) - dz * rtol[ky < 0 ? -ky : ky][kx < 0 ? -kx : kx];
    // Each half weighted by its own colour (so that neither depends on the
    // other's values: the error estimate compares each with the other); the
    // colour term's divisor by its reciprocal estimate (12 bits: the
    // weight's exponent within 4e-4 of itself).
    ea[t] = feature - dca * _mm256_rcp_ps(c2 * load8(sq + kVa * sp) + c2va);
    if constexpr (kBoth) eb[t] = feature - dcb * _mm256_rcp_ps(c2 * load8(sq + kVb * sp) + c2vb);
  }
  __m256 swa = _mm256_setzero_ps(), swb = swa, wva = swa, wvb = swa;
  __m256 sa[3] = {swa, swa, swa}, sb[3] = {swa, swa, swa};
#pragma GCC unroll 25
  for (int t = 0; t < kTaps; ++t) {
    const int ky = t / kSide - kRadius, kx = t % kSide - kRadius;
    const float* sq = s + ky * kStep * ss + kx * kStep;
    const __m256 wa = t == kCentre ? _mm256_set1_ps(kB3[kRadius] * kB3[kRadius]) : exp_weight(ea[t]);
    for (int c = 0; c < 3; ++c) sa[c] += wa * load8(sq + (kXa + c) * sp);
    swa += wa;
    wva += wa * wa * load8(sq + kVa * sp);
    if constexpr (kBoth) {
      const __m256 wb = t == kCentre ? _mm256_set1_ps(kB3[kRadius] * kB3[kRadius]) : exp_weight(eb[t]);
      for (int c = 0; c < 3; ++c) sb[c] += wb * load8(sq + (kXb + c) * sp);
      swb += wb;
      wvb += wb * wb * load8(sq + kVb * sp);
    }
  }
  const __m256 tiny = _mm256_set1_ps(1e-30f);
  swa = _mm256_max_ps(swa, tiny);
  for (int c = 0; c < 3; ++c) store8(L.out.at(kXa + c, y, x), sa[c] / swa);
  // SVGF eq. 6: the variance of a weighted mean of independent values.
  store8(L.out.at(kVa, y, x), wva / (swa * swa));
  if constexpr (kBoth) {
    swb = _mm256_max_ps(swb, tiny);
    for (int c = 0; c < 3; ++c) store8(L.out.at(kXb + c, y, x), sb[c] / swb);
    store8(L.out.at(kVb, y, x), wvb / (swb * swb));
  }
}

// One level's rows [y0, y1), the taps kStep apart.
template <int kStep>
void atrous_rows(const Level& L, bool same_halves, int y0, int y1) {
  for (int y = y0; y < y1; ++y)
    for (int x = 0; x < L.in.w; x += 8) {
      if (same_halves)
        atrous_pixels<false, kStep>(L, y, x);
      else
        atrous_pixels<true, kStep>(L, y, x);
    }
}

void atrous_rows(const Level& L, int step, bool same_halves, int y0, int y1) {
  switch (step) {
    case 1: return atrous_rows<1>(L, same_halves, y0, y1);
    case 2: return atrous_rows<2>(L, same_halves, y0, y1);
    case 4: return atrous_rows<4>(L, same_halves, y0, y1);
    case 8: return atrous_rows<8>(L, same_halves, y0, y1);
    default: return atrous_rows<16>(L, same_halves, y0, y1);
  }
}

}  // namespace

void atrous(Planes& streams, const Planes& features, const AtrousParams& params, int threads, bool same_halves) {
  const int w = streams.w, h = streams.h;
  if (params.levels > 0 && kRadius << (params.levels - 1) > kMargin)
    throw std::logic_error("atrous: taps past the planes' margin");
  const Planes g = guide_planes(features, params);
  // Each level writes every pixel of the planes (the padding columns after).
  Planes next = Planes::margins_zeroed(w, h, kStreamPlanes);
  for (int level = 0; level < params.levels; ++level) {
    const Level L{features, g, streams, next, params};
    parallel_rows(h, threads, [&](int y0, int y1) {
      // Weights far below the centre's flush to zero, not to subnormals.
      const unsigned csr = _mm_getcsr();
      _mm_setcsr(csr | _MM_FLUSH_ZERO_ON | _MM_DENORMALS_ZERO_ON);
      atrous_rows(L, 1 << level, same_halves, y0, y1);
      _mm_setcsr(csr);
    });
    // Columns past the width (the last 8 pixels' padding) stay zero.
    for (int k = 0; k < kStreamPlanes; ++k)
      for (int y = 0; y < h; ++y) std::fill(next.at(k, y, w), next.at(k, y, 0) + (w + 7) / 8 * 8, 0.0f);
    std::swap(streams, next);
  }
  if (same_halves) copy_half_a_to_b(streams);
}

bool same_halves(const DenoiseInput& in) {
  return in.colour_a.data() == in.colour_b.data() && in.albedo_a.data() == in.albedo_b.data() &&
         in.normal_a.data() == in.normal_b.data() && in.depth_a.data() == in.depth_b.data();
}

void copy_half_a_to_b(Planes& streams) {
  for (int c = 0; c < 3; ++c)
    for (int y = 0; y < streams.h; ++y) std::copy_n(streams.at(kXa + c, y, 0), streams.w, streams.at(kXb + c, y, 0));
  for (int y = 0; y < streams.h; ++y) std::copy_n(streams.at(kVa, y, 0), streams.w, streams.at(kVb, y, 0));
}

void atrous_filter(const DenoiseInput& in, int threads, std::vector<float>& a, std::vector<float>& b) {
  Prepared p = prepare(in, threads);
  atrous(p.streams, p.features, AtrousParams{}, threads, same_halves(in));
  modulate(p, p.streams, a, b);
}

}  // namespace whisker::denoising
