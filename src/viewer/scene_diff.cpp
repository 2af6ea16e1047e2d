#include "viewer/scene_diff.h"

namespace whisker {

static bool same_spheres(const Scene& a, const Scene& b) {
  if (a.spheres.size() != b.spheres.size()) return false;
  for (std::size_t i = 0; i < a.spheres.size(); ++i) {
    const SphereObject& s = a.spheres[i];
    const SphereObject& t = b.spheres[i];
    if (s.center != t.center || s.radius != t.radius || s.inner_radius != t.inner_radius ||
        s.material != t.material)
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
        m.material != n.material)
      return false;
  }
  return true;
}

SceneChange classify_change(const Scene& before, const Scene& after) {
  if (before.light != after.light || before.camera != after.camera ||
      !same_spheres(before, after) || !same_meshes(before, after))
    return SceneChange::Scene;
  // Every render setting, through RenderSettings' defaulted comparison.
  if (before.settings != after.settings) return SceneChange::Settings;
  return SceneChange::None;
}

}  // namespace whisker
