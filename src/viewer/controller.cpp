#include "viewer/controller.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include "io/atomic_file.h"
#include "io/image_io.h"
#include "io/render_record.h"
#include "render/film.h"
#include "scene/file_name.h"
#include "scene/scene_io.h"
#include "scene/settings_json.h"
#include "viewer/display.h"
#include "viewer/readout.h"
#include "viewer/save_record.h"
#include "viewer/scene_diff.h"

namespace whisker {

std::string scene_label_of(const Scene& scene, const std::string& path) {
  if (!scene.name.empty()) return scene.name;
  if (!path.empty()) return std::filesystem::path(path).stem().string();
  return "scene";
}

// The name among `names` (the bundled scenes) whose file is `path`, or "".
static std::string bundled_name(const std::vector<std::string>& names, const std::string& path) {
  for (const std::string& name : names) {
    try {
      std::error_code ec;
      if (std::filesystem::equivalent(resolve_scene(name), path, ec)) return name;
    } catch (const std::exception&) {
      // a listed name that no longer resolves is not this file
    }
  }
  return {};
}

std::string scene_choice(const ViewerState& s) {
  if (!s.bundled_scene.empty()) return s.bundled_scene;
  const std::string file = std::filesystem::path(s.scene_path).filename().string();
  return "file: " + (file.empty() ? s.scene_label : file);
}

void request_for_drop(const std::string& path, PanelRequests& req, std::string& error) {
  const std::string ext = lower_extension(path);
  if (ext == ".json")
    req.load_scene = path;
  else if (ext == ".obj")
    req.load_mesh = path;
  else
    error = "dropped " + path + ": not a scene file (.json) or a mesh (.obj)";
}

bool only_target_raised(const Scene& applied, const Scene& edited) {
  const int before = applied.settings.target_spp, after = edited.settings.target_spp;
  if (before == after || before <= 0 || (after > 0 && after < before)) return false;
  Scene same = applied;
  same.settings.target_spp = after;
  return classify_change(same, edited) <= SceneChange::Inert;
}

void Controller::apply_edits(double now, bool record) {
  if (record && classify_change(s.applied, s.edited) != SceneChange::None)
    s.history.changed(s.applied);
  if (only_target_raised(s.applied, s.edited)) {
    // More samples of the same image: the accumulation carries on.
    renderer.set_target_spp(s.edited.settings.target_spp);
    s.applied = s.edited;
    // Past a stop at noise or time: the raised target wins, this render
    // does not stop at them again.
    if (s.stopped_gen == s.generation) s.stop_note.clear();
    return;
  }
  switch (classify_change(s.applied, s.edited)) {
    case SceneChange::None:
      return;
    case SceneChange::Inert:  // the same image: the accumulation carries on
      s.applied = s.edited;
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

void Controller::undo(double now) {
  Scene scene = s.applied;
  if (!s.history.undo(scene)) return;
  s.edited = scene;
  apply_edits(now, false);
}

void Controller::redo(double now) {
  Scene scene = s.applied;
  if (!s.history.redo(scene)) return;
  s.edited = scene;
  apply_edits(now, false);
}

void Controller::save_scene() {
  namespace fs = std::filesystem;
  try {
    const std::string dir = s.save_dir.empty() ? "." : s.save_dir;
    fs::create_directories(dir);
    const std::string wanted = s.save_name.empty() ? s.scene_label + "-edited" : s.save_name;
    const std::string stem = free_stem(dir, wanted, {".json"});
    const std::string path = (fs::path(dir) / (stem + ".json")).string();
    write_file_atomically(path, [&](const std::string& tmp) {
      FILE* f = std::fopen(tmp.c_str(), "w");
      if (!f) return false;
      const std::string text = scene_to_json(s.applied, path) + "\n";
      const bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
      return std::fclose(f) == 0 && ok;
    });
    s.saved_scene = s.applied;
    s.have_saved_scene = true;
    // The folder by its full name, as Save names it for the image.
    std::error_code ec;
    const fs::path full = fs::absolute(path, ec).lexically_normal();
    s.message = "saved the scene as " + (ec ? path : full.string());
    if (stem != wanted) s.message += " (" + wanted + ".json was taken)";
    s.message_is_error = false;
    std::printf("%s\n", s.message.c_str());
    std::fflush(stdout);
  } catch (const std::exception& e) {
    s.message = std::string("save scene failed: ") + e.what();
    s.message_is_error = true;
  }
}

bool Controller::edits_unsaved() const {
  // Edits that are saved in a scene file are not lost by loading another.
  const bool saved = s.have_saved_scene && classify_change(s.saved_scene, s.applied) == SceneChange::None &&
                     classify_change(s.applied, s.edited) == SceneChange::None;
  return s.history.can_undo() && !saved;
}

void Controller::load(const std::string& name_or_path, double now, bool confirmed,
                      const std::string& mesh) {
  const bool ask = !confirmed && edits_unsaved();
  s.pending_load.clear();
  s.pending_mesh.clear();
  try {
    const std::filesystem::path path = resolve_scene(name_or_path);
    Scene scene = load_scene(path, mesh);
    if (!mesh.empty() && scene.meshes.empty())
      throw std::runtime_error(path.string() + " has no mesh to replace with " + mesh);
    if (ask) {
      // The file loads: now the panel asks before the edits go. (A file
      // that does not load says so at once and keeps the edits unasked.)
      s.pending_load = name_or_path;
      s.pending_mesh = mesh;
      return;
    }
    s.initial = scene;
    s.edited = scene;
    s.applied = scene;
    s.scene_label = scene_label_of(scene, path.string());
    s.path_field = path.string();
    s.scene_path = path.string();
    s.bundled_scene = bundled_name(s.scene_names, s.scene_path);
    s.generation = renderer.set_scene(scene);
    s.last_change = now;
    s.history.clear();
    s.have_saved_scene = false;
    s.message = "loaded " + path.string();
    s.message_is_error = false;
  } catch (const std::exception& e) {
    s.message = e.what();
    s.message_is_error = true;
  }
}

static const Snapshot& live_image(const ViewerState& s);

Snapshot shown_means(const ViewerState& s) {
  const Snapshot& live = live_image(s);
  const bool held = s.held.spp > 0 && s.held.width == live.width && s.held.height == live.height;
  const auto means = [](const Snapshot& sn) {
    Snapshot m = sn;
    const Image img = mean_image(sn);
    m.sum.assign(img.rgb.begin(), img.rgb.end());
    m.spp = 1;
    m.sum_sq.assign(sn.sum_sq.size(), 0.0);
    for (std::size_t p = 0; p < m.sum_sq.size() && sn.spp; ++p)
      m.sum_sq[p] = sn.sum_sq[p] / double(sn.spp);
    return m;
  };
  if (held && s.compare == kCompareHeld) return means(s.held);
  Snapshot out = means(live);
  const Snapshot* wiped = wipe_left(s);
  if (wiped && wiped->width == live.width && wiped->height == live.height) {
    const Snapshot left = means(*wiped);
    const int cols = int(std::lround(std::clamp(s.wipe, 0.0f, 1.0f) * float(live.width)));
    for (int y = 0; y < live.height; ++y)
      for (int x = 0; x < cols; ++x) {
        const std::size_t p = std::size_t(y) * live.width + x;
        for (int c = 0; c < 3; ++c) out.sum[3 * p + c] = left.sum[3 * p + c];
        out.sum_sq[p] = left.sum_sq[p];
      }
  }
  return out;
}

// The live image: what the window shows (viewer/blend.h, or its denoised
// copy) once that holds the generation's own passes, else the own passes
// alone.
static const Snapshot& live_image(const ViewerState& s) {
  if (s.shown.image.spp > 0 && s.shown.own_spp > 0) return showing_denoised(s) ? s.denoised : s.shown.image;
  return s.snap;
}

void Controller::save() {
  const Snapshot& own = s.snap;
  if (own.spp == 0 || own.quick || (s.shown.image.spp > 0 && s.shown.own_spp == 0)) {
    s.message = "nothing to save yet: the first full pass is not in";
    s.message_is_error = true;
    return;
  }
  namespace fs = std::filesystem;
  try {
    const std::string dir = s.save_dir.empty() ? "." : s.save_dir;
    fs::create_directories(dir);
    // The denoised image is a separate output, and its name says so.
    const bool denoised = showing_denoised(s) && s.display.mode == kViewImage;
    const std::string wanted =
        (s.save_name.empty() ? s.scene_label + "-" + std::to_string(own.spp) + "spp" : s.save_name) +
        (denoised ? "-denoised" : "");
    const std::string float_ext = have_exr() ? ".exr" : ".pfm";
    // Never overwrite: the first free name, and the panel says which.
    const std::string stem = free_stem(dir, wanted, {".png", float_ext});
    const std::string base = (fs::path(dir) / stem).string();
    // The PNG is what the window shows: exposure, tone curve, gamma, view,
    // the A/B comparison (held, or the wipe's two sides).
    const bool debug = s.display.mode >= kViewNormals && s.debug.view == s.display.mode;
    const Snapshot shown = debug ? s.debug.image : shown_means(s);
    const std::vector<unsigned char> rgb =
        debug ? map_like_display(shown, DisplayParams{1.0f, 1.0f, 0, 0})
        : s.display.mode == kViewNoise ? map_like_display(own, s.display)
                              : map_like_display(shown, s.display);
    write_png_rgb8(base + ".png", shown.width, shown.height, rgb);
    // The float file is the live render's mean (with quick samples combined
    // while the window shows them, viewer/blend.h).
    const Image img = mean_image(live_image(s));
    const bool display_units = s.save_display_units;
    const ImageAttributes record = viewer_record(s, own, display_units);
    write_float_image(base + float_ext, display_units ? display_referred(img) : img, record);
    const char* units = display_units ? " (display units: 1.0 = white)" : " (radiance)";
    const bool wipe = !debug && wipe_left(s);
    const char* as_shown = !wipe ? " (as shown)"
                           : s.compare == kCompareWipe ? " (as shown: held left, live right)"
                                                       : " (as shown: raw left, denoised right)";
    std::string said = "saved " + base + ".png" + as_shown + " and " + base + float_ext + units +
                       (wipe ? " (live)" : "");
    if (stem != wanted) said += "; " + wanted + " was taken, so the name is " + stem;
    std::printf("%s\n", said.c_str());
    std::fflush(stdout);
    // The panel's two lines: the file names, then the folder, by its full
    // name (the tooltip and stdout have the whole line).
    std::error_code ec;
    const fs::path folder = fs::absolute(dir, ec).lexically_normal();
    std::string where = ec ? dir : folder.string();
    if (where.size() > 1 && where.back() == '/') where.pop_back();
    s.message = "saved " + stem + ".png" + as_shown + " and " + float_ext + units +
                (stem != wanted ? "; " + wanted + " was taken" : std::string()) + ", in " + where;
    s.message_is_error = false;
  } catch (const std::exception& e) {
    s.message = std::string("save failed: ") + e.what();
    s.message_is_error = true;
  }
}

void Controller::stop_when_reached() {
  const Snapshot& sn = s.snap;
  if (sn.generation != s.generation || sn.quick || sn.spp == 0 || s.paused) return;
  const std::string why = stop_reason(s.rse, sn.counters.seconds, s.stop_noise_pct, s.stop_seconds);
  if (s.stopped_gen != s.generation && !why.empty() && !sn.done) {
    renderer.set_target_spp(int(sn.spp));
    s.stopped_gen = s.generation;
    s.stop_note = why;
  } else if (s.stopped_gen == s.generation && !s.stop_note.empty() && why.empty()) {
    // The limit was raised or switched off: on to the scene's own target.
    renderer.set_target_spp(s.applied.settings.target_spp);
    s.stopped_gen = 0;
    s.stop_note.clear();
  }
}

void Controller::hold() {
  if (s.snap.spp == 0 || s.snap.quick || (s.shown.image.spp > 0 && s.shown.own_spp == 0)) {
    s.message = "nothing to hold yet";
    s.message_is_error = true;
    return;
  }
  s.held = live_image(s);
  const RenderSettings& r = s.applied.settings;
  s.held_note = std::to_string(s.snap.spp) + " spp, Fresnel " + (r.fresnel ? "on" : "off") +
                ", indirect " + (r.indirect ? "on" : "off");
  if (s.compare == kCompareOff) s.compare = kCompareWipe;
  s.message = "holding the image (" + s.held_note + ") for comparison";
  s.message_is_error = false;
}

void Controller::carry_out(const PanelRequests& req, double now) {
  if (req.reset_camera) s.edited.camera = s.initial.camera;
  // A note about the camera's last move goes with the move.
  if ((req.reset_camera || req.undo || req.redo) && s.message == kCameraStopped) s.message.clear();
  if (req.reset_light) s.edited.light = s.initial.light;
  if (req.threads > 0) {
    renderer.set_threads(req.threads);
    s.threads = renderer.threads();
  }
  if (!req.load_scene.empty()) load(req.load_scene, now);
  // An OBJ goes into the current scene file in place of its meshes.
  if (!req.load_mesh.empty()) load(s.scene_path.empty() ? "cat" : s.scene_path, now, false, req.load_mesh);
  if (req.confirm_load && !s.pending_load.empty()) {
    const std::string name = s.pending_load, mesh = s.pending_mesh;  // load() clears them
    load(name, now, true, mesh);
  }
  if (req.bookmark) s.bookmarks.push_back(s.edited.camera);
  if (req.goto_bookmark >= 0 && req.goto_bookmark < int(s.bookmarks.size()))
    s.edited.camera = s.bookmarks[std::size_t(req.goto_bookmark)];
  // A number being typed applies when its field lets go of the keyboard
  // (Enter, Tab, a click elsewhere), not at every keystroke.
  if (!req.typing) apply_edits(now);
  if (!req.editing) s.history.settle();
  if (req.undo) undo(now);
  if (req.redo) redo(now);
  if (req.save_scene) save_scene();
  if (req.restart) restart(now);
  if (req.toggle_pause) {
    s.paused = !s.paused;
    renderer.set_paused(s.paused);
  }
  if (req.toggle_denoised) s.denoised_view = !s.denoised_view;
  if (req.toggle_panel) s.panel_mode = toggle_panel(s.panel_visible);
  if (req.toggle_readout) s.readout_on = !s.readout_on;
  if (req.save) save();
  if (req.hold) hold();
  if (req.print_camera) {
    std::printf("%s\n", camera_to_json(s.applied.camera).c_str());
    std::fflush(stdout);
  }
}

// A path as the panel shows it: relative to the working folder when it lies
// inside it ("assets/scenes/cat.json"), else as given.
static std::string shown_path(const std::string& path) {
  std::error_code ec;
  const std::filesystem::path rel = std::filesystem::proximate(path, ec);
  if (ec || rel.empty() || *rel.begin() == "..") return path;
  return rel.string();
}

void init_state(ViewerState& s, const Scene& scene, const std::string& path) {
  s.initial = s.applied = s.edited = scene;
  s.scene_label = scene_label_of(scene, path);
  s.path_field = shown_path(path);
  s.scene_path = path;
  try {
    s.scene_names = list_scenes();
    s.bundled_scene = bundled_name(s.scene_names, path);
  } catch (const std::exception& e) {
    s.message = e.what();
    s.message_is_error = true;
  }
}


}  // namespace whisker
