// The command line: options, their checks and how they override a scene.
// The render-settings options come from the settings table (scene/settings.h).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "scene/file_name.h"  // lower_extension, for every app/ file
#include "scene/scene.h"

namespace whisker {

inline constexpr int kUsageError = 2;  // bad option, bad scene, unwritable output

struct CommandLine {
  bool headless = false;
  std::string scene_name = "cat";
  std::string mesh;
  // FILE, the one positional argument (what a desktop launcher passes): a
  // scene file (.json) or a mesh (.obj, shown in the cat scene's room in
  // place of the cat, fitted: fit_in_cat_room). Sets scene_name, or mesh
  // with scene_name "cat".
  std::string file;
  int frames = 0;
  int threads = 0;
  // The settings options given, and their values in `settings`.
  std::vector<const SettingField*> given;
  RenderSettings settings;
  std::string light;
  std::optional<float> intensity;
  std::string out_png, out_float, stats_json, screenshot;
  std::string out_denoised;          // headless: the denoised image (.png, .pfm or .exr)
  std::string denoiser = "quality";  // its filter: "fast" or "quality"
  bool denoised_view = false;        // the viewer starts showing the denoised image
  // Headless: keep the denoiser's feature buffers without --out-denoised (in
  // --out-sum parts, whose merge may then be denoised, and --out-float's EXR).
  bool features = false;
  int edit_after = -1;
  std::string edit_light;
  std::string edit_orbit;   // "dx,dy" radians, as a left drag
  std::string edit_toggle;  // a boolean setting's key ("fresnel")
  std::string edit_log;     // the viewer's event log (bench/viewer_latency.sh)
  bool quiet = false;
  double progress_every = 5.0;      // seconds between progress lines in a log
  std::string float_units = "scene";  // of --out-float: "scene" or "display"
  // Sample-range shards and resuming (docs/SHARDS.md).
  std::string samples;  // "A:B"
  std::string resume;   // an accumulation file to continue
  std::string out_sum;  // accumulation file output (.exr)
  double checkpoint = -1;  // seconds between --out-sum updates while rendering (< 0: off)
};

// Parses argv into `out`. Returns an exit code when the run ends here (--help,
// --version, a bad option: message printed), else nullopt.
std::optional<int> parse_command_line(int argc, char** argv, CommandLine& out);

// Applies the given options over the scene file's values; returns what is
// wrong ("" if nothing), a one-line message naming the option.
std::string apply_command_line(const CommandLine& cl, Scene& scene);

// Checks the output paths and the options that go together; no output may
// name an input (the scene file, its meshes, --resume).
std::string check_outputs(const CommandLine& cl, const Scene& scene);

// Samples per pixel a render takes: --frames N passes of --spp, else the
// scene's target_spp (--target-spp), else one pass.
std::uint64_t samples_per_pixel(const CommandLine& cl, const RenderSettings& settings);

// Whether two paths name one file: the same file now (a hard or symbolic
// link, "./x" and "x"), or the same name once created. Outputs are checked
// with it against inputs and each other.
bool same_file(const std::string& a, const std::string& b);

// Whether a settings option (e.g. "--target-spp") was given.
bool given(const CommandLine& cl, const char* option);

// The candidate nearest to `word` in edits, or "" if none is close.
std::string closest(const std::string& word, const std::vector<std::string>& candidates);

// The render settings' options as man-page source, one entry per row of the
// settings table (printed by the hidden option --man-settings).
std::string settings_man_page();

// Prints "whisker: MESSAGE" to stderr; returns kUsageError.
int usage_error(const std::string& message);

// `whisker merge PART.exr... --out FILE... [--stats F] [--partial]
// [--out-denoised F [--denoiser quality|fast]]` (docs/SHARDS.md).
struct MergeCommandLine {
  std::vector<std::string> parts;
  std::vector<std::string> outs;
  std::string stats_json;
  bool partial = false;
  std::string out_denoised;          // the merge's denoised copy (.png, .pfm or .exr)
  std::string denoiser = "quality";  // its filter, as a render's --denoiser
};

// Parses merge's argv (argv[0] is "merge") into `out`, as parse_command_line.
// Here so that the parser library (heavy to compile) is in one file only.
std::optional<int> parse_merge_command_line(int argc, char** argv, MergeCommandLine& out);

}  // namespace whisker
