// The 8-wide BVH, built: collapse of a binary tree into 8-wide nodes, and the
// packing of triangles into 8-lane packets. Traversal is in bvh_wide.cpp.
#include <cstring>

#include "geometry/bvh_build.h"
#include "geometry/bvh_wide.h"

namespace whisker {

namespace {

struct Collapser {
  const BinaryBvh& bin;
  const std::vector<Triangle>& tris;
  WideBvh out;

  std::uint32_t leaf_ref(const BinaryNode& n) {
    const std::uint32_t first = static_cast<std::uint32_t>(out.packets.size());
    const std::uint32_t count = (n.count + kWidth - 1) / kWidth;
    for (std::uint32_t p = 0; p < count; ++p) {
      TriPacket pk;
      std::memset(&pk, 0, sizeof pk);
      for (int lane = 0; lane < kWidth; ++lane) {
        const std::uint32_t i = p * kWidth + lane;
        if (i >= n.count) break;
        const std::uint32_t prim = bin.prims[n.first + i];
        const Triangle& t = tris[prim];
        const vec3* vs[3] = {&t.v0, &t.v1, &t.v2};
        for (int v = 0; v < 3; ++v)
          for (int a = 0; a < 3; ++a) pk.v[v][a][lane] = (*vs[v])[a];
        pk.prim[lane] = prim;
      }
      out.packets.push_back(pk);
    }
    return kLeafBit | ((count - 1) << 24) | first;
  }

  std::uint32_t node(std::uint32_t b) {
    const std::uint32_t idx = static_cast<std::uint32_t>(out.nodes.size());
    out.nodes.emplace_back();
    std::uint32_t kids[kWidth];
    int n = 0;
    if (bin.nodes[b].leaf()) {
      kids[n++] = b;
    } else {
      kids[n++] = bin.nodes[b].left;
      kids[n++] = bin.nodes[b].right;
    }
    while (n < kWidth) {
      int open = -1;
      float best = -1.0f;
      for (int i = 0; i < n; ++i) {
        const BinaryNode& k = bin.nodes[kids[i]];
        if (!k.leaf() && k.box.half_area() > best) {
          best = k.box.half_area();
          open = i;
        }
      }
      if (open < 0) break;
      const BinaryNode& k = bin.nodes[kids[open]];
      kids[open] = k.left;
      kids[n++] = k.right;
    }
    std::uint32_t refs[kWidth];
    for (int i = 0; i < n; ++i) {
      const BinaryNode& k = bin.nodes[kids[i]];
      refs[i] = k.leaf() ? leaf_ref(k) : node(kids[i]);
    }
    WideNode& w = out.nodes[idx];  // after the recursion: the vector may have grown
    for (int i = 0; i < kWidth; ++i) {
      const bool used = i < n;
      const Box3 box = used ? bin.nodes[kids[i]].box : Box3{};
      for (int a = 0; a < 3; ++a) {
        w.lo[a][i] = box.lo[a];
        w.hi[a][i] = box.hi[a];
      }
      w.child[i] = used ? refs[i] : kEmptyRef;
    }
    return idx;
  }
};

}  // namespace

WideBvh collapse_to_wide(const BinaryBvh& bin, const std::vector<Triangle>& tris) {
  Collapser c{bin, tris, {}};
  if (!bin.nodes.empty()) c.node(0);
  return std::move(c.out);
}

WideBvh packets_only(const std::vector<Triangle>& tris) {
  BinaryBvh bin;
  BinaryNode all;
  all.count = static_cast<std::uint32_t>(tris.size());
  for (std::uint32_t i = 0; i < all.count; ++i) bin.prims.push_back(i);
  Collapser c{bin, tris, {}};
  if (all.count > 0) c.leaf_ref(all);  // only its packets are kept
  return std::move(c.out);
}

}  // namespace whisker
