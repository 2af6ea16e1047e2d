// whisker: the viewer by default, or --headless renders.
#include <cstdio>
#include <filesystem>
#include <optional>
#include <sstream>
#include <string>

#include <CLI/CLI.hpp>
#include <glm/vector_relational.hpp>
#include <unistd.h>

#include "app/headless.h"
#include "render/image_io.h"
#include "scene/scene_io.h"
#ifdef WHISKER_HAVE_VIEWER
#include "viewer/viewer.h"
#endif

namespace fs = std::filesystem;
using namespace whisker;

namespace {

constexpr int kUsageError = 2;  // bad option, bad scene, unwritable output

// "x,y,z" -> vec3, or an error naming the option.
std::optional<vec3> parse_vec3(const std::string& s) {
  std::istringstream in(s);
  vec3 v;
  char c1 = 0, c2 = 0;
  if (!(in >> v.x >> c1 >> v.y >> c2 >> v.z) || c1 != ',' || c2 != ',') return std::nullopt;
  in >> std::ws;
  if (!in.eof() || !std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
    return std::nullopt;
  return v;
}

// An output path is usable if its folder exists and is writable.
std::string check_output(const std::string& path, const char* option) {
  if (path.empty()) return {};
  const fs::path p(path);
  const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    return std::string(option) + " " + path + ": folder " + dir.string() + " does not exist";
  if (fs::is_directory(p, ec)) return std::string(option) + " " + path + ": is a directory";
  if (::access(dir.c_str(), W_OK) != 0)
    return std::string(option) + " " + path + ": folder " + dir.string() + " is not writable";
  return {};
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Whisker: a progressive path tracer for the report's scenes"};
  app.set_version_flag("--version", "whisker 0.1");

  bool headless = false;
  std::string scene_name = "cat";
  std::string mesh;
  int frames = 0;
  std::optional<int> spp, depth, target_spp;
  int threads = 0;
  std::optional<std::uint64_t> seed;
  std::string indirect, fresnel, aa, light, accel, sampler, zero_cutoff, split, split_weights;
  std::optional<float> intensity;
  std::string out_png, out_float, stats_json, screenshot;
  int edit_after = -1;
  std::string edit_light;
  bool quiet = false;

  app.add_flag("--headless", headless, "Render without a window");
  app.add_option("--scene", scene_name,
                 "Scene name (assets/scenes/NAME.json) or path to a scene file")
      ->capture_default_str();
  app.add_option("--mesh", mesh, "Use this OBJ file for the scene's meshes");
  app.add_option("--frames", frames, "Passes to render (headless: default 1)")
      ->check(CLI::Range(1, 1 << 24));
  app.add_option("--spp", spp, "Samples per pixel per pass")->check(CLI::Range(1, 1 << 16));
  app.add_option("--target-spp", target_spp, "Viewer: stop at this many samples per pixel")
      ->check(CLI::Range(0, 1 << 30));
  app.add_option("--depth", depth, "Max bounces after the camera hit")->check(CLI::Range(0, 1000));
  app.add_option("--threads", threads, "Worker threads (0 = all)")->check(CLI::Range(0, 1024));
  app.add_option("--seed", seed, "Random seed");
  app.add_option("--indirect", indirect, "Indirect light")->check(CLI::IsMember({"on", "off"}));
  app.add_option("--fresnel", fresnel, "Fresnel at glass")->check(CLI::IsMember({"on", "off"}));
  app.add_option("--aa", aa, "Anti-aliasing (Gaussian jitter)")->check(CLI::IsMember({"on", "off"}));
  app.add_option("--accel", accel, "Triangle acceleration")
      ->check(CLI::IsMember({"brute", "bbox", "midpoint", "sah"}));
  app.add_option("--sampler", sampler, "Random numbers: independent (the report's) or sobol")
      ->check(CLI::IsMember({"independent", "sobol"}));
  app.add_option("--zero-cutoff", zero_cutoff, "End paths whose throughput is zero")
      ->check(CLI::IsMember({"on", "off"}));
  app.add_option("--split", split,
                 "Indirect paths leaving the 1st, 2nd, ... diffuse hit, e.g. 4,4 (1 = the report's)");
  app.add_option("--split-weights", split_weights,
                 "Per channel r,g,b in [0.01, 1]: paths that carry only low-weight channels split less");
  app.add_option("--light", light, "Light position x,y,z");
  app.add_option("--intensity", intensity, "Light intensity")->check(CLI::Range(0.0, 1e30));
  app.add_option("--out", out_png, "PNG output (the report's display mapping)");
  app.add_option("--out-float", out_float, "Linear radiance output (.pfm or .exr)");
  app.add_option("--stats", stats_json, "Write render statistics as JSON");
  app.add_option("--screenshot", screenshot, "Viewer: save the window after --frames passes");
  app.add_option("--edit-after", edit_after, "Viewer script: apply --edit-light after K passes")
      ->check(CLI::Range(0, 1 << 24));
  app.add_option("--edit-light", edit_light, "Viewer script: new light position x,y,z");
  app.add_flag("--quiet", quiet, "No progress line");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : kUsageError;
  }

  auto usage = [](const std::string& msg) {
    std::fprintf(stderr, "whisker: %s\n", msg.c_str());
    return kUsageError;
  };

  Scene scene;
  try {
    scene = load_scene(resolve_scene(scene_name), mesh);
  } catch (const SceneError& e) {
    return usage(e.what());
  }

  // Command-line settings override the scene file's.
  RenderSettings& s = scene.settings;
  if (spp) s.spp = *spp;
  if (depth) s.max_depth = *depth;
  if (seed) s.seed = *seed;
  if (target_spp) s.target_spp = *target_spp;
  if (!indirect.empty()) s.indirect = indirect == "on";
  if (!fresnel.empty()) s.fresnel = fresnel == "on";
  if (!aa.empty()) s.aa = aa == "on";
  // CLI11 has checked the names already.
  if (!sampler.empty()) parse(sampler, s.sampler);
  if (!accel.empty()) parse(accel, s.accel);
  if (!zero_cutoff.empty()) s.zero_cutoff = zero_cutoff == "on";
  if (!split.empty()) {
    std::vector<int> factors;
    std::istringstream in(split);
    std::string item;
    while (std::getline(in, item, ',')) {
      std::size_t used = 0;
      int k = 0;
      try {
        k = std::stoi(item, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used == 0 || used != item.size())
        return usage("--split " + split + ": expected integers separated by commas, e.g. 4,4");
      factors.push_back(k);
    }
    if (const std::string why = check_split(factors); !why.empty())
      return usage("--split " + split + ": " + why);
    s.split = factors;
  }
  if (!split_weights.empty()) {
    const auto v = parse_vec3(split_weights);
    if (!v || glm::any(glm::lessThan(*v, vec3(0.01f))) || glm::any(glm::greaterThan(*v, vec3(1.0f))))
      return usage("--split-weights " + split_weights +
                   ": expected three numbers r,g,b in [0.01, 1], e.g. 0.5,0.25,1");
    s.split_weights = *v;
  }
  if (!light.empty()) {
    const auto v = parse_vec3(light);
    if (!v) return usage("--light " + light + ": expected three finite numbers x,y,z");
    scene.light.position = *v;
  }
  if (intensity) scene.light.intensity = *intensity;
  // frames x spp samples per pixel must fit the target counter.
  if (std::uint64_t(std::max(frames, 1)) * std::uint64_t(s.spp) > (1ull << 30))
    return usage("--frames " + std::to_string(std::max(frames, 1)) + " x --spp " +
                 std::to_string(s.spp) + " is more than 2^30 samples per pixel");
  for (const auto& [path, option] : {std::pair{out_png, "--out"}, {out_float, "--out-float"},
                                     {stats_json, "--stats"}, {screenshot, "--screenshot"}}) {
    if (auto err = check_output(path, option); !err.empty()) return usage(err);
  }
  if (!out_png.empty() && fs::path(out_png).extension() != ".png")
    return usage("--out " + out_png + ": must end in .png");
  if (!out_float.empty()) {
    const auto ext = fs::path(out_float).extension();
    if (ext != ".pfm" && ext != ".exr")
      return usage("--out-float " + out_float + ": must end in .pfm or .exr");
    if (ext == ".exr" && !have_exr())
      return usage("--out-float " + out_float + ": this build has no OpenEXR; use .pfm");
  }

  try {
    if (headless) {
      if (!screenshot.empty()) return usage("--screenshot needs the viewer; drop --headless");
      if (out_png.empty() && out_float.empty() && stats_json.empty())
        return usage("--headless needs at least one of --out, --out-float, --stats");
      HeadlessOptions h;
      h.scene = scene;
      h.frames = frames > 0 ? frames : 1;
      h.threads = threads;
      h.out_png = out_png;
      h.out_float = out_float;
      h.stats_json = stats_json;
      h.progress = !quiet;
      return run_headless(h);
    }
#ifdef WHISKER_HAVE_VIEWER
    ViewerOptions v;
    v.scene = scene;
    v.scene_path = resolve_scene(scene_name).string();
    v.threads = threads;
    v.frames = frames;
    v.screenshot_path = screenshot;
    if (!screenshot.empty() && frames <= 0) return usage("--screenshot needs --frames N");
    if (edit_after >= 0 || !edit_light.empty()) {
      const auto p = parse_vec3(edit_light);
      if (edit_after < 0 || !p)
        return usage("--edit-after K and --edit-light x,y,z go together");
      v.edits.push_back(ScriptedEdit{edit_after, *p});
    }
    const int code = run_viewer(v);
    if (code == 3)
      std::fprintf(stderr,
                   "whisker: no display for the viewer; render without a window with\n"
                   "  whisker --headless --scene %s --frames 16 --out image.png\n",
                   scene_name.c_str());
    return code;
#else
    std::fprintf(stderr, "whisker: built without the viewer; use --headless\n");
    return 3;
#endif
  } catch (const std::exception& e) {
    // Output errors (ImageError) and anything unexpected: one line, no crash.
    std::fprintf(stderr, "whisker: %s\n", e.what());
    return kUsageError;
  }
}
