// The report's estimator: camera paths of up to max_depth bounces with direct
// light from the point light at every diffuse hit, mirror, glass with optional
// Fresnel, and cosine-sampled indirect light, split at the first diffuse hits
// (RenderSettings::split). Its parts: scattering.h (mirror, glass and the
// cosine bounce), direct_light.h and light_connect.h.
#pragma once

#include <cstdint>
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <span>

#include <xmmintrin.h>

#include "render/camera.h"
#include "render/film.h"
#include "render/light_cache.h"
#include "render/sampler.h"
#include "render/scattering.h"
#include "scene/scene.h"
#include "scene/world.h"

namespace whisker {

struct PathStats {
  std::uint64_t rays = 0;  // intersection and shadow rays traced
};

// What every path of a render shares: the compiled scene, the settings and
// the counters (one per thread). Samplers are per path (splitting branches
// them), so they travel beside it.
class LightCache;
struct Features;
struct PathContext {
  const World& world;
  const RenderSettings& settings;
  PathStats& stats;
  // The light paths of this sample's connections (light_cache.h), or null:
  // then no connection is made (light_connect.h).
  const LightCache* lights = nullptr;
};

// A pixel: row i from the top, column j.
struct Pixel {
  int i = 0, j = 0;
};

// The diffuse vertex a path's ray departed from, where a light path was
// sent too (render/light_connect.h): the cosine of the ray with the facing
// shading normal there (0: no light path can make this bounce) and how many
// cosine bounces left it.
struct Departure {
  float cos = 0.0f;
  float count = 0.0f;
  float light_scale = 1.0f;  // light paths' density factor (light_cache.h: M / M_c)
};

// A path's state where it continues: the ray it follows (render space), its
// throughput so far, the hits before it (`depth`), how many were diffuse,
// and the light it has gathered; `from`, the diffuse vertex the ray left.
// With `features` (Features{} on entry), the path writes there the
// denoiser's features of its first diffuse hit (render/features.h).
struct PathState {
  Ray ray;
  vec3 beta{1.0f};
  int depth = 0;
  int diffuse_hits = 0;
  vec3 L{0.0f};
  Features* features = nullptr;
  Departure from{};
};

// The numbers of pixel px's sample number `sample`: the one place a pixel's
// sampler is made, whichever estimator draws from it.
inline Sampler pixel_sampler(const RenderSettings& s, const CameraFrame& cam, Pixel px,
                             std::uint64_t sample) {
  return Sampler(s.sampler, cam.pixel_index(px.i, px.j), sample, s.seed);
}

// One sample of pixel px: the camera ray (with the AA jitter, camera.h) and
// its radiance (the world's light intensity applied), with at most
// settings.max_depth hits after the first.
vec3 sample_pixel(const PathContext& ctx, const CameraFrame& cam, Pixel px, Sampler& sampler);

// ---- the path loop's parts ------------------------------------------------

// Pixel px's camera ray in render space, jittered when AA is on.
Ray camera_ray(const PathContext& ctx, const CameraFrame& cam, Pixel px, Sampler& sampler);
// The paths of up to 8 samples side by side, at the camera (out[l] for
// px[l], samplers[l]): each sampler draws the same numbers, and each ray is
// the same bit for bit, as camera_ray() (which is this for one sample)
// makes alone. Written into the path states themselves: a ray copied in
// right after it was made waited on the stores that made it.
void camera_paths(const PathContext& ctx, const CameraFrame& cam, std::span<const Pixel> px,
                  Sampler* samplers, PathState* out);

// The light a path gathers from `state` on; the state is advanced in place
// (taken by reference: copying it whole into the call cost a store-forward
// stall per path).
vec3 trace_path(const PathContext& ctx, PathState& state, Sampler& sampler);

// Up to kLanes independent paths traced side by side, each left with its
// light in paths[k].L: a hit at a time, the closest hits of all found
// before any is shaded. One path is a chain of dependent latencies (a hit,
// its shading, the next ray); with several in flight the processor
// overlaps one path's work with another's (docs/PERFORMANCE.md). Each path
// draws the same numbers, gathers the same light and counts the same rays
// as alone (trace_path() is the group of one).
inline constexpr int kLanes = 8;
static_assert(kSeedSlots >= std::uint32_t(kLanes), "each lane's pixel keeps its Sobol seeds");
void trace_paths(const PathContext& ctx, PathState* paths, Sampler* samplers, int count);

// Whether a path of throughput beta ends here (RenderSettings::zero_cutoff):
// it can carry no more light, so its light and bounces would all be zero.
inline bool ends_dark(const RenderSettings& settings, const vec3& beta) {
  return settings.zero_cutoff && beta.x == 0.0f && beta.y == 0.0f && beta.z == 0.0f;
}

// ---- the split factor ------------------------------------------------------
// At the d-th diffuse hit of a path, RenderSettings::split[d] indirect
// continuations leave and their light is averaged (each is an unbiased
// estimate of the same integral, so their mean is too, with less variance),
// the count weighted by the colour channels the path still carries.

// The split factor for a path whose throughput is beta (see
// RenderSettings::split_weights): round(split * the largest weight of a
// channel beta still carries), at least 1.
inline int weighted_split(int split, const vec3& beta, const vec3& weights) {
  float w = 0.0f;
  for (int c = 0; c < 3; ++c)
    if (beta[c] != 0.0f) w = std::max(w, weights[c]);
  return std::max(1, int(float(split) * w + 0.5f));
}

// The number of continuations at a path's diffuse hit number `diffuse_hits`
// (0: the first), given its throughput beta.
inline int split_factor(const RenderSettings& settings, int diffuse_hits, const vec3& beta) {
  const std::size_t d = std::size_t(diffuse_hits);
  return weighted_split(d < settings.split.size() ? settings.split[d] : 1, beta,
                        settings.split_weights);
}

// ---- the pixel loop: a tile of a pass ------------------------------------

// A block of pixels: rows [i0, i1), columns [j0, j1).
struct PixelBlock {
  int i0 = 0, i1 = 0, j0 = 0, j1 = 0;
};

// A tile's pixels and the pass's samples of each: numbers first_sample to
// first_sample + spp - 1. `cancel`, read before every group of kLanes
// paths, says the pass is being dropped (a stop or an edit): a tile of a
// pass of 65536 samples takes minutes, and a stop must not wait for it.
struct TileWork {
  PixelBlock pixels;
  std::uint64_t first_sample = 0;
  int spp = 0;
  const std::atomic<bool>* cancel = nullptr;
  // Light connections' caches of samples first_sample.. (light_cache.h), or
  // null: no connections are made.
  const LightCache* light_caches = nullptr;
  // A pass in chunks of samples: each pixel's sums (indexed by i * width +
  // j) start from `sums` when `in` (else from zero) and are left there when
  // `out` (else added to the film), so the film gets the pass's sums as if
  // its samples had run in one chunk, bit for bit.
  struct Carry {
    PixelSum* sums = nullptr;
    bool in = false, out = false;
  } carry;
  // The denoiser's features of each sample's camera ray (render/features.h)
  // added beside its light (PixelSum::add_features).
  bool features = false;
};

struct TileResult {
  std::uint64_t dropped = 0;  // samples not finite
  bool abandoned = false;     // stopped early: the film holds part of the tile
};

// Adds the tile's samples to the film.
TileResult render_tile(const PathContext& ctx, const CameraFrame& cam, const TileWork& tile,
                       Film& film);

// Denormal floats flushed to zero (FTZ: results; DAZ: inputs) while a tile's
// samples are traced (render_tile: once a tile, as reading and writing MXCSR
// stalls the pipeline), the caller's mode restored after. A path's throughput
// falls geometrically; without this it sinks through the denormal range
// (2^-126 to 2^-149, slow on most cores) instead of reaching the zero that
// ends the path (RenderSettings::zero_cutoff), and a closed room of albedo
// 0.75 runs every path to full depth. Nothing the estimator adds up is that
// small: a value below 2^-126 of the light's scale contributes nothing.
class FlushDenormals {
 public:
  FlushDenormals() : saved_(_mm_getcsr()) { _mm_setcsr(saved_ | kFtz | kDaz); }
  ~FlushDenormals() { _mm_setcsr(saved_); }
  FlushDenormals(const FlushDenormals&) = delete;
  FlushDenormals& operator=(const FlushDenormals&) = delete;

 private:
  static constexpr unsigned kFtz = 0x8000u, kDaz = 0x0040u;  // MXCSR bits 15 and 6
  unsigned saved_;
};

}  // namespace whisker
