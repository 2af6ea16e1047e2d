// The report's estimator: camera paths of up to max_depth bounces with direct
// light from the point light at every diffuse hit, mirror, glass with optional
// Fresnel, and cosine-sampled indirect light, split at the first diffuse hits
// (RenderSettings::split). Its parts: sampling.h, scattering.h,
// direct_light.h, splitting.h.
#pragma once

#include <cstdint>

#include <xmmintrin.h>

#include "render/camera.h"
#include "render/sampler.h"
#include "render/scattering.h"
#include "scene/scene.h"
#include "scene/world.h"

namespace whisker {

struct PathStats {
  std::uint64_t rays = 0;  // intersection and shadow rays traced
};

// Radiance arriving along the world-space `ray` (the world's light intensity applied), with
// at most settings.max_depth hits after the first. The ray is unbounded:
// only its origin and direction are used.
vec3 radiance(const World& world, const RenderSettings& settings, Ray ray, Sampler& sampler,
              PathStats& stats);
// The same for a ray already in the world's render space (World::to_render).
vec3 radiance_from_render(const World& world, const RenderSettings& settings, const Ray& ray,
                          Sampler& sampler, PathStats& stats);

// One sample of pixel (i, j): camera ray (with Gaussian jitter when AA is on)
// and its radiance. `world` is built from `scene`.
vec3 sample_pixel(const World& world, const Scene& scene, const CameraFrame& cam, int i,
                  int j, Sampler& sampler, PathStats& stats);

// ---- the path loop's parts, shared with path reuse (path_reuse.h) --------

// Pixel (i, j)'s camera ray in render space, with the Gaussian jitter of AA
// (the sample's first 2D numbers) when it is on.
Ray camera_ray(const World& world, const Scene& scene, const CameraFrame& cam, int i, int j,
               Sampler& sampler);

// The light a path gathers from `ray` on, given its throughput `beta` so far,
// the number of hits before it (`depth`) and how many were diffuse. With
// `first_hit`, that is the ray's closest hit, already found by the caller.
vec3 trace_path(const World& world, const RenderSettings& settings, const Ray& ray, vec3 beta,
                int depth, int diffuse_hits, Sampler& sampler, PathStats& stats,
                const Hit* first_hit = nullptr);

// Whether a path of throughput beta ends here (RenderSettings::zero_cutoff):
// it can carry no more light, so its light and bounces would all be zero.
inline bool ends_dark(const RenderSettings& settings, const vec3& beta) {
  return settings.zero_cutoff && beta.x == 0.0f && beta.y == 0.0f && beta.z == 0.0f;
}

// Adds the point light's direct light at the recorded diffuse hit h of ray
// `in` (throughput beta, the albedo in it) to L; returns h's normals turned
// to the side `in` came from, the frame of its bounces.
FacingNormals add_direct_light(const World& world, const Ray& in, const SurfaceHit& h,
                               const vec3& beta, PathStats& stats, vec3& L);

// At the recorded diffuse hit h of ray `in` (the albedo already in beta):
// adds its direct light to L and, when the path goes on, either splits (the
// branches' mean added to L; returns false) or sets `next` to the one bounce
// and returns true (the caller follows it). False also where the path ends.
bool diffuse_vertex(const World& world, const RenderSettings& settings, const Ray& in,
                    const SurfaceHit& h, const vec3& beta, int depth, int& diffuse_hits,
                    Sampler& sampler, PathStats& stats, vec3& L, Ray& next);

// Denormal floats flushed to zero (FTZ: results; DAZ: inputs) while a camera
// sample is traced, the caller's mode restored after. A path's throughput
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
