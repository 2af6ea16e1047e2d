// What is drawn over the image with ImGui: the noise view's legend, the
// wipe line of the A/B comparison, and the pixel readout under the mouse.
#pragma once

#include "viewer/viewer_state.h"

namespace whisker {

// The image's rectangle in window units (ImGui's coordinates).
struct ImageArea {
  float x = 0, y = 0, w = 0, h = 0;
};

// `readout`: show the pixel under the mouse (off for scripted screenshots).
void draw_image_overlays(const ViewerState& s, const ImageArea& area, bool readout);

}  // namespace whisker
