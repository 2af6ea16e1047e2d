// How the triangle BVH is built (see bvh.h): every triangle tested (Brute),
// the same behind one bounding box (BBox), or a binary tree, split by the
// report's longest-axis barycentre rule (Midpoint) or by binned SAH (Sah),
// collapsed to 8-wide. Scene files and --accel name it (RenderSettings::accel).
#pragma once

#include <cstdint>

namespace whisker {

enum class BvhMethod : std::uint8_t { Brute, BBox, Midpoint, Sah };

}  // namespace whisker
