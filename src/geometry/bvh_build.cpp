// Binary BVH builders (see bvh_build.h).
#include "geometry/bvh_build.h"

#include <algorithm>

namespace whisker {
namespace {

constexpr int kBins = 32;
// Past this depth a split is forced to the median, so the tree depth (and the
// traversal stack) stays bounded whatever the input: at most 40 + 32 levels.
constexpr int kMaxSahDepth = 40;

// Costs in units of one 8-triangle packet test, which costs the same for 1
// or 8 triangles (the leaf cost of Embree's SAH builders for its
// N-triangle leaves); a binary split costs about two packet tests, since a
// wide node visit stands for about three binary levels. Tuned on the cat's
// ray files (docs/PERFORMANCE.md).
constexpr float kCt = 2.0f;
inline float leaf_cost(std::uint32_t n) { return static_cast<float>((n + kWidth - 1) / kWidth); }

struct Builder {
  std::vector<Box3> boxes;
  std::vector<vec3> cents;
  BinaryBvh out;

  Builder(std::vector<Box3> bx, std::vector<vec3> cs) : boxes(std::move(bx)), cents(std::move(cs)) {
    out.prims.resize(boxes.size());
    for (std::size_t i = 0; i < boxes.size(); ++i) out.prims[i] = static_cast<std::uint32_t>(i);
    out.nodes.reserve(2 * boxes.size() + 1);
  }

  explicit Builder(const std::vector<Triangle>& tris) {
    boxes.reserve(tris.size());
    cents.reserve(tris.size());
    out.prims.resize(tris.size());
    for (std::size_t i = 0; i < tris.size(); ++i) {
      boxes.push_back(bounds_of(tris[i]));
      cents.push_back((tris[i].v0 + tris[i].v1 + tris[i].v2) * (1.0f / 3.0f));
      out.prims[i] = static_cast<std::uint32_t>(i);
    }
    out.nodes.reserve(2 * tris.size() + 1);
  }

  std::uint32_t new_node(std::uint32_t b, std::uint32_t e, Box3* cb) {
    Box3 box;
    for (std::uint32_t i = b; i < e; ++i) {
      box.grow(boxes[out.prims[i]]);
      if (cb) cb->grow(cents[out.prims[i]]);
    }
    out.nodes.push_back(BinaryNode{box, 0, 0, b, 0});
    return static_cast<std::uint32_t>(out.nodes.size() - 1);
  }

  void make_leaf(std::uint32_t node, std::uint32_t b, std::uint32_t e) {
    out.nodes[node].first = b;
    out.nodes[node].count = e - b;
  }

  void median_split(std::uint32_t b, std::uint32_t e, int axis, std::uint32_t& mid) {
    mid = b + (e - b) / 2;
    std::nth_element(out.prims.begin() + b, out.prims.begin() + mid, out.prims.begin() + e,
                     [&](std::uint32_t x, std::uint32_t y) { return cents[x][axis] < cents[y][axis]; });
  }

  template <class Split>
  void children(std::uint32_t node, std::uint32_t b, std::uint32_t mid, std::uint32_t e,
                int depth, Split split) {
    const std::uint32_t l = split(b, mid, depth + 1);
    const std::uint32_t r = split(mid, e, depth + 1);
    out.nodes[node].left = l;
    out.nodes[node].right = r;
  }

  std::uint32_t sah(std::uint32_t b, std::uint32_t e, int depth, std::uint32_t max_leaf) {
    Box3 cb;
    const std::uint32_t node = new_node(b, e, &cb);
    const std::uint32_t n = e - b;
    if (n <= 1) {
      make_leaf(node, b, e);
      return node;
    }
    // A split costs kCt + sum(A_side / A * leaf_cost(N_side)).
    float best = kInf;
    int best_axis = -1, best_bin = 0;
    if (depth < kMaxSahDepth) {
      for (int axis = 0; axis < 3; ++axis) {
        const float lo = cb.lo[axis], ext = cb.hi[axis] - cb.lo[axis];
        if (!(ext > 0.0f)) continue;
        const float scale = kBins / ext;
        Box3 bin_box[kBins];
        std::uint32_t bin_n[kBins] = {};
        for (std::uint32_t i = b; i < e; ++i) {
          const std::uint32_t p = out.prims[i];
          const int k = std::min(kBins - 1, static_cast<int>((cents[p][axis] - lo) * scale));
          bin_box[k].grow(boxes[p]);
          ++bin_n[k];
        }
        float right_cost[kBins];
        Box3 acc;
        std::uint32_t cnt = 0;
        for (int k = kBins - 1; k > 0; --k) {
          acc.grow(bin_box[k]);
          cnt += bin_n[k];
          right_cost[k] = acc.half_area() * leaf_cost(cnt);
        }
        acc = Box3{};
        cnt = 0;
        for (int k = 0; k < kBins - 1; ++k) {
          acc.grow(bin_box[k]);
          cnt += bin_n[k];
          if (cnt == 0 || cnt == n) continue;
          const float c = acc.half_area() * leaf_cost(cnt) + right_cost[k + 1];
          if (c < best) {
            best = c;
            best_axis = axis;
            best_bin = k;
          }
        }
      }
    }
    const float area = out.nodes[node].box.half_area();
    const float split_cost = kCt + (area > 0.0f ? best / area : 0.0f);
    if (n <= max_leaf && (best_axis < 0 || leaf_cost(n) <= split_cost)) {
      make_leaf(node, b, e);
      return node;
    }
    std::uint32_t mid;
    if (best_axis < 0) {
      // No useful plane (all centroids equal, or too deep): halve.
      int axis = 0;
      const vec3 ext = cb.hi - cb.lo;
      if (ext.y > ext[axis]) axis = 1;
      if (ext.z > ext[axis]) axis = 2;
      median_split(b, e, axis, mid);
    } else {
      const float lo = cb.lo[best_axis], scale = kBins / (cb.hi[best_axis] - lo);
      auto it = std::partition(out.prims.begin() + b, out.prims.begin() + e, [&](std::uint32_t p) {
        return std::min(kBins - 1, static_cast<int>((cents[p][best_axis] - lo) * scale)) <= best_bin;
      });
      mid = static_cast<std::uint32_t>(it - out.prims.begin());
    }
    children(node, b, mid, e, depth, [&](std::uint32_t x, std::uint32_t y, int d) {
      return sah(x, y, d, max_leaf);
    });
    return node;
  }

  std::uint32_t midpoint(std::uint32_t b, std::uint32_t e, int depth) {
    const std::uint32_t node = new_node(b, e, nullptr);
    const std::uint32_t n = e - b;
    if (n < 5) {
      make_leaf(node, b, e);
      return node;
    }
    const Box3 box = out.nodes[node].box;
    const vec3 ext = box.hi - box.lo;
    int axis = 0;
    if (ext.y > ext[axis]) axis = 1;
    if (ext.z > ext[axis]) axis = 2;
    const float m = 0.5f * (box.lo[axis] + box.hi[axis]);
    auto it = std::partition(out.prims.begin() + b, out.prims.begin() + e,
                             [&](std::uint32_t p) { return cents[p][axis] < m; });
    std::uint32_t mid = static_cast<std::uint32_t>(it - out.prims.begin());
    if (mid == b || mid == e || depth >= kMaxSahDepth) {
      // The report stops here; a huge leaf would be too slow (and too big
      // for a leaf reference), so those are halved instead.
      if (n <= 64 && depth < kMaxSahDepth) {
        make_leaf(node, b, e);
        return node;
      }
      median_split(b, e, axis, mid);
    }
    children(node, b, mid, e, depth, [&](std::uint32_t x, std::uint32_t y, int d) {
      return midpoint(x, y, d);
    });
    return node;
  }
};

}  // namespace

BinaryBvh build_binary_sah(const std::vector<Triangle>& tris, std::uint32_t max_leaf) {
  Builder b(tris);
  if (!tris.empty()) b.sah(0, static_cast<std::uint32_t>(tris.size()), 0, max_leaf);
  return std::move(b.out);
}

BinaryBvh build_binary_sah(std::vector<Box3> boxes, std::vector<vec3> centroids,
                           std::uint32_t max_leaf) {
  const auto n = static_cast<std::uint32_t>(boxes.size());
  Builder b(std::move(boxes), std::move(centroids));
  if (n > 0) b.sah(0, n, 0, max_leaf);
  return std::move(b.out);
}

BinaryBvh build_binary_midpoint(const std::vector<Triangle>& tris) {
  Builder b(tris);
  if (!tris.empty()) b.midpoint(0, static_cast<std::uint32_t>(tris.size()), 0);
  return std::move(b.out);
}

}  // namespace whisker
