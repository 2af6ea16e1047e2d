// The parts of the 8-wide tree's traversal (bvh_wide.cpp) that are not
// vector code: the slab test's margin, the stack and the node references.
#pragma once

#include <cmath>
#include <cstdint>

#include "geometry/bvh_wide.h"

namespace whisker::wide_parts {

// Robust slab test (Ize, "Robust BVH Ray Traversal", JCGT 2013): the far
// distance grows by 1 + 2 gamma(3), gamma(n) = n u / (1 - n u), to cover the
// three roundings of (b - o) * (1 / d), so a ray through a shared edge is
// never culled by both boxes.
constexpr float kFarScale = 1.0f + 2.0f * (3.0f * 0x1p-24f) / (1.0f - 3.0f * 0x1p-24f);

// 1/d with zero components replaced by a tiny signed value: (b - o) * (1/d)
// stays finite (no 0 * inf), and the sign picks the near plane.
inline float safe_inv(float d) {
  const float tiny = 1e-30f;
  if (std::fabs(d) < tiny) d = std::copysign(tiny, d);
  return 1.0f / d;
}

constexpr int kStackSize = 512;  // 7 entries per level, depth <= 72 (bvh_build.cpp)

struct StackEntry {
  std::uint32_t ref;
  float t;
};

inline bool is_leaf(std::uint32_t ref) { return (ref & kLeafBit) != 0; }
inline std::uint32_t leaf_first(std::uint32_t ref) { return ref & 0xffffffu; }
inline std::uint32_t leaf_packets(std::uint32_t ref) { return ((ref >> 24) & 0x7fu) + 1; }

}  // namespace whisker::wide_parts
