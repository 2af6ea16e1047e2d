#include "render/sampler.h"

namespace whisker {

namespace {

std::uint32_t reverse_bits(std::uint32_t x) {
  x = (x << 16) | (x >> 16);
  x = ((x & 0x00ff00ffu) << 8) | ((x & 0xff00ff00u) >> 8);
  x = ((x & 0x0f0f0f0fu) << 4) | ((x & 0xf0f0f0f0u) >> 4);
  x = ((x & 0x33333333u) << 2) | ((x & 0xccccccccu) >> 2);
  return ((x & 0x55555555u) << 1) | ((x & 0xaaaaaaaau) >> 1);
}

std::uint32_t hash32(std::uint32_t a, std::uint32_t b) {
  return std::uint32_t(mix64((std::uint64_t(a) << 32) | b));
}

// Sobol's second dimension: generator columns v_k for the primitive
// polynomial x + 1 (m_1 = 1), v_1 = 2^31, v_k = v_{k-1} ^ (v_{k-1} >> 1),
// folded into one table per index byte: four lookups instead of a 32-step
// loop (shuffled indices use all 32 bits).
struct SobolDim1 {
  std::uint32_t byte[4][256];
  constexpr SobolDim1() : byte() {
    std::uint32_t v[32] = {};
    v[0] = 0x80000000u;
    for (int k = 1; k < 32; ++k) v[k] = v[k - 1] ^ (v[k - 1] >> 1);
    for (int b = 0; b < 4; ++b)
      for (int x = 0; x < 256; ++x)
        for (int k = 0; k < 8; ++k)
          if (x >> k & 1) byte[b][x] ^= v[8 * b + k];
  }
};
constexpr SobolDim1 kDim1;

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

std::uint32_t sobol_dim1(std::uint32_t index) {
  return kDim1.byte[0][index & 255] ^ kDim1.byte[1][index >> 8 & 255] ^
         kDim1.byte[2][index >> 16 & 255] ^ kDim1.byte[3][index >> 24];
}

void Sampler::sobol2d(float& u, float& v) {
  const std::uint32_t pair_key = hash32(key_, dim_++);
  // Shuffle the order of the points (Burley section 4): i = owen(index)...
  const std::uint32_t i = reverse_bits(laine_karras(reversed_index_, pair_key));
  // ...then scramble each coordinate with its own seed. Dimension 0 is the
  // bit-reversed index, so owen(reverse(i)) = reverse(lk(i)).
  const std::uint32_t x = reverse_bits(laine_karras(i, hash32(pair_key, 1)));
  const std::uint32_t y = owen_scramble(sobol_dim1(i), hash32(pair_key, 2));
  // Top 24 bits: in [0, 1), never 1.
  u = float(x >> 8) * 0x1p-24f;
  v = float(y >> 8) * 0x1p-24f;
}

std::uint32_t Sampler::reverse(std::uint32_t x) { return reverse_bits(x); }

}  // namespace whisker
