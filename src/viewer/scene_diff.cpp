#include "viewer/scene_diff.h"

#include <algorithm>

namespace whisker {

static bool same_spheres(const Scene& a, const Scene& b) {
  return std::equal(a.spheres.begin(), a.spheres.end(), b.spheres.begin(), b.spheres.end(),
                    [](const SphereObject& s, const SphereObject& t) {
                      return s.center == t.center && s.radius == t.radius &&
                             s.inner_radius == t.inner_radius && s.material == t.material;
                    });
}

static bool same_meshes(const Scene& a, const Scene& b) {
  return std::equal(a.meshes.begin(), a.meshes.end(), b.meshes.begin(), b.meshes.end(),
                    [](const MeshObject& m, const MeshObject& n) {
                      return m.mesh == n.mesh && m.path == n.path && m.scale == n.scale &&
                             m.translate == n.translate && m.vertex_normals == n.vertex_normals &&
                             m.material == n.material;
                    });
}

SceneChange classify_change(const Scene& before, const Scene& after) {
  if (before.light != after.light || before.camera != after.camera ||
      !same_spheres(before, after) || !same_meshes(before, after))
    return SceneChange::Scene;
  // Every render setting, through RenderSettings' defaulted comparison.
  if (before.settings != after.settings)
    return image_settings(before) == image_settings(after) ? SceneChange::Inert : SceneChange::Settings;
  return SceneChange::None;
}

}  // namespace whisker
