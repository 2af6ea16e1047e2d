// Rays and hit records: the plain data every intersector shares.
#pragma once

#include <cstdint>
#include <limits>

#include <glm/vec3.hpp>

namespace whisker {

using glm::vec3;

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr std::uint32_t kNoSkip = 0xffffffffu;

struct Ray {
  vec3 o{0.0f};
  vec3 d{0.0f, 0.0f, -1.0f};  // unit length
  float tmin = 0.0f;
  float tmax = kInf;
  // A sphere the ray leaves (its index, kNoSkip for none): spawned on it with
  // no offset, the ray ignores it when leaving it outwards (a sphere is
  // convex) and takes only its far root when entering it (the near root is
  // the origin itself). Exact at every scale, where an offset is not.
  std::uint32_t skip = kNoSkip;
  bool far_only = false;
  // The origin's rounding residual: the exact origin is o + o_lo (a hit
  // point refined in double keeps its low part). The double-precision sphere
  // solutions start from there, so a ray leaving a sphere finds a surface a
  // float ULP away on the right side (a hollow shell 1e-6 thick at 50).
  vec3 o_lo{0.0f};
};

// False for a ray with a NaN in its origin, direction or bounds: it meets
// nothing, and a slab test must not see it (there a NaN distance drops out
// of max/min, which return their other operand, so the ray enters every
// child, unused slots too: a read far outside a tree).
inline bool traceable(const Ray& r) {
  const float v[8] = {r.o.x, r.o.y, r.o.z, r.d.x, r.d.y, r.d.z, r.tmin, r.tmax};
  bool ok = true;
  for (const float x : v) ok &= x == x;  // false for NaN only
  return ok;
}

// Which kind of primitive a hit belongs to.
enum class PrimKind : std::uint8_t { None, Sphere, Triangle };

struct Hit {
  float t = kInf;
  PrimKind kind = PrimKind::None;
  std::uint32_t prim = 0;  // sphere index or triangle index
  float u = 0.0f, v = 0.0f;  // barycentrics for triangles
  std::uint32_t instance = kNoSkip;  // a triangle's mesh instance (ObjectBvh), kNoSkip: none
  bool valid() const { return kind != PrimKind::None; }
};

}  // namespace whisker
