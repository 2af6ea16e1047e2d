// The report's estimator: camera paths of up to max_depth bounces with direct
// light from the point light at every diffuse hit, mirror, glass with optional
// Fresnel, and cosine-sampled indirect light, split at the first diffuse hits
// (RenderSettings::split). Its parts: sampling.h, scattering.h,
// direct_light.h, splitting.h.
#pragma once

#include <cstdint>

#include "render/camera.h"
#include "render/sampler.h"
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

}  // namespace whisker
