// Scripted screenshots (--screenshot): the back buffer as a PNG, and beside
// it a summary of what was rendered and how fast the window ran.
#pragma once

#include <algorithm>
#include <numeric>
#include <string>
#include <vector>

#include "viewer/display.h"
#include "viewer/viewer_state.h"

namespace whisker {

// The window's frame times, in milliseconds: the work of each frame and
// the whole frame.
struct FrameStats {
  std::vector<float> work_ms, total_ms;
  static float mean(const std::vector<float>& v) {
    return v.empty() ? 0.0f : std::accumulate(v.begin(), v.end(), 0.0f) / v.size();
  }
  static float pct(std::vector<float> v, double p) {
    if (v.empty()) return 0.0f;
    std::sort(v.begin(), v.end());
    return v[std::min(v.size() - 1, std::size_t(p * (v.size() - 1) + 0.5))];
  }
};

// Reads the back buffer (fb_w x fb_h) into the PNG at `path` and its summary
// (<path>.json: the shared stats record, the render area `rect`, the frame
// times); false (with a message) if either cannot be written, or if `rect`
// is empty (the window has no room for the render).
bool take_screenshot(const std::string& path, const PixelRect& rect, const ViewerState& s,
                     const FrameStats& f, int fb_w, int fb_h);

}  // namespace whisker
