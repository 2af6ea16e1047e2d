// The positional FILE argument: a scene file, or an OBJ in the cat's room.
#pragma once

#include <string>

#include "app/cli.h"
#include "scene/scene.h"

namespace whisker {

// Applies o.file (FILE; given: it was on the command line, even as "") to
// o.scene_name or o.mesh (scene "cat"). A message naming the clash, or ""
// when it applies: FILE must end in .json or .obj (any case) and not come
// with --scene, nor an .obj with --mesh.
std::string apply_file_argument(CommandLine& o, bool given, bool scene_given);

// Rescales and moves every mesh of `scene` (the cat scene, its mesh replaced
// by the OBJ given as FILE) to fit where the cat stands: within 40 x 28 x 40
// units, centred at x = z = 0, resting on the floor (y = -10). Reloads the
// meshes; throws SceneError as load_obj does.
void fit_in_cat_room(Scene& scene);

}  // namespace whisker
