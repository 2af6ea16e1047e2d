#include "render/sampler.h"

#include <cassert>

#ifdef __GFNI__
#include <immintrin.h>
#endif

namespace whisker {

namespace {

std::uint32_t reverse_bits(std::uint32_t x) {
#ifdef __GFNI__
  // The affine transform with matrix 0x8040201008040201 reverses the bits of
  // each byte (Intel SDM, GF2P8AFFINEQB); a byte swap finishes the job.
  const __m128i v = _mm_gf2p8affine_epi64_epi8(_mm_cvtsi32_si128(int(x)),
                                               _mm_set1_epi64x(0x8040201008040201ll), 0);
  return __builtin_bswap32(std::uint32_t(_mm_cvtsi128_si32(v)));
#else
  x = (x << 16) | (x >> 16);
  x = ((x & 0x00ff00ffu) << 8) | ((x & 0xff00ff00u) >> 8);
  x = ((x & 0x0f0f0f0fu) << 4) | ((x & 0xf0f0f0f0u) >> 4);
  x = ((x & 0x33333333u) << 2) | ((x & 0xccccccccu) >> 2);
  return ((x & 0x55555555u) << 1) | ((x & 0xaaaaaaaau) >> 1);
#endif
}

std::uint32_t hash32(std::uint32_t a, std::uint32_t b) {
  return std::uint32_t(mix64((std::uint64_t(a) << 32) | b));
}

// What a Sobol index's block (its high 32 bits) XORs into the pixel's key:
// MurmurHash3's finalizer fmix32 (Appleby, 2011), a bijection (xor-shifts
// and odd multipliers invert) with fmix32(0) = 0, so distinct blocks give a
// pixel distinct keys and block 0 keeps the key it had.
std::uint32_t block_key(std::uint32_t block) {
  block ^= block >> 16;
  block *= 0x85ebca6bu;
  block ^= block >> 13;
  block *= 0xc2b2ae35u;
  return block ^ (block >> 16);
}

// A Sobol dimension's generator matrix from its primitive polynomial (degree
// deg, inner coefficients a) and initial direction numbers m_1..m_deg:
// v_k = m_k 2^(32-k) for k <= deg, then Bratley and Fox's recurrence
// v_k = a_1 v_(k-1) ^ ... ^ a_(deg-1) v_(k-deg+1) ^ v_(k-deg) ^ (v_(k-deg) >> deg).
// Direction numbers from Joe and Kuo, "Constructing Sobol sequences with
// better two-dimensional projections", SIAM J. Sci. Comput. 2008 (their
// dimensions 2 to 4). Folded into one table per index byte: four lookups
// instead of a 32-step loop (shuffled indices use all 32 bits).
struct SobolMatrix {
  std::uint32_t byte[4][256];
  constexpr SobolMatrix(int deg, std::uint32_t a, const std::uint32_t (&m)[3]) : byte() {
    std::uint32_t v[32] = {};
    for (int k = 0; k < 32; ++k) {
      if (k < deg) {
        v[k] = m[k] << (31 - k);
        continue;
      }
      v[k] = v[k - deg] ^ (v[k - deg] >> deg);
      for (int j = 1; j < deg; ++j)
        if (a >> (deg - 1 - j) & 1u) v[k] ^= v[k - j];
    }
    for (int b = 0; b < 4; ++b)
      for (int x = 0; x < 256; ++x)
        for (int k = 0; k < 8; ++k)
          if (x >> k & 1) byte[b][x] ^= v[8 * b + k];
  }
  // The same matrix with its outputs bit-reversed (reversal is linear, so
  // it applies entry by entry): owen_scramble reverses the point first.
  constexpr SobolMatrix reversed() const {
    SobolMatrix r = *this;
    for (auto& row : r.byte)
      for (auto& e : row) {
        std::uint32_t y = 0;
        for (int k = 0; k < 32; ++k) y |= (e >> k & 1u) << (31 - k);
        e = y;
      }
    return r;
  }
  constexpr std::uint32_t operator()(std::uint32_t i) const {
    return byte[0][i & 255] ^ byte[1][i >> 8 & 255] ^ byte[2][i >> 16 & 255] ^ byte[3][i >> 24];
  }
};
constexpr std::uint32_t kM1[3] = {1, 0, 0}, kM2[3] = {1, 3, 0}, kM3[3] = {1, 3, 1};
constexpr SobolMatrix kDim1(1, 0, kM1);  // x + 1
constexpr SobolMatrix kDim2(2, 1, kM2);  // x^2 + x + 1
constexpr SobolMatrix kDim3(3, 1, kM3);  // x^3 + x + 1
constexpr SobolMatrix kDim1R = kDim1.reversed(), kDim2R = kDim2.reversed(),
                      kDim3R = kDim3.reversed();

// Laine-Karras style hash that permutes bits only towards higher ones,
// with Burley's constants (JCGT 2020, listing 2): applied to reversed bits it
// is a nested uniform (Owen) scramble.
std::uint32_t laine_karras(std::uint32_t x, std::uint32_t seed) {
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return x;
}

}  // namespace

std::uint32_t owen_scramble(std::uint32_t v, std::uint32_t seed) {
  return reverse_bits(laine_karras(reverse_bits(v), seed));
}

namespace {
// owen_scramble(m(i), seed) with the reversal of m folded into its table.
std::uint32_t owen_scramble_reversed(std::uint32_t reversed_v, std::uint32_t seed) {
  return reverse_bits(laine_karras(reversed_v, seed));
}
}  // namespace

std::uint32_t sobol_dim1(std::uint32_t index) { return kDim1(index); }

// Each kind sets up only what it draws from.
Sampler::Sampler(SamplerKind kind, std::uint32_t pixel, std::uint64_t sample, std::uint64_t seed)
    : kind_(kind) {
  if (kind == SamplerKind::Independent) {
    rng_ = Rng(pixel, sample, seed);
  } else {
    reversed_index_ = reverse_bits(std::uint32_t(sample));
    block_ = std::uint32_t(sample >> 32);
    key_ = std::uint32_t(mix64(seed * 0x9E3779B97F4A7C15ull + pixel)) ^ block_key(block_);
    slot_ = std::uint8_t(pixel % kSeedSlots);
  }
}

// A sample index below 2^30 (the --samples limit) through branches whose
// counts multiply to at most kMaxSplitPaths stays below 2^64: no range that
// --samples accepts wraps.
static_assert(kMaxSplitPaths <= (1ll << 34));

Sampler Sampler::branch(std::uint32_t k, std::uint32_t count) {
  Sampler b = *this;
  if (kind_ == SamplerKind::Independent) {
    b.rng_ = Rng(k, rng_.next_u64(), 0);
  } else {
    const std::uint64_t index = std::uint64_t(block_) << 32 | reverse_bits(reversed_index_);
    assert(count > 0 && index <= (~std::uint64_t(0) - k) / count);
    const std::uint64_t i = index * count + k;
    b.reversed_index_ = reverse_bits(std::uint32_t(i));
    b.block_ = std::uint32_t(i >> 32);
    // Past block 0 the key changes with the block (the pixel's key, XOR
    // undone and redone); within block 0, the render's usual case, it stays.
    if ((block_ | b.block_) != 0) [[unlikely]]
      b.key_ = key_ ^ block_key(block_) ^ block_key(b.block_);
  }
  return b;
}

namespace {

// The scrambling seeds depend only on the pixel's key and the dimension, not
// on the sample: one pixel's samples (consecutive in a tile) share them. Each
// thread keeps the seeds of the last pixels, one per slot (the pixel's index
// mod kSeedSlots, so the paths of up to kSeedSlots consecutive pixels traced
// side by side each keep theirs), and the hashes run once per pixel instead
// of three times per 2D request. A pair's seeds are hashed when a path
// first asks for it: a pass of one sample per pixel pays for the pairs its
// paths use, not for all of them.
constexpr std::uint32_t kCachedPairs = 16;
struct PixelSeeds {
  std::uint32_t key = 0;
  bool valid = false;
  std::uint32_t hashed = 0;             // bit d: pair[d] holds pair d's seeds
  std::uint32_t first[4];              // dimensions 0-3 (the 4D point)
  std::uint32_t pair[kCachedPairs][3];  // padded pair d >= 2: shuffle, x, y (0, 1 unused)
};

void pair_seeds(std::uint32_t key, std::uint32_t dim, std::uint32_t out[3]) {
  out[0] = hash32(key, dim);
  out[1] = hash32(out[0], 1);
  out[2] = hash32(out[0], 2);
}

PixelSeeds& pixel_seeds(std::uint32_t key, std::uint32_t slot) {
  thread_local PixelSeeds slots[kSeedSlots];
  PixelSeeds& cache = slots[slot];
  if (cache.valid && cache.key == key) return cache;
  cache.key = key;
  cache.valid = true;
  cache.hashed = 0;
  for (std::uint32_t k = 0; k < 4; ++k) cache.first[k] = hash32(key, 0xd0 + k);
  return cache;
}

}  // namespace

void Sampler::sobol2d(float& u, float& v) {
  PixelSeeds& seeds = pixel_seeds(key_, slot_);
  if (dim_ < 2) {
    // The first four dimensions (pixel jitter and the first bounce, or the
    // first Fresnel choice) are one 4D Sobol point: the index is shuffled
    // once per pixel, so the four stay jointly stratified; each coordinate
    // is Owen-scrambled with its own seed.
    const std::uint32_t i = reverse_bits(laine_karras(reversed_index_, key_));
    std::uint32_t x, y;
    if (dim_ == 0) {
      x = reverse_bits(laine_karras(i, seeds.first[0]));
      y = owen_scramble_reversed(kDim1R(i), seeds.first[1]);
    } else {
      x = owen_scramble_reversed(kDim2R(i), seeds.first[2]);
      y = owen_scramble_reversed(kDim3R(i), seeds.first[3]);
    }
    ++dim_;
    u = float(x >> 8) * 0x1p-24f;
    v = float(y >> 8) * 0x1p-24f;
    return;
  }
  std::uint32_t computed[3];
  const std::uint32_t* pair = computed;
  if (dim_ >= kCachedPairs) {
    pair_seeds(key_, dim_, computed);
  } else {
    if (!(seeds.hashed >> dim_ & 1u)) pair_seeds(key_, dim_, seeds.pair[dim_]);
    seeds.hashed |= 1u << dim_;
    pair = seeds.pair[dim_];
  }
  ++dim_;
  // Shuffle the order of the points (Burley section 4): i = owen(index)...
  const std::uint32_t i = reverse_bits(laine_karras(reversed_index_, pair[0]));
  // ...then scramble each coordinate with its own seed. Dimension 0 is the
  // bit-reversed index, so owen(reverse(i)) = reverse(lk(i)).
  const std::uint32_t x = reverse_bits(laine_karras(i, pair[1]));
  const std::uint32_t y = owen_scramble_reversed(kDim1R(i), pair[2]);
  // Top 24 bits: in [0, 1), never 1.
  u = float(x >> 8) * 0x1p-24f;
  v = float(y >> 8) * 0x1p-24f;
}

}  // namespace whisker
