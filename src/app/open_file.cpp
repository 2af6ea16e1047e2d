#include "app/open_file.h"

#include <algorithm>
#include <memory>

#include <glm/common.hpp>

#include "scene/mesh_io.h"
#include "scene/quote.h"

namespace whisker {

std::string apply_file_argument(CommandLine& o, bool given, bool scene_given) {
  if (o.file.empty()) return given ? "FILE: needs a value, got \"\" (see --help)" : "";
  const std::string ext = lower_extension(o.file);
  if (ext != ".json" && ext != ".obj")
    return "unexpected argument " + cut_for_message(o.file) +
           " (a file to open ends in .json or .obj; options start with --; see --help)";
  if (scene_given)
    return cut_for_message(o.file) + " and --scene " + cut_for_message(o.scene_name) +
           " both name the scene; give one";
  if (ext == ".json") {
    o.scene_name = o.file;  // a path: resolve_scene reads any NAME.json as one
    return {};
  }
  if (!o.mesh.empty())
    return cut_for_message(o.file) + " and --mesh " + cut_for_message(o.mesh) +
           " both name the mesh; give one";
  o.mesh = o.file;
  o.scene_name = "cat";
  return {};
}

void fit_in_cat_room(Scene& scene) {
  const dvec3 room(40.0, 28.0, 40.0);  // about the cat's box (39 x 27 x 10)
  const double floor_y = -10.0;
  for (MeshObject& m : scene.meshes) {
    if (!m.mesh || m.mesh->positions.empty() || m.scale == 0.0f) continue;
    // The file's own coordinates: undo the scale and translation it was loaded with.
    dvec3 lo(1e300), hi(-1e300);
    for (const vec3& p : m.mesh->positions) {
      const dvec3 q = (dvec3(p) - m.translate) / double(m.scale);
      lo = glm::min(lo, q);
      hi = glm::max(hi, q);
    }
    const dvec3 size = hi - lo;
    double s = 1e30;
    for (int a = 0; a < 3; ++a)
      if (size[a] > 0.0) s = std::min(s, room[a] / size[a]);
    if (s == 1e30) continue;  // a single point: nothing to fit
    const dvec3 base(0.5 * (lo.x + hi.x), lo.y, 0.5 * (lo.z + hi.z));
    m.scale = float(s);
    m.translate = dvec3(0.0, floor_y, 0.0) - s * base;
    m.mesh = std::make_shared<const TriangleMesh>(load_obj(m.path, m.scale, m.translate));
  }
}

}  // namespace whisker
