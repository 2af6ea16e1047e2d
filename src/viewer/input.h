// Keys and mouse to actions. The mappings are plain functions of what was
// pressed and what ImGui wants (testable without a window); read_keys() and
// read_mouse() fill their inputs from ImGui's state for this frame.
#pragma once

#include "scene/scene.h"
#include "viewer/viewer_state.h"
#include "viewer/window.h"

namespace whisker {

class World;

// Shortcut keys pressed this frame (not repeats).
struct KeyPresses {
  bool space = false;   // pause / resume
  bool r = false;       // restart
  bool s = false;       // save
  bool c = false;       // print the camera as JSON
  bool d = false;       // raw or denoised image
  bool escape = false;  // close the open popup, else quit
  bool tab = false;     // hide or show the panel
  bool i = false;       // hide or show the pixel readout
  bool undo = false;    // Ctrl+Z
  bool redo = false;    // Ctrl+Y or Ctrl+Shift+Z
};

// Adds the keys' requests to `req`; none while ImGui takes keyboard input
// (a text field has focus), so typing "s" in a path does not save. Esc
// with a popup open (a dropdown, a question) closes it and quits nothing.
void map_keys(const KeyPresses& keys, bool imgui_wants_keyboard, bool popup_open,
              PanelRequests& req);

// The mouse this frame, for buttons left, right, middle.
struct MouseInput {
  bool clicked[3] = {false, false, false};  // pressed this frame
  bool down[3] = {false, false, false};
  float dx = 0.0f, dy = 0.0f;  // movement in window units
  // The pointer now, and where it was when each button went down (from the
  // press event itself: a press and a move in one frame do not put the
  // move before the press into the drag).
  float x = 0.0f, y = 0.0f;
  float press_x[3] = {0.0f, 0.0f, 0.0f}, press_y[3] = {0.0f, 0.0f, 0.0f};
  float wheel = 0.0f;
  bool imgui_wants_mouse = false;  // over the panel or one of its widgets
};

// Left drag: orbit, right/middle drag: pan, wheel: dolly. A drag that starts
// over the panel belongs to ImGui and never moves the camera, wherever it
// goes after.
class MouseCamera {
 public:
  // `image_scale`: image pixels per window unit, so a pan drags the scene
  // with the mouse.
  // With `world`, no move takes the eye into or through a surface
  // (stop_at_surfaces); `stopped` tells whether one was cut short.
  void update(Camera& cam, const MouseInput& in, float image_scale, const World* world = nullptr,
              bool* stopped = nullptr);

 private:
  bool dragging_[3] = {false, false, false};
};

// The shortcuts among GLFW key presses (window.h: take_key_presses).
KeyPresses keys_of(const std::vector<KeyPress>& presses);
// This frame's shortcuts: every press since the last frame, none lost.
KeyPresses read_keys();
MouseInput read_mouse();
// True while ImGui takes keyboard input.
bool imgui_wants_keyboard();
// Whether a popup (a dropdown's list, a question) is open.
bool imgui_popup_open();

}  // namespace whisker
