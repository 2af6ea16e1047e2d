// The top level: one BVH over a scene's objects (every sphere, the
// triangle mesh as one object whose box leads into its own BVH, and each
// mesh instance: a BVH shared by several placements, met in its own frame),
// so the cost of a ray grows with the log of the object count. Leaves hold
// up to 16 objects and test their spheres eight at a time; the report's
// scenes (six walls and up to four balls, or the cat) are one leaf.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "geometry/bvh.h"
#include "geometry/ray.h"
#include "geometry/sphere.h"
#include "geometry/sphere_set.h"

namespace whisker {

// A placement of a BVH built in a frame of its own: a point l of that frame
// is l * scale + offset in render space (a uniform scale, then a move). The
// ray meets it in that frame, its origin moved and its direction divided by
// the scale, so that its distances stay those of render space.
struct MeshInstance {
  const Bvh* bvh = nullptr;  // owned by the caller (World), kept alive as long
  double scale = 1.0;
  glm::dvec3 offset{0.0};
  Box3 box;                  // its triangles' bounds, render space
  std::uint32_t id = 0;      // the caller's number for it: Hit::instance
  Ray to_local(const Ray& ray) const;
};

class ObjectBvh {
 public:
  ObjectBvh() = default;
  // `mesh_box` empty: there is no mesh.
  ObjectBvh(const std::vector<Sphere>& spheres, const Box3& mesh_box,
            std::vector<MeshInstance> instances = {});

  // Closest hit in (ray.tmin, min(ray.tmax, hit.t)): spheres give kind
  // Sphere and prim = their index in `spheres`; the mesh's hits come from
  // `mesh` (instance kNoSkip), an instance's from its BVH (instance = its
  // id). Returns whether hit was updated.
  bool intersect(const Ray& ray, Hit& hit, const Bvh* mesh) const;
  // intersect(*rays[l], hits[l], mesh) for each lane l in `lanes` (l < 8),
  // each hits[l] starting as none, its t the ray's tmax (World::closest_batch);
  // a scene of one leaf with at most eight spheres (the report's) meets its
  // spheres eight rays at a time (SphereSet::intersect_batch). Returns the
  // lanes whose hit was updated.
  unsigned intersect_batch(const Ray* const* rays, unsigned lanes, Hit* hits, const Bvh* mesh) const;
  // Any hit in (ray.tmin, ray.tmax); `end_sphere` as in SphereSet::occluded.
  bool occluded(const Ray& ray, const Bvh* mesh, std::uint32_t end_sphere = kNoSkip) const;
  // Whether an instance meets `ray` in (ray.tmin, ray.tmax); spheres and
  // the mesh are not tested.
  bool instance_occludes(const Ray& ray) const;

  bool has_instances() const { return !instances_.empty(); }
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
    std::uint32_t first_instance = 0, instance_count = 0;  // in instances_
  };
  bool intersect_leaf(const Leaf& leaf, const Ray& ray, Hit& hit, const Bvh* mesh) const;
  bool intersect_instances(const Leaf& leaf, const Ray& ray, Hit& hit) const;
  bool occluded_leaf(const Leaf& leaf, const Ray& ray, const Bvh* mesh,
                     std::uint32_t end_sphere) const;
  bool instances_occlude(const Leaf& leaf, const Ray& ray) const;
  // Whether `test(leaf)` holds for a leaf whose box `ray` enters.
  template <class Test>
  bool any_leaf(const Ray& ray, Test&& test) const;

  std::vector<Node> nodes_;
  std::vector<Leaf> leaves_;
  std::vector<MeshInstance> instances_;  // in leaf order
};

}  // namespace whisker
