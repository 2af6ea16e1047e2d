// Test scene: a closed diffuse sphere lit from inside, whose radiance has a
// closed form at every depth (integrator and accumulation tests).
#pragma once

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

}  // namespace whisker
