// A linear RGB image: what the file writers take.
#pragma once

#include <vector>

namespace whisker {

// Linear RGB radiance, row 0 at the top.
struct Image {
  int width = 0, height = 0;
  std::vector<float> rgb;
};

}  // namespace whisker
