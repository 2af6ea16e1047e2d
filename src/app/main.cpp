// whisker: the viewer by default, or --headless renders.
#include <cerrno>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <new>
#include <system_error>

#include "app/cli.h"
#include "app/headless.h"
#include "app/merge.h"
#include "app/open_file.h"
#include "app/shards.h"
#include "app/signals.h"
#include "scene/mesh_io.h"
#include "scene/quote.h"
#include "scene/scene_io.h"
#ifdef WHISKER_HAVE_VIEWER
#include "viewer/viewer.h"
#endif

#include <fcntl.h>
#include <malloc.h>
#include <sys/resource.h>
#include <unistd.h>

using namespace whisker;

namespace {

int headless(const CommandLine& cl, const Scene& scene) {
  HeadlessOptions h;
  h.scene = scene;
  h.frames = cl.frames > 0 ? cl.frames : 1;
  h.threads = cl.threads;
  h.out_png = cl.out_png;
  h.out_float = cl.out_float;
  h.out_denoised = cl.out_denoised;
  h.denoise_fast = cl.denoiser == "fast";
  h.features = cl.features || !cl.out_denoised.empty();
  h.stats_json = cl.stats_json;
  h.progress = !cl.quiet;
  h.progress_every = cl.progress_every;
  h.display_units = cl.float_units == "display";
  h.out_sum = cl.out_sum;
  h.checkpoint = cl.checkpoint;
  h.one_pass_if_exact = cl.frames <= 0 && cl.samples.empty() && cl.resume.empty();
  h.target_spp_given = given(cl, "--target-spp");
  if (const std::string why = plan_shard(cl, scene, h.plan); !why.empty()) return usage_error(why);
  // What will not fit is refused before anything is rendered.
  const std::uint64_t bytes = render_memory(scene, !h.out_sum.empty(), bool(h.plan.start.resume), h.features);
  const std::string doing = "rendering " + std::to_string(scene.camera.width) + " x " +
                            std::to_string(scene.camera.height) + " pixels";
  if (const std::string why = check_memory(doing, bytes); !why.empty()) return usage_error(why);
  install_signal_handlers(true);
  try {
    return run_headless(h);
  } catch (const std::bad_alloc&) {
    return usage_error("out of memory while " + doing + " or writing its outputs: needs about " +
                       std::to_string((bytes >> 20) + 1) + " MB");
  }
}

// `word` as the shell reads it back: as is if it holds only characters
// no shell treats specially, else in single quotes (a ' as '\'').
std::string shell_word(const std::string& word) {
  const bool plain = !word.empty() && word.find_first_not_of(
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_-+=.,:/@%") == std::string::npos;
  if (plain) return word;
  std::string out = "'";
  for (char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// The scene and mesh of the command line, as arguments that render them
// again: FILE, or --scene and --mesh.
std::string what_to_render(const CommandLine& cl) {
  if (!cl.file.empty()) return shell_word(cl.file);
  std::string args = "--scene " + shell_word(cl.scene_name);
  if (!cl.mesh.empty()) args += " --mesh " + shell_word(cl.mesh);
  return args;
}

int viewer(const CommandLine& cl, const Scene& scene) {
#ifdef WHISKER_HAVE_VIEWER
  ViewerOptions v;
  v.scene = scene;
  v.scene_path = resolve_scene(cl.scene_name).string();
  v.threads = cl.threads;
  v.frames = cl.frames;
  v.screenshot_path = cl.screenshot;
  v.denoised = cl.denoised_view;
  v.event_log = cl.edit_log;
  const bool any_edit = !cl.edit_light.empty() || !cl.edit_orbit.empty() || !cl.edit_toggle.empty();
  if (cl.edit_after >= 0 || any_edit) {
    if (cl.edit_after < 0 || !any_edit)
      return usage_error(
          "--edit-after K goes with one of --edit-light x,y,z, --edit-orbit dx,dy, --edit-toggle NAME");
    ScriptedEdit e;
    e.after_pass = cl.edit_after;
    if (!cl.edit_light.empty()) {
      e.light_position = parse_point(cl.edit_light);
      if (!e.light_position) return usage_error("--edit-light " + cl.edit_light + ": expected x,y,z");
    }
    if (!cl.edit_orbit.empty()) {
      const auto p = parse_point(cl.edit_orbit + ",0");
      if (!p) return usage_error("--edit-orbit " + cl.edit_orbit + ": expected dx,dy");
      e.orbit = glm::dvec2(p->x, p->y);
    }
    e.toggle = cl.edit_toggle;
    v.edits.push_back(e);
  }
  const int code = run_viewer(v);
  if (code == 3)
    std::fprintf(stderr,
                 "whisker: no display for the viewer; render without a window with\n"
                 "  whisker --headless %s --target-spp 32 --out image.png\n",
                 printable(what_to_render(cl)).c_str());
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

// Descriptors 0, 1 and 2 open before anything else opens a file: a program
// started with one closed (`2>&-`) would otherwise get it back from the next
// open(2), which returns the lowest free descriptor (POSIX open(), "shall
// return ... the lowest numbered unused file descriptor"), and its progress
// lines or messages would land in an output file or the X connection. The
// closed ones are opened on /dev/null; if even that fails there is no safe
// way to go on.
void ensure_standard_descriptors() {
  for (int fd = 0; fd <= 2; ++fd) {
    if (::fcntl(fd, F_GETFD) != -1 || errno != EBADF) continue;
    const int got = ::open("/dev/null", fd == 0 ? O_RDONLY : O_WRONLY);
    if (got != fd) ::_exit(2);  // the lowest free one is fd; anything else is beyond repair
  }
}

// Under a limit of address space (ulimit -v) one malloc arena: glibc gives
// threads arenas of their own, each reserving up to 64 MB of address space
// (mallopt(3), M_ARENA_MAX), which the limit counts and the render's
// memory estimate does not.
void one_arena_under_a_limit() {
  struct rlimit lim {};
  if (::getrlimit(RLIMIT_AS, &lim) == 0 && lim.rlim_cur != RLIM_INFINITY) ::mallopt(M_ARENA_MAX, 1);
}

}  // namespace

int main(int argc, char** argv) {
  ensure_standard_descriptors();
  one_arena_under_a_limit();
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
  // FILE.obj: the cat's room, the mesh fitted in place of the cat.
  const bool obj_file = lower_extension(cl.file) == ".obj";
  if (const std::string why = check_mesh_file(cl, obj_file); !why.empty()) return usage_error(why);
  Scene scene;
  std::string loading = resolve_scene(cl.scene_name).string();  // the file being read
  try {
    scene = load_scene(loading, obj_file ? std::string() : cl.mesh);
    if (obj_file) {
      loading = cl.mesh;
      fit_in_cat_room(scene, cl.mesh);
    }
  } catch (const SceneError& e) {
    return usage_error(e.what());
  } catch (const MeshError& e) {
    return usage_error(e.what());  // names the file (and line)
  } catch (const std::filesystem::filesystem_error& e) {
    // A file-system error the loaders did not turn into a message of their own.
    return usage_error(cut_for_message(e.path1().string()) + ": " + e.code().message());
  } catch (const std::system_error& e) {
    return usage_error(cut_for_message(loading) + ": " + e.code().message());
  } catch (const std::bad_alloc&) {
    return usage_error(cut_for_message(loading) + ": out of memory while loading it");
  } catch (const std::exception& e) {
    // Whatever else a library throws while loading: one line, never an abort.
    return usage_error(cut_for_message(loading) + ": " + e.what());
  }
  // Command-line settings override the scene file's.
  if (const std::string why = apply_command_line(cl, scene); !why.empty()) return usage_error(why);
  if (const std::string why = check_outputs(cl, scene); !why.empty())
    return usage_error(why);
  try {
    if (!cl.headless) install_signal_handlers(false);
    return cl.headless ? headless(cl, scene) : viewer(cl, scene);
  } catch (const std::exception& e) {
    // Output errors (ImageError) and anything unexpected: one line, no crash.
    return usage_error(e.what());
  }
}
