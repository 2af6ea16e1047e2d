// Random numbers that depend only on (pixel, sample index, seed), so an image
// is the same whatever the thread count or tile order.
#pragma once

#include <cstdint>

#include "scene/scene.h"

namespace whisker {

// SplitMix64 output function (Steele, Lea, Flood, "Fast splittable
// pseudorandom number generators", OOPSLA 2014): a bijective 64-bit mix.
inline std::uint64_t mix64(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

// One sample's stream of independent uniforms: a SplitMix64 sequence whose
// start is a hash of the pixel, the sample index and the seed.
class Rng {
 public:
  Rng() = default;
  Rng(std::uint32_t pixel, std::uint64_t sample, std::uint64_t seed)
      : state_(mix64(mix64(mix64(seed ^ 0x5157A3C4B2A1ull) + pixel) + sample)) {}

  std::uint64_t next_u64() {
    state_ += 0x9E3779B97F4A7C15ull;
    return mix64(state_);
  }
  // Uniform in [0, 1): the top 24 bits, so 1 is never returned.
  float uniform() { return float(next_u64() >> 40) * 0x1p-24f; }

 private:
  std::uint64_t state_ = 0;
};

// Owen-scrambled Sobol points (Burley, "Practical Hash-based Owen
// Scrambling", JCGT 2020). The first two 2D requests (pixel jitter and the
// first bounce) are the four dimensions of one Sobol point, stratified
// jointly; later requests take padded pairs, the 2D (0,2)-sequence with the
// sample order shuffled per pair (Burley section 4). Every coordinate is
// scrambled with its own per-pixel seed. A 1D request takes a pair's first
// coordinate.
//
// The generator matrices have 32 columns, so the sequence has 2^32 points:
// a 64-bit sample index takes point (index mod 2^32) of the sequence, and
// its high 32 bits (the block) pick the scramble: the pixel's key XOR a
// bijection of the block that keeps block 0's key, so indices below 2^32
// give the points they always did, and each later block of 2^32 is the
// whole sequence again under a scramble of its own. Within a block distinct
// indices give distinct points (the index shuffle is a bijection); blocks
// are independent randomizations of the same sequence.
std::uint32_t owen_scramble(std::uint32_t v, std::uint32_t seed);
std::uint32_t sobol_dim1(std::uint32_t index);

// How many pixels' scrambling seeds a thread keeps (sampler.cpp): as many as
// the paths traced side by side (integrator.h, kLanes).
inline constexpr std::uint32_t kSeedSlots = 8;

// What the estimator draws its numbers from: independent uniforms (the
// report's method) or the scrambled Sobol points.
class Sampler {
 public:
  Sampler() = default;  // a placeholder, to be assigned a real one
  Sampler(SamplerKind kind, std::uint32_t pixel, std::uint64_t sample, std::uint64_t seed);

  float get1d() {
    if (kind_ == SamplerKind::Independent) return rng_.uniform();
    float u, v;
    sobol2d(u, v);
    return u;
  }
  void get2d(float& u, float& v) {
    if (kind_ == SamplerKind::Independent) {
      u = rng_.uniform();
      v = rng_.uniform();
      return;
    }
    sobol2d(u, v);
  }

  // Branch k of `count` taken from here on (splitting): the same dimension,
  // with its own numbers. Sobol: sample index i becomes i*count + k (64-bit),
  // so the `count` branches of one sample are one aligned block of the
  // sequence and stratified among themselves. The index must stay below
  // 2^64: a sample below 2^30 (the --samples limit) through at most
  // kMaxSplitPaths branches (settings.h) stays below 2^42.
  Sampler branch(std::uint32_t k, std::uint32_t count);

 private:
  void sobol2d(float& u, float& v);

  SamplerKind kind_ = SamplerKind::Independent;
  std::uint8_t slot_ = 0;  // Sobol only: which of the thread's cached pixel seeds (sampler.cpp)
  Rng rng_;                           // Independent only
  std::uint32_t reversed_index_ = 0;  // Sobol only: the index's low 32 bits, reversed
  std::uint32_t block_ = 0;           // Sobol only: the index's high 32 bits
  std::uint32_t key_ = 0;             // Sobol only: the pixel's and block's scrambling seed
  std::uint32_t dim_ = 0;  // dimension pair counter
};

}  // namespace whisker
