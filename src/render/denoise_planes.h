// The denoiser's inner parts (render/denoise.h): float planes with a margin
// for the filters' taps, 8 pixels of a row side by side, the threads, and
// the two filters, each of which filters half a with weights from half b
// and the other way round.
#pragma once

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <new>
#include <utility>
#include <vector>

#include <immintrin.h>

#include "render/denoise.h"

namespace whisker::denoising {

// The widest tap offset any filter takes, pixels.
inline constexpr int kMargin = 32;

// Memory of at least 4 MiB in huge pages where the system gives them
// (2 MiB each: a plane's taps rows apart then share a few TLB entries, and
// the first touch faults once a huge page), else from malloc.
void* allocate_planes(std::size_t bytes);
void free_planes(void* p) noexcept;

// An allocator that leaves floats uninitialised (Planes says what is zero),
// from allocate_planes().
template <class T>
struct UninitAllocator : std::allocator<T> {
  using value_type = T;
  template <class U>
  struct rebind {
    using other = UninitAllocator<U>;
  };
  UninitAllocator() = default;
  template <class U>
  UninitAllocator(const UninitAllocator<U>&) noexcept {}
  T* allocate(std::size_t n) { return static_cast<T*>(allocate_planes(n * sizeof(T))); }
  void deallocate(T* p, std::size_t) noexcept { free_planes(p); }
  template <class U>
  void construct(U* p) noexcept {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

// `count` planes of a w x h image, each with kMargin pixels of zeros on
// every side and rows padded to a multiple of 8 pixels, so that 8 pixels of
// a row and their neighbours up to kMargin away load without bounds checks.
// Planes lie `plane` floats apart, a multiple of 4 KiB plus 5 cache lines:
// the same pixel of a dozen planes then falls in different sets of the
// cache, not all in one (which holds 8 lines).
struct Planes {
  int w = 0, h = 0, count = 0;
  std::size_t stride = 0, rows = 0, plane = 0;
  std::vector<float, UninitAllocator<float>> data;

  Planes() = default;
  // All zeros.
  Planes(int width, int height, int planes) : Planes(width, height, planes, false) {
    std::fill(data.begin(), data.end(), 0.0f);
  }
  // Zeros in the margins and the rows' padding only, the image's pixels
  // left for the caller to write.
  static Planes margins_zeroed(int width, int height, int planes) {
    Planes p(width, height, planes, false);
    for (int k = 0; k < planes; ++k) {
      std::fill_n(p.at(k, -kMargin, -kMargin), std::size_t(kMargin) * p.stride, 0.0f);
      std::fill_n(p.at(k, height, -kMargin), std::size_t(kMargin) * p.stride, 0.0f);
      for (int y = 0; y < height; ++y) {
        std::fill_n(p.at(k, y, -kMargin), kMargin, 0.0f);
        std::fill(p.at(k, y, width), p.at(k, y, -kMargin) + p.stride, 0.0f);
      }
    }
    return p;
  }
  float* at(int k, int y, int x) {
    return &data[std::size_t(k) * plane + std::size_t(y + kMargin) * stride + std::size_t(x + kMargin)];
  }
  const float* at(int k, int y, int x) const {
    return &data[std::size_t(k) * plane + std::size_t(y + kMargin) * stride + std::size_t(x + kMargin)];
  }

 private:
  Planes(int width, int height, int planes, bool)
      : w(width), h(height), count(planes),
        stride(std::size_t(kMargin) * 2 + std::size_t((width + 7) / 8 * 8)),
        rows(std::size_t(kMargin) * 2 + std::size_t(height)),
        plane((rows * stride + 1023) / 1024 * 1024 + 80),
        data(std::size_t(planes) * plane) {}
};

inline __m256 load8(const float* p) { return _mm256_loadu_ps(p); }
inline void store8(float* p, __m256 v) { _mm256_storeu_ps(p, v); }

// e^x for x <= 0 (below -87: e^-87), to about 2e-7 relative: x = n ln 2 + r
// with |r| <= ln 2 / 2 (ln 2 in two parts, Cody and Waite), e^r by its
// Taylor series to r^6, times 2^n from the exponent bits.
inline __m256 exp_negative(__m256 x) {
  x = _mm256_max_ps(x, _mm256_set1_ps(-87.0f));
  const __m256 n = _mm256_round_ps(x * 1.44269504f, _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC);
  const __m256 r = (x - n * 0.693145752f) - n * 1.42860677e-6f;
  __m256 p = _mm256_set1_ps(1.0f / 720.0f);
  p = p * r + 1.0f / 120.0f;
  p = p * r + 1.0f / 24.0f;
  p = p * r + 1.0f / 6.0f;
  p = p * r + 0.5f;
  p = p * r + 1.0f;
  p = p * r + 1.0f;
  const __m256i e = _mm256_slli_epi32(_mm256_add_epi32(_mm256_cvtps_epi32(n), _mm256_set1_epi32(127)), 23);
  return p * _mm256_castsi256_ps(e);
}

// Runs fn(y0, y1) on `threads` threads over row bands covering [0, rows).
void parallel_rows(int rows, int threads, const std::function<void(int, int)>& fn);

// The mean of the (2 radius + 1)^2 values around each pixel of a w x h
// plane, over those inside the image.
std::vector<float> box_mean(const std::vector<float>& v, int w, int h, int radius);

// The colour divided by the albedo and the image's scale, per half, with
// its variance, and the features the weights compare (Planes, by index).
enum FeaturePlane { kNx, kNy, kNz, kDepth, kAr, kAg, kAb, kGradX, kGradY, kInside, kFeaturePlanes };
enum StreamPlane { kXa, kXb = 3, kVa = 6, kVb, kStreamPlanes };
struct Prepared {
  Planes features, streams;
  std::vector<float> modulation;  // per value: what the colour was divided by
};
Prepared prepare(const DenoiseInput& in, int threads);
// The halves' filtered colour from streams in `p` (modulated back).
void modulate(const Prepared& p, const Planes& streams, std::vector<float>& a, std::vector<float>& b);

// The edge-stopping weights' constants (Dammertz et al. 2010, eq. 3-5:
// w = exp(-|d|^2 / sigma^2) for each feature; SVGF's luminance weight,
// normalised by the variance, for the colour).
struct AtrousParams {
  int levels = 5;
  float colour = 4.0f;     // sigma of the colour difference, in its standard deviations
  float normal = 64.0f;    // on |n_p - n_q|^2: SVGF's cos^128 near 1 (128 (1 - cos))
  float depth = 1.0f;      // sigma of |z_p - z_q| over the depth's slope times the distance
  float albedo = 400.0f;   // on |a_p - a_q|^2: a step of 0.05 weighs e^-1
};


// Filters the streams of prepare() in place. With `same_halves` (both
// halves one image: denoise() filters each half alone) half a alone is
// filtered and copied to b, half the colour work.
void atrous(Planes& streams, const Planes& features, const AtrousParams& params, int threads,
            bool same_halves = false);
// Whether `in`'s two halves are the same buffers.
bool same_halves(const DenoiseInput& in);
// The streams' half a (colour and variance) copied over half b.
void copy_half_a_to_b(Planes& streams);

void atrous_filter(const DenoiseInput& in, int threads, std::vector<float>& a, std::vector<float>& b);
void regression_filter(const DenoiseInput& in, int threads, std::vector<float>& a, std::vector<float>& b);

}  // namespace whisker::denoising
