#include "scene/scene_io.h"
#include "scene/quote.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <map>
#include <unordered_set>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "scene/json_fields.h"
#include "scene/json_reader.h"
#include "scene/mesh_io.h"
#include "scene/scene_memory.h"
#include "scene/settings_json.h"

namespace whisker {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr double kBig = kMaxCoordinate;

Material read_material(const Fields& f) {
  f.only({"type", "albedo", "ior"});
  Material m;
  const std::string type = f.string("type");
  if (!parse(type, m.kind))
    f.fail(f.field("type"), "unknown material \"" + cut_for_message(type) + "\" (expected " +
                                name_list(m.kind) + ")");
  if (m.kind == MaterialKind::Diffuse) m.albedo = f.vector("albedo", 0.0, 1.0, vec3(1.0f));
  if (is_glass(m.kind))
    m.ior = float(f.number("ior", 1.0, 4.0, 1.5));
  if (m.kind != MaterialKind::Diffuse && f.has("albedo"))
    f.fail(f.field("albedo"), "only diffuse materials have an albedo");
  if (m.kind == MaterialKind::Diffuse || m.kind == MaterialKind::Mirror) {
    if (f.has("ior")) f.fail(f.field("ior"), "only glass materials have an ior");
  }
  return m;
}

void read_camera(const Fields& c, Camera& cam) {
  c.only({"position", "look_at", "up", "fov", "width", "height"});
  cam.position = c.point("position", -kBig, kBig, cam.position);
  cam.look_at = c.point("look_at", -kBig, kBig, cam.look_at);
  if (c.has("up")) cam.up = c.direction("up");
  cam.fov_deg = float(c.number("fov", 1.0, 179.0, cam.fov_deg));
  // The film must fit the machine (named first: a size far past it says
  // what it needs). Each side in [1, 16384]: the viewer shows the film as
  // one OpenGL texture, and 16384 is the size OpenGL 4.1 and later promise.
  constexpr long long kMaxSide = 16384, kAny = 0x7fffffffffffffff;
  const long long w = c.integer("width", -kAny, kAny, cam.width);
  const long long h = c.integer("height", -kAny, kAny, cam.height);
  if (w < 1) c.integer("width", 1, kMaxSide, cam.width);
  if (h < 1) c.integer("height", 1, kMaxSide, cam.height);
  const std::string pixels = std::to_string(w) + " x " + std::to_string(h) + " pixels: the film";
  if (const std::string why = memory_refusal(pixels, film_bytes(w, h), machine_memory()); !why.empty())
    c.fail(c.field(c.has("width") ? "width" : "height"), why);
  cam.width = int(c.integer("width", 1, kMaxSide, cam.width));
  cam.height = int(c.integer("height", 1, kMaxSide, cam.height));
  // As the camera frame will compute them (camera.h, camera_right).
  if (cam.look_at == cam.position) c.fail(c.field("look_at"), "must differ from camera.position");
  if (camera_right(cam, view_direction(cam)) == vec3(0.0f))
    c.fail(c.field("up"), "must not be parallel to the view direction");
}

// The meshes a scene has loaded: each file read once and placed once, at
// its first mention; its other placements share that mesh, which records
// the placement it carries (World places them as instances of it): memory
// follows the distinct files, not the mentions.
class LoadedMeshes {
 public:
  std::shared_ptr<const TriangleMesh> get(const fs::path& resolved, float scale, const dvec3& tr) {
    std::error_code ec;
    fs::path id = fs::canonical(resolved, ec);
    if (ec) id = resolved;
    Loaded& file = files_[id.string()];
    if (!file.mesh) {
      const ObjFile obj = read_obj(resolved.string());
      TriangleMesh mesh = place_obj(obj, scale, tr);
      mesh.placed = TriangleMesh::Placement{scale, tr};
      file.mesh = std::make_shared<const TriangleMesh>(std::move(mesh));
      for (std::size_t i = 0; i < obj.coords.size(); ++i) {
        file.lo[i % 3] = std::min(file.lo[i % 3], obj.coords[i]);
        file.hi[i % 3] = std::max(file.hi[i % 3], obj.coords[i]);
      }
    } else {
      check_finite(file, resolved.string(), scale, tr);
    }
    return file.mesh;
  }

 private:
  struct Loaded {
    std::shared_ptr<const TriangleMesh> mesh;
    dvec3 lo{HUGE_VAL}, hi{-HUGE_VAL};  // of the file's own coordinates
  };
  // What place_obj checks of every placement: its vertices stay finite in
  // float. The placement is monotonic, so the corners of the file's box say it.
  static void check_finite(const Loaded& file, const std::string& path, float scale, const dvec3& tr) {
    for (const dvec3& corner : {file.lo, file.hi}) {
      const glm::vec3 p(corner * double(scale) + tr);
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
        throw MeshError(path + ": a vertex is not finite after scale/translate");
    }
  }
  std::map<std::string, Loaded> files_;
};

// The data folder next to the running binary: <bin>/../share/whisker when
// installed, <bin>/assets in a build tree (a link the build makes to the
// source's assets/; test binaries in build/tests get one too). Found from
// /proc/self/exe, never from a path compiled in.
fs::path data_dir() {
  std::error_code ec;
  const fs::path bin = fs::read_symlink("/proc/self/exe", ec).parent_path();
  if (ec || bin.empty()) return {};
  const fs::path installed = (bin / ".." / "share" / "whisker").lexically_normal();
  if (fs::is_directory(installed / "scenes", ec)) return installed;
  if (fs::is_directory(bin / "assets" / "scenes", ec)) return bin / "assets";
  return installed;
}

// Each folder once (the working folder may be the checkout the binary's
// data links to).
void add_unique(std::vector<fs::path>& dirs, const fs::path& dir) {
  std::error_code ec;
  for (const fs::path& d : dirs)
    if (d == dir || fs::equivalent(d, dir, ec)) return;
  dirs.push_back(dir);
}

}  // namespace

std::vector<fs::path> asset_dirs() {
  std::vector<fs::path> dirs;
  if (const char* env = std::getenv("WHISKER_ASSETS"); env && *env) add_unique(dirs, env);
  std::error_code ec;
  if (const fs::path here = fs::current_path(ec); !ec && fs::is_directory(here / "assets", ec))
    add_unique(dirs, here / "assets");
  if (const fs::path data = data_dir(); !data.empty()) add_unique(dirs, data);
  return dirs;
}

std::vector<fs::path> scene_dirs() {
  std::vector<fs::path> dirs;
  if (const char* env = std::getenv("WHISKER_SCENES"); env && *env) add_unique(dirs, env);
  for (const fs::path& a : asset_dirs()) add_unique(dirs, a / "scenes");
  return dirs;
}

std::string scene_dirs_text() {
  std::string text;
  for (const fs::path& d : scene_dirs()) text += (text.empty() ? "" : ", ") + d.string();
  return text.empty() ? "no folder (no $WHISKER_SCENES, ./assets or data folder)" : text;
}

fs::path scenes_dir() {
  std::error_code ec;
  const auto dirs = scene_dirs();
  for (const fs::path& d : dirs)
    if (fs::is_directory(d, ec)) return d;
  return dirs.empty() ? fs::path("assets/scenes") : dirs.back();
}

fs::path resolve_scene(const std::string& name) {
  if (name.find('/') != std::string::npos || name.ends_with(".json")) return name;
  const auto dirs = scene_dirs();
  std::error_code ec;
  for (const fs::path& d : dirs)
    if (fs::exists(d / (name + ".json"), ec)) return d / (name + ".json");
  return (dirs.empty() ? fs::path("assets/scenes") : dirs.back()) / (name + ".json");
}

std::vector<std::string> list_scenes() {
  std::vector<std::string> names;
  for (const fs::path& d : scene_dirs()) {
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(d, ec))
      if (e.path().extension() == ".json") names.push_back(e.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  names.erase(std::unique(names.begin(), names.end()), names.end());
  return names;
}

namespace {
const char* file_kind(const fs::file_status& st) {
  switch (st.type()) {
    case fs::file_type::directory: return "a folder";
    case fs::file_type::fifo: return "a FIFO";
    case fs::file_type::socket: return "a socket";
    case fs::file_type::block:
    case fs::file_type::character: return "a device";
    default: return "not a file";
  }
}
}  // namespace

fs::path resolve_mesh(const std::string& path, const fs::path& base_dir,
                      const std::string& field) {
  const fs::path p(path);
  std::vector<fs::path> tried;
  if (p.is_absolute()) {
    tried.push_back(p);
  } else {
    tried.push_back(base_dir / p);
    for (const fs::path& a : asset_dirs()) tried.push_back(a / p);
  }
  std::error_code ec;
  for (const auto& t : tried) {
    const fs::file_status st = fs::status(t, ec);
    if (fs::is_regular_file(st)) return t.lexically_normal();
    // Something is there, but not a file to read a mesh from (a FIFO would
    // block the reader, a folder or device is no OBJ): say so, not "not found".
    if (fs::exists(st))
      throw SceneError(field + ": mesh \"" + cut_for_message(t.lexically_normal().string()) +
                       "\" is not a regular file (" + file_kind(st) + ")");
  }
  // One line: the places looked in, then what to do.
  std::string where;
  for (const auto& t : tried)
    where += (where.empty() ? "" : ", ") + cut_for_message(t.lexically_normal().string());
  throw SceneError(field + ": mesh \"" + cut_for_message(path) + "\" not found (looked in " + where +
                   "); put it there, set WHISKER_ASSETS to its folder, or pass --mesh PATH");
}

Scene parse_scene(const std::string& text, const std::string& file, const fs::path& base_dir,
                  const std::string& mesh_override) {
  const json j = read_json(text, file);

  Scene scene;
  scene.source_path = file;
  Fields top(j, "", file);
  top.only({"name", "camera", "light", "settings", "spheres", "meshes", "description"});
  scene.name = top.string("name", fs::path(file).stem().string());

  if (top.has("camera")) read_camera(top.object("camera"), scene.camera);
  if (top.has("light")) {
    Fields l = top.object("light");
    l.only({"position", "intensity"});
    scene.light.position = l.point("position", -kBig, kBig, scene.light.position);
    scene.light.intensity = float(l.number("intensity", 0.0, 1e30, scene.light.intensity));
  }
  if (top.has("settings")) read_settings(top.object("settings"), scene.settings);
  if (top.has("spheres")) {
    const json& arr = top.at("spheres");
    if (!arr.is_array()) top.fail("spheres", "must be an array");
    for (std::size_t i = 0; i < arr.size(); ++i) {
      Fields f(arr[i], "spheres[" + std::to_string(i) + "]", file);
      f.only({"name", "center", "radius", "inner_radius", "material"});
      SphereObject s;
      s.name = f.string("name", "sphere " + std::to_string(i));
      s.center = f.point("center", -kBig, kBig);
      const json& rv = f.at("radius");
      if (rv.is_number() && rv.get<double>() <= 0.0) f.fail(f.field("radius"), "must be positive");
      s.radius = float(f.number("radius", 1e-6, kBig));
      s.material = read_material(f.object("material"));
      if (s.material.kind == MaterialKind::HollowGlass) {
        s.inner_radius = float(f.number("inner_radius", 1e-6, kBig));
        if (s.inner_radius >= s.radius)
          f.fail(f.field("inner_radius"), "must be smaller than radius");
      } else if (f.has("inner_radius")) {
        f.fail(f.field("inner_radius"), "only hollow_glass spheres have an inner_radius");
      }
      scene.spheres.push_back(std::move(s));
    }
  }
  if (top.has("meshes")) {
    const json& arr = top.at("meshes");
    if (!arr.is_array()) top.fail("meshes", "must be an array");
    LoadedMeshes loaded;
    for (std::size_t i = 0; i < arr.size(); ++i) {
      Fields f(arr[i], "meshes[" + std::to_string(i) + "]", file);
      f.only({"name", "path", "scale", "translate", "vertex_normals", "material"});
      MeshObject m;
      m.path = f.string("path");
      m.name = f.string("name", fs::path(m.path).stem().string());
      m.scale = float(f.number("scale", 1e-6, kBig, 1.0));
      m.translate = f.point("translate", -kBig, kBig, glm::dvec3(0.0));
      m.vertex_normals = f.boolean("vertex_normals", false);
      m.material = f.has("material") ? read_material(f.object("material")) : Material{};
      if (m.material.kind == MaterialKind::HollowGlass)
        f.fail(f.field("material.type"), "hollow_glass is for spheres only");
      if (!mesh_override.empty()) m.path = fs::absolute(mesh_override).string();
      const fs::path resolved = resolve_mesh(m.path, base_dir, file + ": " + f.field("path"));
      m.file = resolved.string();
      try {
        // A file named several times is read once and held once.
        m.mesh = loaded.get(resolved, m.scale, m.translate);
      } catch (const MeshError& e) {
        throw SceneError(file + ": " + f.field("path") + ": " + e.what());
      }
      scene.meshes.push_back(std::move(m));
    }
  }
  check_render_memory(scene, file);
  return scene;
}

Scene load_scene(const fs::path& path, const std::string& mesh_override) {
  std::error_code ec;
  if (!fs::exists(path, ec)) {
    // A symbolic link loop or a folder that cannot be searched: say which.
    if (ec && ec != std::errc::no_such_file_or_directory)
      throw SceneError(path.string() + ": cannot open scene file: " + ec.message());
    std::string hint;
    const auto dirs = scene_dirs();
    if (std::find(dirs.begin(), dirs.end(), path.parent_path()) != dirs.end()) {
      for (const auto& n : list_scenes()) hint += (hint.empty() ? "" : ", ") + n;
      hint = " in " + scene_dirs_text() + " (bundled scenes: " + hint + ")";
      throw SceneError(path.filename().string() + ": scene file not found" + hint);
    }
    throw SceneError(path.string() + ": scene file not found" + hint);
  }
  const fs::file_status st = fs::status(path, ec);
  if (fs::is_directory(st)) throw SceneError(path.string() + ": is a directory, not a scene file");
  // A device (/dev/zero, a terminal) or socket is never a scene; a pipe may be
  // (--scene <(generate)), so what is read is capped instead.
  if (fs::is_character_file(st) || fs::is_block_file(st) || fs::is_socket(st))
    throw SceneError(path.string() + ": is a device, not a scene file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path.string() + ": cannot open scene file: " + std::strerror(errno));
  // Reading holds the text, and the parser a copy of its longest token and
  // the value made of it: three times the file, at the least. A file that
  // cannot have that is refused from its size, before it is read; what is
  // read from a pipe stops where it would pass it.
  const std::uint64_t memory = machine_memory();
  const std::uint64_t most = memory ? memory / 3 : ~std::uint64_t(0);
  const auto too_big = [&](std::uint64_t bytes, const char* how) {
    return SceneError(path.string() + ": " +
                      memory_refusal(std::string("reading ") + how + memory_text(bytes, false), 3 * bytes, memory));
  };
  std::string text;
  if (fs::is_regular_file(st)) {
    const auto size = fs::file_size(path, ec);
    if (!ec && size > most) throw too_big(size, "a file of ");
    // Reserved when the size is known, so that growing never holds two copies.
    if (!ec) text.reserve(std::size_t(size));
  }
  std::vector<char> buf(1 << 16);
  while (in.read(buf.data(), std::streamsize(buf.size())) || in.gcount() > 0) {
    const auto n = std::size_t(in.gcount());
    if (text.size() + n > most) throw too_big(text.size() + n, "over ");
    // Grown by at most `most`, so that the copy a reallocation makes stays
    // within the bound too.
    if (text.size() + n > text.capacity())
      text.reserve(std::size_t(std::min<std::uint64_t>(2 * text.capacity() + n, most)));
    text.append(buf.data(), n);
  }
  return parse_scene(text, path.string(), path.parent_path(), mesh_override);
}

namespace {
// A float as the double with the float's shortest round-trip digits, so the
// file says 0.6, not 0.6000000238418579 (reading it back gives the same float).
json num(float f) {
  if (!std::isfinite(f)) return f;
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, f);
  return std::strtod(std::string(buf, r.ptr).c_str(), nullptr);
}
json to_json(const vec3& v) { return json::array({num(v.x), num(v.y), num(v.z)}); }
json to_json(const glm::dvec3& v) { return json::array({v.x, v.y, v.z}); }
json to_json(const Material& m) {
  json j = {{"type", to_string(m.kind)}};
  if (m.kind == MaterialKind::Diffuse) j["albedo"] = to_json(m.albedo);
  if (is_glass(m.kind)) j["ior"] = num(m.ior);
  return j;
}
json to_json(const Camera& c) {
  return {{"position", to_json(c.position)}, {"look_at", to_json(c.look_at)},
          {"up", to_json(c.up)},             {"fov", num(c.fov_deg)},
          {"width", c.width},                {"height", c.height}};
}
}  // namespace

std::string camera_to_json(const Camera& camera) {
  return json{{"camera", to_json(camera)}}.dump(2);
}

json camera_json(const Camera& camera) { return to_json(camera); }

namespace {
// The path of the OBJ `m` was loaded from, as a file in `dir` should name it.
std::string mesh_path_from(const MeshObject& m, const fs::path& dir) {
  if (m.file.empty()) return m.path;
  std::error_code ec;
  // Canonical on both sides: ".." from a folder reached by a symbolic link
  // goes up from where the link points, as the kernel resolves it.
  const fs::path target = fs::weakly_canonical(fs::absolute(m.file, ec), ec);
  if (ec) return fs::absolute(m.file).lexically_normal().string();
  const fs::path from = fs::weakly_canonical(fs::absolute(dir.empty() ? fs::path(".") : dir, ec), ec);
  const fs::path rel = ec ? fs::path() : target.lexically_relative(from);
  return rel.empty() ? target.string() : rel.string();
}
}  // namespace

std::string scene_to_json(const Scene& s, const fs::path& file) {
  // A name from a file name (the scene's stem, a --mesh path) may hold bytes
  // that are not UTF-8; they are written as U+FFFD rather than thrown on.
  return scene_json(s, file).dump(2, ' ', false, json::error_handler_t::replace);
}

json scene_json(const Scene& s, const fs::path& file) {
  json j;
  j["name"] = s.name;
  j["camera"] = to_json(s.camera);
  j["light"] = {{"position", to_json(s.light.position)}, {"intensity", num(s.light.intensity)}};
  j["settings"] = settings_to_json(s.settings);
  j["spheres"] = json::array();
  for (const auto& sp : s.spheres) {
    json o = {{"name", sp.name}, {"center", to_json(sp.center)}, {"radius", num(sp.radius)},
              {"material", to_json(sp.material)}};
    if (sp.material.kind == MaterialKind::HollowGlass) o["inner_radius"] = num(sp.inner_radius);
    j["spheres"].push_back(o);
  }
  if (!s.meshes.empty()) {
    j["meshes"] = json::array();
    for (const auto& m : s.meshes)
      j["meshes"].push_back({{"name", m.name},
                             {"path", file.empty() ? m.path : mesh_path_from(m, file.parent_path())},
                             {"scale", num(m.scale)},
                             {"translate", to_json(m.translate)},
                             {"vertex_normals", m.vertex_normals},
                             {"material", to_json(m.material)}});
  }
  return j;
}

}  // namespace whisker
