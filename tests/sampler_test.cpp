// The samplers: independent uniforms and Owen-scrambled Sobol points.
#include <gtest/gtest.h>

#include <cmath>
#include <array>
#include <set>
#include <vector>

#include "render/sampler.h"

using namespace whisker;

TEST(Sampler, SobolDimensionOneIsTheKnownSequence) {
  // Unscrambled Sobol dim 1 for indices 0..7: 0, 1/2, 3/4, 1/4, 5/8, 1/8, 3/8, 7/8.
  const double expect[] = {0, 0.5, 0.75, 0.25, 0.625, 0.125, 0.375, 0.875};
  for (std::uint32_t i = 0; i < 8; ++i) EXPECT_EQ(sobol_dim1(i) * 0x1p-32, expect[i]) << i;
  // All 32 index bits, against the definition: XOR of the generator columns
  // v_1 = 2^31, v_k = v_{k-1} ^ (v_{k-1} >> 1) for the bits set.
  for (std::uint32_t i : {0x80000000u, 0xdeadbeefu, 0x12345678u, 0xffffffffu, 0x00010001u}) {
    std::uint32_t v = 0x80000000u, r = 0;
    for (int k = 0; k < 32; ++k, v ^= v >> 1)
      if (i >> k & 1) r ^= v;
    EXPECT_EQ(sobol_dim1(i), r) << std::hex << i;
  }
}

TEST(Sampler, OwenScrambleIsAPermutationOfLeadingBits) {
  // Nested uniform scrambling maps the 2^k intervals of size 2^-k onto each other.
  const std::uint32_t seed = 12345;
  std::set<std::uint32_t> top;
  for (std::uint32_t v = 0; v < 256; ++v) top.insert(owen_scramble(v << 24, seed) >> 24);
  EXPECT_EQ(top.size(), 256u);
}

namespace {

// The t of a 2D point set of n = 2^m points as a (t, m, 2)-net: the smallest
// t such that every elementary box of area 2^(t - m) holds exactly 2^t points.
int net_t(const std::vector<std::pair<float, float>>& pts, int m) {
  for (int t = 0; t <= m; ++t) {
    bool ok = true;
    for (int kx = 0; kx <= m - t && ok; ++kx) {
      const int nx = 1 << kx, ny = 1 << (m - t - kx);
      std::vector<int> count(std::size_t(nx) * ny, 0);
      for (const auto& [u, v] : pts) ++count[std::size_t(int(u * nx)) * ny + int(v * ny)];
      for (int c : count) ok &= c == (1 << t);
    }
    if (ok) return t;
  }
  return m + 1;
}

// The first n samples of a pixel, 4 dimension pairs = 8 dimensions each.
std::vector<std::array<float, 8>> points(std::uint32_t pixel, int n) {
  std::vector<std::array<float, 8>> out(n);
  for (int i = 0; i < n; ++i) {
    Sampler s(SamplerKind::Sobol, pixel, std::uint64_t(i), 9);
    for (int d = 0; d < 8; d += 2) s.get2d(out[i][d], out[i][d + 1]);
  }
  return out;
}

std::vector<std::pair<float, float>> project(const std::vector<std::array<float, 8>>& p, int a, int b) {
  std::vector<std::pair<float, float>> out;
  for (const auto& x : p) out.emplace_back(x[a], x[b]);
  return out;
}

}  // namespace

// Every power-of-two prefix of a pixel's points is stratified: each pair of
// dimensions is a (0, m, 2)-net, but dimensions 2-3 (Sobol's third and
// fourth, t = 1), and the first four dimensions are stratified jointly (the
// pixel jitter against the first bounce: t <= 2 in every cross projection),
// which independently shuffled pairs would not be.
TEST(Sampler, SobolPrefixesAreStratified) {
  const int m = 8, n = 1 << m;
  for (std::uint32_t pixel : {0u, 77u, 262143u}) {
    const auto p = points(pixel, n);
    EXPECT_EQ(net_t(project(p, 0, 1), m), 0) << pixel;
    EXPECT_LE(net_t(project(p, 2, 3), m), 1) << pixel;
    EXPECT_EQ(net_t(project(p, 4, 5), m), 0) << pixel;
    EXPECT_EQ(net_t(project(p, 6, 7), m), 0) << pixel;
    // Cross projections of the 4D point: t of Sobol's 2D projections
    // (Joe and Kuo chose the direction numbers to keep these small).
    for (int a = 0; a < 2; ++a)
      for (int b = 2; b < 4; ++b) EXPECT_LE(net_t(project(p, a, b), m), 2) << a << "," << b;
    // Padded pairs are shuffled against each other: no such structure
    // (a random 2D set of 256 points has t near m).
    EXPECT_GE(net_t(project(p, 0, 4), m), 3) << pixel;
  }
}

TEST(Sampler, PairsAreDecorrelated) {
  // Without the per-pair shuffle, pair 0 and pair 1 would be the same points
  // up to scrambling; their first coordinates would be strongly dependent.
  // Check the correlation of u(pair 0) and u(pair 1) over 4096 samples.
  const int n = 4096;
  double su = 0, sv = 0, suv = 0, suu = 0, svv = 0;
  for (int i = 0; i < n; ++i) {
    Sampler s(SamplerKind::Sobol, 5, std::uint64_t(i), 1);
    float u0, v0, u1, v1;
    s.get2d(u0, v0);
    s.get2d(u1, v1);
    su += u0; sv += u1; suv += double(u0) * u1; suu += double(u0) * u0; svv += double(u1) * u1;
  }
  const double cov = suv / n - su / n * sv / n;
  const double corr = cov / std::sqrt((suu / n - su * su / n / n) * (svv / n - sv * sv / n / n));
  EXPECT_LT(std::fabs(corr), 0.05);
}

TEST(Sampler, IndependentUniformsHaveTheRightMoments) {
  double s1 = 0, s2 = 0;
  const int n = 1 << 18;
  for (int i = 0; i < n; ++i) {
    Sampler s(SamplerKind::Independent, std::uint32_t(i % 512), std::uint64_t(i / 512), 3);
    const float u = s.get1d();
    ASSERT_GE(u, 0.0f);
    ASSERT_LT(u, 1.0f);
    s1 += u;
    s2 += double(u) * u;
  }
  EXPECT_NEAR(s1 / n, 0.5, 5 * std::sqrt(1.0 / 12 / n));
  EXPECT_NEAR(s2 / n, 1.0 / 3, 5 * std::sqrt(4.0 / 45 / n));
}

TEST(Sampler, SameInputsSameNumbers) {
  for (auto kind : {SamplerKind::Independent, SamplerKind::Sobol}) {
    Sampler a(kind, 10, 20, 30), b(kind, 10, 20, 30), c(kind, 10, 21, 30);
    float a1, a2, b1, b2, c1, c2;
    a.get2d(a1, a2);
    b.get2d(b1, b2);
    c.get2d(c1, c2);
    EXPECT_EQ(a1, b1);
    EXPECT_EQ(a2, b2);
    EXPECT_NE(a1, c1);
  }
}

// Splitting: the `count` branches of one Sobol sample are an aligned block of
// the sequence, so for count = 4 each coordinate of their next 2D request
// (the first bounce here, then a padded pair) falls once in each quarter of
// [0, 1); the branches of an independent sample differ.
TEST(Sampler, SobolBranchesAreStratifiedAmongThemselves) {
  for (std::uint32_t pixel : {0u, 7u, 1234u}) {
    for (std::uint64_t i = 0; i < 64; ++i) {
      for (int request = 1; request <= 2; ++request) {
        Sampler s(SamplerKind::Sobol, pixel, i, 11);
        float jx, jy;
        s.get2d(jx, jy);  // the pixel jitter, shared by the branches
        int seen_u = 0, seen_v = 0;
        for (std::uint32_t k = 0; k < 4; ++k) {
          Sampler b = s.branch(k, 4);
          float u, v;
          b.get2d(u, v);
          if (request == 2) b.get2d(u, v);
          seen_u |= 1 << int(u * 4.0f);
          seen_v |= 1 << int(v * 4.0f);
        }
        ASSERT_EQ(seen_u, 15) << "pixel " << pixel << " sample " << i << " request " << request;
        ASSERT_EQ(seen_v, 15) << "pixel " << pixel << " sample " << i << " request " << request;
      }
    }
  }
}

TEST(Sampler, IndependentBranchesDiffer) {
  Sampler s(SamplerKind::Independent, 3, 4, 5);
  std::vector<float> first;
  for (std::uint32_t k = 0; k < 8; ++k) first.push_back(s.branch(k, 8).get1d());
  std::sort(first.begin(), first.end());
  EXPECT_EQ(std::adjacent_find(first.begin(), first.end()), first.end());
}

namespace {

// A Sobol sampler's first `n` 2D requests, for comparing streams.
std::vector<float> draws(Sampler s, int n = 3) {
  std::vector<float> out;
  for (int d = 0; d < n; ++d) {
    float u, v;
    s.get2d(u, v);
    out.push_back(u);
    out.push_back(v);
  }
  return out;
}

}  // namespace

// Indices below 2^32 keep the points they had before the index became 64
// bits (values from that version), so the images of such ranges are the same
// bit for bit: a sample, and a split path's branch at index 2^32 - 1.
TEST(Sampler, SobolIndicesBelow2To32KeepTheirPoints) {
  EXPECT_EQ(draws(Sampler(SamplerKind::Sobol, 77, 1000, 9)),
            (std::vector<float>{0x1.fdcd76p-1f, 0x1.4a271ap-1f, 0x1.a7d64p-1f, 0x1.9bd0fp-4f,
                                0x1.2471bp-2f, 0x1.e642acp-1f}));
  const Sampler s(SamplerKind::Sobol, 77, (1u << 20) - 1, 9);
  const std::vector<float> last{0x1.e95ca8p-2f, 0x1.cf4c2p-1f, 0x1.a3d38p-6f,
                                0x1.e7cfp-6f,   0x1.21e76cp-2f, 0x1.f7b91ep-1f};
  EXPECT_EQ(draws(Sampler(s).branch(63, 64).branch(63, 64)), last);
  EXPECT_EQ(draws(Sampler(SamplerKind::Sobol, 77, 0xffffffffull, 9)), last);
}

// The red team's case: with 64 x 64 branches, sample 2^26's branches have
// indices 2^32 + k and 2^38 + k, which in 32 bits were sample 0's. Branch
// indices past 2^32 and 2^40 (sample 2^28 through 64 x 64) must differ from
// those below, and be the same index space as a sample's own index.
TEST(Sampler, SobolBranchesPast2To32And2To40Differ) {
  for (std::uint32_t pixel : {0u, 77u}) {
    for (std::uint64_t t = 0; t < 4; ++t) {
      const Sampler low(SamplerKind::Sobol, pixel, t, 9);
      for (std::uint64_t high : {(1ull << 26) + t, (1ull << 28) + t}) {
        const Sampler s(SamplerKind::Sobol, pixel, high, 9);
        for (std::uint32_t k = 0; k < 64; k += 7) {
          Sampler a = Sampler(s).branch(k, 64), b = Sampler(low).branch(k, 64);
          EXPECT_NE(draws(a), draws(b)) << "sample " << high << " branch " << k;
          EXPECT_EQ(draws(a), draws(Sampler(SamplerKind::Sobol, pixel, high * 64 + k, 9)));
          const Sampler aa = a.branch(63 - k, 64), bb = b.branch(63 - k, 64);
          EXPECT_NE(draws(aa), draws(bb)) << "sample " << high << " branches " << k << ", " << 63 - k;
          const std::uint64_t index = (high * 64 + k) * 64 + 63 - k;
          EXPECT_EQ(draws(aa), draws(Sampler(SamplerKind::Sobol, pixel, index, 9)));
        }
      }
    }
  }
}

// Every block of 2^32 indices has its own scramble: the first 2D points of
// indices t, 2^32 + t, 2^33 + t and 2^40 + t (a 32-bit index: all one) are
// all distinct, and so are those of consecutive indices across a block's end.
TEST(Sampler, SobolIndicesInDifferentBlocksGiveDistinctPoints) {
  std::set<std::pair<float, float>> seen;
  int n = 0;
  for (std::uint64_t base : {0ull, 1ull << 32, 1ull << 33, 1ull << 40, (1ull << 36) - 2048}) {
    for (std::uint64_t t = 0; t < 4096; ++t, ++n) {
      Sampler s(SamplerKind::Sobol, 5, base + t, 3);
      float u, v;
      s.get2d(u, v);
      seen.insert({u, v});
    }
  }
  EXPECT_EQ(seen.size(), std::size_t(n));
}

// Past 2^32 the 64 branches of a sample are still an aligned block of one
// scramble: their 4D points' first pair is a (0, 6, 2)-net, the second (after
// the jitter, Sobol's third and fourth dimensions) a (1, 6, 2)-net.
TEST(Sampler, SobolBranchesPast2To32AreStratified) {
  for (std::uint64_t i : {(1ull << 26), (1ull << 26) + 3, (1ull << 28) + 1, (1ull << 30) - 1}) {
    for (int request = 1; request <= 2; ++request) {
      Sampler s(SamplerKind::Sobol, 1234, i, 11);
      float u, v;
      if (request == 2) s.get2d(u, v);  // the pixel jitter, shared by the branches
      std::vector<std::pair<float, float>> pts;
      for (std::uint32_t k = 0; k < 64; ++k) {
        Sampler b = s.branch(k, 64);
        b.get2d(u, v);
        pts.emplace_back(u, v);
      }
      EXPECT_LE(net_t(pts, 6), request - 1) << "sample " << i << " request " << request;
    }
  }
}
