// Light vertex cache: the light paths of light connections
// (render/light_connect.h) traced once per sample number and shared by every
// pixel's vertices of that sample, instead of one light ray per vertex
// (Davidovic, Krivanek, Hasan, Slusallek, "Progressive Light Transport
// Simulation on the GPU: Survey and Improvements", TOG 2014, section 5.1).
//
// The cache of sample s holds the first hits of kPaths light paths leaving
// the point light in stratified directions uniform on the sphere (strata of
// equal area, one jittered direction each), so an entry picked uniformly is
// a light path's hit with the light path's density p_l. A vertex x that
// carries the colour channels c picks uniformly among the M_c entries whose
// albedo shares a channel with c (the others would bring nothing) and weighs
// it by M_c / M: the mean over its pick is (1/M) sum over all entries, whose
// mean over the cache is the light path's estimate, so each pixel stays
// unbiased. In the balance heuristic the light paths' density is taken as
// p_l M / M_c for x's channels, in the bounces' weights and the picked
// entry's alike, so the weights of a path still sum to 1 (Veach 1997, 9.2.2).
//
// A vertex on a sphere, reached from outside it, also leaves out the entries
// on that sphere: every point of a sphere lies on or below the tangent plane
// at another, so none of them can be connected to it, and none of its
// bounces can reach one. It picks among the M_c' entries left and weighs by
// M_c' / M; with p_l M / M_c' in the balance heuristic for it and its
// bounces, the weights of each of its paths still sum to 1, and the picks
// the zero connections took go to entries that can bring light.
//
// The caches of different samples are independent, so the error they share
// across pixels falls with the samples like any other.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "scene/world.h"

namespace whisker {

// A light path's first hit, diffuse and lit, in one cache line (a
// connection reads one entry at random): the point and what a segment
// ending there needs of its hit record (geometry/surface_point.h), its
// geometric normal turned to the light's side, albedo, the light's weight
// there (direct_light.h) and pi times the light path's area density there,
// cos_l / (4 d^2).
struct alignas(64) CachedLightVertex {
  vec3 p{0.0f};
  vec3 err{0.0f};  // the record's err (a triangle's rounding bound)
  vec3 ng{0.0f};   // geometric normal, on the light's side
  vec3 albedo{0.0f};
  float weight = 0.0f;
  float B = 0.0f;
  std::uint32_t sphere = kNoSkip;  // the sphere hit, or kNoSkip for a triangle
  // Bit 0: the sphere's outward normal is -ng (the light shines on its
  // inside); bit 1: the record's normal is -ng.
  std::uint32_t flags = 0;

  vec3 outward() const { return flags & 1u ? -ng : ng; }
  vec3 record_ng() const { return flags & 2u ? -ng : ng; }
};
static_assert(sizeof(CachedLightVertex) == 64);

// The colour channels a throughput still carries, as bits r = 1, g = 2, b = 4.
inline unsigned channel_bits(const vec3& c) {
  return (c.x != 0.0f ? 1u : 0u) | (c.y != 0.0f ? 2u : 0u) | (c.z != 0.0f ? 4u : 0u);
}

class LightCache {
 public:
  static constexpr int kSide = 64;  // strata per side of the unit square
  static constexpr int kPaths = kSide * kSide;
  // Spheres whose entries a pick can leave out: those numbered below this
  // (a run per sphere and channel set; the room's walls come first).
  static constexpr std::uint32_t kRunSpheres = 256;

  LightCache() = default;
  // Traces the cache of sample `sample` (its directions depend only on the
  // seed and the sample number). Counts its rays in `rays`.
  void build(const World& world, const RenderSettings& settings, std::uint64_t sample,
             std::uint64_t& rays);

  // The entry picked by u in [0, 1) among those that share a channel with
  // `channels` and do not lie on sphere `exclude` (kNoSkip: leave none
  // out), or nullptr if there is none.
  const CachedLightVertex* pick(unsigned channels, float u, std::uint32_t exclude = kNoSkip) const {
    const std::vector<std::uint32_t>& list = lists_[channels & 7u];
    const Run r = run(channels, exclude);
    const std::size_t n = list.size() - r.count;
    if (n == 0) return nullptr;
    std::size_t k = std::min(n - 1, std::size_t(u * float(n)));
    if (k >= r.start) k += r.count;  // past the left-out run
    return &entries_[list[k]];
  }
  // M / M_c' for `channels` and `exclude` (0 when no entry is left: then
  // light paths make none of that vertex's paths).
  float density_scale(unsigned channels, std::uint32_t exclude = kNoSkip) const {
    const std::vector<Run>& runs = runs_[channels & 7u];
    return exclude < runs.size() ? runs[exclude].scale : scale_[channels & 7u];
  }

 private:
  // The entries of one sphere in a channel list: where they start, how
  // many, and M / M_c' with them left out.
  struct Run {
    std::uint32_t start = 0, count = 0;
    float scale = 0.0f;
  };
  Run run(unsigned channels, std::uint32_t exclude) const {
    const std::vector<Run>& runs = runs_[channels & 7u];
    return exclude < runs.size() ? runs[exclude] : Run{};
  }
  std::vector<CachedLightVertex> entries_;
  // Per channel set, the entries sharing one of its channels, grouped by
  // the sphere they lie on (in sphere order, triangles last; within a
  // group in the order of their strata), and each sphere's run.
  std::vector<std::uint32_t> lists_[8];
  std::vector<Run> runs_[8];
  float scale_[8] = {};
};

}  // namespace whisker
