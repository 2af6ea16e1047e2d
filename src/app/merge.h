// `whisker merge`: sums accumulation files (sample-range parts of one render)
// into one, exactly (docs/SHARDS.md).
#pragma once

namespace whisker {

// argv[0] is "merge". Returns the process exit code: 0, or 2 for bad input
// (a message naming the files and the field).
int run_merge(int argc, char** argv);

}  // namespace whisker
