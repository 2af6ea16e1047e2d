#include "scene/scene.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <unordered_set>

#include <glm/geometric.hpp>

#include "geometry/mesh.h"
#include "geometry/unit.h"

namespace whisker {

namespace {
constexpr EnumName<MaterialKind> kMaterials[] = {{MaterialKind::Diffuse, "diffuse"},
                                                 {MaterialKind::Mirror, "mirror"},
                                                 {MaterialKind::Glass, "glass"},
                                                 {MaterialKind::HollowGlass, "hollow_glass"}};
}  // namespace

std::span<const EnumName<MaterialKind>> enum_names(MaterialKind) { return kMaterials; }

vec3 view_direction(const Camera& camera) {
  const glm::dvec3 d = camera.look_at - camera.position;
  const double m = std::max({std::fabs(d.x), std::fabs(d.y), std::fabs(d.z)});
  return vec3(glm::normalize(d / m));
}

vec3 camera_right(const Camera& camera, const vec3& forward) {
  return unit_or_zero(glm::cross(forward, pow2_scaled(camera.up)));
}

std::size_t triangle_count(const Scene& scene) {
  std::size_t n = 0;
  for (const MeshObject& m : scene.meshes)
    if (m.mesh) n += m.mesh->triangles.size();
  return n;
}

bool has_glass(const Scene& scene) {
  for (const SphereObject& sp : scene.spheres)
    if (is_glass(sp.material.kind)) return true;
  for (const MeshObject& m : scene.meshes)
    if (is_glass(m.material.kind)) return true;
  return false;
}

bool deterministic_estimate(const Scene& scene) {
  const RenderSettings& s = scene.settings;
  return !s.indirect && !s.aa && !(s.fresnel && has_glass(scene));
}

RenderSettings image_settings(const Scene& scene) {
  RenderSettings s = scene.settings;
  if (!has_glass(scene)) s.fresnel = false;
  if (!s.indirect) {
    s.split = {1};
    s.split_weights = vec3(1.0f);
    s.connect = false;
  }
  return s;
}

}  // namespace whisker
