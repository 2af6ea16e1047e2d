// Test scene: a closed diffuse sphere lit from inside, whose radiance has a
// closed form at every depth (integrator and accumulation tests).
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <glm/geometric.hpp>

#include "render/camera.h"
#include "render/film.h"
#include "scene/scene.h"

namespace whisker {

inline constexpr double kPi = 3.14159265358979323846;

// A closed diffuse sphere of radius R and grey albedo rho, the camera inside
// looking at the far wall.
inline Scene closed_sphere(vec3 rho, vec3 light, int depth, int spp, int size) {
  Scene s;
  s.name = "closed-sphere";
  s.spheres.push_back({"shell", vec3(0.0f), 10.0f, 0.0f, {MaterialKind::Diffuse, rho}});
  s.light = {light, 1000.0f};
  s.camera.position = vec3(0.0f, 0.0f, 5.0f);
  s.camera.look_at = vec3(0.0f, 0.0f, -10.0f);
  s.camera.width = s.camera.height = size;
  s.camera.fov_deg = 90.0f;
  s.settings.indirect = true;
  s.settings.max_depth = depth;
  s.settings.spp = spp;
  s.settings.target_spp = spp;
  return s;
}
inline Scene closed_sphere(float rho, vec3 light, int depth, int spp, int size) {
  return closed_sphere(vec3(rho), light, depth, spp, size);
}

// A point light c in the closed sphere (radius R about the origin, grey
// albedo rho, intensity I), `share` of its light entering (1 inside it, 1/2
// exactly on it). With B = depth + 1 diffuse hits, at the first hit y:
//   L(y) = rho/pi [I cos/|c-y|^2 + share (I/R^2) rho (1 - rho^(B-1))/(1 - rho)] / (4 pi)
// (report normalisation; a cosine-sampled direction inside a sphere lands
// uniformly on its area, so every bounce after the first sees the mean).
struct ClosedSphereLight {
  double rho = 0.5, I = 1000.0, R = 10.0;
  glm::dvec3 c{0.0};
  double share = 1.0;

  double radiance(const glm::dvec3& y, int depth) const {
    const glm::dvec3 to = c - y;
    const double d2 = glm::dot(to, to);
    const double cos = glm::dot(-y / R, to) / std::sqrt(d2);
    return rho / kPi *
           (I * cos / d2 + share * I / (R * R) * rho * (1 - std::pow(rho, depth)) / (1 - rho)) /
           (4 * kPi);
  }
};

// Each pixel of a render of the closed sphere (`scene`, its light `k`)
// within 5 standard errors of the closed form at its centre ray's hit; the
// squared z-scores sum below 80, a chi-square with 36 degrees of freedom
// for the 6 x 6 images of these tests (P(> 80) < 1e-4).
inline void expect_closed_form(const Snapshot& s, const Scene& scene, const ClosedSphereLight& k,
                               const std::string& what) {
  ASSERT_EQ(s.counters.nan_count, 0u) << what;
  const CameraFrame cam(scene.camera);
  const double n = double(s.spp);
  double chi2 = 0.0;
  for (int i = 0; i < scene.camera.height; ++i) {
    for (int j = 0; j < scene.camera.width; ++j) {
      const glm::dvec3 o(cam.origin), d(cam.centre_direction(i, j));
      const double b = glm::dot(o, d);
      const glm::dvec3 y = o + (-b + std::sqrt(b * b - (glm::dot(o, o) - k.R * k.R))) * d;
      const double expect = k.radiance(y, scene.settings.max_depth);
      const std::size_t p = std::size_t(i) * std::size_t(scene.camera.width) + std::size_t(j);
      const double mean = s.sum[3 * p] / n;
      const double se = std::sqrt((s.sum_sq[p] / n - mean * mean) / (n - 1.0));
      EXPECT_NEAR(mean, expect, 5 * se + 1e-9) << what << " pixel " << i << "," << j;
      chi2 += (mean - expect) * (mean - expect) / (se * se);
    }
  }
  EXPECT_LT(chi2, 80.0) << what;
}

}  // namespace whisker
