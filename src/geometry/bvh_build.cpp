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

// --- Spatial splits (Stich, Friedrich, Dietrich, "Spatial Splits in Bounding
// Volume Hierarchies", HPG 2009): a node may also be cut by a plane through
// its triangles, each straddling triangle then referenced on both sides by
// the box of its part there (box.h, split_triangle). Tried where the best
// object split's children overlap by more than kAlpha of the root's area,
// and only in nodes of at least kMinSpatialRefs references (8 packets):
// below, the binning took most of the build time for no measured gain. 8
// spatial bins traced the cat's rays as fast as 32 (docs/PERFORMANCE.md).
constexpr int kSpatialBins = 8;
constexpr float kAlpha = 1e-5f;
constexpr std::uint32_t kMinSpatialRefs = 64;
static_assert(kSpatialBins <= kBins, "sweep() sizes its arrays by kBins");
// At most this many references per triangle in all (the paper's alpha alone
// bounds it on real meshes; this bounds it on any).
constexpr std::uint32_t kMaxRefsPerTriangle = 2;

struct Ref {
  Box3 box;  // of the part of the triangle this reference stands for
  std::uint32_t prim;
};

struct SplitBin {
  Box3 box;
  std::uint32_t enter = 0, exit = 0;  // references starting, ending here
};

struct Split {
  float cost = kInf;  // sum over the sides of A_side * leaf_cost(N_side)
  int axis = -1, bin = 0;
  bool spatial = false;
  Box3 left, right;
  std::uint32_t nl = 0, nr = 0;
};

// The cheapest plane between bins k and k + 1: references entering at or
// left of it against those leaving right of it. An object split must leave
// fewer on each side; a spatial one may keep all on both (each part in a
// smaller box), the references budget bounding that.
void sweep(const SplitBin* bins, int nbins, int axis, std::uint32_t total, bool spatial,
           Split& best) {
  Box3 right_box[kBins];
  std::uint32_t right_n[kBins];
  Box3 acc;
  std::uint32_t cnt = 0;
  for (int k = nbins - 1; k > 0; --k) {
    acc.grow(bins[k].box);
    cnt += bins[k].exit;
    right_box[k] = acc;
    right_n[k] = cnt;
  }
  acc = Box3{};
  cnt = 0;
  for (int k = 0; k < nbins - 1; ++k) {
    acc.grow(bins[k].box);
    cnt += bins[k].enter;
    const std::uint32_t nr = right_n[k + 1];
    if (cnt == 0 || nr == 0 || (!spatial && (cnt >= total || nr >= total))) continue;
    const float c = acc.half_area() * leaf_cost(cnt) + right_box[k + 1].half_area() * leaf_cost(nr);
    if (c < best.cost) best = Split{c, axis, k, spatial, acc, right_box[k + 1], cnt, nr};
  }
}

struct SpatialBuilder {
  const std::vector<Triangle>& tris;
  std::uint32_t max_leaf;
  float min_overlap = 0.0f;  // kAlpha * the root's area
  std::uint32_t budget = 0;  // references that may still be added
  BinaryBvh out;

  static vec3 centre(const Ref& r) { return 0.5f * (r.box.lo + r.box.hi); }

  void object_split(const std::vector<Ref>& refs, const Box3& cb, Split& best) const {
    for (int axis = 0; axis < 3; ++axis) {
      const float lo = cb.lo[axis], ext = cb.hi[axis] - lo;
      if (!(ext > 0.0f)) continue;
      const float scale = kBins / ext;
      SplitBin bins[kBins];
      for (const Ref& r : refs) {
        SplitBin& b = bins[std::min(kBins - 1, static_cast<int>((centre(r)[axis] - lo) * scale))];
        b.box.grow(r.box);
        ++b.enter;
        ++b.exit;
      }
      sweep(bins, kBins, axis, static_cast<std::uint32_t>(refs.size()), false, best);
    }
  }

  static float plane(const Box3& box, int axis, int k) {
    return box.lo[axis] + (box.hi[axis] - box.lo[axis]) * (float(k) / kSpatialBins);
  }

  void spatial_split(const std::vector<Ref>& refs, const Box3& box, Split& best) const {
    for (int axis = 0; axis < 3; ++axis) {
      const float lo = box.lo[axis], ext = box.hi[axis] - lo;
      if (!(ext > 0.0f)) continue;
      const float scale = kSpatialBins / ext;
      auto bin_of = [&](float x) {
        return std::clamp(static_cast<int>((x - lo) * scale), 0, kSpatialBins - 1);
      };
      SplitBin bins[kSpatialBins];
      for (const Ref& r : refs) {
        const int b0 = bin_of(r.box.lo[axis]), b1 = bin_of(r.box.hi[axis]);
        Box3 rest = r.box;
        for (int k = b0; k < b1; ++k) {
          Box3 part, right;
          split_triangle(tris[r.prim], rest, axis, plane(box, axis, k + 1), part, right);
          bins[k].box.grow(part);
          rest = right;
        }
        bins[b1].box.grow(rest);
        ++bins[b0].enter;
        ++bins[b1].exit;
      }
      sweep(bins, kSpatialBins, axis, static_cast<std::uint32_t>(refs.size()), true, best);
    }
  }

  // The references of a spatial split: those on one side go there; one
  // straddling the plane goes to both sides as its two parts, or whole to
  // one side when that is cheaper (the paper's reference unsplitting).
  void spatial_partition(std::vector<Ref>& refs, const Box3& box, const Split& s,
                         std::vector<Ref>& l, std::vector<Ref>& r) {
    const float p = plane(box, s.axis, s.bin + 1);
    const float al = s.left.half_area(), ar = s.right.half_area();
    const float nl = float(s.nl), nr = float(s.nr), both = al * nl + ar * nr;
    for (const Ref& x : refs) {
      if (x.box.hi[s.axis] <= p) {
        l.push_back(x);
      } else if (x.box.lo[s.axis] >= p) {
        r.push_back(x);
      } else {
        Box3 gl = s.left, gr = s.right;
        gl.grow(x.box);
        gr.grow(x.box);
        const float to_left = gl.half_area() * nl + ar * (nr - 1.0f);
        const float to_right = al * (nl - 1.0f) + gr.half_area() * nr;
        Box3 pl, pr;
        split_triangle(tris[x.prim], x.box, s.axis, p, pl, pr);
        if (pr.empty() || (to_left <= both && to_left <= to_right && !pl.empty())) {
          l.push_back(x);
        } else if (pl.empty() || to_right <= both) {
          r.push_back(x);
        } else if (budget > 0) {
          --budget;
          l.push_back({pl, x.prim});
          r.push_back({pr, x.prim});
        } else {
          (to_left <= to_right ? l : r).push_back(x);
        }
      }
    }
  }

  void object_partition(std::vector<Ref>& refs, const Box3& cb, const Split& s,
                        std::vector<Ref>& l, std::vector<Ref>& r) const {
    const float lo = cb.lo[s.axis], scale = kBins / (cb.hi[s.axis] - lo);
    for (const Ref& x : refs) {
      const int k = std::min(kBins - 1, static_cast<int>((centre(x)[s.axis] - lo) * scale));
      (k <= s.bin ? l : r).push_back(x);
    }
  }

  static void median_partition(std::vector<Ref>& refs, const Box3& cb, std::vector<Ref>& l,
                               std::vector<Ref>& r) {
    const vec3 ext = cb.hi - cb.lo;
    int axis = 0;
    if (ext.y > ext[axis]) axis = 1;
    if (ext.z > ext[axis]) axis = 2;
    const auto mid = refs.begin() + refs.size() / 2;
    std::nth_element(refs.begin(), mid, refs.end(), [&](const Ref& a, const Ref& b) {
      return centre(a)[axis] < centre(b)[axis];
    });
    l.assign(refs.begin(), mid);
    r.assign(mid, refs.end());
  }

  std::uint32_t build(std::vector<Ref>& refs, int depth) {
    Box3 box, cb;
    for (const Ref& x : refs) {
      box.grow(x.box);
      cb.grow(centre(x));
    }
    const auto node = static_cast<std::uint32_t>(out.nodes.size());
    const auto n = static_cast<std::uint32_t>(refs.size());
    out.nodes.push_back(BinaryNode{box, 0, 0, static_cast<std::uint32_t>(out.prims.size()), 0});
    Split best;
    if (n > 1 && depth < kMaxSahDepth) {
      object_split(refs, cb, best);
      Box3 overlap;
      overlap.lo = glm::max(best.left.lo, best.right.lo);
      overlap.hi = glm::min(best.left.hi, best.right.hi);
      if (n >= kMinSpatialRefs && budget >= n &&
          (best.axis < 0 || overlap.half_area() > min_overlap))
        spatial_split(refs, box, best);
    }
    const float area = box.half_area();
    const float split_cost = kCt + (area > 0.0f ? best.cost / area : 0.0f);
    if (n <= 1 || (n <= max_leaf && (best.axis < 0 || leaf_cost(n) <= split_cost))) {
      for (const Ref& x : refs) out.prims.push_back(x.prim);
      out.nodes[node].count = n;
      return node;
    }
    std::vector<Ref> l, r;
    if (best.axis >= 0 && best.spatial) spatial_partition(refs, box, best, l, r);
    if (best.axis >= 0 && !best.spatial) object_partition(refs, cb, best, l, r);
    if (l.empty() || r.empty() || (!best.spatial && (l.size() >= n || r.size() >= n))) {
      l.clear();
      r.clear();
      median_partition(refs, cb, l, r);
    }
    std::vector<Ref>().swap(refs);
    const std::uint32_t left = build(l, depth + 1);
    const std::uint32_t right = build(r, depth + 1);
    out.nodes[node].left = left;
    out.nodes[node].right = right;
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

BinaryBvh build_binary_sbvh(const std::vector<Triangle>& tris, std::uint32_t max_leaf) {
  if (tris.empty()) return {};
  SpatialBuilder b{tris, max_leaf, 0.0f, 0, {}};
  std::vector<Ref> refs(tris.size());
  Box3 root;
  for (std::size_t i = 0; i < tris.size(); ++i) {
    refs[i] = {bounds_of(tris[i]), static_cast<std::uint32_t>(i)};
    root.grow(refs[i].box);
  }
  b.min_overlap = kAlpha * root.half_area();
  b.budget = static_cast<std::uint32_t>(tris.size()) * (kMaxRefsPerTriangle - 1);
  b.out.nodes.reserve(4 * tris.size() + 1);
  b.out.prims.reserve(kMaxRefsPerTriangle * tris.size());
  b.build(refs, 0);
  return std::move(b.out);
}

BinaryBvh build_binary_midpoint(const std::vector<Triangle>& tris) {
  Builder b(tris);
  if (!tris.empty()) b.midpoint(0, static_cast<std::uint32_t>(tris.size()), 0);
  return std::move(b.out);
}

}  // namespace whisker
