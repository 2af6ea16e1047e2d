// The compiled scene: everything a ray can hit (the spheres and the
// triangles of all meshes, in one BVH, under one object-level BVH), each
// primitive's material, and the point light with its shadow test.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "geometry/bvh.h"
#include "geometry/bvh_method.h"
#include "geometry/ray.h"
#include "geometry/sphere.h"
#include "geometry/object_bvh.h"
#include "scene/scene.h"

namespace whisker {

// The scene's name for a BVH method (RenderSettings::accel) to geometry's.
BvhMethod bvh_method(AccelKind k);

struct SurfaceHit {
  float t = kInf;
  vec3 p{0.0f};   // hit point (on the surface to about one ULP)
  vec3 ng{0.0f};  // unit geometric normal (outward; inward for inverted shells)
  vec3 ns{0.0f};  // unit shading normal (== ng unless vertex normals are on)
  const Material* material = nullptr;
};

class World {
 public:
  World() = default;
  // Expands hollow spheres into their two glass shells, gathers triangles.
  // `reuse` may hold a World built from the same meshes: its BVH is shared.
  explicit World(const Scene& scene, const World* reuse = nullptr);

  bool intersect(const Ray& ray, SurfaceHit& out) const;
  // The same in two steps, so that a caller can look at the material before
  // paying for the hit record (the double-precision sphere refinement):
  // closest hit only, then the record of that hit.
  bool closest(const Ray& ray, Hit& hit) const;
  const Material& material(const Hit& hit) const {
    return hit.kind == PrimKind::Sphere ? sphere_material_[hit.prim]
                                        : mesh_material_[mesh_->object[hit.prim]];
  }
  void record(const Ray& ray, const Hit& hit, SurfaceHit& out) const;
  bool occluded(const Ray& ray) const;
  // The scene's point light, as it was when this World was built.
  const PointLight& light() const { return light_; }
  // occluded() for a shadow ray from a hit point towards light().position,
  // dist2 = its squared length: when no sphere can stand between them (see
  // light_clear2_) only the triangles are tested. Same answer as occluded().
  bool occluded_to_light(const Ray& ray, float dist2) const {
    if (dist2 < light_clear2_) return mesh_ && mesh_->bvh.occluded(ray);
    return occluded(ray);
  }

  // The squared distance from the light within which occluded_to_light()
  // skips the spheres (see light_clear2_).
  float light_clearance2() const { return light_clear2_; }
  std::size_t sphere_count() const { return spheres_.size(); }
  std::size_t triangle_count() const { return mesh_ ? mesh_->bvh.triangle_count() : 0; }
  const Bvh* bvh() const { return mesh_ ? &mesh_->bvh : nullptr; }

 private:
  // Triangle data, immutable once built and shared between Worlds.
  struct MeshData {
    Bvh bvh;
    std::vector<std::uint32_t> object;    // per triangle: mesh index in the scene
    std::vector<vec3> ng;                 // per triangle: unit geometric normal
    std::vector<std::array<vec3, 3>> ns;  // per triangle corner normals (if any mesh uses them)
    std::vector<const TriangleMesh*> sources;  // identity of the meshes it was built from
    BvhMethod method = BvhMethod::Sah;
    Box3 bounds;  // of all triangles
  };
  void set_light_clearance(const Scene& scene);

  std::vector<Sphere> spheres_;
  ObjectBvh objects_;  // spheres and the mesh, one structure
  std::vector<Material> sphere_material_;
  std::vector<Material> mesh_material_;
  std::vector<bool> mesh_vertex_normals_;
  std::shared_ptr<const MeshData> mesh_;
  // A segment from the light L to a point p outside a sphere (centre c,
  // radius r) that passes through the sphere leaves it at distance
  // t2 >= sqrt(|L - c|^2 - r^2) from L (the product of the two roots is the
  // power of L, |L - c|^2 - r^2, and t1 <= t2), so |p - L| >= t2 then.
  // This is the smallest such bound over all spheres (squared, with a margin
  // for float rounding); 0 if the light is inside or on a sphere. For the
  // report's room it is about 196^2, and no point of the room is that far
  // from the light: shadow rays there never test the six wall spheres.
  float light_clear2_ = 0.0f;
  PointLight light_;  // the scene light (light_clear2_ is computed for it)
};

}  // namespace whisker
