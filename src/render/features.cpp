#include "render/features.h"

#include "render/scattering.h"

namespace whisker {

Features ray_features(const World& world, const RenderSettings& settings, Ray ray,
                      Sampler* fresnel) {
  Features out;
  float travelled = 0.0f;
  // The camera hit and up to max_depth more, as trace_paths() counts them.
  for (int depth = 0; depth <= settings.max_depth; ++depth) {
    SurfaceHit h;
    if (!world.intersect(ray, h)) return Features{};
    travelled += h.t;
    const Material& m = *h.material;
    if (m.kind == MaterialKind::Diffuse) {
      out.albedo = m.albedo;
      out.normal = FacingNormals(h, ray.d).ns;
      out.depth = travelled;
      return out;
    }
    // Past the last hit the path follows: no albedo, the last normal.
    out.normal = FacingNormals(h, ray.d).ns;
    out.depth = travelled;
    if (m.kind == MaterialKind::Mirror) {
      ray = sample_mirror(ray, h);
    } else {
      Sampler none;  // never drawn from: Fresnel off
      const bool choose = settings.fresnel && fresnel;
      ray = sample_glass(ray, h, m.ior, choose, choose ? *fresnel : none);
    }
  }
  return out;
}

Features FeatureSum::mean() const {
  if (count == 0) return Features{};
  const double n = double(count);
  Features f;
  f.albedo = vec3(albedo / n);
  f.normal = vec3(normal / n);
  f.depth = float(depth / n);
  return f;
}

FeatureSum pixel_features(const PathContext& ctx, const CameraFrame& cam, Pixel px,
                          std::uint64_t first, std::uint64_t count) {
  FeatureSum sum;
  for (std::uint64_t s = first; s < first + count; ++s) {
    Sampler sampler = pixel_sampler(ctx.settings, cam, px, s);
    const Ray ray = camera_ray(ctx, cam, px, sampler);
    sum.add(ray_features(ctx.world, ctx.settings, ray, &sampler));
  }
  return sum;
}

}  // namespace whisker
