#include "viewer/script.h"

#include <algorithm>
#include <cstdint>

#include "viewer/camera_control.h"

namespace whisker {

void ScriptedRun::prepare(ViewerState& s) const {
  if (opt_.frames <= 0) return;
  s.initial.settings.target_spp = opt_.frames * std::max(1, opt_.scene.settings.spp);
  s.applied = s.edited = s.initial;
}

void ScriptedRun::apply_due_edit(ViewerState& s) {
  if (next_edit_ >= opt_.edits.size()) return;
  const ScriptedEdit& edit = opt_.edits[next_edit_];
  const Snapshot& sn = s.snap;
  if (sn.generation != s.generation || sn.quick) return;
  if (sn.counters.passes < std::uint64_t(std::max(0, edit.after_pass)) && !sn.done) return;
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
         !sn.quick && (sn.counters.passes >= std::uint64_t(opt_.frames) || sn.done);
}

}  // namespace whisker
