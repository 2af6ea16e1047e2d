// Path reuse across a block of pixels: every pixel of a small block shares
// the indirect paths of all the others (Bekaert, Sbert, Halton, "Accelerating
// Path Tracing by Re-Using Paths", EGWR 2002), weighted by the balance
// heuristic over the block's sampling techniques (Veach's multi-sample
// model, Veach and Guibas, SIGGRAPH 1995), so each pixel's estimate stays
// unbiased. RenderSettings::reuse sets the block's side.
#pragma once

#include <cstdint>

#include "render/camera.h"
#include "render/integrator.h"
#include "scene/scene.h"
#include "scene/world.h"

namespace whisker {

// Whether a render with these settings shares paths between pixels (a block
// of more than one pixel and indirect light that leaves the first hit).
inline bool reuses_paths(const RenderSettings& s) {
  return s.reuse > 1 && s.indirect && s.max_depth > 0;
}

// A block of pixels: rows [i0, i1), columns [j0, j1).
struct PixelBlock {
  int i0 = 0, i1 = 0, j0 = 0, j1 = 0;
};

// One sample, number `sample`, of each pixel of the block (at most
// kMaxReuse on a side), written to out[(i - i0) * (j1 - j0) + (j - j0)].
// Each pixel draws its numbers from its own Sampler (pixel_sampler), as
// sample_pixel does.
//
// A pixel whose camera ray meets a diffuse surface at x_j sends its
// split[0] bounces from there as usual; every bounce that meets a diffuse
// point y (whose outgoing light L_o(y) is the same in every direction) is
// then used by every pixel m of the block whose point x_m sees y: the bounce
// from x_k is a sample of technique k, whose density at y in area measure is
// p_k(y) = cos_k cos_y / (pi d_k^2) V(x_k, y), and pixel j adds
// rho_j cos_j cos_y / (pi d_j^2) V(x_j, y) L_o(y) / sum_m n_m p_m(y)
// (n_m: pixel m's bounce count). With the block of one pixel this is the
// plain estimator rho L_o / n. A bounce that meets glass or a mirror (whose
// light depends on the direction) and a pixel whose first hit is not
// diffuse keep to their own pixel, as sample_pixel traces them.
void sample_block(const PathContext& ctx, const CameraFrame& cam, const PixelBlock& block,
                  std::uint64_t sample, vec3* out);

}  // namespace whisker
