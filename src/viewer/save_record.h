// The float file's header for a Save in the viewer: the render as the
// headless outputs record it (io/render_record.h), then what the viewer
// adds: the scene file, the objects with their materials, the edits made
// since it was loaded, and how to view the values as the window did.
#pragma once

#include "io/image_io.h"
#include "render/film.h"
#include "viewer/viewer_state.h"

namespace whisker {

// `own`: the generation's own passes; `display_units`: the values are in
// display units (1.0 = the report's white) rather than scene units.
//   whisker.scene_file        the file the scene was loaded from
//   whisker.objects           {"spheres": [...], "meshes": [...]} as in a scene file
//   whisker.edits             a JSON Patch (RFC 6902) from the scene as
//                             loaded to the one rendered ("[]": none)
//   whisker.display_exposure  the exposure in stops that maps the values to
//                             the report's display (white at 1.0, then gamma 2.2)
//   whisker.display_scale     the same as a factor, 2^display_exposure
//   whisker.viewer_exposure   the viewer's own exposure slider (stops) at the save
//   whisker.display_note      the above in words, and for scene units that
//                             a half-float reader overflows
ImageAttributes viewer_record(const ViewerState& s, const Snapshot& own, bool display_units);

}  // namespace whisker
