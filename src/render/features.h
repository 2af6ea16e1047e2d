// The denoiser's auxiliary features (render/denoise.h) of a camera ray: the
// albedo, shading normal and depth of its first non-specular hit, the
// images OpenImageDenoise's documentation asks for beside the colour
// ("Ray tracing filter", albedo and normal: the first diffuse hit's, found
// by following perfect mirrors and glass along the path).
#pragma once

#include <cstdint>

#include <glm/vec3.hpp>

#include "render/camera.h"
#include "render/integrator.h"
#include "render/sampler.h"
#include "scene/scene.h"
#include "scene/world.h"

namespace whisker {

// The depth of a ray that meets nothing: finite, so that sums and means of
// it stay finite, and far past any scene (kMaxCoordinate across).
inline constexpr float kMissDepth = 1e9f;

struct Features {
  // The diffuse colour at the feature hit times the tint of the specular
  // surfaces before it (the report's mirrors and glass have none: 1). Zero
  // for a miss, and for a chain of more specular hits than the path follows
  // (the path's light is zero there too).
  vec3 albedo{0.0f};
  // The unit shading normal there, world space, turned to the side the ray
  // arrived from (a mesh's triangles may face either way); zero for a miss.
  vec3 normal{0.0f};
  // The length of the chain from the camera to the feature hit: the first
  // hit's distance along the camera ray when that hit is diffuse, and through
  // a mirror the distance to what the mirror shows. kMissDepth for a miss.
  float depth = kMissDepth;
};

// The features of `ray` (a camera ray in render space, as camera_ray() makes
// it): the first diffuse hit along the path it starts, through at most
// settings.max_depth specular hits after the first, as the path goes. At a
// mirror the path reflects; at glass it refracts (reflects on total
// internal reflection), or, with `fresnel` given and settings.fresnel on,
// reflects or refracts as sample_glass() chooses with those numbers: a copy
// of the sample's sampler right after its camera ray then makes the path's
// own choices (nothing draws before the first diffuse hit but glass).
// Deterministic given the ray (and the sampler's state).
Features ray_features(const World& world, const RenderSettings& settings, Ray ray,
                      Sampler* fresnel = nullptr);

// Sums of features over samples, double, in the order of the samples (as
// PixelSum's colour), and their mean.
struct FeatureSum {
  glm::dvec3 albedo{0.0}, normal{0.0};
  double depth = 0.0;
  std::uint64_t count = 0;

  void add(const Features& f) {
    albedo += glm::dvec3(f.albedo);
    normal += glm::dvec3(f.normal);
    depth += double(f.depth);
    ++count;
  }
  // The mean (a mean normal is shorter than 1 where the samples' normals
  // differ: kept so, as OpenImageDenoise takes normals of any length).
  Features mean() const;
};

// The features of pixel px's samples first .. first + count - 1 (their
// camera rays as the render makes them: pixel_sampler(), camera_ray(), the
// AA jitter included, and their Fresnel choices), summed.
FeatureSum pixel_features(const PathContext& ctx, const CameraFrame& cam, Pixel px,
                          std::uint64_t first, std::uint64_t count);

}  // namespace whisker
