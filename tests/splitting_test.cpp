// Path splitting's factors (render/splitting.h).
#include <gtest/gtest.h>

#include "render/splitting.h"

using namespace whisker;

// Split factors per diffuse hit: the listed ones, then 1 past the end.
TEST(Splitting, FactorsPerDiffuseHitEndInOnes) {
  RenderSettings settings;
  settings.split = {4, 2};
  const vec3 white(1.0f);
  EXPECT_EQ(split_factor(settings, 0, white), 4);
  EXPECT_EQ(split_factor(settings, 1, white), 2);
  EXPECT_EQ(split_factor(settings, 2, white), 1);
  settings.split_weights = vec3(1.0f, 1.0f, 0.25f);
  EXPECT_EQ(split_factor(settings, 0, vec3(0.0f, 0.0f, 0.7f)), 1);  // blue only: 4 * 0.25
}
