// The interactive progressive viewer: a thin consumer of ProgressiveRenderer.
#pragma once

#include "viewer/viewer_options.h"

namespace whisker {

// True if a window can be opened (a display is there and GLFW initialises).
bool display_available();

// Runs the window until closed (or `frames` passes). Returns the process exit
// code: 0 ok, 3 no display / no OpenGL 3.3 (message printed to stderr).
int run_viewer(const ViewerOptions& options);

}  // namespace whisker
