#include "viewer/layout.h"

#include <algorithm>

namespace whisker {

PanelLayout layout_panel(PanelMode mode, float win_w, float win_h, float image_w, float image_h,
                         float full_w, float min_w) {
  if (mode == PanelMode::Hidden || win_w <= 0.0f) return {false, false, 0.0f};
  // The widest the image can be at this height, never past one to one.
  const float need = image_w > 0.0f && image_h > 0.0f ? std::min(image_w, win_h * image_w / image_h) : 0.0f;
  const float width = std::clamp(win_w - need, std::min(min_w, full_w), full_w);
  if (win_w - width >= 0.5f * win_w) return {true, false, width};
  if (mode == PanelMode::Auto) return {false, false, 0.0f};
  return {true, true, std::min(win_w, std::min(min_w, full_w))};
}

}  // namespace whisker
