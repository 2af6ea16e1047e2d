// What an image is and how it was made, as the EXR header records it: one
// writer for the headless outputs and the viewer's saves.
#pragma once

#include <cstdint>

#include "io/image_io.h"
#include "render/film.h"
#include "scene/scene.h"

namespace whisker {

// The samples per pixel a deterministic estimate stands for: its target
// (one pass of it is exact), or more if more were rendered.
std::uint64_t stands_for_spp(const Scene& scene, const Snapshot& snap);

// The scene's name, the units, spp, passes, seed, render seconds, camera,
// light and settings (JSON), and for a deterministic estimate that it is
// exact and the samples per pixel it stands for.
ImageAttributes render_record(const Scene& scene, const Snapshot& snap, bool display_units);

}  // namespace whisker
