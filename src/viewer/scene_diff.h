// What an edit changed, so the viewer restarts accumulation only when a value
// really changed, and rebuilds nothing it does not need to.
#pragma once

#include "scene/scene.h"

namespace whisker {

enum class SceneChange {
  None,      // nothing the renderer sees
  Settings,  // render settings only: set_settings()
  Scene,     // light, materials, camera or geometry: set_scene()
};

SceneChange classify_change(const Scene& before, const Scene& after);

bool same_material(const Material& a, const Material& b);
bool same_camera(const Camera& a, const Camera& b);
bool same_settings(const RenderSettings& a, const RenderSettings& b);

}  // namespace whisker
