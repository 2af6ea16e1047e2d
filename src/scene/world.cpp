#include "scene/world.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>

#include <glm/geometric.hpp>

#include "geometry/mesh.h"
#include "geometry/unit.h"

namespace whisker {

World::World(const Scene& scene, const World* previous) {
  origin_ = glm::dvec3(scene.camera.position);
  const auto here = [&](const glm::dvec3& p) { return to_render(p); };
  set_light_clearance(scene);
  light_ = {here(scene.light.position), scene.light.intensity};
  for (const auto& s : scene.spheres) {
    const vec3 c = here(s.center);
    if (s.material.kind == MaterialKind::HollowGlass) {
      // Report section 2: a glass ball holding an air bubble whose normal is inverted.
      Material glass = s.material;
      glass.kind = MaterialKind::Glass;
      spheres_.push_back({c, s.radius, false});
      sphere_material_.push_back(glass);
      spheres_.push_back({c, s.inner_radius, true});
      sphere_material_.push_back(glass);
    } else {
      spheres_.push_back({c, s.radius, false});
      sphere_material_.push_back(s.material);
    }
  }
  set_light_cages();
  for (const auto& m : scene.meshes) {
    mesh_material_.push_back(m.material);
    mesh_vertex_normals_.push_back(m.vertex_normals);
  }
  build_meshes(scene, previous);
}

void World::build_meshes(const Scene& scene, const World* previous) {
  // The objects holding each mesh, meshes in the order of their first holder.
  std::vector<const TriangleMesh*> order;
  std::unordered_map<const TriangleMesh*, std::vector<std::uint32_t>> users;
  for (std::uint32_t mi = 0; mi < scene.meshes.size(); ++mi) {
    auto& u = users[scene.meshes[mi].mesh.get()];
    if (u.empty()) order.push_back(scene.meshes[mi].mesh.get());
    u.push_back(mi);
  }
  std::vector<std::uint32_t> once;
  std::vector<const TriangleMesh*> sources;
  for (std::uint32_t mi = 0; mi < scene.meshes.size(); ++mi)
    if (users[scene.meshes[mi].mesh.get()].size() == 1) {
      once.push_back(mi);
      sources.push_back(scene.meshes[mi].mesh.get());
    }
  const BvhMethod method = scene.settings.accel;
  if (!once.empty()) {
    // The triangles are in render space: a BVH is shared only by Worlds with
    // the same camera position (a moved camera rebuilds it).
    if (previous && previous->mesh_ && previous->mesh_->sources == sources &&
        previous->mesh_->method == method && previous->mesh_->origin == origin_)
      mesh_ = previous->mesh_;
    else
      mesh_ = build_mesh(scene, once, origin_);
  }
  std::vector<MeshInstance> placed;
  for (const TriangleMesh* mesh : order) {
    const std::vector<std::uint32_t>& u = users[mesh];
    if (u.size() < 2) continue;
    const auto index = static_cast<std::uint32_t>(shared_.size());
    shared_.push_back(shared_mesh(scene, u.front(), previous));
    for (MeshInstance& m : place_instances(scene, u, index)) placed.push_back(m);
  }
  objects_ = ObjectBvh(spheres_, mesh_ ? mesh_->bounds : Box3{}, std::move(placed));
  if (mesh_) build_light_buffer(method);
}

// The mesh of scene.meshes[object], built in a frame of its own (its
// middle, as the mesh holds it): whatever the camera, the same BVH, so
// `previous`'s is taken when it has one.
std::shared_ptr<const World::MeshData> World::shared_mesh(const Scene& scene, std::uint32_t object,
                                                         const World* previous) const {
  const TriangleMesh& mesh = *scene.meshes[object].mesh;
  if (previous)
    for (const auto& d : previous->shared_)
      if (d->sources.front() == &mesh && d->method == scene.settings.accel) return d;
  glm::dvec3 lo(HUGE_VAL), hi(-HUGE_VAL);
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    const glm::dvec3 p = mesh.exact.empty() ? glm::dvec3(mesh.positions[i]) : mesh.exact[i];
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  return build_mesh(scene, {object}, 0.5 * (lo + hi));
}

// The instances of shared_[mesh], one for each object in `users`: the
// object's placement relative to the one the mesh's positions carry.
std::vector<MeshInstance> World::place_instances(const Scene& scene,
                                                 const std::vector<std::uint32_t>& users,
                                                 std::uint32_t mesh) {
  const MeshData& data = *shared_[mesh];
  std::vector<MeshInstance> placed;
  for (const std::uint32_t mi : users) {
    const MeshObject& m = scene.meshes[mi];
    const TriangleMesh::Placement own{m.scale, m.translate};
    const TriangleMesh::Placement held = m.mesh->placed.value_or(own);
    Instance in;
    in.object = mi;
    in.mesh = mesh;
    // x (as held) -> (x - held.translate) * scale + translate (the object's).
    if (held.scale == m.scale && held.translate == m.translate) {
      in.offset = data.origin - origin_;
    } else {
      in.scale = double(m.scale) / double(held.scale);
      in.offset = (data.origin - held.translate) * in.scale + m.translate - origin_;
    }
    MeshInstance bvh_in;
    bvh_in.bvh = &data.bvh;
    bvh_in.scale = in.scale;
    bvh_in.offset = in.offset;
    bvh_in.id = static_cast<std::uint32_t>(instances_.size());
    // Its box in render space, padded past the roundings of the ray's move
    // into the frame and of the box's corners.
    const glm::dvec3 lo = glm::dvec3(data.bounds.lo) * in.scale + in.offset;
    const glm::dvec3 hi = glm::dvec3(data.bounds.hi) * in.scale + in.offset;
    const glm::dvec3 pad = (glm::abs(lo) + glm::abs(hi) + (hi - lo)) * 0x1p-20;
    bvh_in.box = Box3{vec3(lo - pad), vec3(hi + pad)};
    instances_.push_back(in);
    placed.push_back(bvh_in);
  }
  return placed;
}

std::size_t World::triangle_count() const {
  std::size_t n = mesh_ ? mesh_->tris.size() : 0;
  for (const Instance& in : instances_) n += shared_[in.mesh]->tris.size();
  return n;
}

std::size_t World::stored_triangle_count() const {
  std::size_t n = mesh_ ? mesh_->tris.size() : 0;
  for (const auto& d : shared_) n += d->tris.size();
  return n;
}

void World::build_light_buffer(BvhMethod method) {
  if (method != BvhMethod::Sah || !(light_clear2_ > 0.0f) || mesh_->tris.empty()) return;
  // Shadow rays from farther than the mesh's farthest corner, four times
  // over, go to the tree: the cells' margins grow with the rays' length.
  const Box3& b = mesh_->bounds;
  double corner = 0.0;
  for (int k = 0; k < 8; ++k) {
    const glm::dvec3 c(k & 1 ? b.hi.x : b.lo.x, k & 2 ? b.hi.y : b.lo.y, k & 4 ? b.hi.z : b.lo.z);
    corner = std::max(corner, glm::length(c - glm::dvec3(light_.position)));
  }
  const float reach = float(std::min(std::sqrt(double(light_clear2_)), 4.0 * corner));
  // About two cells a side per square root of the triangles: a few
  // triangles a cell where the mesh is.
  const int cells = std::clamp(int(2.0 * std::sqrt(double(mesh_->tris.size()))), 8, 128);
  light_buffer_ = LightBuffer(light_.position, mesh_->tris, reach, cells);
}

// The triangles of the scene's mesh objects `objects`, less `origin` (in
// double, then rounded to float), in one BVH.
std::shared_ptr<const World::MeshData> World::build_mesh(const Scene& scene,
                                                        const std::vector<std::uint32_t>& objects,
                                                        const glm::dvec3& origin) const {
  auto data = std::make_shared<MeshData>();
  for (const std::uint32_t mi : objects) data->sources.push_back(scene.meshes[mi].mesh.get());
  data->method = scene.settings.accel;
  data->origin = origin;
  std::vector<Triangle> tris;
  bool any_normals = false;
  for (const std::uint32_t mi : objects)
    any_normals |= scene.meshes[mi].vertex_normals && !scene.meshes[mi].mesh->normals.empty();
  for (const std::uint32_t mi : objects) {
    const TriangleMesh& mesh = *scene.meshes[mi].mesh;
    // Vertices less the origin, subtracted in double from the double-precision
    // positions when the loader kept them (one rounding to float).
    const auto vertex = [&](unsigned i) {
      return mesh.exact.empty() ? vec3(glm::dvec3(mesh.positions[i]) - origin) : vec3(mesh.exact[i] - origin);
    };
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      const glm::uvec3 idx = mesh.triangles[t];
      const Triangle tri{vertex(idx.x), vertex(idx.y), vertex(idx.z)};
      tris.push_back(tri);
      data->bounds.grow(bounds_of(tri));
      data->object.push_back(mi);
      // The unit normal of the float triangle the ray meets, from double edges.
      const glm::dvec3 e1 = glm::dvec3(tri.v1) - glm::dvec3(tri.v0);
      const glm::dvec3 e2 = glm::dvec3(tri.v2) - glm::dvec3(tri.v0);
      const glm::dvec3 c = glm::cross(e1, e2);
      const double len = glm::length(c);
      const vec3 n = len > 0.0 ? vec3(c / len) : vec3(0.0f, 0.0f, 1.0f);
      data->ng.push_back(n);
      if (any_normals) {
        std::array<vec3, 3> cn{n, n, n};
        if (!mesh.normal_idx.empty()) {
          const glm::uvec3 ni = mesh.normal_idx[t];
          cn = {unit_or_zero(mesh.normals[ni.x]), unit_or_zero(mesh.normals[ni.y]),
                unit_or_zero(mesh.normals[ni.z])};
        }
        data->ns.push_back(cn);
      }
    }
  }
  data->tris = tris;
  data->bvh = Bvh::build(std::move(tris), data->method);
  return data;
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
    const bool outside = !is_glass(s.material.kind) && glm::dot(fc, fc) > r * r;
    const double near = std::max(0.0, std::sqrt(d2) - r);
    clear = std::min(clear, outside ? std::max(0.0, d2 - r * r) : near * near);
  }
  // |p - L|^2 is rounded in float (a few ULP); 1e-3 covers it many times over.
  light_clear2_ = float(clear * (1.0 - 1e-3));
}

void World::set_light_cages() {
  // Spheres holding the light strictly inside (by more than their float
  // rounding): a shadow ray from outside one must cross it, however close to
  // the light, where the shadow ray's margin (offset.h) would let it through.
  const glm::dvec3 L(light_.position);
  for (std::uint32_t k = 0; k < spheres_.size(); ++k) {
    const Sphere& s = spheres_[k];
    const glm::dvec3 f = L - glm::dvec3(s.center);
    const double r = double(s.radius);
    // The light and the centre are rounded to float in render space, the
    // radius too: within 2^-24 of each. 4x that is "on the surface".
    const double tol = 0x1p-22 * (glm::length(L) + glm::length(glm::dvec3(s.center)) + r);
    if (glm::length(f) < r - tol) light_cages_.push_back(k);
    else if (glm::length(f) <= r + tol) light_on_.push_back(k);
  }
}

// The sphere, of those the light lies on, that a shadow ray `ray` cannot
// cross before reaching the light (kNoSkip if none). With m = L - c (|m| = r)
// the line o + t w through L meets the sphere at L and at a second point
// 2 m.w before it; the open segment from o to L crosses the sphere only if
// that point lies on it, i.e. o is outside the sphere and below its tangent
// plane at L (m.(o - L) < 0). A chord (o on the sphere itself, or inside it)
// and a point above the tangent plane see L. Skipping the sphere is then
// exact, where testing it is not: near L, at grazing angles, its float root
// at L itself lands before the ray's end (radius 940, 60 from the camera).
// A light on two spheres (their seam) skips the first that qualifies.
std::uint32_t World::light_sphere_passed(const Ray& ray) const {
  const glm::dvec3 o = exact_origin(ray);
  const glm::dvec3 L(light_.position);
  for (const std::uint32_t k : light_on_) {
    if (ray.skip == k) return k;
    const Sphere& s = spheres_[k];
    const glm::dvec3 f = o - glm::dvec3(s.center);
    const double r = double(s.radius);
    const bool crosses = glm::dot(f, f) > r * r && glm::dot(L - glm::dvec3(s.center), o - L) < 0.0;
    if (!crosses) return k;
  }
  return kNoSkip;
}

bool World::outside_a_light_cage(const Ray& ray) const {
  const glm::dvec3 o = exact_origin(ray);
  for (const std::uint32_t k : light_cages_) {
    const Sphere& s = spheres_[k];
    if (ray.skip == k) continue;  // leaving the cage itself: its inner side, if lit
    const glm::dvec3 f = o - glm::dvec3(s.center);
    const double r = double(s.radius) * (1.0 + 0x1p-22);
    if (glm::dot(f, f) > r * r) return true;
  }
  return false;
}

bool World::intersect(const Ray& ray, SurfaceHit& out) const {
  Hit hit;
  if (!closest(ray, hit)) return false;
  record(ray, hit, out);
  return true;
}

void World::record(const Ray& ray, const Hit& hit, SurfaceHit& out) const {
  if (hit.kind == PrimKind::Sphere) record_sphere(ray, hit, out);
  else if (hit.instance == kNoSkip) record_triangle(hit, out);
  else record_instance(hit, out);
}

void World::record_sphere(const Ray& ray, const Hit& hit, SurfaceHit& out) const {
  static_cast<SurfacePoint&>(out) = sphere_surface_point(spheres_[hit.prim], hit.prim, ray, hit.t);
  out.material = &sphere_material_[hit.prim];
}

void World::record_triangle(const Hit& hit, SurfaceHit& out) const {
  const MeshData& m = *mesh_;
  const std::uint32_t obj = m.object[hit.prim];
  static_cast<SurfacePoint&>(out) =
      triangle_surface_point(m.tris[hit.prim], m.ng[hit.prim], hit.t, hit.u, hit.v);
  if (mesh_vertex_normals_[obj] && !m.ns.empty())
    out.ns = interpolated_normal(m.ns[hit.prim], hit.u, hit.v, out.ng);
  out.material = &mesh_material_[obj];
}

// As record_triangle, in the instance's frame, the point then moved to
// render space (in double). Its error bound grows by the scale, by the
// rounding of the move, and by that of a ray leaving it moved back into the
// frame (MeshInstance::to_local): each half an ulp of the point's
// coordinates there or here, doubled.
void World::record_instance(const Hit& hit, SurfaceHit& out) const {
  const Instance& in = instances_[hit.instance];
  const MeshData& m = *shared_[in.mesh];
  static_cast<SurfacePoint&>(out) =
      triangle_surface_point(m.tris[hit.prim], m.ng[hit.prim], hit.t, hit.u, hit.v);
  const glm::dvec3 local(out.p);
  const glm::dvec3 p = local * in.scale + in.offset;
  out.p = vec3(p);
  const glm::dvec3 err = (glm::dvec3(out.err) + glm::abs(local) * 0x1p-23) * in.scale + glm::abs(p) * 0x1p-23;
  out.err = vec3(err * (1.0 + 0x1p-20));
  if (mesh_vertex_normals_[in.object] && !m.ns.empty())
    out.ns = interpolated_normal(m.ns[hit.prim], hit.u, hit.v, out.ng);
  out.material = &mesh_material_[in.object];
}

bool World::occluded(const Ray& ray, std::uint32_t end_sphere) const {
  return objects_.occluded(ray, mesh_ ? &mesh_->bvh : nullptr, end_sphere);
}

}  // namespace whisker
