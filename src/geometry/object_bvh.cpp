#include "geometry/object_bvh.h"

#include <algorithm>
#include <utility>

#include "geometry/bvh_build.h"

namespace whisker {

Ray MeshInstance::to_local(const Ray& ray) const {
  // From the exact origin (a sphere's hit keeps its low part), in double.
  const double inv = 1.0 / scale;
  Ray local;
  local.o = vec3((exact_origin(ray) - offset) * inv);
  local.d = vec3(glm::dvec3(ray.d) * inv);
  local.tmin = ray.tmin;
  local.tmax = ray.tmax;
  return local;
}

ObjectBvh::ObjectBvh(const std::vector<Sphere>& spheres, const Box3& mesh_box,
                     std::vector<MeshInstance> instances) {
  // Objects 0..n-1 are the spheres, object n the mesh (if any), then the
  // instances.
  std::vector<Box3> boxes;
  std::vector<vec3> cents;
  for (const Sphere& s : spheres) {
    boxes.push_back(Box3{s.center - vec3(s.radius), s.center + vec3(s.radius)});
    cents.push_back(s.center);
  }
  const auto mesh_id = static_cast<std::uint32_t>(spheres.size());
  if (!mesh_box.empty()) {
    boxes.push_back(mesh_box);
    cents.push_back(0.5f * (mesh_box.lo + mesh_box.hi));
  }
  const auto first_instance = static_cast<std::uint32_t>(boxes.size());
  for (const MeshInstance& m : instances) {
    boxes.push_back(m.box);
    cents.push_back(0.5f * (m.box.lo + m.box.hi));
  }
  if (boxes.empty()) return;
  // Up to 16 objects per leaf (two 8-wide sphere blocks): the report's
  // scenes, 7 to 10 objects, are then a single leaf.
  const BinaryBvh bin = build_binary_sah(std::move(boxes), std::move(cents), 16);
  nodes_.reserve(bin.nodes.size());
  for (const BinaryNode& b : bin.nodes) {
    Node n;
    n.box = b.box;
    n.left = b.left;
    n.right = b.right;
    if (b.leaf()) {
      Leaf leaf;
      leaf.first_instance = static_cast<std::uint32_t>(instances_.size());
      std::vector<Sphere> ss;
      std::vector<std::uint32_t> ids;
      for (std::uint32_t k = b.first; k < b.first + b.count; ++k) {
        const std::uint32_t obj = bin.prims[k];
        if (obj >= first_instance) {
          instances_.push_back(instances[obj - first_instance]);
        } else if (obj == mesh_id) {
          leaf.mesh = true;
        } else {
          ss.push_back(spheres[obj]);
          ids.push_back(obj);
        }
      }
      leaf.instance_count = static_cast<std::uint32_t>(instances_.size()) - leaf.first_instance;
      leaf.spheres = SphereSet(ss, std::move(ids));
      n.leaf = static_cast<std::uint32_t>(leaves_.size());
      leaves_.push_back(std::move(leaf));
    }
    nodes_.push_back(n);
  }
}

bool ObjectBvh::intersect_leaf(const Leaf& leaf, const Ray& ray, Hit& hit, const Bvh* mesh) const {
  bool found = false;
  float t;
  std::uint32_t id;
  if (leaf.spheres.size() && leaf.spheres.intersect(ray, std::min(ray.tmax, hit.t), t, id)) {
    hit.t = t;
    hit.kind = PrimKind::Sphere;
    hit.prim = id;
    hit.instance = kNoSkip;
    found = true;
  }
  if (leaf.mesh && mesh && mesh->intersect(ray, hit)) {
    hit.instance = kNoSkip;
    found = true;
  }
  if (leaf.instance_count) [[unlikely]]
    found |= intersect_instances(leaf, ray, hit);
  return found;
}

// Out of line: the bundled scenes have no instances, and their rays' hot
// loop stays as small as it was.
[[gnu::noinline]] bool ObjectBvh::intersect_instances(const Leaf& leaf, const Ray& ray, Hit& hit) const {
  bool found = false;
  const vec3 inv = safe_inverse(ray.d);
  for (std::uint32_t k = leaf.first_instance; k < leaf.first_instance + leaf.instance_count; ++k) {
    const MeshInstance& m = instances_[k];
    if (box_entry(m.box, ray, inv, std::min(ray.tmax, hit.t)) == kInf) continue;
    if (m.bvh->intersect(m.to_local(ray), hit)) {
      hit.instance = m.id;
      found = true;
    }
  }
  return found;
}

[[gnu::noinline]] bool ObjectBvh::instances_occlude(const Leaf& leaf, const Ray& ray) const {
  const vec3 inv = safe_inverse(ray.d);
  for (std::uint32_t k = leaf.first_instance; k < leaf.first_instance + leaf.instance_count; ++k) {
    const MeshInstance& m = instances_[k];
    if (box_entry(m.box, ray, inv, ray.tmax) < kInf && m.bvh->occluded(m.to_local(ray))) return true;
  }
  return false;
}

unsigned ObjectBvh::intersect_batch(const Ray* const* rays, unsigned lanes, Hit* hits,
                                    const Bvh* mesh) const {
  unsigned found = 0;
  if (nodes_.size() != 1 || !leaves_[0].spheres.batchable()) {
    for (unsigned a = lanes; a; a &= a - 1) {
      const int l = __builtin_ctz(a);
      if (intersect(*rays[l], hits[l], mesh)) found |= 1u << l;
    }
    return found;
  }
  // intersect_leaf(), its sphere step for all the lanes first (bounded by
  // the rays' own tmax: the hits start as none).
  const Leaf& leaf = leaves_[0];
  float t[8];
  std::uint32_t id[8];
  found = leaf.spheres.intersect_batch(rays, lanes, t, id);
  for (unsigned a = found; a; a &= a - 1) {
    const int l = __builtin_ctz(a);
    hits[l].t = t[l];
    hits[l].kind = PrimKind::Sphere;
    hits[l].prim = id[l];
  }
  if (leaf.mesh && mesh)
    for (unsigned a = lanes; a; a &= a - 1) {
      const int l = __builtin_ctz(a);
      if (mesh->intersect(*rays[l], hits[l])) {
        hits[l].instance = kNoSkip;
        found |= 1u << l;
      }
    }
  if (leaf.instance_count)
    for (unsigned a = lanes; a; a &= a - 1) {
      const int l = __builtin_ctz(a);
      if (intersect_instances(leaf, *rays[l], hits[l])) found |= 1u << l;
    }
  return found;
}

bool ObjectBvh::intersect(const Ray& ray, Hit& hit, const Bvh* mesh) const {
  if (nodes_.empty()) return false;
  // A single leaf (every scene of the report): its exact tests are all the
  // culling there is; a box test in front would only cost.
  if (nodes_.size() == 1) return intersect_leaf(leaves_[0], ray, hit, mesh);
  const vec3 inv = safe_inverse(ray.d);
  bool found = false;
  struct Entry {
    std::uint32_t node;
    float t;  // where the ray enters the node's box
  };
  Entry stack[128];  // trivial, so not zeroed per ray; builder depth is at most 72
  int top = 0;
  const float t_root = box_entry(nodes_[0].box, ray, inv, ray.tmax);
  if (t_root == kInf) return false;
  stack[top++] = {0u, t_root};
  while (top > 0) {
    const auto [index, t_enter] = stack[--top];
    if (t_enter >= hit.t) continue;  // a closer hit was found since it was pushed
    const Node& n = nodes_[index];
    if (n.leaf != kInner) {
      found |= intersect_leaf(leaves_[n.leaf], ray, hit, mesh);
      continue;
    }
    // Nearer child on top of the stack, so it is opened first.
    const float tl = box_entry(nodes_[n.left].box, ray, inv, ray.tmax);
    const float tr = box_entry(nodes_[n.right].box, ray, inv, ray.tmax);
    const bool left_first = tl <= tr;
    const Entry a{left_first ? n.left : n.right, left_first ? tl : tr};
    const Entry b{left_first ? n.right : n.left, left_first ? tr : tl};
    if (b.t < hit.t) stack[top++] = b;
    if (a.t < hit.t) stack[top++] = a;
  }
  return found;
}

bool ObjectBvh::occluded_leaf(const Leaf& leaf, const Ray& ray, const Bvh* mesh,
                              std::uint32_t end_sphere) const {
  return (leaf.spheres.size() && leaf.spheres.occluded(ray, end_sphere)) ||
         (leaf.mesh && mesh && mesh->occluded(ray)) || (leaf.instance_count && instances_occlude(leaf, ray));
}

template <class Test>
bool ObjectBvh::any_leaf(const Ray& ray, Test&& test) const {
  if (nodes_.empty()) return false;
  if (nodes_.size() == 1) return test(leaves_[0]);
  const vec3 inv = safe_inverse(ray.d);
  std::uint32_t stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[stack[--top]];
    if (box_entry(n.box, ray, inv, ray.tmax) == kInf) continue;
    if (n.leaf != kInner) {
      if (test(leaves_[n.leaf])) return true;
      continue;
    }
    stack[top++] = n.left;
    stack[top++] = n.right;
  }
  return false;
}

bool ObjectBvh::occluded(const Ray& ray, const Bvh* mesh, std::uint32_t end_sphere) const {
  return any_leaf(ray, [&](const Leaf& leaf) { return occluded_leaf(leaf, ray, mesh, end_sphere); });
}

bool ObjectBvh::instance_occludes(const Ray& ray) const {
  return any_leaf(ray, [&](const Leaf& leaf) { return instances_occlude(leaf, ray); });
}

}  // namespace whisker
