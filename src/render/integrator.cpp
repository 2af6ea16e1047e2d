#include "render/integrator.h"

#include <cmath>

#include <glm/geometric.hpp>

#include "geometry/offset.h"

namespace whisker {

namespace {
constexpr float kPi = 3.14159265358979323846f;

// An orthonormal basis (b1, b2, n) around unit n (Duff et al., "Building an
// Orthonormal Basis, Revisited", JCGT 2017). Built once per shading point:
// its division would otherwise be repeated for every split branch.
struct Frame {
  vec3 b1, b2, n;
  explicit Frame(const vec3& normal) : n(normal) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float b = n.x * n.y * a;
    b1 = vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
    b2 = vec3(b, sign + n.y * n.y * a, -n.y);
  }
};

// Cosine-weighted hemisphere (report section 3, Scene::random_cos):
// x = cos(2 pi u1) sqrt(1 - u2), y = sin(2 pi u1) sqrt(1 - u2), z = sqrt(u2).
// b1, b2, n are orthonormal, so the result is unit to rounding (a few ULP).
inline vec3 cosine_direction(const Frame& f, float u1, float u2) {
  const float r = std::sqrt(1.0f - u2);
  float s, c;
  sincos_turn(u1, s, c);
  return r * c * f.b1 + r * s * f.b2 + std::sqrt(u2) * f.n;
}
}  // namespace

vec3 reflect(const vec3& d, const vec3& n) { return d - 2.0f * glm::dot(n, d) * n; }

bool refract(const vec3& d, const vec3& n, float eta, vec3& out) {
  // Snell-Descartes (report section 2): tangential part scales by eta.
  const float cos_i = -glm::dot(n, d);
  const float k = 1.0f - eta * eta * (1.0f - cos_i * cos_i);
  if (k < 0.0f) return false;
  out = glm::normalize(eta * d + (eta * cos_i - std::sqrt(k)) * n);
  return true;
}

float schlick(float cos_i, float n1, float n2) {
  // R = R0 + (1 - R0)(1 - |cos|)^5, R0 = ((n1 - n2)/(n1 + n2))^2 (SCENES.md).
  const float r0 = (n1 - n2) / (n1 + n2);
  const float R0 = r0 * r0;
  const float c = 1.0f - std::fabs(cos_i);
  return R0 + (1.0f - R0) * c * c * c * c * c;
}

vec3 cosine_direction(const vec3& n, float u1, float u2) {
  return cosine_direction(Frame(n), u1, u2);
}

namespace {

// The light a path gathers from `ray` on, given its throughput `beta` so far,
// the number of hits before it and how many of those were diffuse. At the
// d-th diffuse hit, settings.split[d] continuations are traced and averaged
// (splitting: each is an unbiased estimate of the same integral, so their
// mean is too, with less variance).
// The ray comes as origin and direction (tmin 0, tmax infinite): vec3s
// travel in registers, where a Ray passed by value is stored in pieces and
// read back whole, a store-forwarding stall on every split branch.
vec3 trace(const World& world, const PointLight& light, const RenderSettings& settings, vec3 o,
           vec3 d, vec3 beta, int first_depth, int diffuse_hits, Sampler& sampler,
           PathStats& stats) {
  Ray ray{o, d, 0.0f, kInf};
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
    switch (m.kind) {
      case MaterialKind::Diffuse: {
        // Shade the side the ray arrived from.
        const vec3 ng = glm::dot(h.ng, ray.d) < 0.0f ? h.ng : -h.ng;
        const vec3 ns = glm::dot(h.ns, ng) >= 0.0f ? h.ns : -h.ns;
        // Direct light, report section 2: I/(4 pi d^2) * rho/pi * <N, w_i> * V.
        const vec3 to_light = light.position - h.p;
        const float d2 = glm::dot(to_light, to_light);
        const float inv_d = 1.0f / std::sqrt(d2);
        const vec3 wi = to_light * inv_d;
        const float cos_s = glm::dot(ns, wi);
        // The geometric test keeps vertex normals from lighting the far side.
        if (cos_s > 0.0f && glm::dot(ng, wi) > 0.0f) {
          ++stats.rays;
          const Ray shadow = spawn_shadow_ray(h.p, ng, light.position, wi);
          if (!world.occluded_to_light(shadow, light.position, d2))
            L += beta * (light.intensity * cos_s * (inv_d * inv_d) * (1.0f / (4.0f * kPi * kPi)));
        }
        if (!settings.indirect) return L;
        // Indirect, report section 3: cosine sampling makes the estimator rho * L_in
        // (beta already holds rho).
        if (depth == settings.max_depth) return L;
        const int split = weighted_split(std::size_t(diffuse_hits) < settings.split.size()
                                             ? settings.split[std::size_t(diffuse_hits)]
                                             : 1,
                                         beta, settings.split_weights);
        ++diffuse_hits;
        const Frame frame(ns);
        if (split > 1) {
          vec3 sum(0.0f);
          for (int k = 0; k < split; ++k) {
            Sampler branch = sampler.branch(std::uint32_t(k), std::uint32_t(split));
            float u1, u2;
            branch.get2d(u1, u2);
            const Ray r = spawn_ray(h.p, ng, cosine_direction(frame, u1, u2));
            sum += trace(world, light, settings, r.o, r.d, beta, depth + 1, diffuse_hits, branch,
                         stats);
          }
          return L + sum / float(split);
        }
        float u1, u2;
        sampler.get2d(u1, u2);
        ray = spawn_ray(h.p, ng, cosine_direction(frame, u1, u2));
        break;
      }
      case MaterialKind::Mirror:
        ray = spawn_ray(h.p, h.ng, reflect(ray.d, h.ns));
        break;
      case MaterialKind::Glass:
      case MaterialKind::HollowGlass: {
        // Entering or leaving: the normal is flipped to face the ray and the
        // indices swapped (an inverted inner shell thus reads glass -> air).
        vec3 n = h.ng;
        float n1 = 1.0f, n2 = m.ior;
        if (glm::dot(ray.d, n) > 0.0f) {
          n = -n;
          std::swap(n1, n2);
        }
        vec3 t;
        bool reflected = !refract(ray.d, n, n1 / n2, t);  // total internal reflection
        if (!reflected && settings.fresnel)
          reflected = sampler.get1d() < schlick(glm::dot(ray.d, n), n1, n2);
        ray = spawn_ray(h.p, h.ng, reflected ? reflect(ray.d, n) : t);
        break;
      }
    }
  }
  return L;
}

}  // namespace

vec3 radiance(const World& world, const PointLight& light, const RenderSettings& settings,
              Ray ray, Sampler& sampler, PathStats& stats) {
  return trace(world, light, settings, ray.o, ray.d, vec3(1.0f), 0, 0, sampler, stats);
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
  return radiance(world, scene.light, scene.settings, cam.ray(i, j, dx, dy), sampler, stats);
}

}  // namespace whisker
