// Undo and redo of the viewer's edits. A step is one gesture: a whole drag
// or a typed number is one step, not one per frame.
#pragma once

#include <cstddef>
#include <vector>

#include "scene/scene.h"

namespace whisker {

class EditHistory {
 public:
  // A change was applied; `before` is the scene it replaced. Changes until
  // the next settle() belong to the same step.
  void changed(const Scene& before);
  // The gesture ended (no widget held, no mouse button down).
  void settle() { open_ = false; }
  // Steps back (forward): `scene` is the current one on the way in and the
  // one to apply on the way out. False if there is nothing to go to.
  bool undo(Scene& scene);
  bool redo(Scene& scene);
  void clear();

  bool can_undo() const { return !undo_.empty(); }
  bool can_redo() const { return !redo_.empty(); }
  std::size_t steps() const { return undo_.size(); }

  static constexpr std::size_t kLimit = 200;

 private:
  // Undo and redo: `scene` goes on `to`, the top of `from` replaces it.
  bool step(std::vector<Scene>& from, std::vector<Scene>& to, Scene& scene);
  std::vector<Scene> undo_, redo_;
  bool open_ = false;
};

}  // namespace whisker
