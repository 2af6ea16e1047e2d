// Binary BVH builders: binned SAH and the report's longest-axis barycentre
// split. Their output is collapsed into the 8-wide tree that is traversed.
#pragma once

#include <cstdint>
#include <vector>

#include "geometry/bvh_wide.h"
#include "geometry/triangle.h"

namespace whisker {

struct BinaryNode {
  Box3 box;
  // Inner: children left/right. Leaf (count > 0): prims[first, first+count).
  std::uint32_t left = 0, right = 0;
  std::uint32_t first = 0, count = 0;
  bool leaf() const { return count > 0; }
};

struct BinaryBvh {
  std::vector<BinaryNode> nodes;  // nodes[0] is the root
  std::vector<std::uint32_t> prims;  // triangle indices, leaf ranges point here
};

// Binned SAH (Wald, "On fast Construction of SAH-based Bounding Volume
// Hierarchies", IRT 2007): 32 centroid bins per axis, the cheapest plane of
// the three axes, a leaf when that is cheaper than any split.
BinaryBvh build_binary_sah(const std::vector<Triangle>& tris, std::uint32_t max_leaf);
// The same over arbitrary primitives given by their boxes and centroids (the
// objects of a scene: spheres and meshes).
BinaryBvh build_binary_sah(std::vector<Box3> boxes, std::vector<vec3> centroids,
                           std::uint32_t max_leaf);

// The report's builder (its section on BVH, after the lecture notes): split
// the node's box at the middle of its longest axis, triangles going left or
// right by their barycentre; a leaf below 5 triangles or when a side is empty.
BinaryBvh build_binary_midpoint(const std::vector<Triangle>& tris);

}  // namespace whisker
