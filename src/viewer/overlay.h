// What is drawn over the image with ImGui: the noise view's legend, the
// wipe line of the A/B comparison, and the pixel readout under the mouse.
#pragma once

#include <string>
#include <vector>

#include "viewer/viewer_state.h"

namespace whisker {

// The image's rectangle in window units (ImGui's coordinates).
struct ImageArea {
  float x = 0, y = 0, w = 0, h = 0;
};

// The pixel readout as drawn this frame (for --edit-log): its box in window
// units, as ImGui placed and sized it, and its lines.
struct ReadoutShown {
  bool shown = false;
  float x = 0, y = 0, w = 0, h = 0;
  std::vector<std::string> lines;
};

// `readout`: show the pixel under the mouse (off for scripted screenshots);
// `shown`, if given, says what of it was drawn.
void draw_image_overlays(const ViewerState& s, const ImageArea& area, bool readout,
                         ReadoutShown* shown = nullptr);

}  // namespace whisker
