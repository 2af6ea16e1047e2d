// The 8-wide BVH, built: collapse of a binary tree into 8-wide nodes, and the
// packing of triangles into 8-lane packets. Traversal is in bvh_wide.cpp.
#include <algorithm>
#include <array>
#include <cstring>

#include "geometry/bvh_build.h"
#include "geometry/bvh_wide.h"

namespace whisker {

namespace {

// SAH costs of the optimal collapse, per unit of half area: a wide node
// visit against one packet test (docs/PERFORMANCE.md: a flat optimum on the
// cat's ray files), and the most packets of a leaf made
// from an inner binary node.
constexpr float kNodeCost = 0.5f;
constexpr float kPacketCost = 1.0f;
constexpr std::uint32_t kDpMaxLeafPackets = 4;

struct Collapser {
  const BinaryBvh& bin;
  const std::vector<Triangle>& tris;
  WideBvh out;

  std::uint32_t leaf_ref(const BinaryNode& n) { return leaf_ref(n.first, n.count); }
  // Packets of prims[b, b + n) (a subtree's triangles are contiguous there).
  std::uint32_t leaf_ref(std::uint32_t b, std::uint32_t n) {
    const std::uint32_t first = static_cast<std::uint32_t>(out.packets.size());
    const std::uint32_t count = (n + kWidth - 1) / kWidth;
    for (std::uint32_t p = 0; p < count; ++p) {
      TriPacket pk;
      std::memset(&pk, 0, sizeof pk);
      for (int lane = 0; lane < kWidth; ++lane) {
        const std::uint32_t i = p * kWidth + lane;
        if (i >= n) break;
        const std::uint32_t prim = bin.prims[b + i];
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
    fill(idx, kids, refs, n);
    return idx;
  }

  void fill(std::uint32_t idx, const std::uint32_t* kids, const std::uint32_t* refs, int n) {
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
  }
};

// The SAH-optimal collapse (Ylitie, Karras, Laine, "Efficient Incoherent Ray
// Traversal on GPUs Through Compressed Wide BVHs", HPG 2017, section 3):
// cost[n][j] is the least SAH cost of binary subtree n given as at most j
// subtrees (wide children), each a leaf or a wide node:
//   cost[n][1] = min(leaf: kPacketCost A(n) packets(n),
//                    node: kNodeCost A(n) + dist(n, 8)),
//   cost[n][j] = min(cost[n][j - 1], dist(n, j)),
//   dist(n, j) = min over k of cost[left][k] + cost[right][j - k].
struct SahCollapse {
  Collapser& c;
  std::vector<std::array<float, kWidth + 1>> cost;
  // how[n][j]: j = 1: 1 for a wide node, 0 for a leaf; j > 1: the slots
  // given to the left child, 0 when cost[n][j] = cost[n][j - 1].
  // how[n][0]: the left child's slots of dist(n, 8).
  std::vector<std::array<std::int8_t, kWidth + 1>> how;
  std::vector<std::uint32_t> count;  // triangles under n

  float dist(std::uint32_t n, int j, std::int8_t& k_best) const {
    const BinaryNode& b = c.bin.nodes[n];
    float best = kInf;
    for (int k = 1; k < j; ++k) {
      const float x = cost[b.left][k] + cost[b.right][j - k];
      if (x < best) {
        best = x;
        k_best = static_cast<std::int8_t>(k);
      }
    }
    return best;
  }

  void tables() {
    const std::size_t m = c.bin.nodes.size();
    cost.resize(m);
    how.assign(m, {});
    count.resize(m);
    for (std::size_t i = m; i-- > 0;) {  // children come after their parent
      const BinaryNode& b = c.bin.nodes[i];
      const float area = std::max(b.box.half_area(), 1e-30f);
      count[i] = b.leaf() ? b.count : count[b.left] + count[b.right];
      const std::uint32_t packets = (count[i] + kWidth - 1) / kWidth;
      const bool may_be_leaf = b.leaf() || packets <= kDpMaxLeafPackets;
      const float leaf = may_be_leaf ? kPacketCost * area * packets : kInf;
      cost[i].fill(leaf);
      if (b.leaf()) continue;
      const float node = kNodeCost * area + dist(static_cast<std::uint32_t>(i), kWidth, how[i][0]);
      if (node < leaf) {
        cost[i][1] = node;
        how[i][1] = 1;
      }
      for (int j = 2; j <= kWidth; ++j) {
        std::int8_t k = 0;
        const float d = dist(static_cast<std::uint32_t>(i), j, k);
        cost[i][j] = cost[i][j - 1];
        if (d < cost[i][j]) {
          cost[i][j] = d;
          how[i][j] = k;
        }
      }
    }
  }

  void gather(std::uint32_t n, int j, std::uint32_t* kids, int& k) const {
    while (j > 1 && how[n][j] == 0) --j;
    if (j == 1) {
      kids[k++] = n;
      return;
    }
    const BinaryNode& b = c.bin.nodes[n];
    gather(b.left, how[n][j], kids, k);
    gather(b.right, j - how[n][j], kids, k);
  }

  std::uint32_t ref(std::uint32_t n) {
    if (how[n][1] == 0) return c.leaf_ref(c.bin.nodes[n].first, count[n]);
    const std::uint32_t idx = static_cast<std::uint32_t>(c.out.nodes.size());
    c.out.nodes.emplace_back();
    std::uint32_t kids[kWidth];
    int k = 0;
    const BinaryNode& b = c.bin.nodes[n];
    gather(b.left, how[n][0], kids, k);
    gather(b.right, kWidth - how[n][0], kids, k);
    std::uint32_t refs[kWidth];
    for (int i = 0; i < k; ++i) refs[i] = ref(kids[i]);
    c.fill(idx, kids, refs, k);
    return idx;
  }

  void root() {
    tables();
    if (how[0][1] == 1) {
      ref(0);
      return;
    }
    // The whole mesh is one leaf: a root with that one child.
    c.out.nodes.emplace_back();
    const std::uint32_t kid = 0, r = c.leaf_ref(c.bin.nodes[0].first, count[0]);
    c.fill(0, &kid, &r, 1);
  }
};

}  // namespace

WideBvh collapse_to_wide(const BinaryBvh& bin, const std::vector<Triangle>& tris) {
  Collapser c{bin, tris, {}};
  if (!bin.nodes.empty()) c.node(0);
  return std::move(c.out);
}

WideBvh collapse_to_wide_sah(const BinaryBvh& bin, const std::vector<Triangle>& tris) {
  Collapser c{bin, tris, {}};
  if (!bin.nodes.empty()) SahCollapse{c, {}, {}, {}}.root();
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
