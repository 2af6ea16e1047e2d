// Path splitting's factors (render/splitting.h): per diffuse hit, and
// scaled by the channels a path carries (split_weights).
#include <gtest/gtest.h>

#include "render/splitting.h"
#include "scene/scene_io.h"

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

TEST(Split, WeightsScaleByTheMostWeightedCarriedChannel) {
  const vec3 w(1.0f, 0.5f, 0.25f);
  EXPECT_EQ(weighted_split(4, vec3(1, 1, 1), w), 4);        // white: the largest weight
  EXPECT_EQ(weighted_split(4, vec3(0, 1, 0), w), 2);        // green only
  EXPECT_EQ(weighted_split(4, vec3(0, 0, 1), w), 1);        // blue only: 4 * 0.25
  EXPECT_EQ(weighted_split(4, vec3(0, 0.3f, 0.7f), w), 2);  // cyan: green's 0.5 wins
  EXPECT_EQ(weighted_split(2, vec3(0, 0, 1), w), 1);        // 0.5 rounds up to 1
  EXPECT_EQ(weighted_split(3, vec3(0, 0, 1), vec3(0.01f)), 1);  // never below 1
  EXPECT_EQ(weighted_split(6, vec3(0, 1, 0), w), 3);
  EXPECT_EQ(weighted_split(4, vec3(1, 0, 0), vec3(1.0f)), 4);   // all 1: the plain factor
  // The cat scene's file: paths that carry green but neither red nor blue split half.
  const Scene cat = load_scene(resolve_scene("cat"));
  EXPECT_EQ(cat.settings.split_weights, vec3(1.0f, 0.5f, 1.0f));
}
