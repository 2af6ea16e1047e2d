#include "app/open_file.h"

#include <filesystem>
#include <memory>

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

std::string check_mesh_file(const CommandLine& o, bool from_file) {
  if (o.mesh.empty()) return {};
  // Named as the user gave it: FILE alone, or the option.
  const std::string name = (from_file ? "" : "--mesh ") + cut_for_message(o.mesh);
  std::error_code ec;
  const std::filesystem::file_status st = std::filesystem::status(o.mesh, ec);
  if (std::filesystem::is_regular_file(st)) return {};
  if (st.type() == std::filesystem::file_type::not_found) return name + ": no such file";
  if (ec) return name + ": " + ec.message();  // a symbolic link loop, a name too long
  return name + ": not a regular file" + (std::filesystem::is_directory(st) ? " (a folder)" : "");
}

void fit_in_cat_room(Scene& scene, const std::string& path) {
  const glm::dvec3 room(40.0, 28.0, 40.0);  // about the cat's box (39 x 27 x 10)
  const glm::dvec3 floor(0.0, -10.0, 0.0);
  const ObjFile obj = read_obj(path);
  const ObjPlacement fit = fit_obj(obj, room, floor);
  const auto mesh = std::make_shared<const TriangleMesh>(place_obj(obj, fit.scale, fit.translate));
  // As --mesh would name it (scene_io.h: load_scene).
  const std::filesystem::path file = std::filesystem::absolute(path);
  for (MeshObject& m : scene.meshes) {
    m.path = file.string();
    m.file = file.lexically_normal().string();
    m.scale = fit.scale;
    m.translate = fit.translate;
    m.mesh = mesh;
  }
}

}  // namespace whisker
