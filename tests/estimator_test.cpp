// The estimator's choices for the renderer (render/estimator.h): the quick
// passes' cheap settings differ from the settings' own only where they are
// cheaper. (render_tile is tested beside the paths it traces in lanes,
// integrator_test.cpp.)
#include <gtest/gtest.h>

#include "render/estimator.h"

using namespace whisker;

// The quick passes' settings (cheap_settings) differ from the settings' own
// only with more than one sample per pass or with indirect paths split.
TEST(Estimator, QuickPassesOnlyWhenTheyAreCheaper) {
  RenderSettings s;
  s.indirect = false;
  s.spp = 1;
  s.split = {4, 4};
  EXPECT_FALSE(cheap_differs(s));  // splitting needs indirect light
  s.spp = 4;
  EXPECT_TRUE(cheap_differs(s));
  s.spp = 1;
  s.indirect = true;
  EXPECT_TRUE(cheap_differs(s));
  s.split = {1};
  EXPECT_FALSE(cheap_differs(s));
}
