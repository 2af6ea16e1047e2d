#include "scene/world.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/geometric.hpp>

#include "geometry/mesh.h"

namespace whisker {

BvhMethod bvh_method(AccelKind k) {
  switch (k) {
    case AccelKind::Brute: return BvhMethod::Brute;
    case AccelKind::BBox: return BvhMethod::BBox;
    case AccelKind::Midpoint: return BvhMethod::Midpoint;
    case AccelKind::Sah: break;
  }
  return BvhMethod::Sah;
}

World::World(const Scene& scene, const World* reuse) {
  set_light_clearance(scene);
  for (const auto& s : scene.spheres) {
    if (s.material.kind == MaterialKind::HollowGlass) {
      // Report section 2: a glass ball holding an air bubble whose normal is inverted.
      Material glass = s.material;
      glass.kind = MaterialKind::Glass;
      spheres_.push_back({s.center, s.radius, false});
      sphere_material_.push_back(glass);
      spheres_.push_back({s.center, s.inner_radius, true});
      sphere_material_.push_back(glass);
    } else {
      spheres_.push_back({s.center, s.radius, false});
      sphere_material_.push_back(s.material);
    }
  }
  std::vector<const TriangleMesh*> sources;
  for (const auto& m : scene.meshes) {
    mesh_material_.push_back(m.material);
    mesh_vertex_normals_.push_back(m.vertex_normals);
    sources.push_back(m.mesh.get());
  }
  if (sources.empty()) {
    objects_ = ObjectBvh(spheres_, Box3{});
    return;
  }
  const BvhMethod method = bvh_method(scene.settings.accel);
  if (reuse && reuse->mesh_ && reuse->mesh_->sources == sources &&
      reuse->mesh_->method == method) {
    mesh_ = reuse->mesh_;
    objects_ = ObjectBvh(spheres_, mesh_->bounds);
    return;
  }
  auto data = std::make_shared<MeshData>();
  data->sources = sources;
  data->method = method;
  std::vector<Triangle> tris;
  bool any_normals = false;
  for (const auto& m : scene.meshes) any_normals |= m.vertex_normals && !m.mesh->normals.empty();
  for (std::uint32_t mi = 0; mi < scene.meshes.size(); ++mi) {
    const TriangleMesh& mesh = *scene.meshes[mi].mesh;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      const glm::uvec3 idx = mesh.triangles[t];
      const Triangle tri{mesh.positions[idx.x], mesh.positions[idx.y], mesh.positions[idx.z]};
      tris.push_back(tri);
      data->bounds.grow(bounds_of(tri));
      data->object.push_back(mi);
      const vec3 n = glm::normalize(glm::cross(tri.v1 - tri.v0, tri.v2 - tri.v0));
      data->ng.push_back(n);
      if (any_normals) {
        std::array<vec3, 3> c{n, n, n};
        if (!mesh.normal_idx.empty()) {
          const glm::uvec3 ni = mesh.normal_idx[t];
          c = {glm::normalize(mesh.normals[ni.x]), glm::normalize(mesh.normals[ni.y]),
               glm::normalize(mesh.normals[ni.z])};
        }
        data->ns.push_back(c);
      }
    }
  }
  data->bvh = Bvh::build(std::move(tris), method);
  mesh_ = std::move(data);
  objects_ = ObjectBvh(spheres_, mesh_->bounds);
}

void World::set_light_clearance(const Scene& scene) {
  double clear = kInf;
  for (const auto& s : scene.spheres) {
    const glm::dvec3 f = glm::dvec3(scene.light.position) - glm::dvec3(s.center);
    const double d2 = glm::dot(f, f), r = double(s.radius);
    const glm::dvec3 fc = glm::dvec3(scene.camera.position) - glm::dvec3(s.center);
    // Paths reach a point inside a sphere only through glass (the others
    // send every ray back to the side it came from) or if the camera is
    // inside. Then only the near root t1 >= |L - c| - r bounds the segment.
    // (A hollow sphere's inner shell lies inside its outer one, which bounds both.)
    const bool outside = s.material.kind != MaterialKind::Glass &&
                         s.material.kind != MaterialKind::HollowGlass &&
                         glm::dot(fc, fc) > r * r;
    const double near = std::max(0.0, std::sqrt(d2) - r);
    clear = std::min(clear, outside ? std::max(0.0, d2 - r * r) : near * near);
  }
  // |p - L|^2 is rounded in float (a few ULP); 1e-3 covers it many times over.
  light_clear2_ = float(clear * (1.0 - 1e-3));
  light_ = scene.light;
}

bool World::intersect(const Ray& ray, SurfaceHit& out) const {
  Hit hit;
  if (!closest(ray, hit)) return false;
  record(ray, hit, out);
  return true;
}

bool World::closest(const Ray& ray, Hit& hit) const {
  hit = Hit{};
  hit.t = ray.tmax;
  objects_.intersect(ray, hit, mesh_ ? &mesh_->bvh : nullptr);
  return hit.valid();
}

void World::record(const Ray& ray, const Hit& hit, SurfaceHit& out) const {
  out.t = hit.t;
  if (hit.kind == PrimKind::Sphere) {
    const Sphere& s = spheres_[hit.prim];
    const double t = refine_sphere_t(s, ray, hit.t);
    out.t = float(t);
    out.p = sphere_hit_point(ray, t);
    out.ng = sphere_normal(s, out.p);
    out.ns = out.ng;
    out.material = &sphere_material_[hit.prim];
  } else {
    const MeshData& m = *mesh_;
    const std::uint32_t obj = m.object[hit.prim];
    // Barycentric interpolation of the vertices would be more exact than
    // o + t d for long rays; the ray offset's 256-ULP margin covers either.
    out.p = ray.o + hit.t * ray.d;
    out.ng = m.ng[hit.prim];
    out.ns = out.ng;
    if (mesh_vertex_normals_[obj] && !m.ns.empty()) {
      const auto& c = m.ns[hit.prim];
      out.ns = glm::normalize((1.0f - hit.u - hit.v) * c[0] + hit.u * c[1] + hit.v * c[2]);
    }
    out.material = &mesh_material_[obj];
  }
}

bool World::occluded(const Ray& ray) const {
  return objects_.occluded(ray, mesh_ ? &mesh_->bvh : nullptr);
}

}  // namespace whisker
