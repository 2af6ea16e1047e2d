// The denoiser's quality filter (render/denoise.h): per pixel, a weighted
// first-order regression of each half's colour (divided by the albedo) on
// the features and the position in a window around it (NFOR, Bitterli et
// al. 2016, section 4: the colour is a linear function of the features in
// the window, its constant term the pixel's estimate), the weights from the
// other half's colour, pre-filtered (section 4.2's collaborative
// filtering). Several bandwidths, and the fast filter's output, are
// candidates; each pixel takes the one of least estimated MSE over the
// pixels around (section 5: the per-pixel selection by the MSE estimate of
// the two halves), as denoise.h's ScaleError computes it.
#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "render/denoise_planes.h"

namespace whisker::denoising {

namespace {

constexpr int kDims = 7;  // 1, the normal's change (3), the depth's, x, y
constexpr int kPairs = kDims * (kDims + 1) / 2;

struct RegressionParams {
  int radius = 6;          // the window: (2 radius + 1)^2 pixels
  float colour = 2.0f;     // the colour weight's sigma, in standard deviations of the guide
  float albedo = 400.0f;   // on |a_p - a_q|^2, as the fast filter's
  float depth = 10.0f;     // the relative depth change's scale in the regression
  float ridge = 1e-3f;     // on the slopes, relative to the total weight
};

struct Job {
  const Planes& f;       // features
  const Planes& guide;   // both halves' guides (their kXa/kXb and kVa/kVb planes)
  const Planes& values;  // both halves' colour
  Planes& out;           // the filtered colour, into the half's planes
  int half;              // 0: a (weighted by b's guide), 1: b
  const RegressionParams& p;
};

constexpr int pair_index(int i, int j) { return i * kDims - i * (i - 1) / 2 + (j - i); }

// Solves the normal equations of one lane (a Cholesky factorisation, the
// slopes held back by the ridge) for the constant terms of three colours.
void solve_lane(const float* a, const float (*b)[3], float ridge, float value[3], float out[3]) {
  double m[kDims][kDims], r[kDims][3];
  const double total = a[0];
  if (!(total > 0.0)) {
    for (int c = 0; c < 3; ++c) out[c] = value[c];
    return;
  }
  for (int i = 0; i < kDims; ++i) {
    for (int j = i; j < kDims; ++j) m[i][j] = m[j][i] = a[pair_index(i, j)];
    if (i) m[i][i] += ridge * total;
    for (int c = 0; c < 3; ++c) r[i][c] = b[i][c];
  }
  for (int j = 0; j < kDims; ++j) {  // L L^T in place (lower triangle)
    double d = m[j][j];
    for (int k = 0; k < j; ++k) d -= m[j][k] * m[j][k];
    if (!(d > 1e-12 * total)) {  // degenerate: the weighted mean
      for (int c = 0; c < 3; ++c) out[c] = float(b[0][c] / total);
      return;
    }
    m[j][j] = std::sqrt(d);
    for (int i = j + 1; i < kDims; ++i) {
      double s = m[i][j];
      for (int k = 0; k < j; ++k) s -= m[i][k] * m[j][k];
      m[i][j] = s / m[j][j];
    }
  }
  for (int c = 0; c < 3; ++c) {
    double y[kDims];
    for (int i = 0; i < kDims; ++i) {
      double s = r[i][c];
      for (int k = 0; k < i; ++k) s -= m[i][k] * y[k];
      y[i] = s / m[i][i];
    }
    for (int i = kDims - 1; i >= 0; --i) {
      double s = y[i];
      for (int k = i + 1; k < kDims; ++k) s -= m[k][i] * y[k];
      y[i] = s / m[i][i];
    }
    out[c] = float(y[0]);
  }
}

void regress_pixels(const Job& j, int y, int x) {
  const int guide = j.half ? kXb : kXa, guide_var = j.half ? kVb : kVa, val = j.half ? kXb : kXa;
  __m256 g[3], n[3], al[3];
  for (int c = 0; c < 3; ++c) {
    g[c] = load8(j.guide.at(guide + c, y, x));
    n[c] = load8(j.f.at(kNx + c, y, x));
    al[c] = load8(j.f.at(kAr + c, y, x));
  }
  const __m256 vg = load8(j.guide.at(guide_var, y, x)), z = load8(j.f.at(kDepth, y, x));
  const __m256 zs = j.p.depth / _mm256_max_ps(z, _mm256_set1_ps(1e-30f));
  const float c2 = j.p.colour * j.p.colour, inv_r = 1.0f / float(j.p.radius);
  __m256 a[kPairs], b[kDims][3];
  for (__m256& v : a) v = _mm256_setzero_ps();
  for (auto& row : b)
    for (__m256& v : row) v = _mm256_setzero_ps();
  for (int dy = -j.p.radius; dy <= j.p.radius; ++dy)
    for (int dx = -j.p.radius; dx <= j.p.radius; ++dx) {
      const int qy = y + dy, qx = x + dx;
      __m256 dc = _mm256_setzero_ps(), da = dc, f[kDims], yq[3];
      f[0] = _mm256_set1_ps(1.0f);
      for (int c = 0; c < 3; ++c) {
        const __m256 e = g[c] - load8(j.guide.at(guide + c, qy, qx));
        const __m256 d = al[c] - load8(j.f.at(kAr + c, qy, qx));
        dc += e * e;
        da += d * d;
        f[1 + c] = load8(j.f.at(kNx + c, qy, qx)) - n[c];
        yq[c] = load8(j.values.at(val + c, qy, qx));
      }
      const __m256 lim = _mm256_set1_ps(j.p.depth);
      f[4] = _mm256_min_ps(lim, _mm256_max_ps(-lim, (load8(j.f.at(kDepth, qy, qx)) - z) * zs));
      f[5] = _mm256_set1_ps(float(dx) * inv_r);
      f[6] = _mm256_set1_ps(float(dy) * inv_r);
      const __m256 var = c2 * (vg + load8(j.guide.at(guide_var, qy, qx))) + 1e-14f;
      const __m256 w = load8(j.f.at(kInside, qy, qx)) * exp_negative(-(dc / var + j.p.albedo * da));
      for (int r = 0; r < kDims; ++r) {
        const __m256 wf = w * f[r];
        for (int s = r; s < kDims; ++s) a[pair_index(r, s)] += wf * f[s];
        for (int c = 0; c < 3; ++c) b[r][c] += wf * yq[c];
      }
    }
  alignas(32) float av[kPairs][8], bv[kDims][3][8], yv[3][8];
  for (int k = 0; k < kPairs; ++k) _mm256_store_ps(av[k], a[k]);
  for (int r = 0; r < kDims; ++r)
    for (int c = 0; c < 3; ++c) _mm256_store_ps(bv[r][c], b[r][c]);
  for (int c = 0; c < 3; ++c) _mm256_store_ps(yv[c], load8(j.values.at(val + c, y, x)));
  for (int l = 0; l < 8 && x + l < j.f.w; ++l) {
    float al_[kPairs], bl[kDims][3], value[3] = {yv[0][l], yv[1][l], yv[2][l]}, out[3];
    for (int k = 0; k < kPairs; ++k) al_[k] = av[k][l];
    for (int r = 0; r < kDims; ++r)
      for (int c = 0; c < 3; ++c) bl[r][c] = bv[r][c][l];
    solve_lane(al_, bl, j.p.ridge, value, out);
    for (int c = 0; c < 3; ++c) *j.out.at(val + c, y, x + l) = out[c];
  }
}

// TUNING: read from the environment while the constants are chosen.
}  // namespace

void regression_filter(const DenoiseInput& in, int threads, std::vector<float>& a, std::vector<float>& b) {
  Prepared p = prepare(in, threads);
  // Each half's guide: that half filtered by the fast filter (its own colour
  // weights), so that neither half's result depends on the other's values.
  Planes guide = p.streams;
  const bool same = same_halves(in);
  atrous(guide, p.features, AtrousParams{}, threads, same);
  const RegressionParams rp;
  Planes out(in.width, in.height, kStreamPlanes);
  // Both halves one image (denoise() filters each alone): half a, copied.
  for (int half = 0; half < (same ? 1 : 2); ++half) {
    const Job job{p.features, guide, p.streams, out, half, rp};
    parallel_rows(in.height, threads, [&](int y0, int y1) {
      for (int y = y0; y < y1; ++y)
        for (int x = 0; x < in.width; x += 8) regress_pixels(job, y, x);
    });
  }
  if (same) copy_half_a_to_b(out);
  modulate(p, out, a, b);
}

}  // namespace whisker::denoising
