// Test helper: a reproducible stream of doubles in [0, 1) for synthetic
// data, xorshift64* (Marsaglia, "Xorshift RNGs", 2003; the multiplier of
// Vigna's xorshift64*).
#pragma once

#include <cstdint>

namespace whisker {

class TestRandom {
 public:
  explicit TestRandom(unsigned seed) : x_(0x9e3779b97f4a7c15ull * (seed + 1)) {}
  double next() {
    x_ ^= x_ >> 12, x_ ^= x_ << 25, x_ ^= x_ >> 27;
    return double((x_ * 0x2545f4914f6cdd1dull) >> 11) * 0x1p-53;
  }

 private:
  std::uint64_t x_;
};

}  // namespace whisker
