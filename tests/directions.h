// Test helper: random unit directions, uniform over the sphere.
#pragma once

#include <random>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace whisker {

inline glm::vec3 random_direction(std::mt19937& g) {
  std::normal_distribution<float> n;
  const glm::vec3 v(n(g), n(g), n(g));
  return glm::normalize(v);
}

}  // namespace whisker
