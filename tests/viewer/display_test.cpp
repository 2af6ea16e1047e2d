// Where the image goes in the window (viewer/display.h).
#include <gtest/gtest.h>

#include "viewer/display.h"

using namespace whisker;

TEST(FitImage, OneToOneWhenItFits) {
  const PixelRect r = fit_image({0, 0, 600, 720}, 512, 512);
  EXPECT_EQ(r.w, 512);
  EXPECT_EQ(r.h, 512);
  EXPECT_EQ(r.x, 44);
  EXPECT_EQ(r.y, 104);
  const PixelRect z = fit_image({0, 0, 1100, 1100}, 512, 512);  // integer zoom
  EXPECT_EQ(z.w, 1024);
  const PixelRect s = fit_image({0, 0, 256, 400}, 512, 512);  // shrink, keep aspect
  EXPECT_EQ(s.w, 256);
  EXPECT_EQ(s.h, 256);
}
