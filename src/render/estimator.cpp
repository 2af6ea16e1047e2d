#include "render/estimator.h"

#include <algorithm>

namespace whisker {

std::uint64_t render_tile(const PathContext& ctx, const CameraFrame& cam, const TileWork& tile,
                          Film& film) {
  const RenderSettings& s = ctx.settings;
  const PixelBlock& t = tile.pixels;
  const bool reuse = reuses_paths(s);
  const int side = reuse ? std::min(s.reuse, kMaxReuseBlock) : 1;
  std::uint64_t nans = 0;
  // Once per tile, not per block: a pixel by itself clears one sum, not 64.
  PixelSum sums[kMaxReuseBlock * kMaxReuseBlock];
  vec3 out[kMaxReuseBlock * kMaxReuseBlock];
  for (int bi = t.i0; bi < t.i1; bi += side) {
    for (int bj = t.j0; bj < t.j1; bj += side) {
      const PixelBlock block{bi, std::min(t.i1, bi + side), bj, std::min(t.j1, bj + side)};
      const int cols = block.j1 - block.j0, pixels = (block.i1 - block.i0) * cols;
      std::fill_n(sums, pixels, PixelSum{});
      for (int k = 0; k < tile.spp; ++k) {
        const std::uint64_t sample = tile.first_sample + std::uint64_t(k);
        if (reuse) {
          sample_block(ctx, cam, block, sample, out);
        } else {  // one pixel
          Sampler sampler = pixel_sampler(s, cam, Pixel{bi, bj}, sample);
          out[0] = sample_pixel(ctx, cam, Pixel{bi, bj}, sampler);
        }
        for (int p = 0; p < pixels; ++p) sums[p].add(out[p], sample);
      }
      for (int p = 0; p < pixels; ++p) {
        const int i = bi + p / cols, j = bj + p % cols;
        film.add(std::uint32_t(i) * std::uint32_t(cam.width) + std::uint32_t(j), sums[p]);
        nans += sums[p].dropped;
      }
    }
  }
  return nans;
}

}  // namespace whisker
