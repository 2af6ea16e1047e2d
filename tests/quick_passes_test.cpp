// The quick passes (render/quick_passes.h): their settings, which differ
// from the settings' own only where they are cheaper, and their stride while
// the mouse drags, the smallest that brings a pass under its aim, dividing
// the image.
#include <gtest/gtest.h>

#include <vector>

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

// The quick passes' settings (quick_settings) differ from the settings' own
// only with more than one sample per pass or with indirect paths split.
TEST(QuickPasses, QuickPassesOnlyWhenTheyAreCheaper) {
  RenderSettings s;
  s.indirect = false;
  s.spp = 1;
  s.split = {4, 4};
  EXPECT_FALSE(quick_differs(s));  // splitting needs indirect light
  s.spp = 4;
  EXPECT_TRUE(quick_differs(s));
  s.spp = 1;
  s.indirect = true;
  EXPECT_TRUE(quick_differs(s));
  s.split = {1};
  EXPECT_FALSE(quick_differs(s));
}

// The quick passes' settings: one path per sample (no splitting, unit
// weights), no light connections (a quick pass builds no light cache),
// independent numbers and a seed of their own; the rest as set.
TEST(QuickPasses, CheapSettingsAreOnePathPerSampleWithASeedOfTheirOwn) {
  RenderSettings s;
  s.spp = 16;
  s.split = {4, 2};
  s.split_weights = vec3(1.0f, 0.5f, 1.0f);
  s.connect = true;
  s.sampler = SamplerKind::Sobol;
  s.indirect = s.aa = s.fresnel = true;
  s.max_depth = 3;
  s.seed = 42;
  const RenderSettings q = quick_settings(s);
  EXPECT_EQ(q.spp, 1);
  EXPECT_EQ(q.split, std::vector<int>({1}));
  EXPECT_EQ(q.split_weights, vec3(1.0f));
  EXPECT_FALSE(q.connect);
  EXPECT_EQ(q.sampler, SamplerKind::Independent);
  EXPECT_NE(q.seed, s.seed);
  EXPECT_TRUE(q.indirect && q.aa && q.fresnel);
  EXPECT_EQ(q.max_depth, 3);
  EXPECT_FALSE(quick_differs(q));  // already the cheapest
}
