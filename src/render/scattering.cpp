#include "render/scattering.h"

namespace whisker {

bool refract(const vec3& d, const vec3& n, float eta, vec3& out) {
  // Snell-Descartes (report section 2): tangential part scales by eta.
  const float cos_i = -glm::dot(n, d);
  const float k = 1.0f - eta * eta * (1.0f - cos_i * cos_i);
  if (k < 0.0f) return false;
  out = glm::normalize(eta * d + (eta * cos_i - std::sqrt(k)) * n);
  return true;
}

}  // namespace whisker
