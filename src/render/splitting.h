// Splitting: at the d-th diffuse hit of a path, RenderSettings::split[d]
// indirect continuations leave and their light is averaged (each is an
// unbiased estimate of the same integral, so their mean is too, with less
// variance), the count weighted by the colour channels the path still carries.
#pragma once

#include <algorithm>
#include <cstddef>

#include "scene/scene.h"

namespace whisker {

// The split factor for a path whose throughput is beta (see
// RenderSettings::split_weights): round(split * the largest weight of a
// channel beta still carries), at least 1.
inline int weighted_split(int split, const vec3& beta, const vec3& weights) {
  float w = 0.0f;
  for (int c = 0; c < 3; ++c)
    if (beta[c] != 0.0f) w = std::max(w, weights[c]);
  return std::max(1, int(float(split) * w + 0.5f));
}

// The number of continuations at a path's diffuse hit number `diffuse_hits`
// (0: the first), given its throughput beta.
inline int split_factor(const RenderSettings& settings, int diffuse_hits, const vec3& beta) {
  const std::size_t d = std::size_t(diffuse_hits);
  return weighted_split(d < settings.split.size() ? settings.split[d] : 1, beta,
                        settings.split_weights);
}

}  // namespace whisker
