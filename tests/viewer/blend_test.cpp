// The window's image from the quick and the own passes (viewer/blend.h).
#include <gtest/gtest.h>

#include "viewer/blend.h"

using namespace whisker;

// The window's image after an edit: the quick passes alone, then combined
// with the generation's own by count x fixed weight, then the own alone.
TEST(Blend, QuickThenCombinedThenTheOwnPassesAlone) {
  RenderSettings st;
  st.indirect = true;
  st.split = {4, 2};  // one own sample weighs 8 quick ones
  ASSERT_EQ(own_sample_weight(st), 8.0);
  Snapshot own, quick;
  own.width = quick.width = 1;
  own.height = quick.height = 1;
  quick.generation = 2;
  quick.spp = 4;
  quick.sum = {4.0f, 8.0f, 0.0f};  // mean 1, 2, 0
  own.generation = 1;
  own.spp = 3;
  own.sum = {30.0f, 30.0f, 30.0f};
  Shown out;
  blend_for_display(own, quick, st, out);  // the own passes are the old edit's
  EXPECT_EQ(out.quick_spp, 4u);
  EXPECT_EQ(out.image.mean(0, 0, 0), 1.0f);
  own.generation = 2;
  own.spp = 1;
  own.sum = {3.0f, 3.0f, 3.0f};  // mean 3
  blend_for_display(own, quick, st, out);
  // weights 8 x 1 own, 1 x 4 quick: (8 * 3 + 4 * 1) / 12, (8 * 3 + 4 * 2) / 12, 24 / 12
  EXPECT_FLOAT_EQ(out.image.mean(0, 0, 0), 28.0f / 12.0f);
  EXPECT_FLOAT_EQ(out.image.mean(0, 0, 1), 32.0f / 12.0f);
  EXPECT_FLOAT_EQ(out.image.mean(0, 0, 2), 2.0f);
  EXPECT_EQ(out.image.spp, 1u);
  EXPECT_EQ(out.quick_spp, 4u);
  own.spp = 8;  // 64 >= 16 x 4: the quick samples are dropped
  own.sum = {24.0f, 24.0f, 24.0f};
  blend_for_display(own, quick, st, out);
  EXPECT_EQ(out.quick_spp, 0u);
  EXPECT_EQ(out.image.sum, own.sum);
}

// A drag's coarse quick pass (Snapshot::stride 2, half the size) is shown
// while its generation has no pass of its own, and never combined with one.
TEST(Blend, CoarseQuickPassShownAloneNeverCombined) {
  RenderSettings st;
  st.indirect = true;
  st.split = {4, 2};
  Snapshot own, quick;
  own.width = 2;
  own.height = 2;
  quick.width = quick.height = 1;
  quick.stride = 2;
  quick.generation = own.generation = 3;
  quick.spp = 1;
  quick.sum = {1.0f, 1.0f, 1.0f};
  own.spp = 0;
  own.sum.assign(12, 0.0f);
  Shown out;
  blend_for_display(own, quick, st, out);
  EXPECT_EQ(out.image.stride, 2);
  EXPECT_EQ(out.image.width, 1);
  EXPECT_EQ(out.quick_spp, 1u);
  own.spp = 1;  // the own first pass: shown alone, full size
  own.sum.assign(12, 5.0f);
  blend_for_display(own, quick, st, out);
  EXPECT_EQ(out.image.stride, 1);
  EXPECT_EQ(out.image.width, 2);
  EXPECT_EQ(out.quick_spp, 0u);
  EXPECT_EQ(out.image.sum, own.sum);
}
