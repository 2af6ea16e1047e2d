// A fixture for scripts/check_structure.py: the file formats may include the
// layers below them, but not the app, which the check must name.
#include "geometry/ray.h"
#include "scene/scene.h"
#include "render/film.h"
#include "app/cli.h"
