// whisker: the viewer by default, or --headless renders.
#include <cstdio>
#include <exception>
#include <filesystem>
#include <new>
#include <system_error>

#include "app/cli.h"
#include "app/headless.h"
#include "app/merge.h"
#include "app/open_file.h"
#include "app/signals.h"
#include "scene/quote.h"
#include "scene/scene_io.h"
#ifdef WHISKER_HAVE_VIEWER
#include "viewer/viewer.h"
#endif

using namespace whisker;

namespace {

int headless(const CommandLine& cl, const Scene& scene) {
  HeadlessOptions h;
  h.scene = scene;
  h.frames = cl.frames > 0 ? cl.frames : 1;
  h.threads = cl.threads;
  h.out_png = cl.out_png;
  h.out_float = cl.out_float;
  h.stats_json = cl.stats_json;
  h.progress = !cl.quiet;
  h.progress_every = cl.progress_every;
  h.display_units = cl.float_units == "display";
  h.out_sum = cl.out_sum;
  h.checkpoint = cl.checkpoint;
  if (const std::string why = plan_shard(cl, scene, h.plan); !why.empty()) return usage_error(why);
  install_signal_handlers(true);
  return run_headless(h);
}

int viewer(const CommandLine& cl, const Scene& scene) {
#ifdef WHISKER_HAVE_VIEWER
  ViewerOptions v;
  v.scene = scene;
  v.scene_path = resolve_scene(cl.scene_name).string();
  v.threads = cl.threads;
  v.frames = cl.frames;
  v.screenshot_path = cl.screenshot;
  if (!cl.screenshot.empty() && cl.frames <= 0) return usage_error("--screenshot needs --frames N");
  if (cl.edit_after >= 0 || !cl.edit_light.empty()) {
    const auto p = parse_point(cl.edit_light);
    if (cl.edit_after < 0 || !p)
      return usage_error("--edit-after K and --edit-light x,y,z go together");
    v.edits.push_back(ScriptedEdit{cl.edit_after, *p});
  }
  const int code = run_viewer(v);
  if (code == 3)
    std::fprintf(stderr,
                 "whisker: no display for the viewer; render without a window with\n"
                 "  whisker --headless --scene %s --target-spp 32 --out image.png\n",
                 cl.scene_name.c_str());
  return code;
#else
  (void)cl;
  (void)scene;
  std::fprintf(stderr, "whisker: built without the viewer; use --headless\n");
  return 3;
#endif
}

// A scene that is not there: the bundled ones, and the nearest name.
std::string missing_scene(const std::string& name) {
  std::error_code ec;
  const auto path = resolve_scene(name);
  // There, or not to be looked at (a symbolic link loop): load_scene says why.
  if (std::filesystem::exists(path, ec) || (ec && ec != std::errc::no_such_file_or_directory))
    return {};
  const auto names = list_scenes();
  std::string list;
  for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
  const std::string hint = closest(std::filesystem::path(name).stem().string(), names);
  // A name: which file, and every folder it was looked for in.
  const std::string where = path.string() == name ? "scene file not found"
                            : path.filename().string() + ": scene file not found in " +
                                  scene_dirs_text();
  return "--scene " + name + ": " + where + "; bundled scenes: " +
         list + (hint.empty() ? "" : "; did you mean --scene " + hint + "?");
}

}  // namespace

int main(int argc, char** argv) {
  ignore_broken_pipes();
  if (argc > 1 && std::string(argv[1]) == "merge") {
    install_signal_handlers(false);
    return run_merge(argc - 1, argv + 1);
  }
  CommandLine cl;
  if (const auto code = parse_command_line(argc, argv, cl)) return *code;
  // While loading, SIGINT and SIGTERM keep the dispositions the program was
  // started with: by default they end it at once, in the kernel (nothing is
  // written yet; a scene read from a pipe nobody writes would never end
  // otherwise, and a handler can be held back while a call blocks, as under
  // TSan); a SIG_IGN from nohup stays. Once the render starts, headless:
  // Ctrl-C writes the passes so far; the viewer: ends at once. Both handlers
  // remove the temporary files of writes in progress.
  if (const std::string why = missing_scene(cl.scene_name); !why.empty()) return usage_error(why);
  std::error_code ec;
  if (!cl.mesh.empty() && !std::filesystem::is_regular_file(cl.mesh, ec))
    return usage_error("--mesh " + cl.mesh + ": no such file");
  Scene scene;
  try {
    scene = load_scene(resolve_scene(cl.scene_name), cl.mesh);
    if (lower_extension(cl.file) == ".obj") fit_in_cat_room(scene);
  } catch (const SceneError& e) {
    return usage_error(e.what());
  } catch (const std::filesystem::filesystem_error& e) {
    // A file-system error the loaders did not turn into a message of their own.
    return usage_error(cut_for_message(e.path1().string()) + ": " + e.code().message());
  } catch (const std::system_error& e) {
    return usage_error(resolve_scene(cl.scene_name).string() + ": " + e.code().message());
  } catch (const std::bad_alloc&) {
    return usage_error(resolve_scene(cl.scene_name).string() + ": out of memory while loading the scene");
  }
  // Command-line settings override the scene file's.
  if (const std::string why = apply_command_line(cl, scene); !why.empty()) return usage_error(why);
  if (const std::string why = check_outputs(cl, scene); !why.empty())
    return usage_error(why);
  if (!cl.headless &&
      (!cl.samples.empty() || !cl.resume.empty() || !cl.out_sum.empty() || cl.checkpoint >= 0))
    return usage_error("--samples, --resume, --out-sum and --checkpoint need --headless");
  try {
    if (!cl.headless) install_signal_handlers(false);
    return cl.headless ? headless(cl, scene) : viewer(cl, scene);
  } catch (const std::exception& e) {
    // Output errors (ImageError) and anything unexpected: one line, no crash.
    return usage_error(e.what());
  }
}
