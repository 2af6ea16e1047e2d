// The scene reader's one-line refusal of a scene file's text, for the
// tests of what it refuses.
#pragma once

#include <string>

#include "scene/scene_error.h"
#include "scene/scene_io.h"

// The message parse_scene gives for `text` (as bad.json), or "(accepted)".
inline std::string scene_refusal(const std::string& text) {
  try {
    whisker::parse_scene(text, "bad.json");
  } catch (const whisker::SceneError& e) {
    return e.what();
  }
  return "(accepted)";
}
