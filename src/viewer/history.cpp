#include "viewer/history.h"

namespace whisker {

void EditHistory::changed(const Scene& before) {
  redo_.clear();
  if (open_) return;
  undo_.push_back(before);
  if (undo_.size() > kLimit) undo_.erase(undo_.begin());
  open_ = true;
}

bool EditHistory::undo(Scene& scene) {
  if (undo_.empty()) return false;
  redo_.push_back(scene);
  scene = undo_.back();
  undo_.pop_back();
  open_ = false;
  return true;
}

bool EditHistory::redo(Scene& scene) {
  if (redo_.empty()) return false;
  undo_.push_back(scene);
  scene = redo_.back();
  redo_.pop_back();
  open_ = false;
  return true;
}

void EditHistory::clear() {
  undo_.clear();
  redo_.clear();
  open_ = false;
}

}  // namespace whisker
