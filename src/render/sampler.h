// Random numbers that depend only on (pixel, sample index, seed), so an image
// is the same whatever the thread count or tile order.
#pragma once

#include <cstdint>

namespace whisker {

// SplitMix64 output function (Steele, Lea, Flood, "Fast splittable
// pseudorandom number generators", OOPSLA 2014): a bijective 64-bit mix.
inline std::uint64_t mix64(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

// One sample's stream: a SplitMix64 sequence whose start is a hash of the
// pixel, the sample index and the seed.
class Rng {
 public:
  Rng(std::uint32_t pixel, std::uint64_t sample, std::uint64_t seed)
      : state_(mix64(mix64(mix64(seed ^ 0x5157A3C4B2A1ull) + pixel) + sample)) {}

  std::uint64_t next_u64() {
    state_ += 0x9E3779B97F4A7C15ull;
    return mix64(state_);
  }
  // Uniform in [0, 1): the top 24 bits, so 1 is never returned.
  float uniform() { return float(next_u64() >> 40) * 0x1p-24f; }

 private:
  std::uint64_t state_;
};

}  // namespace whisker
