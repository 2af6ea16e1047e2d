#include "viewer/script.h"

#include <algorithm>
#include <cstdint>

#include "viewer/camera_control.h"

namespace whisker {

// Passes are counted in samples: the viewer's first passes after an edit
// are smaller (ProgressiveRenderer::set_growing_passes).
std::uint64_t ScriptedRun::samples(int passes) const {
  return std::uint64_t(std::max(0, passes)) * std::uint64_t(std::max(1, opt_.scene.settings.spp));
}

void ScriptedRun::prepare(ViewerState& s) const {
  if (opt_.frames <= 0) return;
  s.initial.settings.target_spp = int(samples(opt_.frames));
  s.applied = s.edited = s.initial;
}

void ScriptedRun::apply_due_edit(ViewerState& s) {
  if (next_edit_ >= opt_.edits.size()) return;
  const ScriptedEdit& edit = opt_.edits[next_edit_];
  const Snapshot& sn = s.snap;
  if (sn.generation != s.generation || sn.quick) return;
  if (sn.spp < samples(edit.after_pass) && !sn.done) return;
  if (edit.light_position) s.edited.light.position = *edit.light_position;
  if (edit.orbit) orbit(s.edited.camera, float(edit.orbit->x), float(edit.orbit->y));
  if (const SettingField* f = boolean_setting(edit.toggle)) {
    bool& on = s.edited.settings.*std::get<bool RenderSettings::*>(f->member);
    on = !on;
  }
  ++next_edit_;
}

bool ScriptedRun::finished(const ViewerState& s) const {
  const Snapshot& sn = s.snap;
  return opt_.frames > 0 && next_edit_ == opt_.edits.size() && sn.generation == s.generation &&
         !sn.quick && (sn.spp >= samples(opt_.frames) || sn.done);
}

}  // namespace whisker
