#include "render/integrator.h"

#include <cmath>

#include <xmmintrin.h>

#include "render/direct_light.h"
#include "render/sampling.h"
#include "render/scattering.h"
#include "render/splitting.h"

namespace whisker {

namespace {

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

// The light a path gathers from `ray` on, given its throughput `beta` so far,
// the number of hits before it and how many of those were diffuse.
// The ray is in render space (World).
vec3 trace(const World& world, const RenderSettings& settings, const Ray& start, vec3 beta,
           int first_depth, int diffuse_hits, Sampler& sampler, PathStats& stats) {
  Ray ray = start;
  vec3 L(0.0f);
  // depth counts hits: the camera hit plus up to max_depth more (getColor(ray, 5)).
  for (int depth = first_depth; depth <= settings.max_depth; ++depth) {
    Hit hit;
    ++stats.rays;
    if (!world.closest(ray, hit)) break;
    const Material& m = world.material(hit);
    if (m.kind == MaterialKind::Diffuse) {
      // A path that can carry no more light ends here (the walls' albedos
      // are pure primaries): its light and bounce would both be multiplied
      // by zero. It changes the time, not the estimate, and is decided
      // before the hit record is made.
      beta *= m.albedo;
      if (settings.zero_cutoff && beta.x == 0.0f && beta.y == 0.0f && beta.z == 0.0f) return L;
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
    const FacingNormals n(h, ray.d);
    float weight;
    if (direct_light(world, h, n.ng, n.ns, stats.rays, weight)) L += beta * weight;
    if (!settings.indirect || depth == settings.max_depth) return L;
    const int split = split_factor(settings, diffuse_hits++, beta);
    const Frame frame(n.ns);
    if (split > 1) {
      vec3 sum(0.0f);
      for (int k = 0; k < split; ++k) {
        Sampler branch = sampler.branch(std::uint32_t(k), std::uint32_t(split));
        const Ray r = sample_diffuse(h, frame, branch);
        sum += trace(world, settings, r, beta, depth + 1, diffuse_hits, branch, stats);
      }
      return L + sum / float(split);
    }
    ray = sample_diffuse(h, frame, sampler);
  }
  return L;
}

}  // namespace

vec3 radiance(const World& world, const RenderSettings& settings, Ray ray, Sampler& sampler,
              PathStats& stats) {
  return radiance_from_render(world, settings, world.to_render(ray), sampler, stats);
}

vec3 radiance_from_render(const World& world, const RenderSettings& settings, const Ray& ray,
                          Sampler& sampler, PathStats& stats) {
  const FlushDenormals ftz;
  return trace(world, settings, ray, vec3(1.0f), 0, 0, sampler, stats);
}

vec3 sample_pixel(const World& world, const Scene& scene, const CameraFrame& cam, int i, int j,
                  Sampler& sampler, PathStats& stats) {
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
  return radiance_from_render(world, scene.settings,
                              world.to_render(cam.origin, cam.direction(i, j, dx, dy)), sampler,
                              stats);
}

}  // namespace whisker
