// A scripted run (--frames, --edit-after / --edit-light): it renders exactly
// `frames` passes' samples of its last generation, as the headless mode does, so its
// screenshot compares with that render; its edits go through the same path
// as the panel's.
#pragma once

#include <cstddef>
#include <cstdint>

#include "viewer/viewer_options.h"
#include "viewer/viewer_state.h"

namespace whisker {

class ScriptedRun {
 public:
  explicit ScriptedRun(const ViewerOptions& options) : opt_(options) {}

  // Sets the scene's target spp to `frames` passes (nothing without --frames).
  void prepare(ViewerState& s) const;
  // Makes the next edit once the current generation has rendered its pass
  // (or is done); at most one edit a frame.
  void apply_due_edit(ViewerState& s);
  // True once every edit is made and the last generation has its passes.
  bool finished(const ViewerState& s) const;

 private:
  std::uint64_t samples(int passes) const;

  const ViewerOptions& opt_;
  std::size_t next_edit_ = 0;
};

}  // namespace whisker
