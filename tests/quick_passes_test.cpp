// The quick passes' stride while the mouse drags (render/quick_passes.h):
// the smallest that brings a pass under its aim, dividing the image.
#include <gtest/gtest.h>

#include "render/quick_passes.h"

using namespace whisker;

TEST(QuickPasses, DragStrideBringsAPassUnderItsAim) {
  EXPECT_EQ(QuickPasses::drag_stride(0.0, 512, 512), 2);    // not timed yet
  EXPECT_EQ(QuickPasses::drag_stride(0.015, 512, 512), 1);  // already fast enough
  EXPECT_EQ(QuickPasses::drag_stride(0.07, 512, 512), 2);   // 70 ms / 4 = 17.5 ms
  EXPECT_EQ(QuickPasses::drag_stride(0.2, 512, 512), 4);    // 200 ms / 16 = 12.5 ms
  EXPECT_EQ(QuickPasses::drag_stride(5.0, 512, 512), 4);    // at most 4
  EXPECT_EQ(QuickPasses::drag_stride(0.2, 510, 510), 3);    // 4 does not divide 510
  EXPECT_EQ(QuickPasses::drag_stride(0.2, 511, 512), 1);    // nothing divides 511 and 512
}
