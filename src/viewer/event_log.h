// The viewer's event log (--edit-log FILE), read by the viewer tests and
// bench/viewer_latency.sh. One line per event, a word and then key=value
// fields (a `text=` field runs to the end of the line):
//   edit t=T gen=G                the settings changed (T: the frame that made it)
//   message t=T text=...          the panel's message line changed to this
//   ask t=T load=NAME             the panel asks "Discard the edits?" before loading
//   scene t=T text=CHOICE         what the Scene dropdown says changed (scene_choice)
//   panel t=T visible=V overlay=O width=W
//                                 the panel's place changed: shown or not (Tab,
//                                 a small window), over the image or beside
//                                 it, its width in window units
//   state t=T text=STATE          the panel's state changed (state_text:
//                                 rendering, done: target reached, stopped: ...)
//   tip t=T text=TEXT             the panel's tooltip changed to this ("": none)
//   outside t=T text=WHY          the eye is outside the room or in an object
//                                 (empty: back inside), as the panel says in red
//   readout t=T box=X,Y,W,H text=LINE|LINE|...
//                                 the pixel readout drawn: its box in window
//                                 units and its lines
//   frame t=T gen=G shown_gen=... a frame was swapped: what it shows of which
//                                 generation, the samples the title and the
//                                 panel's bar say, the samples dropped as
//                                 NaN/Inf, the image's area in window units
// Times are glfwGetTime() seconds, after the buffer swap for frame lines.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>

#include "viewer/overlay.h"
#include "viewer/viewer_state.h"

namespace whisker {

class EventLog {
 public:
  EventLog() = default;
  EventLog(const EventLog&) = delete;
  EventLog& operator=(const EventLog&) = delete;
  ~EventLog();

  // False if the file cannot be written.
  bool open(const std::string& path);
  bool is_open() const { return f_ != nullptr; }
  // The lines for one drawn frame: t0 when it began, t_shown after its swap,
  // `title_spp` as the title says it, the readout and image area as drawn.
  void frame(const ViewerState& s, double t0, double t_shown, std::uint64_t title_spp,
             const ReadoutShown& readout, const ImageArea& area);

 private:
  std::FILE* f_ = nullptr;
  std::uint64_t generation_ = 0;
  std::string message_, pending_load_, outside_, light_outside_, scene_choice_, tip_, state_;
  bool panel_logged_ = false, panel_visible_ = false, panel_overlay_ = false;
  float panel_width_ = 0.0f;
};

}  // namespace whisker
