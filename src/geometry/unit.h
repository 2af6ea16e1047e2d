// Unit vectors of any length. glm::normalize squares its argument in float:
// a vector 1e-23 long underflows to a zero length (NaN), one 1e20 long
// overflows (zero). Scaled first by the power of two that puts its largest
// component in [1, 2) - exact, and no bit of an ordinary vector's normalised
// result changes - every finite nonzero vector has a direction.
#pragma once

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace whisker {

// v times the power of two that puts its largest component in [1, 2); v
// itself when it is zero or not finite.
inline glm::vec3 pow2_scaled(glm::vec3 v) {
  const float m = std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
  if (!(m > 0.0f) || !std::isfinite(m)) return v;
  const int e = -std::ilogb(m);
  return glm::vec3(std::ldexp(v.x, e), std::ldexp(v.y, e), std::ldexp(v.z, e));
}

// The unit vector along v at any finite length; zero for a zero or
// non-finite v (no direction).
inline glm::vec3 unit_or_zero(glm::vec3 v) {
  const float m = std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
  if (!(m > 0.0f) || !std::isfinite(m)) return glm::vec3(0.0f);
  return glm::normalize(pow2_scaled(v));
}

}  // namespace whisker
