// The traversed structure: an 8-wide BVH with boxes and triangles laid out for
// AVX2 (one node tests 8 boxes at once, one packet tests 8 triangles at once).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "geometry/box.h"
#include "geometry/ray.h"
#include "geometry/triangle.h"

namespace whisker {

constexpr int kWidth = 8;  // children per node, triangles per packet

// 224 bytes of data in 256: boxes as [axis][child] so one load gets one slab
// of all 8 children. An unused slot has an inverted box (lo = +inf, hi =
// -inf), which the sign-selected slab test below never enters.
struct alignas(64) WideNode {
  float lo[3][kWidth];
  float hi[3][kWidth];
  // Child reference: an inner node index, or kLeafBit | (packets - 1) << 24 |
  // first packet.
  std::uint32_t child[kWidth];
};

constexpr std::uint32_t kLeafBit = 0x80000000u;
constexpr std::uint32_t kEmptyRef = 0xffffffffu;
constexpr std::uint32_t kMaxLeafPackets = 128;

// 8 triangles as vertex coordinates [vertex][axis][lane]; an unused lane is
// all zeros, a degenerate triangle the watertight test never hits.
struct alignas(32) TriPacket {
  float v[3][3][kWidth];
  std::uint32_t prim[kWidth];
};

struct WideBvh {
  std::vector<WideNode> nodes;  // nodes[0] is the root; none: brute force
  std::vector<TriPacket> packets;

  bool empty() const { return nodes.empty(); }
  // See Bvh::intersect and Bvh::occluded.
  bool intersect(const Ray& ray, Hit& hit) const;
  bool occluded(const Ray& ray) const;
};

// Whether any triangle of `count` packets meets `ray` in (tmin, tmax): the
// leaves' own test (WideBvh::occluded), for packets kept elsewhere (the
// light buffer, light_buffer.h).
bool occluded_by_packets(const Ray& ray, const TriPacket* packets, std::size_t count);

struct BinaryBvh;
// Collapses a binary tree into the 8-wide one: each wide node takes its
// binary node's children and keeps opening the largest-area inner one until
// it has 8 (Wald, Benthin, Boulos, "Getting rid of packets", RT 2008).
WideBvh collapse_to_wide(const BinaryBvh& bin, const std::vector<Triangle>& tris);
// The same by the SAH-optimal choice of the 8 children (bvh_collapse.cpp).
WideBvh collapse_to_wide_sah(const BinaryBvh& bin, const std::vector<Triangle>& tris);
// No tree: every triangle in packets, in their order (brute force).
WideBvh packets_only(const std::vector<Triangle>& tris);

}  // namespace whisker
