#include "viewer/event_log.h"

#include <cmath>

namespace whisker {

EventLog::~EventLog() {
  if (f_) std::fclose(f_);
}

bool EventLog::open(const std::string& path) {
  f_ = std::fopen(path.c_str(), "w");
  return f_ != nullptr;
}

void EventLog::frame(const ViewerState& s, double t0, double t_shown, std::uint64_t title_spp,
                     const ReadoutShown& readout, const ImageArea& area) {
  if (!f_) return;
  using ull = unsigned long long;
  if (s.generation != generation_) {
    std::fprintf(f_, "edit t=%.6f gen=%llu\n", t0, ull(s.generation));
    generation_ = s.generation;
  }
  if (s.message != message_) {
    std::fprintf(f_, "message t=%.6f text=%s\n", t0, s.message.c_str());
    message_ = s.message;
  }
  if (s.pending_load != pending_load_) {
    if (!s.pending_load.empty()) std::fprintf(f_, "ask t=%.6f load=%s\n", t0, s.pending_load.c_str());
    pending_load_ = s.pending_load;
  }
  if (const std::string choice = scene_choice(s); choice != scene_choice_) {
    std::fprintf(f_, "scene t=%.6f text=%s\n", t0, choice.c_str());
    scene_choice_ = choice;
  }
  if (!panel_logged_ || s.panel_visible != panel_visible_ || s.panel_overlay != panel_overlay_ ||
      s.panel_width != panel_width_) {
    std::fprintf(f_, "panel t=%.6f visible=%d overlay=%d width=%.1f\n", t0, int(s.panel_visible),
                 int(s.panel_overlay), double(s.panel_width));
    panel_logged_ = true;
    panel_visible_ = s.panel_visible;
    panel_overlay_ = s.panel_overlay;
    panel_width_ = s.panel_width;
  }
  if (const std::string state = state_text(s); state != state_) {
    std::fprintf(f_, "state t=%.6f text=%s\n", t0, state.c_str());
    state_ = state;
  }
  if (tooltip_shown() != tip_) {
    std::fprintf(f_, "tip t=%.6f text=%s\n", t0, tooltip_shown().c_str());
    tip_ = tooltip_shown();
  }
  if (s.light_outside != light_outside_) {
    std::fprintf(f_, "light-outside t=%.6f text=%s\n", t0, s.light_outside.c_str());
    light_outside_ = s.light_outside;
  }
  if (s.eye_outside != outside_) {
    std::fprintf(f_, "outside t=%.6f text=%s\n", t0, s.eye_outside.c_str());
    outside_ = s.eye_outside;
  }
  if (readout.shown) {
    std::string text;
    for (const std::string& line : readout.lines) text += (text.empty() ? "" : "|") + line;
    std::fprintf(f_, "readout t=%.6f box=%.1f,%.1f,%.1f,%.1f text=%s\n", t_shown, readout.x,
                 readout.y, readout.w, readout.h, text.c_str());
  }
  const bool own_current = s.snap.generation == s.generation;
  std::fprintf(f_,
               "frame t=%.6f gen=%llu shown_gen=%llu shown_quick=%llu shown_own=%llu own_gen=%llu "
               "own_spp=%llu own_passes=%llu rse=%.6g title_spp=%llu panel_spp=%llu nan=%llu "
               "area=%.1f,%.1f,%.1f,%.1f\n",
               t_shown, ull(s.generation), ull(s.shown.image.generation), ull(s.shown.quick_spp),
               ull(s.shown.own_spp), ull(s.snap.generation), ull(s.snap.spp), ull(s.snap.counters.passes),
               own_current ? s.rse : std::nan(""), ull(title_spp), ull(s.bar_spp),
               ull(s.snap.counters.nan_count), area.x, area.y, area.w, area.h);
  std::fflush(f_);
}

}  // namespace whisker
