#include "scene/scene_io.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <initializer_list>
#include <sstream>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "geometry/mesh.h"

namespace whisker {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// Reads fields of one JSON object, naming "file: field" in every error.
class Fields {
 public:
  Fields(const json& j, std::string path, const std::string& file)
      : j_(j), path_(std::move(path)), file_(file) {
    if (!j_.is_object()) fail(path_, "must be an object");
  }

  [[noreturn]] void fail(const std::string& field, const std::string& what) const {
    throw SceneError(file_ + ": " + (field.empty() ? "top level" : field) + ": " + what);
  }
  std::string field(const std::string& key) const {
    return path_.empty() ? key : path_ + "." + key;
  }

  void only(std::initializer_list<const char*> allowed) const {
    for (const auto& [key, value] : j_.items()) {
      if (std::none_of(allowed.begin(), allowed.end(),
                       [&key = key](const char* a) { return key == a; })) {
        std::string list;
        for (const char* a : allowed) list += std::string(list.empty() ? "" : ", ") + a;
        fail(field(key), "unknown key (expected one of: " + list + ")");
      }
    }
  }

  bool has(const char* key) const { return j_.contains(key); }
  const json& at(const char* key) const {
    if (!j_.contains(key)) fail(field(key), "missing");
    return j_.at(key);
  }
  Fields object(const char* key) const { return Fields(at(key), field(key), file_); }

  double number(const char* key, double lo, double hi) const {
    const json& v = at(key);
    if (!v.is_number()) fail(field(key), "must be a number, got " + type(v));
    const double x = v.get<double>();
    check_range(field(key), x, lo, hi);
    return x;
  }
  double number(const char* key, double lo, double hi, double fallback) const {
    return has(key) ? number(key, lo, hi) : fallback;
  }
  long long integer(const char* key, long long lo, long long hi, long long fallback) const {
    if (!has(key)) return fallback;
    const json& v = at(key);
    if (!v.is_number_integer()) fail(field(key), "must be an integer, got " + type(v));
    const long long x = v.get<long long>();
    if (x < lo || x > hi)
      fail(field(key), "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                           "], got " + std::to_string(x));
    return x;
  }
  bool boolean(const char* key, bool fallback) const {
    if (!has(key)) return fallback;
    const json& v = at(key);
    if (!v.is_boolean()) fail(field(key), "must be true or false, got " + type(v));
    return v.get<bool>();
  }
  std::string string(const char* key) const {
    const json& v = at(key);
    if (!v.is_string()) fail(field(key), "must be a string, got " + type(v));
    return v.get<std::string>();
  }
  std::string string(const char* key, const std::string& fallback) const {
    return has(key) ? string(key) : fallback;
  }
  vec3 vector(const char* key, double lo, double hi) const {
    const json& v = at(key);
    if (!v.is_array() || v.size() != 3)
      fail(field(key), "must be an array of 3 numbers, got " + type(v));
    vec3 out;
    for (int i = 0; i < 3; ++i) {
      const std::string f = field(key) + "[" + std::to_string(i) + "]";
      if (!v[i].is_number()) fail(f, "must be a number, got " + type(v[i]));
      const double x = v[i].get<double>();
      check_range(f, x, lo, hi);
      out[i] = float(x);
    }
    return out;
  }
  vec3 vector(const char* key, double lo, double hi, vec3 fallback) const {
    return has(key) ? vector(key, lo, hi) : fallback;
  }
  vec3 direction(const char* key) const {
    const vec3 v = vector(key, -1e30, 1e30);
    if (v.x == 0.0f && v.y == 0.0f && v.z == 0.0f) fail(field(key), "must not be zero-length");
    return v;
  }
  const std::string& file() const { return file_; }
  const std::string& path() const { return path_; }
  const json& raw() const { return j_; }

 private:
  static std::string type(const json& v) {
    if (v.is_number()) return "number " + v.dump();
    if (v.is_string()) return "string " + v.dump();
    return v.type_name();
  }
  void check_range(const std::string& f, double x, double lo, double hi) const {
    if (!std::isfinite(x)) fail(f, "must be finite");
    if (x < lo || x > hi) {
      std::ostringstream s;
      s << "must be in [" << lo << ", " << hi << "], got " << x;
      fail(f, s.str());
    }
  }

  const json& j_;
  std::string path_;
  const std::string& file_;
};

constexpr double kBig = 1e7;  // coordinates beyond this lose float precision

Material read_material(const Fields& f) {
  f.only({"type", "albedo", "ior"});
  Material m;
  const std::string type = f.string("type");
  if (!parse(type, m.kind))
    f.fail(f.field("type"), "unknown material \"" + type +
                                "\" (expected diffuse, mirror, glass or hollow_glass)");
  if (m.kind == MaterialKind::Diffuse) m.albedo = f.vector("albedo", 0.0, 1.0, vec3(1.0f));
  if (m.kind == MaterialKind::Glass || m.kind == MaterialKind::HollowGlass)
    m.ior = float(f.number("ior", 1.0, 4.0, 1.5));
  if (m.kind != MaterialKind::Diffuse && f.has("albedo"))
    f.fail(f.field("albedo"), "only diffuse materials have an albedo");
  if (m.kind == MaterialKind::Diffuse || m.kind == MaterialKind::Mirror) {
    if (f.has("ior")) f.fail(f.field("ior"), "only glass materials have an ior");
  }
  return m;
}

std::string line_column(const std::string& text, std::size_t byte) {
  std::size_t line = 1, col = 1;
  for (std::size_t i = 0; i < byte && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      col = 1;
    } else {
      ++col;
    }
  }
  return std::to_string(line) + ":" + std::to_string(col);
}

fs::path source_root() { return fs::path(WHISKER_SOURCE_DIR); }

}  // namespace

fs::path scenes_dir() {
  if (const char* env = std::getenv("WHISKER_SCENES"); env && *env) return env;
  return source_root() / "assets" / "scenes";
}

fs::path resolve_scene(const std::string& name) {
  if (name.find('/') != std::string::npos || name.ends_with(".json")) return name;
  return scenes_dir() / (name + ".json");
}

std::vector<std::string> list_scenes() {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(scenes_dir(), ec))
    if (e.path().extension() == ".json") names.push_back(e.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

fs::path resolve_mesh(const std::string& path, const fs::path& base_dir,
                      const std::string& field) {
  const fs::path p(path);
  std::vector<fs::path> tried;
  if (p.is_absolute()) {
    tried.push_back(p);
  } else {
    tried.push_back(base_dir / p);
    if (const char* env = std::getenv("WHISKER_ASSETS"); env && *env)
      tried.push_back(fs::path(env) / p);
    tried.push_back(source_root() / "assets" / p);
  }
  std::error_code ec;
  for (const auto& t : tried)
    if (fs::is_regular_file(t, ec)) return t.lexically_normal();
  std::string where;
  for (const auto& t : tried) where += "\n  " + t.lexically_normal().string();
  throw SceneError(field + ": mesh \"" + path + "\" not found; looked in:" + where +
                   "\nput the file in one of these places, set WHISKER_ASSETS to its "
                   "folder, or pass --mesh PATH");
}

Scene parse_scene(const std::string& text, const std::string& file, const fs::path& base_dir,
                  const std::string& mesh_override) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::parse_error& e) {
    std::string msg = e.what();
    // Keep nlohmann's description, drop its "[json.exception...] parse error at ...:" prefix.
    if (auto colon = msg.find(": "); colon != std::string::npos) msg = msg.substr(colon + 2);
    throw SceneError(file + ":" + line_column(text, e.byte ? e.byte - 1 : 0) +
                     ": invalid JSON: " + msg);
  } catch (const json::exception& e) {
    std::string msg = e.what();  // e.g. a number too large for a double
    if (auto bracket = msg.find("] "); bracket != std::string::npos) msg = msg.substr(bracket + 2);
    throw SceneError(file + ": invalid JSON: " + msg);
  }

  Scene scene;
  scene.source_path = file;
  Fields top(j, "", file);
  top.only({"name", "camera", "light", "settings", "spheres", "meshes", "description"});
  scene.name = top.string("name", fs::path(file).stem().string());

  if (top.has("camera")) {
    Fields c = top.object("camera");
    c.only({"position", "look_at", "up", "fov", "width", "height"});
    Camera& cam = scene.camera;
    cam.position = c.vector("position", -kBig, kBig, cam.position);
    cam.look_at = c.vector("look_at", -kBig, kBig, cam.look_at);
    if (c.has("up")) cam.up = c.direction("up");
    cam.fov_deg = float(c.number("fov", 1.0, 179.0, cam.fov_deg));
    cam.width = int(c.integer("width", 1, 16384, cam.width));
    cam.height = int(c.integer("height", 1, 16384, cam.height));
    // The accumulation holds 32 bytes a pixel (plus a 16-byte snapshot):
    // 4096 x 4096 is half a gigabyte; beyond that, refuse rather than thrash.
    constexpr long long kMaxPixels = 4096LL * 4096LL;
    if ((long long)cam.width * cam.height > kMaxPixels)
      c.fail(c.field("width"), std::to_string(cam.width) + " x " + std::to_string(cam.height) +
                                   " pixels is more than 4096 x 4096");
    const vec3 fwd = cam.look_at - cam.position;
    if (fwd == vec3(0.0f)) c.fail(c.field("look_at"), "must differ from camera.position");
    const vec3 side = glm::cross(fwd, cam.up);
    if (side == vec3(0.0f)) c.fail(c.field("up"), "must not be parallel to the view direction");
  }
  if (top.has("light")) {
    Fields l = top.object("light");
    l.only({"position", "intensity"});
    scene.light.position = l.vector("position", -kBig, kBig, scene.light.position);
    scene.light.intensity = float(l.number("intensity", 0.0, 1e30, scene.light.intensity));
  }
  if (top.has("settings")) {
    Fields s = top.object("settings");
    s.only({"spp", "max_depth", "indirect", "fresnel", "aa", "seed", "target_spp", "accel",
            "sampler", "zero_cutoff", "split", "split_weights"});
    RenderSettings& r = scene.settings;
    r.spp = int(s.integer("spp", 1, 1 << 20, r.spp));
    r.max_depth = int(s.integer("max_depth", 0, 1000, r.max_depth));
    r.indirect = s.boolean("indirect", r.indirect);
    r.fresnel = s.boolean("fresnel", r.fresnel);
    r.aa = s.boolean("aa", r.aa);
    r.seed = std::uint64_t(s.integer("seed", 0, (1LL << 53), (long long)r.seed));
    r.target_spp = int(s.integer("target_spp", 0, 1 << 30, r.target_spp));
    if (s.has("accel") && !parse(s.string("accel"), r.accel))
      s.fail(s.field("accel"), "unknown accel \"" + s.string("accel") +
                                   "\" (expected brute, bbox, midpoint or sah)");
    if (s.has("sampler") && !parse(s.string("sampler"), r.sampler))
      s.fail(s.field("sampler"), "unknown sampler \"" + s.string("sampler") +
                                     "\" (expected independent or sobol)");
    r.zero_cutoff = s.boolean("zero_cutoff", r.zero_cutoff);
    if (s.has("split")) {
      // An integer (one factor, at the first diffuse hit) or an array of them.
      const json& v = s.at("split");
      std::vector<int> split;
      if (v.is_number_integer()) {
        split.push_back(int(std::clamp<long long>(v.get<long long>(), INT_MIN, INT_MAX)));
      } else if (v.is_array()) {
        for (std::size_t i = 0; i < v.size(); ++i) {
          if (!v[i].is_number_integer())
            s.fail(s.field("split") + "[" + std::to_string(i) + "]", "must be an integer");
          split.push_back(int(std::clamp<long long>(v[i].get<long long>(), INT_MIN, INT_MAX)));
        }
      } else {
        s.fail(s.field("split"), "must be an integer or an array of integers");
      }
      if (const std::string why = check_split(split); !why.empty()) s.fail(s.field("split"), why);
      r.split = split;
    }
    r.split_weights = s.vector("split_weights", 0.01, 1.0, r.split_weights);
  }
  if (top.has("spheres")) {
    const json& arr = top.at("spheres");
    if (!arr.is_array()) top.fail("spheres", "must be an array");
    for (std::size_t i = 0; i < arr.size(); ++i) {
      Fields f(arr[i], "spheres[" + std::to_string(i) + "]", file);
      f.only({"name", "center", "radius", "inner_radius", "material"});
      SphereObject s;
      s.name = f.string("name", "sphere " + std::to_string(i));
      s.center = f.vector("center", -kBig, kBig);
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
    for (std::size_t i = 0; i < arr.size(); ++i) {
      Fields f(arr[i], "meshes[" + std::to_string(i) + "]", file);
      f.only({"name", "path", "scale", "translate", "vertex_normals", "material"});
      MeshObject m;
      m.path = f.string("path");
      m.name = f.string("name", fs::path(m.path).stem().string());
      m.scale = float(f.number("scale", 1e-6, kBig, 1.0));
      m.translate = f.vector("translate", -kBig, kBig, vec3(0.0f));
      m.vertex_normals = f.boolean("vertex_normals", false);
      m.material = f.has("material") ? read_material(f.object("material")) : Material{};
      if (m.material.kind == MaterialKind::HollowGlass)
        f.fail(f.field("material.type"), "hollow_glass is for spheres only");
      if (!mesh_override.empty()) m.path = fs::absolute(mesh_override).string();
      const fs::path resolved = resolve_mesh(m.path, base_dir, file + ": " + f.field("path"));
      try {
        m.mesh = std::make_shared<const TriangleMesh>(
            load_obj(resolved.string(), m.scale, m.translate));
      } catch (const MeshError& e) {
        throw SceneError(file + ": " + f.field("path") + ": " + e.what());
      }
      scene.meshes.push_back(std::move(m));
    }
  }
  return scene;
}

Scene load_scene(const fs::path& path, const std::string& mesh_override) {
  std::error_code ec;
  if (!fs::exists(path, ec)) {
    std::string hint;
    if (path.parent_path() == scenes_dir()) {
      for (const auto& n : list_scenes()) hint += (hint.empty() ? "" : ", ") + n;
      hint = " (bundled scenes: " + hint + ")";
    }
    throw SceneError(path.string() + ": scene file not found" + hint);
  }
  if (fs::is_directory(path, ec)) throw SceneError(path.string() + ": is a directory, not a scene file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path.string() + ": cannot open scene file");
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_scene(ss.str(), path.string(), path.parent_path(), mesh_override);
}

namespace {
json to_json(const vec3& v) { return json::array({v.x, v.y, v.z}); }
json to_json(const Material& m) {
  json j = {{"type", to_string(m.kind)}};
  if (m.kind == MaterialKind::Diffuse) j["albedo"] = to_json(m.albedo);
  if (m.kind == MaterialKind::Glass || m.kind == MaterialKind::HollowGlass) j["ior"] = m.ior;
  return j;
}
json to_json(const Camera& c) {
  return {{"position", to_json(c.position)}, {"look_at", to_json(c.look_at)},
          {"up", to_json(c.up)},             {"fov", c.fov_deg},
          {"width", c.width},                {"height", c.height}};
}
}  // namespace

std::string camera_to_json(const Camera& camera) {
  return json{{"camera", to_json(camera)}}.dump(2);
}

std::string scene_to_json(const Scene& s) {
  json j;
  j["name"] = s.name;
  j["camera"] = to_json(s.camera);
  j["light"] = {{"position", to_json(s.light.position)}, {"intensity", s.light.intensity}};
  const RenderSettings& r = s.settings;
  j["settings"] = {{"spp", r.spp},         {"max_depth", r.max_depth}, {"indirect", r.indirect},
                   {"fresnel", r.fresnel}, {"aa", r.aa},               {"seed", r.seed},
                   {"target_spp", r.target_spp}, {"accel", to_string(r.accel)},
                   {"sampler", to_string(r.sampler)}, {"zero_cutoff", r.zero_cutoff},
                   {"split", r.split}, {"split_weights", to_json(r.split_weights)}};
  j["spheres"] = json::array();
  for (const auto& sp : s.spheres) {
    json o = {{"name", sp.name}, {"center", to_json(sp.center)}, {"radius", sp.radius},
              {"material", to_json(sp.material)}};
    if (sp.material.kind == MaterialKind::HollowGlass) o["inner_radius"] = sp.inner_radius;
    j["spheres"].push_back(o);
  }
  if (!s.meshes.empty()) {
    j["meshes"] = json::array();
    for (const auto& m : s.meshes)
      j["meshes"].push_back({{"name", m.name}, {"path", m.path}, {"scale", m.scale},
                             {"translate", to_json(m.translate)},
                             {"vertex_normals", m.vertex_normals},
                             {"material", to_json(m.material)}});
  }
  return j.dump(2);
}

}  // namespace whisker
