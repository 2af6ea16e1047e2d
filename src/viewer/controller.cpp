#include "viewer/controller.h"

#include <cstdio>
#include <exception>
#include <filesystem>

#include "render/image_io.h"
#include "scene/scene_io.h"
#include "viewer/scene_diff.h"

namespace whisker {

std::string scene_label_of(const Scene& scene, const std::string& path) {
  if (!scene.name.empty()) return scene.name;
  if (!path.empty()) return std::filesystem::path(path).stem().string();
  return "scene";
}

bool only_target_raised(const Scene& applied, const Scene& edited) {
  const int before = applied.settings.target_spp, after = edited.settings.target_spp;
  if (before == after || before <= 0 || (after > 0 && after < before)) return false;
  Scene same = applied;
  same.settings.target_spp = after;
  return classify_change(same, edited) == SceneChange::None;
}

void Controller::apply_edits(double now) {
  if (only_target_raised(s.applied, s.edited)) {
    // More samples of the same image: the accumulation carries on.
    renderer.set_target_spp(s.edited.settings.target_spp);
    s.applied = s.edited;
    return;
  }
  switch (classify_change(s.applied, s.edited)) {
    case SceneChange::None:
      return;
    case SceneChange::Settings:
      s.generation = renderer.set_settings(s.edited.settings);
      break;
    case SceneChange::Scene:
      s.generation = renderer.set_scene(s.edited);
      break;
  }
  s.applied = s.edited;
  s.last_change = now;
}

void Controller::restart(double now) {
  s.generation = renderer.set_scene(s.applied);
  s.last_change = now;
}

void Controller::load(const std::string& name_or_path, double now) {
  try {
    const std::filesystem::path path = resolve_scene(name_or_path);
    Scene scene = load_scene(path);
    s.initial = scene;
    s.edited = scene;
    s.applied = scene;
    s.scene_label = scene_label_of(scene, path.string());
    s.path_field = path.string();
    s.generation = renderer.set_scene(scene);
    s.last_change = now;
    s.message = "loaded " + path.string();
    s.message_is_error = false;
  } catch (const std::exception& e) {
    s.message = e.what();
    s.message_is_error = true;
  }
}

void Controller::save() {
  const Snapshot& sn = s.snap;
  if (sn.spp == 0 || sn.preview) {
    s.message = "nothing to save yet";
    s.message_is_error = true;
    return;
  }
  const std::string base = (std::filesystem::path(s.save_dir) /
                            (s.scene_label + "-" + std::to_string(sn.spp) + "spp"))
                               .string();
  try {
    const Image img = Image::mean_of(sn);
    write_png(base + ".png", img);
    const std::string float_path = base + (have_exr() ? ".exr" : ".pfm");
    write_float_image(float_path, img);
    s.message = "saved " + base + ".png and " + float_path;
    s.message_is_error = false;
    std::printf("%s\n", s.message.c_str());
    std::fflush(stdout);
  } catch (const std::exception& e) {
    s.message = std::string("save failed: ") + e.what();
    s.message_is_error = true;
  }
}

void Controller::carry_out(const PanelRequests& req, double now) {
  if (req.reset_camera) s.edited.camera = s.initial.camera;
  if (req.threads > 0) {
    renderer.set_threads(req.threads);
    s.threads = renderer.threads();
  }
  if (!req.load_scene.empty()) load(req.load_scene, now);
  // A number being typed applies when its field lets go of the keyboard
  // (Enter, Tab, a click elsewhere), not at every keystroke.
  if (!req.typing) apply_edits(now);
  if (req.restart) restart(now);
  if (req.toggle_pause) {
    s.paused = !s.paused;
    renderer.set_paused(s.paused);
  }
  if (req.save) save();
  if (req.print_camera) {
    std::printf("%s\n", camera_to_json(s.applied.camera).c_str());
    std::fflush(stdout);
  }
}

}  // namespace whisker
