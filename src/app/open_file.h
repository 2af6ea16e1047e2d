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

// Why the OBJ file o.mesh cannot be read ("" if it is a regular file, or no
// mesh is given): named as given, FILE alone (from_file) or "--mesh PATH";
// "no such file", "not a regular file (a folder)", or the system's reason.
std::string check_mesh_file(const CommandLine& o, bool from_file);

// Replaces every mesh of `scene` (the cat scene) by the OBJ file at `path`
// (FILE), scaled and moved to fit where the cat stands: its faces within
// 40 x 28 x 40 units, centred at x = z = 0, resting on the floor (y = -10).
// Vertices that no face uses play no part (mesh_io.h: fit_obj). Reads the
// file once; throws MeshError naming it as read_obj does.
void fit_in_cat_room(Scene& scene, const std::string& path);

}  // namespace whisker
