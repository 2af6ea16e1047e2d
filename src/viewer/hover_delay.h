// When a tooltip may show: once the pointer has rested on a widget, never
// while a mouse button is held, never for a widget the window opened under
// before the pointer has moved. ImGui 1.86 (the packaged version) has no
// ImGuiHoveredFlags_DelayNormal, so the viewer keeps this itself.
#pragma once

namespace whisker {

class HoverDelay {
 public:
  static constexpr double kRestSeconds = 0.5;

  // Once a frame, before any widget asks: the time, whether the pointer moved
  // since the last frame and whether a mouse button is down.
  void begin_frame(double now, bool pointer_moved, bool button_down);
  // For the hovered widget `key` (any value that tells widgets apart, e.g.
  // its rectangle): whether its tooltip shows this frame. Once shown it
  // stays while the widget stays hovered and no button goes down.
  bool due(unsigned long long key);
  // Whether a hovered widget waits for its tooltip (the window then needs a
  // frame when the rest is long enough).
  bool waiting() const { return waiting_; }

 private:
  double now_ = 0.0, last_move_ = 0.0;
  bool moved_ever_ = false, button_down_ = false;
  bool asked_this_frame_ = false;
  unsigned long long key_ = 0;
  bool have_key_ = false, shown_ = false, waiting_ = false;
};

}  // namespace whisker
