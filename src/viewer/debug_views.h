// Debug views of the scene, one camera ray through each pixel's centre:
// shading normals, material colours, depth. Computed on the CPU in the
// viewer (a ray per pixel is quick next to a pass) and shown as they are.
#pragma once

#include <string>

#include "render/progressive.h"
#include "scene/scene.h"

namespace whisker {

// DisplayParams::mode values: the image and the noise view come first.
enum ViewMode : int { kViewImage = 0, kViewNoise = 1, kViewNormals = 2, kViewAlbedo = 3,
                      kViewDepth = 4 };
inline constexpr int kViewModes = 5;

// Colours for the material view of non-diffuse surfaces.
inline constexpr float kMirrorGrey = 0.75f;
inline const vec3 kGlassColour{0.55f, 0.85f, 1.0f};

struct DebugImage {
  Snapshot image;      // RGB in [0, 1] in `sum`, spp 1: drawn without a tone curve
  int view = -1;
  float far = 0.0f;    // the farthest hit (depth view), scene units
};

// Normals: n * 0.5 + 0.5 (x red, y green, z blue). Albedo: a diffuse
// surface's albedo, mirrors grey, glass light blue. Depth: 1 - t / far
// (near white, far black). Background black.
DebugImage render_debug_view(const Scene& scene, int view);

// One line for the legend over the image.
std::string debug_legend(const DebugImage& d);

}  // namespace whisker
