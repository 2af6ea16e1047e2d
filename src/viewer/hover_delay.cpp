#include "viewer/hover_delay.h"

namespace whisker {

void HoverDelay::begin_frame(double now, bool pointer_moved, bool button_down) {
  now_ = now;
  if (pointer_moved) moved_ever_ = true;
  if (pointer_moved || button_down) last_move_ = now;
  button_down_ = button_down;
  // No widget asked last frame: nothing was hovered, the next one starts over.
  if (!asked_this_frame_) have_key_ = false;
  asked_this_frame_ = false;
  waiting_ = false;
}

bool HoverDelay::due(unsigned long long key) {
  asked_this_frame_ = true;
  if (!have_key_ || key != key_) {
    key_ = key;
    have_key_ = true;
    shown_ = false;
  }
  if (button_down_) {
    shown_ = false;
    return false;
  }
  if (!shown_ && moved_ever_ && now_ - last_move_ >= kRestSeconds) shown_ = true;
  waiting_ = !shown_ && moved_ever_;
  return shown_;
}

}  // namespace whisker
