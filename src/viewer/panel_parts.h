// The panel's sections (panel.cpp, panel_status.cpp), drawn in order by
// draw_panel().
#pragma once

#include <cstdint>

#include "viewer/viewer_state.h"

namespace whisker {

// A plain-language tooltip for the last widget (also when it is disabled),
// once the pointer has rested on it (viewer/hover_delay.h).
void tip(const char* text);
// Before the frame's widgets: where the pointer is and whether a button is
// down, for tip().
void tooltips_frame();

// State, progress toward the target, speed, error and its plot: a fixed
// number of lines, so nothing below moves while it renders. Returns the
// samples per pixel its progress bar says.
std::uint64_t status_section(const ViewerState& s, double now);
// Pause, restart, save; the last message in a fixed two-line box.
void controls(const ViewerState& s, PanelRequests& req);
// Where Save writes, and under which name; Save scene.
void save_section(ViewerState& s, PanelRequests& req);
// Asks before a load throws away edits that could be undone.
void confirm_load_popup(ViewerState& s, PanelRequests& req);
// "Quit and discard the edits?" while s.pending_quit.
void confirm_quit_popup(ViewerState& s, PanelRequests& req);
// Hold the current image and compare it with the live one.
void compare_section(ViewerState& s, PanelRequests& req);

}  // namespace whisker
