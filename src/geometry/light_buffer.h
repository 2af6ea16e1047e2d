// The light buffer (Haines, Greenberg, "The Light Buffer: A Shadow-Testing
// Accelerator", IEEE CG&A 1986): a cube of direction cells around the point
// light, each listing the triangles seen from the light in its directions.
// A shadow ray ends at the light, so all of it lies (to rounding) along one
// direction from the light: only its cell's triangles can stop it. In the
// report's room most shadow rays' cells are empty, and a ray near the cat
// tests a few packets in place of a walk down the tree.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "geometry/bvh_wide.h"
#include "geometry/ray.h"
#include "geometry/triangle.h"

namespace whisker {

class LightBuffer {
 public:
  LightBuffer() = default;
  // For the point light at `light`, over `tris`, for shadow rays of length at
  // most `reach` (their rounding, which the cells' margins cover, grows with
  // it). `cells`: the cube's faces are cells x cells. Triangles that pass
  // through the light, or lie so near it that the margins reach half a
  // face, go to every cell of a face; where the lists would hold more than
  // 16 entries a triangle, or the packets take more than 64 MB, none is
  // kept (covers() then answers false for every ray, and the tree answers).
  LightBuffer(const vec3& light, const std::vector<Triangle>& tris, float reach, int cells);

  // Whether occluded() answers for `ray`, a shadow ray aimed at the light.
  bool covers(const Ray& ray) const { return ray.tmax <= reach_; }
  // Whether a triangle meets `ray` in (tmin, tmax): the same answer as the
  // tree's (WideBvh::occluded), the same test on a superset of the triangles
  // the ray can meet. `ray`: a shadow ray aimed at the light, within reach;
  // `from_light`: its cell's direction, the difference of the point it
  // starts from and the light (any length; -ray.d serves too). The
  // difference is known a square root and a division before ray.d, and the
  // occupancy branch below waits on it.
  bool occluded(const Ray& ray, const vec3& from_light) const {
    const std::uint32_t c = cell_of(from_light);
    // Most cells are empty: a bit each (12 KB for the cat's 6 x 125^2) says
    // so without reading the larger index.
    if (!(occupied_[c >> 6] >> (c & 63) & 1u)) return false;
    return occluded_by_packets(ray, packets_.data() + first_[c], first_[c + 1] - first_[c]);
  }

  // The cell of direction u (from the light), 0 to 6 cells^2 - 1.
  std::uint32_t cell_of(const vec3& u) const;
  bool empty() const { return first_.empty(); }
  std::size_t packet_count() const { return packets_.size(); }

 private:
  int cells_ = 0;
  float reach_ = -1.0f;  // none built (or given up): covers no ray
  std::vector<std::uint64_t> occupied_;  // bit c: cell c has triangles
  std::vector<std::uint32_t> first_;     // per cell, its first packet; one more at the end
  std::vector<TriPacket> packets_;
};

}  // namespace whisker
