#include "viewer/scene_diff.h"

namespace whisker {

bool same_material(const Material& a, const Material& b) {
  return a.kind == b.kind && a.albedo == b.albedo && a.ior == b.ior;
}

bool same_camera(const Camera& a, const Camera& b) {
  return a.position == b.position && a.look_at == b.look_at && a.up == b.up &&
         a.fov_deg == b.fov_deg && a.width == b.width && a.height == b.height;
}

bool same_settings(const RenderSettings& a, const RenderSettings& b) {
  return a.spp == b.spp && a.max_depth == b.max_depth && a.indirect == b.indirect &&
         a.fresnel == b.fresnel && a.aa == b.aa && a.seed == b.seed &&
         a.target_spp == b.target_spp && a.accel == b.accel && a.sampler == b.sampler &&
         a.zero_cutoff == b.zero_cutoff && a.split == b.split &&
         a.split_weights == b.split_weights;
}

static bool same_spheres(const Scene& a, const Scene& b) {
  if (a.spheres.size() != b.spheres.size()) return false;
  for (std::size_t i = 0; i < a.spheres.size(); ++i) {
    const SphereObject& s = a.spheres[i];
    const SphereObject& t = b.spheres[i];
    if (s.center != t.center || s.radius != t.radius ||
        s.inner_radius != t.inner_radius || !same_material(s.material, t.material))
      return false;
  }
  return true;
}

static bool same_meshes(const Scene& a, const Scene& b) {
  if (a.meshes.size() != b.meshes.size()) return false;
  for (std::size_t i = 0; i < a.meshes.size(); ++i) {
    const MeshObject& m = a.meshes[i];
    const MeshObject& n = b.meshes[i];
    if (m.mesh != n.mesh || m.path != n.path || m.scale != n.scale ||
        m.translate != n.translate || m.vertex_normals != n.vertex_normals ||
        !same_material(m.material, n.material))
      return false;
  }
  return true;
}

SceneChange classify_change(const Scene& before, const Scene& after) {
  if (before.light.position != after.light.position ||
      before.light.intensity != after.light.intensity ||
      !same_camera(before.camera, after.camera) || !same_spheres(before, after) ||
      !same_meshes(before, after))
    return SceneChange::Scene;
  if (!same_settings(before.settings, after.settings)) return SceneChange::Settings;
  return SceneChange::None;
}

}  // namespace whisker
