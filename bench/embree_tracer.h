// Embree 3 behind a small opaque interface, for the comparison only.
#pragma once

#include <vector>

#include "geometry/ray.h"
#include "geometry/triangle.h"

namespace whisker::bench {

struct EmbreeScene;
// Builds with RTC_BUILD_QUALITY_HIGH (Embree's best tree for tracing).
EmbreeScene* embree_build(const std::vector<Triangle>& tris, double& build_seconds);
// rtcIntersect1 closest hit; t is the hit distance.
bool embree_intersect(const EmbreeScene* s, const Ray& ray, float& t);
void embree_release(EmbreeScene* s);

}  // namespace whisker::bench
