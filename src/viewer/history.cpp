#include "viewer/history.h"

namespace whisker {

void EditHistory::changed(const Scene& before) {
  redo_.clear();
  if (open_) return;
  undo_.push_back(before);
  if (undo_.size() > kLimit) undo_.erase(undo_.begin());
  open_ = true;
}

bool EditHistory::undo(Scene& scene) { return step(undo_, redo_, scene); }

bool EditHistory::redo(Scene& scene) { return step(redo_, undo_, scene); }

bool EditHistory::step(std::vector<Scene>& from, std::vector<Scene>& to, Scene& scene) {
  if (from.empty()) return false;
  to.push_back(scene);
  scene = from.back();
  from.pop_back();
  open_ = false;
  return true;
}

void EditHistory::clear() {
  undo_.clear();
  redo_.clear();
  open_ = false;
}

}  // namespace whisker
