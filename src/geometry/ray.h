// Rays and hit records: the plain data every intersector shares.
#pragma once

#include <cstdint>
#include <limits>

#include <glm/vec3.hpp>

namespace whisker {

using glm::vec3;

constexpr float kInf = std::numeric_limits<float>::infinity();

struct Ray {
  vec3 o{0.0f};
  vec3 d{0.0f, 0.0f, -1.0f};  // unit length
  float tmin = 0.0f;
  float tmax = kInf;
};

// Which kind of primitive a hit belongs to.
enum class PrimKind : std::uint8_t { None, Sphere, Triangle };

struct Hit {
  float t = kInf;
  PrimKind kind = PrimKind::None;
  std::uint32_t prim = 0;  // sphere index or triangle index
  float u = 0.0f, v = 0.0f;  // barycentrics for triangles
  bool valid() const { return kind != PrimKind::None; }
};

}  // namespace whisker
