// Test helper: two vectors of sums equal bit for bit (what the exactness
// claims of merges, resumes and the accumulation files are about; == would
// take -0.0 for 0.0 and never a NaN for itself).
#pragma once

#include <cstring>
#include <vector>

namespace whisker {

inline bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  // memcmp must not see the null data() of an empty vector, even for 0 bytes (C17 7.24.1).
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

}  // namespace whisker
