// How the window is shared between the image and the panel: the panel
// narrows so that the image keeps the size the window's height allows, and
// in a window too small for both it steps aside (Tab brings it back over
// the image, or hides it at any size).
#pragma once

namespace whisker {

enum class PanelMode : int {
  Auto = 0,  // beside the image when both fit, else hidden
  Shown,     // asked for with Tab: beside the image, over it when both do not fit
  Hidden,    // asked away with Tab: the image has the whole window
};

struct PanelLayout {
  bool visible = true;
  bool overlay = false;  // drawn over the image, which keeps the whole window
  float width = 0.0f;    // window units; 0 when hidden
};

// For a window of win_w x win_h and an image of image_w x image_h at one
// image pixel per framebuffer pixel (both in window units): the panel takes
// what the image cannot use at this height, between min_w and full_w. It
// shares the window only while the image keeps at least half the width.
PanelLayout layout_panel(PanelMode mode, float win_w, float win_h, float image_w, float image_h,
                         float full_w, float min_w);

// Tab: hides a visible panel, shows a hidden one.
inline PanelMode toggle_panel(bool visible_now) { return visible_now ? PanelMode::Hidden : PanelMode::Shown; }

}  // namespace whisker
