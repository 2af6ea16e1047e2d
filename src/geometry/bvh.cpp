// Bvh: the four selectable methods behind one interface (see bvh.h).
#include "geometry/bvh.h"

#include <chrono>
#include <cmath>

#include "geometry/bvh_build.h"

namespace whisker {
namespace {

// Leaves of the binary SAH tree hold at most one packet.
constexpr std::uint32_t kSahMaxLeaf = kWidth;

bool box_hit(const Box3& b, const Ray& ray, float tmax) {
  return box_entry(b, ray, safe_inverse(ray.d), tmax) < kInf;
}

// Exactly zero area: the edge cross product is zero. Products of floats are
// exact in double, so only exactly collinear vertices pass.
bool zero_area(const Triangle& t) {
  const glm::dvec3 a(t.v0), e1 = glm::dvec3(t.v1) - a, e2 = glm::dvec3(t.v2) - a;
  return e1.y * e2.z - e1.z * e2.y == 0.0 && e1.z * e2.x - e1.x * e2.z == 0.0 &&
         e1.x * e2.y - e1.y * e2.x == 0.0;
}

}  // namespace

Bvh Bvh::build(std::vector<Triangle> tris, BvhMethod method) {
  const auto start = std::chrono::steady_clock::now();
  Bvh b;
  b.method_ = method;
  b.tri_count_ = tris.size();
  // The shear of the watertight test rounds, so three distinct collinear
  // vertices can come out not quite collinear and be hit along their
  // segment. Stored as a point instead, such a triangle can never be hit
  // (all three edge functions are exactly zero), and keeps its index.
  for (Triangle& t : tris)
    if (zero_area(t)) t = Triangle{t.v0, t.v0, t.v0};
  switch (method) {
    case BvhMethod::Brute:
      b.wide_ = packets_only(tris);
      break;
    case BvhMethod::BBox:
      for (const Triangle& t : tris) b.box_.grow(bounds_of(t));
      b.wide_ = packets_only(tris);
      b.node_count_ = 1;
      break;
    case BvhMethod::Midpoint:
      // The report's method: its tree, collapsed greedily.
      b.wide_ = collapse_to_wide(build_binary_midpoint(tris), tris);
      b.node_count_ = b.wide_.nodes.size();
      break;
    case BvhMethod::Sah:
      // Binned SAH, then the SAH-optimal choice of each node's 8 children.
      b.wide_ = collapse_to_wide_sah(build_binary_sah(tris, kSahMaxLeaf), tris);
      b.node_count_ = b.wide_.nodes.size();
      break;
  }
  b.build_seconds_ =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return b;
}

bool Bvh::intersect(const Ray& ray, Hit& hit) const {
  if (method_ == BvhMethod::BBox && !box_hit(box_, ray, std::min(ray.tmax, hit.t))) return false;
  return wide_.intersect(ray, hit);
}

bool Bvh::occluded(const Ray& ray) const {
  if (method_ == BvhMethod::BBox && !box_hit(box_, ray, ray.tmax)) return false;
  return wide_.occluded(ray);
}

std::size_t Bvh::bytes() const {
  return wide_.nodes.size() * sizeof(WideNode) + wide_.packets.size() * sizeof(TriPacket);
}

}  // namespace whisker
