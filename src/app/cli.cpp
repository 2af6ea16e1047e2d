#include "app/cli.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <sstream>

#include <CLI/CLI.hpp>
#include <unistd.h>

#include "render/image_io.h"
#include "scene/quote.h"

namespace whisker {

namespace fs = std::filesystem;

namespace {

// "on|off", "brute|bbox|midpoint|sah", "INT in [1, 65536]": the value an
// option takes, for --help.
struct TypeName {
  const SettingField& f;
  std::string bounds(double hi) const {
    std::ostringstream s;
    s << std::setprecision(12) << " in [" << f.lo << ", " << hi << "]";
    return s.str();
  }
  std::string operator()(bool RenderSettings::*) const { return "on|off"; }
  std::string operator()(int RenderSettings::*) const {
    return "INT" + bounds(f.option_hi > 0 ? f.option_hi : f.hi);
  }
  std::string operator()(std::uint64_t RenderSettings::*) const { return "UINT"; }
  template <NamedEnum E>
  std::string operator()(E RenderSettings::*) const {
    std::string s;
    for (const auto& n : enum_names(E{})) s += std::string(s.empty() ? "" : "|") + n.name;
    return s;
  }
  std::string operator()(std::vector<int> RenderSettings::*) const {
    return std::string("INT,... e.g. ") + f.example;
  }
  std::string operator()(vec3 RenderSettings::*) const { return "R,G,B each" + bounds(f.hi); }
};

// An output path is usable if its folder exists and is writable, and the
// path names a regular file or nothing.
std::string check_output(const std::string& path, const char* option) {
  if (path.empty()) return {};
  const fs::path p(path);
  const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    return std::string(option) + " " + path + ": folder " + dir.string() + " does not exist";
  // Never replace a directory, FIFO, device node or socket (nor what a
  // symbolic link points to) by a regular file.
  if (const std::string why = not_replaceable(path); !why.empty())
    return std::string(option) + " " + path + ": " + why;
  if (::access(dir.c_str(), W_OK) != 0)
    return std::string(option) + " " + path + ": folder " + dir.string() + " is not writable";
  return {};
}

// A float option's check: a finite number in [lo, hi]. (CLI::Range lets
// NaN through, since every comparison with NaN is false.)
CLI::Validator finite_in(double lo, double hi) {
  std::ostringstream range;
  range << "[" << lo << ", " << hi << "]";
  return CLI::Validator(
      [lo, hi, r = range.str()](std::string& text) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (text.empty() || *end != '\0' || !std::isfinite(v) || v < lo || v > hi)
          return "must be a finite number in " + r + ", got " + cut_for_message(text);
        return {};
      },
      "FLOAT in " + range.str());
}

void add_app_options(CLI::App& app, CommandLine& o) {
  app.add_flag("--headless", o.headless, "Render without a window");
  app.add_option("--scene", o.scene_name,
                 "Scene name (assets/scenes/NAME.json) or path to a scene file")
      ->capture_default_str();
  app.add_option("--mesh", o.mesh, "Use this OBJ file for the scene's meshes");
  app.add_option("--frames", o.frames, "Passes to render (headless: default 1)")
      ->check(CLI::Range(1, 1 << 24));
  app.add_option("--threads", o.threads, "Worker threads (0 = all)")->check(CLI::Range(0, 1024));
  app.add_option("--light", o.light, "Light position x,y,z");
  app.add_option("--intensity", o.intensity, "Light intensity")->check(finite_in(0.0, 1e30));
  app.add_option("--out", o.out_png, "PNG output (the report's display mapping)");
  app.add_option("--out-float", o.out_float, "Linear radiance output (.pfm or .exr)");
  app.add_option("--stats", o.stats_json, "Write render statistics as JSON");
  app.add_option("--screenshot", o.screenshot, "Viewer: save the window after --frames passes");
  app.add_option("--edit-after", o.edit_after, "Viewer script: apply --edit-light after K passes")
      ->check(CLI::Range(0, 1 << 24));
  app.add_option("--edit-light", o.edit_light, "Viewer script: new light position x,y,z");
  app.add_flag("--quiet", o.quiet, "No progress line");
  app.add_option("--samples", o.samples,
                 "Headless: render sample indices A to B-1 of every pixel (A:B), in passes of --spp");
  app.add_option("--resume", o.resume,
                 "Headless: continue the render in this accumulation file (.exr from --out-sum)");
  app.add_option("--out-sum", o.out_sum,
                 "Headless: accumulation file (.exr): exact sums, sample range, scene and settings");
  app.add_option("--checkpoint", o.checkpoint,
                 "Headless: also write --out-sum while rendering, at most every SECONDS (0: every "
                 "pass), to --resume a killed render")
      ->check(finite_in(0.0, 1e9));
}

}  // namespace

int usage_error(const std::string& message) {
  // What a message quotes is cut where it is built; this bounds the rest.
  constexpr std::size_t kMax = 4000;
  const std::string shown = message.size() > kMax ? cut_for_message(message, kMax) : message;
  std::fprintf(stderr, "whisker: %s\n", shown.c_str());
  return kUsageError;
}

std::optional<int> parse_command_line(int argc, char** argv, CommandLine& out) {
  CLI::App app{"Whisker: a progressive path tracer for the report's scenes"};
  app.set_version_flag("--version", "whisker 0.1");
  add_app_options(app, out);
  // One line, like every other refusal: "whisker: --frames: ...".
  app.failure_message([](const CLI::App*, const CLI::Error& e) {
    return "whisker: " + cut_for_message(e.what(), 1000) + " (see --help)\n";
  });
  const auto fields = setting_fields();
  std::vector<std::string> texts(fields.size());
  std::vector<CLI::Option*> options(fields.size());
  for (std::size_t i = 0; i < fields.size(); ++i)
    options[i] = app.add_option(fields[i].option, texts[i], fields[i].help)
                     ->type_name(std::visit(TypeName{fields[i]}, fields[i].member));
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : kUsageError;
  }
  for (std::size_t i = 0; i < fields.size(); ++i) {
    if (options[i]->count() == 0) continue;
    if (const std::string why = set_from_text(fields[i], texts[i], out.settings); !why.empty())
      return usage_error(std::string(fields[i].option) + " " + cut_for_message(texts[i]) + ": " + why);
    out.given.push_back(&fields[i]);
  }
  return std::nullopt;
}

std::string apply_command_line(const CommandLine& cl, Scene& scene) {
  for (const SettingField* f : cl.given) copy_field(*f, cl.settings, scene.settings);
  if (!cl.light.empty()) {
    const auto v = parse_vec3(cl.light);
    if (!v) return "--light " + cl.light + ": expected three finite numbers x,y,z";
    scene.light.position = *v;
  }
  if (cl.intensity) scene.light.intensity = *cl.intensity;
  return {};
}

std::string check_outputs(const CommandLine& cl, const RenderSettings& s) {
  // frames x spp samples per pixel must fit the target counter.
  const int frames = std::max(cl.frames, 1);
  if (std::uint64_t(frames) * std::uint64_t(s.spp) > (1ull << 30))
    return "--frames " + std::to_string(frames) + " x --spp " + std::to_string(s.spp) +
           " is more than 2^30 samples per pixel";
  for (const auto& [path, option] :
       {std::pair{cl.out_png, "--out"}, {cl.out_float, "--out-float"},
        {cl.stats_json, "--stats"}, {cl.screenshot, "--screenshot"}, {cl.out_sum, "--out-sum"}}) {
    if (auto err = check_output(path, option); !err.empty()) return err;
  }
  if (!cl.out_png.empty() && fs::path(cl.out_png).extension() != ".png")
    return "--out " + cl.out_png + ": must end in .png";
  if (!cl.out_float.empty()) {
    const auto ext = fs::path(cl.out_float).extension();
    if (ext != ".pfm" && ext != ".exr")
      return "--out-float " + cl.out_float + ": must end in .pfm or .exr";
    if (ext == ".exr" && !have_exr())
      return "--out-float " + cl.out_float + ": this build has no OpenEXR; use .pfm";
  }
  if (cl.headless && !cl.screenshot.empty()) return "--screenshot needs the viewer; drop --headless";
  if (cl.headless && cl.out_png.empty() && cl.out_float.empty() && cl.stats_json.empty() &&
      cl.out_sum.empty())
    return "--headless needs at least one of --out, --out-float, --stats, --out-sum";
  return {};
}

}  // namespace whisker
