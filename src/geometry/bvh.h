// Bounding volume hierarchy over triangles.
//
// Sah and Midpoint build a binary tree (bvh_build.h; Sah with spatial splits,
// so a triangle may sit in several leaves), then collapse it into an 8-wide
// tree (bvh_wide.h; Sah by the SAH-optimal choice of children, Midpoint
// greedily): one node holds the boxes of up to 8 children in SIMD layout, a
// leaf is a run of 8-triangle packets. Brute and BBox are the
// report's figure 7 loop over every triangle (without, then behind one box),
// testing the same packets 8 triangles at a time.
#pragma once

#include <cstddef>
#include <vector>

#include "geometry/box.h"
#include "geometry/bvh_method.h"
#include "geometry/bvh_wide.h"
#include "geometry/ray.h"
#include "geometry/triangle.h"

namespace whisker {

class Bvh {
 public:
  Bvh() = default;
  // Builds over `tris` with the chosen method (brute force, one box, the
  // report's longest-axis barycentre split, binned SAH).
  static Bvh build(std::vector<Triangle> tris, BvhMethod method);

  // Closest hit in (ray.tmin, min(ray.tmax, hit.t)): fills hit (t, kind =
  // Triangle, prim = index into the triangles given to build, u, v) and
  // returns true if it found one closer than hit.t.
  bool intersect(const Ray& ray, Hit& hit) const;
  // Any hit in (ray.tmin, ray.tmax).
  bool occluded(const Ray& ray) const;

  std::size_t triangle_count() const { return tri_count_; }
  std::size_t node_count() const { return node_count_; }
  std::size_t bytes() const;
  double build_seconds() const { return build_seconds_; }

 private:
  BvhMethod method_ = BvhMethod::Brute;
  Box3 box_;      // BBox only
  WideBvh wide_;  // the tree (Midpoint, Sah) or only the packets (Brute, BBox)
  std::size_t tri_count_ = 0;
  std::size_t node_count_ = 0;
  double build_seconds_ = 0.0;
};

}  // namespace whisker
