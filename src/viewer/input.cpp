#include "viewer/input.h"

#include <algorithm>
#include <cmath>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include "viewer/camera_control.h"
#include "viewer/window.h"

namespace whisker {

void map_keys(const KeyPresses& keys, bool imgui_wants_keyboard, bool popup_open,
              PanelRequests& req) {
  // Before the keyboard test: ImGui takes the keyboard while a question is open.
  if (keys.escape && popup_open) req.close_popups = true;
  if (imgui_wants_keyboard) return;
  if (keys.space) req.toggle_pause = true;
  if (keys.r) req.restart = true;
  if (keys.s) req.save = true;
  if (keys.c) req.print_camera = true;
  if (keys.d) req.toggle_denoised = true;
  if (keys.tab) req.toggle_panel = true;
  if (keys.i) req.toggle_readout = true;
  if (keys.escape && !popup_open) req.quit = true;
  if (keys.undo) req.undo = true;
  if (keys.redo) req.redo = true;
}

void MouseCamera::update(Camera& cam, const MouseInput& in, float image_scale, const World* world,
                         bool* stopped) {
  const Camera before = cam;
  for (int b = 0; b < 3; ++b) {
    if (in.clicked[b]) dragging_[b] = !in.imgui_wants_mouse;
    if (!in.down[b]) dragging_[b] = false;
  }
  // A drag moves by what the pointer did since the button went down: in the
  // press's own frame from the press position, after it frame by frame.
  const auto drag = [&](int b, float& dx, float& dy) {
    dx = in.clicked[b] ? in.x - in.press_x[b] : in.dx;
    dy = in.clicked[b] ? in.y - in.press_y[b] : in.dy;
    return dragging_[b] && (dx != 0.0f || dy != 0.0f) && std::isfinite(dx) && std::isfinite(dy);
  };
  float dx = 0.0f, dy = 0.0f;
  if (drag(0, dx, dy)) orbit(cam, -dx * 0.008f, -dy * 0.008f);
  for (int b : {1, 2})
    if (drag(b, dx, dy)) {
      pan(cam, dx / image_scale, dy / image_scale);
      break;
    }
  if (in.wheel != 0.0f && !in.imgui_wants_mouse) dolly(cam, std::pow(0.9f, in.wheel));
  const bool cut = world && cam.position != before.position && stop_at_surfaces(before, cam, *world);
  if (stopped) *stopped = cut;
}

KeyPresses keys_of(const std::vector<KeyPress>& presses) {
  KeyPresses k;
  for (const KeyPress& p : presses) {
    const bool ctrl = (p.mods & GLFW_MOD_CONTROL) != 0, shift = (p.mods & GLFW_MOD_SHIFT) != 0;
    if (ctrl) {
      // Ctrl+letter is never the letter's own shortcut; undo and redo repeat.
      if (p.key == GLFW_KEY_Z) (shift ? k.redo : k.undo) = true;
      if (p.key == GLFW_KEY_Y) k.redo = true;
      continue;
    }
    if (p.repeat) continue;
    if (p.key == GLFW_KEY_SPACE) k.space = true;
    if (p.key == GLFW_KEY_R) k.r = true;
    if (p.key == GLFW_KEY_S) k.s = true;
    if (p.key == GLFW_KEY_C) k.c = true;
    if (p.key == GLFW_KEY_D) k.d = true;
    if (p.key == GLFW_KEY_ESCAPE) k.escape = true;
    if (p.key == GLFW_KEY_TAB) k.tab = true;
    if (p.key == GLFW_KEY_I) k.i = true;
  }
  return k;
}

KeyPresses read_keys() {
  // One press of a key per frame: a second one (two Space presses between
  // two frames) waits for the next frame instead of merging with the first.
  std::vector<KeyPress> now, later;
  for (const KeyPress& p : take_key_presses()) {
    const bool again = std::any_of(now.begin(), now.end(), [&](const KeyPress& q) { return q.key == p.key; });
    (again || !later.empty() ? later : now).push_back(p);
  }
  put_back_key_presses(later);
  return keys_of(now);
}

MouseInput read_mouse() {
  const ImGuiIO& io = ImGui::GetIO();
  MouseInput m;
  for (int b = 0; b < 3; ++b) {
    m.clicked[b] = ImGui::IsMouseClicked(b);
    m.down[b] = ImGui::IsMouseDown(b);
  }
  m.dx = io.MouseDelta.x;
  m.dy = io.MouseDelta.y;
  m.x = io.MousePos.x;
  m.y = io.MousePos.y;
  for (int b = 0; b < 3; ++b) press_position(b, m.press_x[b], m.press_y[b]);
  m.wheel = io.MouseWheel;
  m.imgui_wants_mouse = io.WantCaptureMouse;
  return m;
}

bool imgui_wants_keyboard() { return ImGui::GetIO().WantCaptureKeyboard; }

bool imgui_popup_open() {
  return ImGui::IsPopupOpen("", ImGuiPopupFlags_AnyPopupId | ImGuiPopupFlags_AnyPopupLevel);
}

}  // namespace whisker
