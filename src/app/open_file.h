// The positional FILE argument's OBJ case: the mesh in the cat's room.
#pragma once

#include "scene/scene.h"

namespace whisker {

// Rescales and moves every mesh of `scene` (the cat scene, its mesh replaced
// by the OBJ given as FILE) to fit where the cat stands: within 40 x 28 x 40
// units, centred at x = z = 0, resting on the floor (y = -10). Reloads the
// meshes; throws SceneError as load_obj does.
void fit_in_cat_room(Scene& scene);

}  // namespace whisker
