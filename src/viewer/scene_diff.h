// What an edit changed, so the viewer restarts accumulation only when a value
// really changed, and rebuilds nothing it does not need to.
#pragma once

#include "scene/scene.h"

namespace whisker {

enum class SceneChange {
  None,      // nothing the renderer sees
  Inert,     // settings that cannot change this scene's image (image_settings):
             // applied, nothing restarts
  Settings,  // render settings only: set_settings()
  Scene,     // light, materials, camera or geometry: set_scene()
};

SceneChange classify_change(const Scene& before, const Scene& after);

}  // namespace whisker
