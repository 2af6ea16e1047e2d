#include "render/estimator.h"

#include <algorithm>
#include <new>
#include <vector>

#include "render/features.h"

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
  if (!s.indirect) return false;  // splitting acts on indirect paths only
  for (int f : s.split)
    if (f > 1) return true;
  return false;
}

RenderSettings cheap_settings(const RenderSettings& s) {
  RenderSettings q = s;
  q.spp = 1;
  q.split = {1};
  q.split_weights = vec3(1.0f);
  // Light connections need the light cache a quick pass does not build.
  q.connect = false;
  // The cheapest numbers: a quick pass is one sample per pixel, where the
  // Sobol points' stratification over a pixel's samples has little to give,
  // and drawing them is a noticeable part of a one-sample pass.
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

// Whether the pass is being dropped (asked before each group of paths).
bool abandoned(const TileWork& tile, TileResult& result) {
  if (!(tile.abandon && tile.abandon())) return false;
  result.abandoned = true;
  return true;
}

}  // namespace

// The tile's (pixel, sample) pairs, kLanes at a time side by side
// (trace_paths), each pixel adding its samples in order. With light caches
// the samples are the outer loop and a group never straddles two of them, so
// a thread reads one sample's cache at a time (a pass's caches together
// outgrow the processor's caches); without, the pixels are, so a pixel's
// Sobol seeds are made once for all its samples. Both orders give the same
// sums bit for bit.
TileResult render_tile(const PathContext& ctx, const CameraFrame& cam, const TileWork& tile,
                       Film& film) {
  const PixelBlock& t = tile.pixels;
  const int cols = t.j1 - t.j0;
  const std::int64_t pixels = std::int64_t(t.i1 - t.i0) * cols, pairs = pixels * tile.spp;
  const bool by_sample = tile.light_caches != nullptr;
  TileResult result;
  const FlushDenormals ftz;
  std::vector<PixelSum> sums(static_cast<std::size_t>(pixels));
  auto index = [&](std::int64_t p) { return cam.pixel_index(t.i0 + int(p / cols), t.j0 + int(p % cols)); };
  for (std::int64_t p = 0; p < pixels; ++p) sums[std::size_t(p)] = start_sum(tile, index(p));
  for (std::int64_t q0 = 0; q0 < pairs;) {
    if (abandoned(tile, result)) return result;
    int n = int(std::min<std::int64_t>(kLanes, pairs - q0));
    if (by_sample) n = int(std::min<std::int64_t>(n, pixels - q0 % pixels));
    const std::int64_t k0 = by_sample ? q0 / pixels : 0;
    PathContext group_ctx = ctx;
    if (by_sample) group_ctx.lights = &tile.light_caches[k0];
    PathState path[kLanes];
    Sampler sampler[kLanes];
    Pixel px[kLanes];
    std::int64_t pixel[kLanes];
    std::uint64_t sample[kLanes];
    for (int l = 0; l < n; ++l) {
      const std::int64_t q = q0 + l;
      pixel[l] = by_sample ? q % pixels : q / tile.spp;
      sample[l] = tile.first_sample + std::uint64_t(by_sample ? k0 : q % tile.spp);
      px[l] = Pixel{t.i0 + int(pixel[l] / cols), t.j0 + int(pixel[l] % cols)};
      // Made in place: a copy of a sampler just built (its fields stored
      // one by one, read back by one wide load) waited on the stores.
      ::new (&sampler[l]) Sampler(pixel_sampler(ctx.settings, cam, px[l], sample[l]));
    }
    camera_paths(group_ctx, cam, {px, std::size_t(n)}, sampler, path);
    Features features[kLanes];
    if (tile.features)
      for (int l = 0; l < n; ++l) path[l].features = &features[l];
    trace_paths(group_ctx, path, sampler, n);
    for (int l = 0; l < n; ++l) {
      PixelSum& sum = sums[std::size_t(pixel[l])];
      if (tile.features) sum.add_features(features[l].albedo, features[l].normal, features[l].depth, sample[l]);
      sum.add(path[l].L, sample[l]);
    }
    q0 += n;
  }
  for (std::int64_t p = 0; p < pixels; ++p) finish_sum(tile, index(p), sums[std::size_t(p)], film, result);
  return result;
}

}  // namespace whisker
