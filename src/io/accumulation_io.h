// Accumulation files: OpenEXR images whose R, G, B channels are the mean
// radiance (any EXR viewer shows them) and whose other channels carry the
// exact double sums, with the sample ranges and the render's identity as
// header attributes (docs/SHARDS.md, "File format").
#pragma once

#include <string>

#include "render/accumulation.h"

namespace whisker {

// Through a temporary file renamed into place; throws ImageError naming the
// path if it cannot (or if the build has no OpenEXR).
void write_accumulation(const std::string& path, const Accumulation& acc);
// Throws AccumulationError naming the path and what is wrong.
// Its sums are checked: finite and >= 0, from UINT word channels.
Accumulation read_accumulation(const std::string& path);
// The same without the sums (left empty): size, ranges, identity, counters.
Accumulation read_accumulation_header(const std::string& path);

}  // namespace whisker
