// What the viewer is started with: the scene, the window and a script of
// edits. Apart from the window's entry point so that the script's runner
// needs only this.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "scene/scene.h"

namespace whisker {

// An edit applied by the viewer after a given number of passes (scripted
// runs and tests drive the UI path with these).
struct ScriptedEdit {
  int after_pass = 0;
  std::optional<glm::dvec3> light_position;
  std::optional<glm::dvec2> orbit;  // radians, as orbit() (a left drag)
  std::string toggle;               // a boolean setting's key ("fresnel"): switched
};

struct ViewerOptions {
  Scene scene;                   // loaded scene with CLI overrides applied
  std::string scene_path;        // file it came from (for the picker / titles)
  int threads = 0;               // 0 = all hardware threads
  int frames = 0;                // > 0: exit after this many passes of the final generation
  std::string screenshot_path;   // with frames: save the window framebuffer here
  bool denoised = false;         // start showing the denoised image (--denoised)
  std::vector<ScriptedEdit> edits;
  int width = 0, height = 0;     // window size (0 = fit the image plus panel)
  // A line per edit and per drawn frame (times, generations, samples) goes
  // here; with --frames the window then closes when the script is done.
  std::string event_log;
};

}  // namespace whisker
