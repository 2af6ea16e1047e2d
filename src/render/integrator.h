// The report's estimator: one path per sample, direct light from the point
// light at every diffuse hit, mirror, glass with optional Fresnel, and
// cosine-sampled indirect light.
#pragma once

#include <cstdint>

#include "geometry/world.h"
#include "render/camera.h"
#include "render/sampler.h"
#include "scene/scene.h"

namespace whisker {

struct PathStats {
  std::uint64_t rays = 0;  // intersection and shadow rays traced
};

// Radiance arriving along `ray` (light intensity applied), with at most
// settings.max_depth hits after the first.
vec3 radiance(const World& world, const PointLight& light, const RenderSettings& settings,
              Ray ray, Sampler& sampler, PathStats& stats);

// One sample of pixel (i, j): camera ray (with Gaussian jitter when AA is on)
// and its radiance.
vec3 sample_pixel(const World& world, const Scene& scene, const CameraFrame& cam, int i,
                  int j, Sampler& sampler, PathStats& stats);

// Directions, exposed for tests.
vec3 reflect(const vec3& d, const vec3& n);
// Refracts unit d through the interface with unit normal n (facing against
// d) and relative index eta = n1/n2; false on total internal reflection.
bool refract(const vec3& d, const vec3& n, float eta, vec3& out);
// Schlick's approximation of the Fresnel reflectance.
float schlick(float cos_i, float n1, float n2);
// sin and cos of 2 pi u, for u in [0, 1], to within 1e-7.
void sincos_turn(float u, float& s, float& c);
// Cosine-distributed direction around unit n from two uniforms.
vec3 cosine_direction(const vec3& n, float u1, float u2);

}  // namespace whisker
