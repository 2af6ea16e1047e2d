#include "geometry/light_buffer.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace whisker {

namespace {

// How far a shadow ray's direction, or the direction its cell is looked up
// along (occluded()'s from_light), may be from the exact direction from its
// origin to the light, in radians: the difference, the square root and the
// division that make it round by a few float ULPs each (offset.h); 64 of
// them is several times that.
constexpr double kDirectionError = 64.0 * 0x1p-24;

// A cell's extent in the face's coordinates a, b in [-1, 1]: the rectangle
// [a0, a1] x [b0, b1] of cell indices.
struct CellRect {
  std::uint32_t tri;
  int face, a0, a1, b0, b1;
};

// The cell index along one face axis of coordinate x (NaN gives 0).
int cell_index(float x, int cells) {
  const float f = (x + 1.0f) * 0.5f * float(cells);
  return int(std::max(0.0f, std::min(f, float(cells - 1))));
}

// The part of the triangle v (corners relative to the light) in the
// directions of face `face`, widened to |a|, |b| <= w: its bounds in the
// face's coordinates, or false if it has none there. The triangle is clipped
// to the face's pyramid (Sutherland, Hodgman, "Reentrant polygon clipping",
// CACM 1974), four planes through the light, so every point left is in
// front of the light along the face's axis and projects to a bounded point.
// A clipped corner at the light itself gives NaN bounds: every cell.
bool face_extent(const glm::dvec3 (&v)[3], int face, double w, double& a0, double& a1,
                 double& b0, double& b1) {
  const int k = face / 2, i = (k + 1) % 3, j = (k + 2) % 3;
  const double sign = face % 2 ? -1.0 : 1.0;
  // Corners in the face's frame: (a-axis, b-axis, depth).
  glm::dvec3 poly[8], next[8];
  int n = 3;
  for (int q = 0; q < 3; ++q) poly[q] = glm::dvec3(v[q][i], v[q][j], sign * v[q][k]);
  // Inside: w z - x >= 0, w z + x >= 0, w z - y >= 0, w z + y >= 0.
  const glm::dvec3 planes[4] = {{-1, 0, w}, {1, 0, w}, {0, -1, w}, {0, 1, w}};
  for (const glm::dvec3& pl : planes) {
    int m = 0;
    for (int q = 0; q < n; ++q) {
      const glm::dvec3 &p = poly[q], &r = poly[(q + 1) % n];
      const double dp = glm::dot(pl, p), dr = glm::dot(pl, r);
      if (dp >= 0.0) next[m++] = p;
      if ((dp >= 0.0) != (dr >= 0.0)) next[m++] = p + (r - p) * (dp / (dp - dr));
    }
    n = m;
    if (n == 0) return false;
    std::copy(next, next + n, poly);
  }
  a0 = b0 = kInf;
  a1 = b1 = -kInf;
  for (int q = 0; q < n; ++q) {
    if (!(poly[q].z > 0.0)) {
      a0 = a1 = b0 = b1 = std::nan("");
      return true;
    }
    a0 = std::min(a0, poly[q].x / poly[q].z), a1 = std::max(a1, poly[q].x / poly[q].z);
    b0 = std::min(b0, poly[q].y / poly[q].z), b1 = std::max(b1, poly[q].y / poly[q].z);
  }
  return true;
}

}  // namespace

// Face 2k + s looks along +axis k (s = 0) or -axis k (s = 1); its
// coordinates are a = u[k+1] / |u[k]|, b = u[k+2] / |u[k]| (axes mod 3).
std::uint32_t LightBuffer::cell_of(const vec3& u) const {
  const float ax = std::fabs(u.x), ay = std::fabs(u.y), az = std::fabs(u.z);
  // The largest axis (the first of equals) from a table, not branches: the
  // directions of successive shadow rays are all over the sphere.
  static constexpr std::int8_t kAxis[8] = {2, 2, 1, 0, 1, 2, 1, 0};
  const int k = kAxis[(ax >= ay) | (ax >= az) << 1 | (ay >= az) << 2];
  const float c[5] = {u.x, u.y, u.z, u.x, u.y};
  const float inv = 1.0f / std::fabs(c[k]);
  const int face = 2 * k + (c[k] < 0.0f ? 1 : 0);
  const int a = cell_index(c[k + 1] * inv, cells_);
  const int b = cell_index(c[k + 2] * inv, cells_);
  return std::uint32_t((face * cells_ + a) * cells_ + b);
}

LightBuffer::LightBuffer(const vec3& light, const std::vector<Triangle>& tris, float reach,
                         int cells)
    : cells_(cells), reach_(reach) {
  const glm::dvec3 L(light);
  std::vector<CellRect> rects;
  for (std::uint32_t t = 0; t < tris.size(); ++t) {
    const glm::dvec3 v[3] = {glm::dvec3(tris[t].v0) - L, glm::dvec3(tris[t].v1) - L,
                             glm::dvec3(tris[t].v2) - L};
    // The triangle lies at least s from the light (its centroid's distance
    // less the farthest corner's from the centroid).
    const glm::dvec3 c = (v[0] + v[1] + v[2]) / 3.0;
    const double spread = std::max({glm::length(v[0] - c), glm::length(v[1] - c), glm::length(v[2] - c)});
    const double s = glm::length(c) - spread;
    // A shadow ray from distance d <= reach whose direction is off by e
    // passes a point at distance s from the light up to e (1 + d / s) off
    // the direction from the light; in a face's coordinates that moves
    // by at most 1 + a^2 + b^2 <= 3 times as much. The margin covers it,
    // and the cell lookup's own two roundings.
    const double angle = s > 0.0 ? kDirectionError * (1.0 + 1.001 * double(reach) / s) : kInf;
    const double margin = 4.0 * angle + 1e-5;
    for (int face = 0; face < 6; ++face) {
      CellRect r{t, face, 0, cells - 1, 0, cells - 1};
      if (margin < 0.5) {
        double a0, a1, b0, b1;
        if (!face_extent(v, face, 1.0 + 2.0 * margin, a0, a1, b0, b1)) continue;
        if (a0 == a0) {  // NaN: through the light, every direction of the face
          r.a0 = cell_index(float(a0 - margin), cells);
          r.a1 = cell_index(float(a1 + margin), cells);
          r.b0 = cell_index(float(b0 - margin), cells);
          r.b1 = cell_index(float(b1 + margin), cells);
        }
      }
      rects.push_back(r);
    }
  }
  // Each cell's triangles, then its packets of eight. Counted from the
  // rectangles first: past 16 entries a triangle, or 64 MB of packets, the
  // buffer is given up before a cell is filled (a mesh hugging the light
  // would otherwise fill every cell of every face with every triangle).
  const std::size_t count = std::size_t(6) * std::size_t(cells) * std::size_t(cells);
  std::size_t entries = 0;
  for (const CellRect& r : rects) entries += std::size_t(r.a1 - r.a0 + 1) * std::size_t(r.b1 - r.b0 + 1);
  const std::size_t packets_at_most = entries / kWidth + std::min(entries, count);
  if (entries > 16 * tris.size() || packets_at_most > (std::size_t(64) << 20) / sizeof(TriPacket)) {
    reach_ = -1.0f;
    return;
  }
  std::vector<std::uint32_t> n(count + 1, 0);
  for (const CellRect& r : rects)
    for (int a = r.a0; a <= r.a1; ++a)
      for (int b = r.b0; b <= r.b1; ++b) ++n[std::size_t((r.face * cells + a) * cells + b)];
  std::vector<std::uint32_t> start(count + 1, 0);
  for (std::size_t c = 0; c < count; ++c) start[c + 1] = start[c] + n[c];
  std::vector<std::uint32_t> ids(start[count]);
  std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
  for (const CellRect& r : rects)
    for (int a = r.a0; a <= r.a1; ++a)
      for (int b = r.b0; b <= r.b1; ++b) ids[fill[std::size_t((r.face * cells + a) * cells + b)]++] = r.tri;
  first_.assign(count + 1, 0);
  occupied_.assign((count + 63) / 64, 0);
  for (std::size_t c = 0; c < count; ++c) {
    const std::uint32_t len = start[c + 1] - start[c];
    first_[c + 1] = first_[c] + (len + kWidth - 1) / kWidth;
    if (len) occupied_[c / 64] |= std::uint64_t(1) << (c % 64);
  }
  packets_.assign(first_[count], TriPacket{});
  for (std::size_t c = 0; c < count; ++c) {
    for (std::uint32_t e = 0; e < start[c + 1] - start[c]; ++e) {
      TriPacket& p = packets_[first_[c] + e / kWidth];
      const std::uint32_t lane = e % kWidth, t = ids[start[c] + e];
      const vec3 corner[3] = {tris[t].v0, tris[t].v1, tris[t].v2};
      for (int q = 0; q < 3; ++q)
        for (int axis = 0; axis < 3; ++axis) p.v[q][axis][lane] = corner[q][axis];
      p.prim[lane] = t;
    }
  }
}

}  // namespace whisker
