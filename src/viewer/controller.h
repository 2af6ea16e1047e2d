// The viewer's actions on the renderer: every restart goes through here.
#pragma once

#include "io/render_record.h"

#include <string>

#include "io/image_io.h"
#include "render/progressive.h"
#include "scene/scene.h"
#include "viewer/viewer_state.h"

namespace whisker {

// The scene's name, else the file's stem, else "scene".
std::string scene_label_of(const Scene& scene, const std::string& path);

// What a file dropped on the window asks for: a scene file loads, an OBJ
// replaces the current scene's meshes; anything else is refused with a message.
void request_for_drop(const std::string& path, PanelRequests& req, std::string& error);

// The image the window shows, as a mean per pixel (spp 1): the live one (raw
// or denoised), the held one, or in a wipe the left image's columns left of
// the line (wipe_left; the same whole columns as Display::draw_columns) and
// the live one's right of it.
Snapshot shown_means(const ViewerState& s);

// The panel's state for the scene given on the command line, read from `path`.
void init_state(ViewerState& s, const Scene& scene, const std::string& path);

// True if the edit only raises the target samples per pixel (or lifts it to
// 0 = never stop): the render goes on instead of restarting.
bool only_target_raised(const Scene& applied, const Scene& edited);

struct Controller {
  ProgressiveRenderer& renderer;
  ViewerState& s;

  // Hands the panel's edits to the renderer if a value really changed;
  // `record`: as an undo step.
  void apply_edits(double now, bool record = true);
  // One step back or forward in the edit history.
  void undo(double now);
  void redo(double now);
  // Writes the applied scene as a scene file (scene_io's format) into
  // s.save_dir, under a name that overwrites nothing.
  void save_scene();
  // Renders the applied scene again from the first pass.
  void restart(double now);
  // Loads a bundled scene by name or a scene file; errors go to the panel.
  // With edits that could be undone it first asks (s.pending_load) unless
  // `confirmed`.
  // Whether edits would be lost by loading another scene or quitting: there
  // are edits to undo and the applied scene is not the one last saved.
  bool edits_unsaved() const;
  void load(const std::string& name_or_path, double now, bool confirmed = false,
            const std::string& mesh = {});
  // Writes the image as shown (PNG) and its radiance (EXR, or PFM; in
  // display units if s.save_display_units) into s.save_dir, under a name
  // that overwrites nothing.
  void save();
  // Stops the render at Sampling > stop at (its target becomes the samples
  // it has), once a generation; lets it go on when the limit is raised or
  // switched off before the target is raised.
  void stop_when_reached();
  // Keeps the current image for the A/B comparison.
  void hold();
  // Carries out the panel's and the keys' requests, except quitting.
  void carry_out(const PanelRequests& req, double now);
};

}  // namespace whisker
