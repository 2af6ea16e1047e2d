// The error of the output files: thrown by every writer in io/ (images,
// accumulation files, stats, the atomic writes under them) and by the image
// reader; what() is one line naming the file.
#pragma once

#include <stdexcept>

namespace whisker {

struct ImageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace whisker
