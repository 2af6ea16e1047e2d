#include "render/estimator.h"

#include <algorithm>
#include <new>
#include <vector>

namespace whisker {

bool deterministic_estimate(const Scene& scene) {
  const RenderSettings& s = scene.settings;
  if (s.indirect || s.aa) return false;
  if (!s.fresnel) return true;
  for (const SphereObject& sp : scene.spheres)
    if (is_glass(sp.material.kind)) return false;
  for (const MeshObject& m : scene.meshes)
    if (is_glass(m.material.kind)) return false;
  return true;
}

bool cheap_differs(const RenderSettings& s) {
  if (s.spp > 1) return true;
  if (!s.indirect) return false;  // splitting and reuse act on indirect paths only
  if (reuses_paths(s)) return true;
  for (int f : s.split)
    if (f > 1) return true;
  return false;
}

RenderSettings cheap_settings(const RenderSettings& s) {
  RenderSettings q = s;
  q.spp = 1;
  q.split = {1};
  q.split_weights = vec3(1.0f);
  q.reuse = 1;
  // Light connections need the light cache a quick pass does not build.
  q.connect = false;
  // The cheapest numbers: a quick pass is one sample per pixel, where the
  // Sobol points' stratification over a pixel's samples has little to give,
  // and drawing them costs about 8 % of the pass on the cat.
  q.sampler = SamplerKind::Independent;
  // Samples independent of the generation's own (which use `seed`).
  q.seed = s.seed ^ 0x9e3779b97f4a7c15ull;
  return q;
}

namespace {

// A pixel's sums at the start of the tile's samples: carried from the
// pass's earlier chunk, or zero.
PixelSum start_sum(const TileWork& tile, std::uint32_t pixel) {
  return tile.carry.in ? tile.carry.sums[pixel] : PixelSum{};
}

// A pixel's sums at the end: left for the pass's next chunk, or added to the
// film (its non-finite samples counted in `result` then).
void finish_sum(const TileWork& tile, std::uint32_t pixel, const PixelSum& sum, Film& film,
                TileResult& result) {
  if (tile.carry.out) {
    tile.carry.sums[pixel] = sum;
    return;
  }
  film.add(pixel, sum);
  result.dropped += sum.dropped;
}

std::uint32_t pixel_index(const CameraFrame& cam, int i, int j) {
  return std::uint32_t(i) * std::uint32_t(cam.width) + std::uint32_t(j);
}

// Whether the pass is being dropped (asked before each of a tile's samples).
bool abandoned(const TileWork& tile, TileResult& result) {
  if (!(tile.abandon && tile.abandon())) return false;
  result.abandoned = true;
  return true;
}

// The context of the tile's k-th sample: with its light cache, if any.
PathContext sample_context(const PathContext& ctx, const TileWork& tile, int k) {
  PathContext c = ctx;
  if (tile.light_caches) c.lights = &tile.light_caches[k];
  return c;
}

// render_tile() with light caches and one pixel per block: the samples in
// the outer loop, so that a thread reads one sample's cache at a time (a
// pass's caches together outgrow the processor's caches, and a connection
// that misses them waits longer than its shadow ray takes). Each pixel still
// adds its samples in order: the same sums as the pixel-major loop.
TileResult render_tile_by_sample(const PathContext& ctx, const CameraFrame& cam,
                                 const TileWork& tile, Film& film) {
  const RenderSettings& s = ctx.settings;
  const PixelBlock& t = tile.pixels;
  const int cols = t.j1 - t.j0, pixels = (t.i1 - t.i0) * cols;
  TileResult result;
  const FlushDenormals ftz;
  std::vector<PixelSum> sums(static_cast<std::size_t>(pixels));
  for (int p = 0; p < pixels; ++p)
    sums[std::size_t(p)] = start_sum(tile, pixel_index(cam, t.i0 + p / cols, t.j0 + p % cols));
  for (int k = 0; k < tile.spp; ++k) {
    if (abandoned(tile, result)) return result;
    const std::uint64_t sample = tile.first_sample + std::uint64_t(k);
    const PathContext sample_ctx = sample_context(ctx, tile, k);
    for (int p = 0; p < pixels; ++p) {
      const Pixel px{t.i0 + p / cols, t.j0 + p % cols};
      Sampler sampler = pixel_sampler(s, cam, px, sample);
      sums[std::size_t(p)].add(sample_pixel(sample_ctx, cam, px, sampler), sample);
    }
  }
  for (int p = 0; p < pixels; ++p)
    finish_sum(tile, pixel_index(cam, t.i0 + p / cols, t.j0 + p % cols), sums[std::size_t(p)], film, result);
  return result;
}

// Whether every sample is one path (no split, no path reuse): fig 8's
// estimator, the report's.
bool one_path_per_sample(const RenderSettings& s) {
  return !reuses_paths(s) &&
         std::all_of(s.split.begin(), s.split.end(), [](int f) { return f <= 1; });
}

// render_tile() for one path per sample without light caches: the tile's
// (pixel, sample) pairs, a pixel's samples in order, kLanes at a time side
// by side (trace_paths; a group may straddle pixels, as with the viewer's
// passes of one sample): 1.09x on fig 8's settings, 1.08x on passes of one
// sample, the same sums bit for bit. (With splitting the paths' work is in
// their branches, and lanes of camera paths measured 1 % slower.)
TileResult render_tile_in_lanes(const PathContext& ctx, const CameraFrame& cam,
                                const TileWork& tile, Film& film) {
  const PixelBlock& t = tile.pixels;
  const int cols = t.j1 - t.j0;
  const std::int64_t pairs = std::int64_t(t.i1 - t.i0) * cols * tile.spp;
  TileResult result;
  const FlushDenormals ftz;
  PixelSum sum;  // of the pixel whose samples are being added
  for (std::int64_t q0 = 0; q0 < pairs; q0 += kLanes) {
    if (abandoned(tile, result)) return result;
    const int n = int(std::min<std::int64_t>(kLanes, pairs - q0));
    PathState path[kLanes];
    Sampler sampler[kLanes];
    Pixel px[kLanes];
    std::uint64_t sample[kLanes];
    for (int l = 0; l < n; ++l) {
      const std::int64_t q = q0 + l, p = q / tile.spp;
      px[l] = Pixel{t.i0 + int(p / cols), t.j0 + int(p % cols)};
      sample[l] = tile.first_sample + std::uint64_t(q % tile.spp);
      // Made in place: a copy of a sampler just built (its fields stored
      // one by one, read back by one wide load) waited on the stores.
      ::new (&sampler[l]) Sampler(pixel_sampler(ctx.settings, cam, px[l], sample[l]));
    }
    camera_paths(ctx, cam, {px, std::size_t(n)}, sampler, path);
    trace_paths(ctx, path, sampler, n);
    for (int l = 0; l < n; ++l) {
      const std::uint32_t index = pixel_index(cam, px[l].i, px[l].j);
      if (sample[l] == tile.first_sample) sum = start_sum(tile, index);
      sum.add(path[l].L, sample[l]);
      if (sample[l] + 1 == tile.first_sample + std::uint64_t(tile.spp))
        finish_sum(tile, index, sum, film, result);
    }
  }
  return result;
}

}  // namespace

TileResult render_tile(const PathContext& ctx, const CameraFrame& cam, const TileWork& tile,
                       Film& film) {
  const RenderSettings& s = ctx.settings;
  const PixelBlock& t = tile.pixels;
  const bool reuse = reuses_paths(s);
  if (tile.light_caches && !reuse) return render_tile_by_sample(ctx, cam, tile, film);
  if (one_path_per_sample(s)) return render_tile_in_lanes(ctx, cam, tile, film);
  const int side = reuse ? std::min(s.reuse, kMaxReuse) : 1;
  TileResult result;
  const FlushDenormals ftz;
  // Once per tile, not per block: a pixel by itself clears one sum, not 64.
  PixelSum sums[kMaxReuse * kMaxReuse];
  vec3 out[kMaxReuse * kMaxReuse];
  for (int bi = t.i0; bi < t.i1; bi += side) {
    for (int bj = t.j0; bj < t.j1; bj += side) {
      const PixelBlock block{bi, std::min(t.i1, bi + side), bj, std::min(t.j1, bj + side)};
      const int cols = block.j1 - block.j0, pixels = (block.i1 - block.i0) * cols;
      for (int p = 0; p < pixels; ++p)
        sums[p] = start_sum(tile, pixel_index(cam, bi + p / cols, bj + p % cols));
      for (int k = 0; k < tile.spp; ++k) {
        if (abandoned(tile, result)) return result;
        const std::uint64_t sample = tile.first_sample + std::uint64_t(k);
        const PathContext sample_ctx = sample_context(ctx, tile, k);
        if (reuse) {
          sample_block(sample_ctx, cam, block, sample, out);
        } else {  // one pixel
          Sampler sampler = pixel_sampler(s, cam, Pixel{bi, bj}, sample);
          out[0] = sample_pixel(sample_ctx, cam, Pixel{bi, bj}, sampler);
        }
        for (int p = 0; p < pixels; ++p) sums[p].add(out[p], sample);
      }
      for (int p = 0; p < pixels; ++p)
        finish_sum(tile, pixel_index(cam, bi + p / cols, bj + p % cols), sums[p], film, result);
    }
  }
  return result;
}

}  // namespace whisker
