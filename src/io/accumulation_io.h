// Accumulation files: OpenEXR images whose R, G, B channels are the mean
// radiance (any EXR viewer shows them) and whose other channels carry the
// exact double sums (and, when the render kept them, the denoiser's feature
// sums: io/part_layers.h), with the sample ranges, the render's identity and
// a checksum of both as header attributes (docs/SHARDS.md, "File format").
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "render/accumulation.h"

namespace whisker {

// Rows a part is written and read in: a band of them at a time, never a
// copy of the whole image's words.
inline constexpr int kBandRows = 32;

// Through a temporary file renamed into place; throws ImageError naming the
// path if it cannot (or if the build has no OpenEXR). The file is the same
// whatever band_rows.
void write_accumulation(const std::string& path, const Accumulation& acc, int band_rows = kBandRows);
// Throws AccumulationError naming the path and what is wrong (one line).
// Its checksums are checked (whisker.checksum: Whisker's header attributes
// and the pixels as stored), and its sums: finite and >= 0, from UINT word
// channels; its feature layers (whisker.features) all there, summing the
// part's samples, their values possible (part_layers.h).
Accumulation read_accumulation(const std::string& path, int band_rows = kBandRows);
// The same without the sums (left empty): size, ranges, identity, counters;
// the header's checksum is checked, the pixels' is not.
Accumulation read_accumulation_header(const std::string& path);

// A band of rows of a part's sums (its feature sums too when it has them).
using SumBand = std::function<void(const SumsBand& band)>;
// Reads the part's sums band by band from the top, giving each to `band`,
// and returns its header (sums empty). The pixels' checksum is checked
// after the last band: a band given before a throw may be damaged.
Accumulation read_accumulation_bands(const std::string& path, int band_rows, const SumBand& band);

// `whisker merge` of the parts at `paths`: their headers read and checked
// against each other (plan_merge), `before_sums` called with the merged
// header (sums empty; it may throw), then each part's sums added band by
// band into the merged sums in range order, each part's checksums checked.
// Holds the merged sums and one band of one part. Throws AccumulationError.
// The merge keeps feature sums when every part has them; when only some do
// it keeps none, and `features_dropped` (if given) says which part has none
// (mixed_features), before `before_sums` is called.
Accumulation merge_accumulation_files(const std::vector<std::string>& paths,
                                      const std::function<void(const Accumulation&)>& before_sums = {},
                                      int band_rows = kBandRows, std::string* features_dropped = nullptr);

}  // namespace whisker
