// The pixels of an accumulation file as its channels hold them
// (docs/SHARDS.md, "File format"): which channels a part has, with or
// without the denoiser's feature layers, and a band of rows as the 32-bit
// words stored and back to checked doubles. Below OpenEXR: the file itself
// is accumulation_io's.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "render/accumulation.h"

namespace whisker {

// A double as a part's header and messages write it: "%.17g", every digit.
std::string exact_text(double v);

// A part's channels in the order of a band's words: R, G, B (FLOAT, the
// mean radiance), then each double's .hi and .lo words (UINT): sum.R, G, B
// and sumsq.Y, and with features odd.sum.R, G, B and the feature layers
// (feature.albedo.R ... feature.odd.depth.Z, kFeatureSums of them).
struct PartLayout {
  static constexpr std::size_t kMeanWords = 3;
  std::vector<std::string> channels;
  explicit PartLayout(bool features);
  std::size_t words() const { return channels.size(); }
  bool is_float(std::size_t channel) const { return channel < kMeanWords; }
};

// The words of rows y0 .. y0 + rows - 1 of `acc` as `layout` stores them.
void fill_band(const Accumulation& acc, const PartLayout& layout, int y0, int rows,
               std::vector<std::uint32_t>& band);

// A band's doubles, rebuilt from its words.
struct BandDoubles {
  std::vector<double> sum, sum_sq, odd_rgb, features;
  // The band as add_sums takes it, its first pixel `first` (row-major).
  SumsBand view(std::size_t first) const;
};

// Rebuilds the doubles of `pixels` pixels (rows of `width` from row y0) from
// `words` and checks them: radiance, albedo and depth sums finite and >= 0,
// an odd half no larger than its whole, normal sums finite. Returns what is
// wrong, naming the layer and the pixel ("feature.depth.Z of pixel (3, 1)
// is nan; ..."), or "".
std::string decode_band(const std::vector<std::uint32_t>& words, const PartLayout& layout,
                        std::size_t pixels, int width, int y0, BandDoubles& out);

}  // namespace whisker
