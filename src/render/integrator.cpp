#include "render/integrator.h"

#include <cmath>

#include "render/direct_light.h"
#include "render/sampling.h"
#include "render/scattering.h"
#include "render/splitting.h"

namespace whisker {

// The light a path gathers from `ray` on, given its throughput `beta` so far,
// the number of hits before it and how many of those were diffuse.
// The ray is in render space (World).
vec3 trace_path(const World& world, const RenderSettings& settings, const Ray& start, vec3 beta,
                int first_depth, int diffuse_hits, Sampler& sampler, PathStats& stats,
                const Hit* first_hit) {
  Ray ray = start;
  vec3 L(0.0f);
  // depth counts hits: the camera hit plus up to max_depth more (getColor(ray, 5)).
  for (int depth = first_depth; depth <= settings.max_depth; ++depth) {
    Hit hit;
    if (first_hit) {  // the caller found this ray's hit already
      hit = *first_hit;
      first_hit = nullptr;
    } else {
      ++stats.rays;
      if (!world.closest(ray, hit)) break;
    }
    const Material& m = world.material(hit);
    if (m.kind == MaterialKind::Diffuse) {
      // A path that can carry no more light ends here (the walls' albedos
      // are pure primaries): its light and bounce would both be multiplied
      // by zero. It changes the time, not the estimate, and is decided
      // before the hit record is made.
      beta *= m.albedo;
      if (ends_dark(settings, beta)) return L;
    }
    SurfaceHit h;
    world.record(ray, hit, h);
    if (m.kind == MaterialKind::Mirror) {
      ray = sample_mirror(ray, h);
      continue;
    }
    if (m.kind != MaterialKind::Diffuse) {  // glass, or a hollow ball's shells
      ray = sample_glass(ray, h, m.ior, settings.fresnel, sampler);
      continue;
    }
    if (!diffuse_vertex(world, settings, ray, h, beta, depth, diffuse_hits, sampler, stats, L, ray))
      return L;
  }
  return L;
}

FacingNormals add_direct_light(const World& world, const Ray& in, const SurfaceHit& h,
                               const vec3& beta, PathStats& stats, vec3& L) {
  const FacingNormals n(h, in.d);
  float weight;
  if (direct_light(world, h, n.ng, n.ns, stats.rays, weight)) L += beta * weight;
  return n;
}

bool diffuse_vertex(const World& world, const RenderSettings& settings, const Ray& in,
                    const SurfaceHit& h, const vec3& beta, int depth, int& diffuse_hits,
                    Sampler& sampler, PathStats& stats, vec3& L, Ray& next) {
  const FacingNormals n = add_direct_light(world, in, h, beta, stats, L);
  if (!settings.indirect || depth == settings.max_depth) return false;
  const int split = split_factor(settings, diffuse_hits++, beta);
  const Frame frame(n.ns);
  if (split > 1) {
    vec3 sum(0.0f);
    for (int k = 0; k < split; ++k) {
      Sampler branch = sampler.branch(std::uint32_t(k), std::uint32_t(split));
      const Ray r = sample_diffuse(h, frame, branch);
      sum += trace_path(world, settings, r, beta, depth + 1, diffuse_hits, branch, stats);
    }
    L = L + sum / float(split);
    return false;
  }
  next = sample_diffuse(h, frame, sampler);
  return true;
}

Ray camera_ray(const World& world, const Scene& scene, const CameraFrame& cam, int i, int j,
               Sampler& sampler) {
  float dx = 0.0f, dy = 0.0f;
  if (scene.settings.aa) {
    // Box-Muller (report section 3): two independent N(0, 0.5^2) offsets in pixels.
    float u1, u2;
    sampler.get2d(u1, u2);
    u1 = 1.0f - u1;  // (0, 1]: log stays finite
    const float r = 0.5f * std::sqrt(-2.0f * std::log(u1));
    float s, c;
    sincos_turn(u2, s, c);
    dx = r * c;
    dy = r * s;
  }
  return world.to_render(cam.origin, cam.direction(i, j, dx, dy));
}

vec3 radiance(const World& world, const RenderSettings& settings, Ray ray, Sampler& sampler,
              PathStats& stats) {
  return radiance_from_render(world, settings, world.to_render(ray), sampler, stats);
}

vec3 radiance_from_render(const World& world, const RenderSettings& settings, const Ray& ray,
                          Sampler& sampler, PathStats& stats) {
  const FlushDenormals ftz;
  return trace_path(world, settings, ray, vec3(1.0f), 0, 0, sampler, stats);
}

vec3 sample_pixel(const World& world, const Scene& scene, const CameraFrame& cam, int i, int j,
                  Sampler& sampler, PathStats& stats) {
  return radiance_from_render(world, scene.settings, camera_ray(world, scene, cam, i, j, sampler),
                              sampler, stats);
}

}  // namespace whisker
