// A fixture for scripts/check_structure.py: the estimator's layer may not
// include the file formats above it, which the check must name.
#include "render/film.h"
#include "io/image_io.h"
