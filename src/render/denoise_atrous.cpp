// The denoiser's shared preparation (the colour divided by the albedo, the
// variance, the feature planes) and its fast filter, edge-avoiding a-trous
// wavelets (render/denoise.h).
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <thread>

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

// The mean depth of the two halves, row-major.
struct DepthMap {
  std::vector<float> z;
  int w = 0, h = 0;
  float at(int x, int y) const { return z[std::size_t(y) * std::size_t(w) + std::size_t(x)]; }
};

// The smaller of the depth's differences to the two neighbours along x (or
// y): one across an edge is large; the other then says the slope.
float depth_slope(const DepthMap& d, int x, int y, bool along_x) {
  const float c = d.at(x, y);
  float best = INFINITY;
  for (int s : {-1, 1}) {
    const int qx = along_x ? x + s : x, qy = along_x ? y : y + s;
    if (qx < 0 || qy < 0 || qx >= d.w || qy >= d.h) continue;
    best = std::min(best, std::fabs(d.at(qx, qy) - c));
  }
  return std::isfinite(best) ? best : 0.0f;
}

void prepare_features(const DenoiseInput& in, Prepared& p) {
  const int w = in.width, h = in.height;
  DepthMap d{std::vector<float>(std::size_t(w) * std::size_t(h)), w, h};
  std::vector<float>& z = d.z;
  for (std::size_t i = 0; i < z.size(); ++i) z[i] = 0.5f * (in.depth_a[i] + in.depth_b[i]);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t i = std::size_t(y) * std::size_t(w) + std::size_t(x);
      for (int c = 0; c < 3; ++c) {
        *p.features.at(kNx + c, y, x) = 0.5f * (in.normal_a[3 * i + std::size_t(c)] + in.normal_b[3 * i + std::size_t(c)]);
        *p.features.at(kAr + c, y, x) = 0.5f * (in.albedo_a[3 * i + std::size_t(c)] + in.albedo_b[3 * i + std::size_t(c)]);
      }
      *p.features.at(kDepth, y, x) = z[i];
      *p.features.at(kGradX, y, x) = depth_slope(d, x, y, true);
      *p.features.at(kGradY, y, x) = depth_slope(d, x, y, false);
      *p.features.at(kInside, y, x) = 1.0f;
    }
}

}  // namespace

Prepared prepare(const DenoiseInput& in, int threads) {
  (void)threads;
  const int w = in.width, h = in.height;
  const std::size_t values = std::size_t(w) * std::size_t(h) * 3;
  Prepared p{Planes(w, h, kFeaturePlanes), Planes(w, h, kStreamPlanes), std::vector<float>(values)};
  prepare_features(in, p);
  // The image's scale: its mean value, so that the filters' constants are
  // the same for any light intensity.
  double sum = 0.0;
  for (std::size_t k = 0; k < values; ++k) sum += 0.5 * (double(in.colour_a[k]) + double(in.colour_b[k]));
  const double mean = sum / double(values);
  const float scale = mean > 0.0 && std::isfinite(mean) ? float(mean) : 1.0f;
  std::vector<float> channel[2][3];
  for (auto& half : channel)
    for (auto& c : half) c.resize(std::size_t(w) * std::size_t(h));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t i = std::size_t(y) * std::size_t(w) + std::size_t(x);
      for (int c = 0; c < 3; ++c) {
        const std::size_t k = 3 * i + std::size_t(c);
        const float albedo = *p.features.at(kAr + c, y, x);
        const float m = (albedo > kAlbedoFloor ? albedo : 1.0f) * scale;
        p.modulation[k] = m;
        const float a = in.colour_a[k] / m, b = in.colour_b[k] / m;
        *p.streams.at(kXa + c, y, x) = a;
        *p.streams.at(kXb + c, y, x) = b;
        channel[0][c][i] = a;
        channel[1][c][i] = b;
      }
    }
  // Each half's variance (summed over channels) from that half alone, as
  // SVGF estimates it where it has no history (Schied et al. 2017, section
  // 4.2: spatially): the squared residual from the 3 x 3 mean (times 9/8,
  // the residual's share of a pixel's variance), averaged over 7 x 7. From
  // the half alone, so that neither filtered half depends on the other.
  // Both halves one image (denoise() filters each alone): computed once.
  const bool same = same_halves(in);
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
constexpr float kB3[5] = {1.0f / 16.0f, 1.0f / 4.0f, 3.0f / 8.0f, 1.0f / 4.0f, 1.0f / 16.0f};

struct Level {
  const Planes& f;
  const Planes& in;
  Planes& out;
  int step;
  const AtrousParams& params;
};

inline __m256 abs8(__m256 v) { return _mm256_andnot_ps(_mm256_set1_ps(-0.0f), v); }

// One level at 8 pixels of row y from column x: each half's colour and
// variance filtered with weights from its own colour (and both
// halves' features); with kBoth false half a alone (half b the same).
template <bool kBoth>
void atrous_pixels(const Level& L, int y, int x) {
  const AtrousParams& k = L.params;
  // The planes of one pixel lie a plane apart: offsets from plane 0's.
  const std::ptrdiff_t fp = L.f.at(1, 0, 0) - L.f.at(0, 0, 0), sp = L.in.at(1, 0, 0) - L.in.at(0, 0, 0);
  const float* f = L.f.at(0, y, x);
  const float* s = L.in.at(0, y, x);
  __m256 pn[3], pa[3], pxa[3], pxb[3];
  for (int c = 0; c < 3; ++c) {
    pn[c] = load8(f + (kNx + c) * fp);
    pa[c] = load8(f + (kAr + c) * fp);
    pxa[c] = load8(s + (kXa + c) * sp);
    if constexpr (kBoth) pxb[c] = load8(s + (kXb + c) * sp);
  }
  const __m256 pz = load8(f + kDepth * fp), pva = load8(s + kVa * sp);
  // The depth's tolerance depends on the tap only through |kx| and |ky|:
  // its reciprocal for the 3 x 3 of them, here once.
  const __m256 base = 1e-3f * pz + 1e-6f;
  const __m256 tx = (k.depth * float(L.step)) * load8(f + kGradX * fp);
  const __m256 ty = (k.depth * float(L.step)) * load8(f + kGradY * fp);
  __m256 rtol[3][3];
  for (int ay = 0; ay < 3; ++ay)
    for (int ax = 0; ax < 3; ++ax) rtol[ay][ax] = 1.0f / (tx * float(ax) + ty * float(ay) + base);
  const float c2 = k.colour * k.colour;
  constexpr float kEps = 1e-14f;  // a noise-free image (variance 0) is left as it is
  const __m256 c2va = c2 * pva + kEps;
  __m256 c2vb = c2va;
  if constexpr (kBoth) c2vb = c2 * load8(s + kVb * sp) + kEps;
  __m256 swa = _mm256_setzero_ps(), swb = swa, wva = swa, wvb = swa;
  __m256 sa[3] = {swa, swa, swa}, sb[3] = {swa, swa, swa};
  for (int ky = -2; ky <= 2; ++ky) {
    const float* fr = L.f.at(0, y + ky * L.step, x);
    const float* sr = L.in.at(0, y + ky * L.step, x);
    for (int kx = -2; kx <= 2; ++kx) {
      const float* fq = fr + kx * L.step;
      const float* sq = sr + kx * L.step;
      __m256 dn = _mm256_setzero_ps(), da = dn, dca = dn, dcb = dn;
      __m256 xa[3], xb[3];
      for (int c = 0; c < 3; ++c) {
        const __m256 n = pn[c] - load8(fq + (kNx + c) * fp);
        const __m256 a = pa[c] - load8(fq + (kAr + c) * fp);
        xa[c] = load8(sq + (kXa + c) * sp);
        const __m256 ea = pxa[c] - xa[c];
        dn += n * n;
        da += a * a;
        dca += ea * ea;
        if constexpr (kBoth) {
          xb[c] = load8(sq + (kXb + c) * sp);
          const __m256 eb = pxb[c] - xb[c];
          dcb += eb * eb;
        }
      }
      const __m256 va = load8(sq + kVa * sp);
      const __m256 dz = abs8(pz - load8(fq + kDepth * fp)) * rtol[std::abs(ky)][std::abs(kx)];
      const __m256 feature = k.normal * dn + k.albedo * da + dz;
      const __m256 h = kB3[ky + 2] * kB3[kx + 2] * load8(fq + kInside * fp);
      // Each half weighted by its own colour (so that neither depends on the
      // other's values: the error estimate compares each with the other).
      const __m256 ca = dca / (c2 * va + c2va);
      const __m256 wa = h * exp_negative(-(feature + ca));
      for (int c = 0; c < 3; ++c) sa[c] += wa * xa[c];
      swa += wa;
      wva += wa * wa * va;
      if constexpr (kBoth) {
        const __m256 vb = load8(sq + kVb * sp);
        const __m256 cb = dcb / (c2 * vb + c2vb);
        const __m256 wb = h * exp_negative(-(feature + cb));
        for (int c = 0; c < 3; ++c) sb[c] += wb * xb[c];
        swb += wb;
        wvb += wb * wb * vb;
      }
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

}  // namespace

void atrous(Planes& streams, const Planes& features, const AtrousParams& params, int threads, bool same_halves) {
  const int w = streams.w, h = streams.h;
  Planes next(w, h, kStreamPlanes);
  for (int level = 0; level < params.levels; ++level) {
    const Level L{features, streams, next, 1 << level, params};
    parallel_rows(h, threads, [&](int y0, int y1) {
      for (int y = y0; y < y1; ++y)
        for (int x = 0; x < w; x += 8) {
          if (same_halves)
            atrous_pixels<false>(L, y, x);
          else
            atrous_pixels<true>(L, y, x);
        }
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
