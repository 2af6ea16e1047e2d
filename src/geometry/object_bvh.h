// The top level: one BVH over a scene's objects (every sphere, and the
// triangle mesh as one object whose box leads into its own BVH), so the cost
// of a ray grows with the log of the object count. Leaves hold up to 16
// objects and test their spheres eight at a time; the report's scenes (six
// walls and up to four balls, or the cat) are one leaf.
#pragma once

#include <cstdint>
#include <vector>

#include "geometry/bvh.h"
#include "geometry/ray.h"
#include "geometry/sphere.h"
#include "geometry/sphere_set.h"

namespace whisker {

class ObjectBvh {
 public:
  ObjectBvh() = default;
  // `mesh_box` empty: there is no mesh.
  ObjectBvh(const std::vector<Sphere>& spheres, const Box3& mesh_box);

  // Closest hit in (ray.tmin, min(ray.tmax, hit.t)): spheres give kind
  // Sphere and prim = their index in `spheres`; the mesh's hits come from
  // `mesh`. Returns whether hit was updated.
  bool intersect(const Ray& ray, Hit& hit, const Bvh* mesh) const;
  // intersect(*rays[l], hits[l], mesh) for each lane l in `lanes` (l < 8),
  // each hits[l] starting as none, its t the ray's tmax (World::closest_batch);
  // a scene of one leaf with at most eight spheres (the report's) meets its
  // spheres eight rays at a time (SphereSet::intersect_batch). Returns the
  // lanes whose hit was updated.
  unsigned intersect_batch(const Ray* const* rays, unsigned lanes, Hit* hits, const Bvh* mesh) const;
  // Any hit in (ray.tmin, ray.tmax); `end_sphere` as in SphereSet::occluded.
  bool occluded(const Ray& ray, const Bvh* mesh, std::uint32_t end_sphere = kNoSkip) const;

  std::size_t node_count() const { return nodes_.size(); }
  std::size_t leaf_count() const { return leaves_.size(); }

 private:
  static constexpr std::uint32_t kInner = 0xffffffffu;
  struct Node {
    Box3 box;
    std::uint32_t left = 0, right = 0;
    std::uint32_t leaf = kInner;  // index into leaves_, or kInner
  };
  struct Leaf {
    SphereSet spheres;
    bool mesh = false;
  };
  static bool intersect_leaf(const Leaf& leaf, const Ray& ray, Hit& hit, const Bvh* mesh);
  static bool occluded_leaf(const Leaf& leaf, const Ray& ray, const Bvh* mesh,
                            std::uint32_t end_sphere);

  std::vector<Node> nodes_;
  std::vector<Leaf> leaves_;
};

}  // namespace whisker
