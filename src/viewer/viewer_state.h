// The viewer's state between frames and the ImGui panel that edits it.
#pragma once

#include <limits>

#include <cstdint>
#include <string>
#include <vector>

#include "render/progressive.h"
#include "scene/scene.h"
#include "viewer/blend.h"
#include "viewer/debug_views.h"
#include "viewer/denoised_view.h"
#include "viewer/display.h"
#include "viewer/history.h"
#include "viewer/layout.h"

namespace whisker {

// The panel's note when a camera move was cut short at a surface.
inline constexpr const char* kCameraStopped = "the camera stopped at a surface";

// What the panel (or a key) asked for this frame; the loop carries it out.
struct PanelRequests {
  bool toggle_pause = false;
  bool restart = false;
  bool save = false;
  bool reset_camera = false;
  bool reset_light = false;
  bool print_camera = false;
  bool toggle_denoised = false;  // raw or denoised image (D)
  bool quit = false;
  std::string load_scene;  // name or path
  std::string load_mesh;   // an OBJ for the current scene's meshes
  int threads = 0;         // > 0: new thread count
  bool typing = false;     // a text field has the keyboard: hold the edits
  bool hold = false;       // keep the current image for comparison
  bool undo = false, redo = false;
  bool save_scene = false;  // the applied scene as a scene file
  bool bookmark = false;    // remember the camera
  int goto_bookmark = -1;   // >= 0: take that bookmark's camera
  bool editing = false;     // a widget or a mouse button is held: one undo step
  bool confirm_load = false;  // discard the edits and load s.pending_load
  bool close_popups = false;  // Esc with a dropdown or a question open
  bool confirm_quit = false;  // discard the edits and quit
  bool toggle_panel = false;    // Tab: hide or show the panel
  bool toggle_readout = false;  // I: hide or show the pixel readout
};

// The A/B comparison: an image held back, shown instead of or beside the
// live one.
// kCompareRawDenoised: with the denoised view, the live raw image left of the
// wipe line and its denoised copy right of it.
enum CompareMode : int { kCompareOff = 0, kCompareHeld = 1, kCompareWipe = 2, kCompareRawDenoised = 3 };

struct ViewerState {
  Scene initial;   // as loaded: what "reset camera" returns to
  Scene applied;   // what the renderer was last given
  Scene edited;    // the panel's working copy; compared with `applied`
  std::string scene_label;
  std::vector<std::string> scene_names;
  // The bundled scene (of scene_names) the current one was loaded from;
  // empty for any other file, which the dropdown then names.
  std::string bundled_scene;
  std::string path_field;
  std::string scene_path;  // the file the current scene came from
  std::string save_dir = ".";
  std::string save_name;  // file name without extension; empty: SCENE-Nspp
  bool save_display_units = false;  // the float file: 1.0 = the report's white
  std::string message;  // last save / load result shown in the panel
  bool message_is_error = false;

  int threads = 1;
  int threads_edit = 0;  // the slider's value while it is dragged
  bool paused = false;
  std::uint64_t generation = 0;  // last generation asked for
  double last_change = 0.0;      // glfwGetTime() of the last edit

  Snapshot snap;   // the generation's own passes (what headless writes)
  Snapshot quick;  // the quick passes after an edit (ProgressiveRenderer::set_quick_passes)
  Shown shown;     // what the window draws and S saves: snap, quick, or both combined
  ProgressiveRenderer::PassProgress progress;  // the pass in flight
  // Relative standard error of snap; NaN before a pass of its own has two samples.
  double rse = std::numeric_limits<double>::quiet_NaN();
  std::size_t nodes = 0;  // 0: not known
  // log10 of the relative standard error, one entry per pass of this generation.
  std::vector<float> rse_history;

  float exposure_stops = 0.0f;  // relative to the report's mapping
  DisplayParams display;
  bool readout_on = true;  // the pixel readout over the image (I)

  PanelMode panel_mode = PanelMode::Auto;  // Tab
  bool panel_visible = true;               // as drawn last frame
  bool panel_overlay = false;              // over the image (a small window)
  float panel_width = 0.0f;                // window units

  EditHistory history;
  std::vector<Camera> bookmarks;
  std::string pending_load;  // a load waiting for "discard the edits?"
  bool pending_quit = false;  // a quit waiting for "discard the edits?"
  // The scene as last written by Save scene: its edits are kept, so loading
  // another scene asks nothing while the applied scene is still this one.
  Scene saved_scene;
  bool have_saved_scene = false;
  std::string pending_mesh;  // with this OBJ for its meshes

  DebugImage debug;       // the debug view on screen (display.mode >= 2)
  // Not empty when the applied camera's eye is outside the room or inside an
  // object (eye_inside_room): the panel says so and offers Reset camera.
  std::string eye_outside;
  // The same for the light (a light out there leaves the room black).
  std::string light_outside;

  // The denoised view (the Denoised box, key D; viewer/denoised_view.h):
  // a separate image beside the raw film, shown while `denoised_view` is on.
  bool denoised_view = false;
  Snapshot denoised;  // the latest denoised image (sum / spp its mean)
  DenoisedFigures denoised_figures;

  Snapshot held;          // the image held for comparison (spp 0: none)
  std::string held_note;  // what it showed, e.g. "Fresnel on, 64 spp"
  int compare = kCompareOff;
  float wipe = 0.5f;      // held image left of this fraction of the width

  // Sampling > stop at: a render stops once its noise (percent of the mean)
  // or its render time (seconds) reaches these (0: off); the next render,
  // after an edit, starts as ever and stops at them too.
  float stop_noise_pct = 0.0f, stop_seconds = 0.0f;
  float stop_noise_field = 0.0f, stop_seconds_field = 0.0f;  // as being typed
  std::uint64_t stopped_gen = 0;  // the generation stopped (or let go on) by them
  std::string stop_note;          // why it stopped ("noise 2 % reached"); "" once let go on

  std::uint64_t bar_spp = 0;  // the samples per pixel the panel's bar said last frame

  // The mean UI frame time (ms) of the last frames, for the panel.
  float frame_ms_avg = 0.0f;
};

// Draws the panel at the right edge of a window of `window_w` x `window_h`
// (window coordinates), `panel_w` wide (0: hidden, only its questions show);
// edits state.edited and fills `req`.
void draw_panel(ViewerState& state, float window_w, float window_h, float panel_w,
                double now, PanelRequests& req);

// What the Scene dropdown says: the bundled scene's name, or "file: NAME"
// for a scene loaded from any other file (a saved, edited scene keeps the
// name of the scene it came from, so its name alone would say "cat").
std::string scene_choice(const ViewerState& state);

// The panel's first line after the scene and size: "rendering", "paused",
// "done: target reached", "stopped: noise 2 % reached", ...
std::string state_text(const ViewerState& state);

// Whether a hovered widget waits for the pointer to rest before its tooltip
// shows: the window then draws frames until it does.
bool tooltip_waiting();
// The text of the tooltip shown this frame ("" for none).
const std::string& tooltip_shown();

// The samples per pixel that the window's title and the panel's progress
// bar both say: the current settings' own published passes (0 until the
// first of them lands; never the quick passes, never a pass in flight, which
// moves the bar's fill only).
std::uint64_t shown_spp(const ViewerState& state);

// Whether the window shows the denoised image: asked for, in the image
// view, and one of the generation shown is in.
inline bool showing_denoised(const ViewerState& s) {
  return s.denoised_view && s.display.mode == kViewImage && s.denoised.spp > 0 &&
         s.denoised.generation == s.shown.image.generation && s.denoised.width == s.shown.image.width &&
         s.denoised.height == s.shown.image.height;
}

// The image left of the wipe line: the held one (kCompareWipe), the raw
// live one while its denoised copy is shown (kCompareRawDenoised), or none.
inline const Snapshot* wipe_left(const ViewerState& s) {
  if (s.compare == kCompareWipe && s.held.spp > 0) return &s.held;
  if (s.compare == kCompareRawDenoised && showing_denoised(s)) return &s.shown.image;
  return nullptr;
}

// With the denoised view on: the newest image of the current generation
// with feature buffers and two samples (its own passes, else the quick
// passes at full size), for the filter; null if none (an exact image has
// nothing to denoise). denoise_key names it, to hand each over once.
const Snapshot* denoise_source(const ViewerState& s);
std::uint64_t denoise_key(const ViewerState& s, const Snapshot& source);
// A scripted run with the denoised view ends on the denoised image of its
// last pass: whether that is in (always true with the view off).
bool denoised_caught_up(const ViewerState& s);

// The report's display mapping as an exposure: L / 255^2.2.
float report_exposure();

}  // namespace whisker
