// The compiled scene: everything a ray can hit (the spheres; the triangles
// of the meshes placed once, in one BVH; the meshes placed several times,
// each in a BVH of its own that every placement shares; all under one
// object-level BVH), each primitive's material, and the point light with
// its shadow test.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>

#include "geometry/bvh.h"
#include "geometry/bvh_method.h"
#include "geometry/light_buffer.h"
#include "geometry/ray.h"
#include "geometry/sphere.h"
#include "geometry/surface_point.h"
#include "geometry/object_bvh.h"
#include "geometry/offset.h"
#include "scene/scene.h"

namespace whisker {

// A hit record (geometry/surface_point.h) with the material that was hit;
// its positions are in render space (see World).
struct SurfaceHit : SurfacePoint {
  const Material* material = nullptr;
};

// Render space: the World holds every position relative to the scene's
// camera (pbrt-v4's "camera-world" space), subtracted in double from the
// scene's numbers, so a scene far from the origin renders as it would at the
// origin, and float keeps its precision where the image needs it. Rays given
// to intersect(), closest() and occluded() are in render space (to_render());
// radiance() converts the camera's rays.
class World {
 public:
  World() = default;
  // Expands hollow spheres into their two glass shells, gathers triangles.
  // A mesh several of the scene's objects hold (scene_io.cpp shares one
  // between the placements of a file) is built once, in a frame of its own
  // (its middle, unscaled), and each of them is an instance of it: memory
  // follows the distinct meshes, not the placements. A mesh one object
  // holds is placed in render space with the others held once, in one BVH.
  // `previous`, a World built before from the same meshes, lends its BVHs.
  explicit World(const Scene& scene, const World* previous = nullptr);

  bool intersect(const Ray& ray, SurfaceHit& out) const;
  // The same in two steps, so that a caller can look at the material before
  // paying for the hit record (the double-precision sphere refinement):
  // closest hit only, then the record of that hit.
  // Inline: the caller's own initialisation of `hit` and this one merge.
  bool closest(const Ray& ray, Hit& hit) const {
    hit = Hit{};
    hit.t = ray.tmax;
    objects_.intersect(ray, hit, mesh_ ? &mesh_->bvh : nullptr);
    return hit.valid();
  }
  // closest(*rays[l], hits[l]) for each lane l in `lanes` (l < 8), the
  // rays side by side where the scene allows (ObjectBvh::intersect_batch);
  // returns the lanes that hit.
  unsigned closest_batch(const Ray* const* rays, unsigned lanes, Hit* hits) const {
    for (unsigned a = lanes; a; a &= a - 1) {
      const int l = __builtin_ctz(a);
      hits[l] = Hit{};
      hits[l].t = rays[l]->tmax;
    }
    // A hit that was updated is valid: each starts as none.
    return objects_.intersect_batch(rays, lanes, hits, mesh_ ? &mesh_->bvh : nullptr);
  }
  const Material& material(const Hit& hit) const {
    if (hit.kind == PrimKind::Sphere) return sphere_material_[hit.prim];
    return mesh_material_[hit.instance == kNoSkip ? mesh_->object[hit.prim] : instances_[hit.instance].object];
  }
  void record(const Ray& ray, const Hit& hit, SurfaceHit& out) const;
  // Any hit in (ray.tmin, ray.tmax). A segment that ends on a sphere, seen
  // from outside it (the caller's check), names it as `end_sphere`: it is not
  // tested (SphereSet::occluded).
  bool occluded(const Ray& ray, std::uint32_t end_sphere = kNoSkip) const;
  // The scene's point light, as it was when this World was built (its
  // position in render space).
  struct Light {
    vec3 position;
    float intensity;
  };
  const Light& light() const { return light_; }
  // The world-space point that is render space's origin (the camera).
  const glm::dvec3& origin() const { return origin_; }
  vec3 to_render(const glm::dvec3& world_point) const { return vec3(world_point - origin_); }
  vec3 to_render(const vec3& world_point) const { return to_render(glm::dvec3(world_point)); }
  // The ray from the world-space point `o` along d in render space, o's
  // remainder kept in o_lo (the camera itself maps to 0).
  Ray to_render(const glm::dvec3& o, const vec3& d) const {
    Ray ray{vec3(0.0f), d, 0.0f, kInf};
    split_double(o - origin_, ray.o, ray.o_lo);
    return ray;
  }
  // A world-space ray (a camera ray) in render space, its origin's remainder
  // kept in o_lo (the camera itself maps to 0).
  Ray to_render(Ray ray) const {
    split_double(glm::dvec3(ray.o) - origin_, ray.o, ray.o_lo);
    return ray;
  }
  // occluded() for a shadow ray from a hit point towards light().position,
  // dist2 = its squared length, from_light = the hit point less the light:
  // when no sphere can stand between them (see light_clear2_) only the
  // triangles are tested. Same answer as occluded().
  bool occluded_to_light(const Ray& ray, float dist2, const vec3& from_light) const {
    if (!light_cages_.empty() && outside_a_light_cage(ray)) return true;
    if (dist2 < light_clear2_) {
      if (mesh_ && (light_buffer_.covers(ray) ? light_buffer_.occluded(ray, from_light)
                                              : mesh_->bvh.occluded(ray)))
        return true;
      return objects_.has_instances() && objects_.instance_occludes(ray);
    }
    return occluded(ray, light_on_.empty() ? kNoSkip : light_sphere_passed(ray));
  }

  // The squared distance from the light within which occluded_to_light()
  // skips the spheres (see light_clear2_).
  float light_clearance2() const { return light_clear2_; }
  std::size_t sphere_count() const { return spheres_.size(); }
  // The triangles a ray may meet: an instance's count once for each.
  std::size_t triangle_count() const;
  // The BVH of the meshes placed once (none: nullptr).
  const Bvh* bvh() const { return mesh_ ? &mesh_->bvh : nullptr; }
  // The triangles stored: each mesh once, however many times it is placed.
  std::size_t stored_triangle_count() const;
  std::size_t instance_count() const { return instances_.size(); }

 private:
  // Triangle data, immutable once built and shared between Worlds.
  struct MeshData {
    Bvh bvh;
    std::vector<std::uint32_t> object;    // per triangle: mesh index in the scene
    std::vector<Triangle> tris;           // the triangles (less `origin`), for hit points
    std::vector<vec3> ng;                 // per triangle: unit geometric normal
    std::vector<std::array<vec3, 3>> ns;  // per triangle corner normals (if any mesh uses them)
    std::vector<const TriangleMesh*> sources;  // identity of the meshes it was built from
    BvhMethod method = BvhMethod::Sah;
    // The world point its coordinates are relative to: the camera (render
    // space) for the meshes placed once; a shared mesh's middle.
    glm::dvec3 origin{0.0};
    Box3 bounds;  // of all triangles
  };
  // A placement of a shared mesh: render point = its point * scale + offset.
  struct Instance {
    std::uint32_t object = 0;  // the scene's mesh object (material, normals)
    std::uint32_t mesh = 0;    // in shared_
    double scale = 1.0;
    glm::dvec3 offset{0.0};
  };
  void set_light_clearance(const Scene& scene);
  void set_light_cages();
  bool outside_a_light_cage(const Ray& ray) const;
  std::uint32_t light_sphere_passed(const Ray& ray) const;
  void build_meshes(const Scene& scene, const World* previous);
  std::shared_ptr<const MeshData> build_mesh(const Scene& scene, const std::vector<std::uint32_t>& objects,
                                             const glm::dvec3& origin) const;
  std::shared_ptr<const MeshData> shared_mesh(const Scene& scene, std::uint32_t object,
                                              const World* previous) const;
  std::vector<MeshInstance> place_instances(const Scene& scene, const std::vector<std::uint32_t>& users,
                                            std::uint32_t mesh);
  void build_light_buffer(BvhMethod method);
  void record_sphere(const Ray& ray, const Hit& hit, SurfaceHit& out) const;
  void record_triangle(const Hit& hit, SurfaceHit& out) const;
  void record_instance(const Hit& hit, SurfaceHit& out) const;

  std::vector<Sphere> spheres_;
  ObjectBvh objects_;  // spheres and the mesh, one structure
  std::vector<Material> sphere_material_;
  std::vector<Material> mesh_material_;
  std::vector<bool> mesh_vertex_normals_;
  std::shared_ptr<const MeshData> mesh_;  // the meshes placed once, render space
  std::vector<std::shared_ptr<const MeshData>> shared_;  // meshes placed several times
  std::vector<Instance> instances_;  // their placements (Hit::instance)
  // A segment from the light L to a point p outside a sphere (centre c,
  // radius r) that passes through the sphere leaves it at distance
  // t2 >= sqrt(|L - c|^2 - r^2) from L (the product of the two roots is the
  // power of L, |L - c|^2 - r^2, and t1 <= t2), so |p - L| >= t2 then.
  // This is the smallest such bound over all spheres (squared, with a margin
  // for float rounding); 0 if the light is inside or on a sphere. For the
  // report's room it is about 196^2, and no point of the room is that far
  // from the light: shadow rays there never test the six wall spheres.
  float light_clear2_ = 0.0f;
  std::vector<std::uint32_t> light_cages_;  // spheres holding the light strictly inside
  // Spheres the light lies on (within the cages' tolerance): a shadow ray
  // that cannot cross one before the light does not test it
  // (light_sphere_passed()).
  std::vector<std::uint32_t> light_on_;
  Light light_;  // the scene light in render space (light_clear2_ is computed for it)
  // The triangles by direction from the light, for the shadow rays that test
  // only triangles (within light_clear2_); built with the SAH tree only
  // (--accel brute, bbox and midpoint time those structures as they are).
  LightBuffer light_buffer_;
  glm::dvec3 origin_{0.0};
};

}  // namespace whisker
