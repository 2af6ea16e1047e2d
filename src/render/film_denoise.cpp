#include "render/film_denoise.h"

namespace whisker {

DenoiseInput FilmHalves::input() const {
  return {width,     height,    colour[0], colour[1], albedo[0],
          albedo[1], normal[0], normal[1], depth[0],  depth[1]};
}

std::string film_halves(const Snapshot& s, FilmHalves& out) {
  const std::size_t pixels = std::size_t(s.width) * std::size_t(s.height);
  if (s.features.size() != pixels * kFeatureSums || s.odd_rgb.size() != pixels * 3)
    return "the render kept no feature buffers";
  // Odd sample indices in [first_sample, first_sample + spp).
  const std::uint64_t odd = (s.first_sample + s.spp) / 2 - s.first_sample / 2, even = s.spp - odd;
  if (odd == 0 || even == 0) return "it needs at least 2 samples per pixel (one in each half)";
  const double inv[2] = {1.0 / double(even), 1.0 / double(odd)};
  out.width = s.width;
  out.height = s.height;
  for (int h = 0; h < 2; ++h) {
    out.colour[h].resize(pixels * 3);
    out.albedo[h].resize(pixels * 3);
    out.normal[h].resize(pixels * 3);
    out.depth[h].resize(pixels);
  }
  for (std::size_t p = 0; p < pixels; ++p) {
    const double* f = &s.features[p * kFeatureSums];  // all samples, then the odd ones
    for (int c = 0; c < 3; ++c) {
      const std::size_t k = 3 * p + std::size_t(c);
      // A non-finite sample is dropped from its half's sum but not from its
      // count: the NaN policy's count says how many (RenderCounters).
      out.colour[1][k] = float(s.odd_rgb[k] * inv[1]);
      out.colour[0][k] = float((s.sum[k] - s.odd_rgb[k]) * inv[0]);
      out.albedo[1][k] = float(f[7 + c] * inv[1]);
      out.albedo[0][k] = float((f[c] - f[7 + c]) * inv[0]);
      out.normal[1][k] = float(f[10 + c] * inv[1]);
      out.normal[0][k] = float((f[3 + c] - f[10 + c]) * inv[0]);
    }
    out.depth[1][p] = float(f[13] * inv[1]);
    out.depth[0][p] = float((f[6] - f[13]) * inv[0]);
  }
  return {};
}

}  // namespace whisker
