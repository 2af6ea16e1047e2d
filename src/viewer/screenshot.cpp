#include "viewer/screenshot.h"

#include <cstdio>
#include <exception>

#include "io/atomic_file.h"
#include "io/image_io.h"
#include "io/stats_io.h"

namespace whisker {

namespace {

// A summary next to a scripted screenshot (<screenshot>.json): what was
// rendered (the shared stats record), where the render area is, how fast the
// UI ran.
void write_summary(const std::string& path, const PixelRect& r, const ViewerState& s,
                   const FrameStats& f, int fb_w, int fb_h) {
  using V = std::vector<long long>;
  RenderStats st{s.scene_label, &s.snap, s.threads, &s.applied.settings, {}};
  const float max_ms =
      f.total_ms.empty() ? 0.0f : *std::max_element(f.total_ms.begin(), f.total_ms.end());
  st.extra = {{"framebuffer", V{fb_w, fb_h}},
              {"render_rect", V{r.x, r.y, r.w, r.h}},
              {"ui_frames", (long long)f.total_ms.size()},
              {"ui_frame_ms_mean", double(FrameStats::mean(f.total_ms))},
              {"ui_frame_ms_p95", double(FrameStats::pct(f.total_ms, 0.95))},
              {"ui_frame_ms_max", double(max_ms)},
              {"ui_frame_work_ms_mean", double(FrameStats::mean(f.work_ms))}};
  write_stats_json(path, st);
}

}  // namespace

bool take_screenshot(const std::string& path, const PixelRect& rect, const ViewerState& s,
                     const FrameStats& f, int fb_w, int fb_h) {
  // A window too small for anything but the panel (a 16 x 16 screen) has no
  // render to show: an image without one is no screenshot of it.
  if (rect.w <= 0 || rect.h <= 0) {
    std::fprintf(stderr,
                 "whisker: --screenshot %s: the window (%d x %d pixels) leaves no room for the "
                 "render beside the panel; nothing written (the screen is too small)\n",
                 path_for_message(path).c_str(), fb_w, fb_h);
    return false;
  }
  try {
    write_png_rgb8(path, fb_w, fb_h, read_framebuffer(fb_w, fb_h));
    write_summary(path + ".json", rect, s, f, fb_w, fb_h);
    return true;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "whisker: %s\n", e.what());
    return false;
  }
}

}  // namespace whisker
